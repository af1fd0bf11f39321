// The live 3D view: the machine structure moving with the MCS stream, the tool between the
// spindle (tool holder) and the tool tip, the WCS origin, the executed toolpath.

import * as THREE from "three";
import type { State } from "../api/types";
import { byId } from "../core/dom";
import { NcData } from "../core/ncdata";
import type { SessionController, SessionInfo } from "../core/session";
import { Kinematics } from "./kinematics";
import { buildMachine, type MachineModel } from "./machineModel";
import { Toolpath } from "./toolpath";
import { Viewport, type ViewName } from "./viewport";

const AXIS_COLORS = { X: 0xe5534b, Y: 0x57ab5a, Z: 0x539bf5 } as const;
const DEFAULT_TOOL_RADIUS = 5;

/** Three arrows at the WCS origin along the geometry axes. */
function wcsTriad(k: Kinematics, size: number): THREE.Group {
  const triad = new THREE.Group();
  for (const letter of ["X", "Y", "Z"] as const) {
    if (!k.linear.has(letter)) continue;
    triad.add(new THREE.ArrowHelper(k.dir(letter), new THREE.Vector3(), size, AXIS_COLORS[letter], size * 0.2, size * 0.1));
  }
  return triad;
}

/** The tool as a cylinder from the tool tip to the tool holder point. */
class ToolSolid {
  readonly mesh = new THREE.Mesh(
    new THREE.CylinderGeometry(1, 1, 1, 24).translate(0, 0.5, 0), // unit height from y=0 to 1
    new THREE.MeshLambertMaterial({ color: 0xe0b341 }),
  );
  private readonly up = new THREE.Vector3(0, 1, 0);
  private readonly dir = new THREE.Vector3();

  place(tip: THREE.Vector3, holder: THREE.Vector3, radius: number): void {
    this.dir.subVectors(holder, tip);
    const length = this.dir.length();
    this.mesh.visible = length > 0.5;
    if (!this.mesh.visible) return;
    this.mesh.position.copy(tip);
    this.mesh.quaternion.setFromUnitVectors(this.up, this.dir.divideScalar(length));
    this.mesh.scale.set(radius, length, radius);
  }
}

export class MachineView {
  private readonly viewport: Viewport;
  private readonly toolpath = new Toolpath();
  private readonly tool = new ToolSolid();
  private readonly content = new THREE.Group(); // what belongs to the attached machine
  private kinematics: Kinematics | null = null;
  private model: MachineModel | null = null;
  private triad: THREE.Group | null = null;
  private ncData = new NcData("");
  private machineAxesKey = "";
  private info: SessionInfo | null = null;
  /** Tool holder minus tool tip in the scene, measured while no transformation is active. */
  private readonly toolOffset = new THREE.Vector3();
  private readonly holder = new THREE.Vector3();
  private readonly tip = new THREE.Vector3();
  private readonly wcs = new THREE.Vector3();
  private readonly bcs = new THREE.Vector3();

  constructor(host: HTMLElement) {
    this.viewport = new Viewport(host);
    this.viewport.scene.add(this.content);
  }

  attach(info: SessionInfo, opts: { keepPath?: boolean } = {}): void {
    this.info = info;
    this.ncData = new NcData(info.machine.machine_data);
    this.machineAxesKey = ""; // rebuilt from the first state (it names the machine axes)
    if (!opts.keepPath) this.toolpath.clear();
  }

  show(st: State): void {
    const axes = Object.keys(st.positions.machine);
    if (axes.join(",") !== this.machineAxesKey) this.build(axes);
    const k = this.kinematics;
    if (!k || !this.model) return;

    this.model.update(st.positions.machine);
    k.machinePoint(st.positions.machine, this.holder);
    k.geometryPoint(st.positions.basic, this.bcs);
    if (!st.transformation) this.toolOffset.subVectors(this.holder, this.bcs);
    this.tip.subVectors(this.holder, this.toolOffset);
    this.tool.place(this.tip, this.holder, this.toolRadius(st.tool.t, st.tool.d));

    // WCS origin: where WCS zero lies in the BCS (translation only).
    k.geometryPoint(st.positions.workpiece, this.wcs);
    this.triad?.position.subVectors(this.bcs, this.wcs);

    this.toolpath.add(this.tip);
    this.viewport.invalidate();
  }

  setView(view: ViewName): void {
    const box = new THREE.Box3().setFromObject(this.content);
    if (!box.isEmpty()) this.viewport.frameBox(box, view);
  }

  /** Zooms to the executed toolpath (keeps the viewing direction). */
  zoomToPath(): void {
    const box = this.toolpath.bounds();
    if (box.isEmpty()) return;
    box.expandByScalar(20);
    const dir = this.viewport.camera.position.clone().sub(this.viewport.controls.target).normalize();
    this.viewport.frameBox(box, dir);
  }

  clearPath(): void {
    this.toolpath.clear();
    this.viewport.invalidate();
  }

  private build(machineAxes: string[]): void {
    this.machineAxesKey = machineAxes.join(",");
    this.content.clear();
    const k = new Kinematics(machineAxes, this.info?.machine.machine_data ?? "");
    this.kinematics = k;
    this.model = buildMachine(k);
    const spans = [...k.linear.values()].map((a) => a.max - a.min);
    this.triad = wcsTriad(k, Math.max(40, Math.max(...spans, 0) * 0.08));
    this.content.add(this.model.root, this.triad, this.tool.mesh, this.toolpath.line);
    this.model.update({});
    this.setView("iso");
  }

  private toolRadius(t: number, d: number): number {
    if (t === 0 || d === 0) return DEFAULT_TOOL_RADIUS;
    return Math.max(3, this.ncData.number("$TC_DP6", `${t},${d}`) || DEFAULT_TOOL_RADIUS);
  }
}

export function mountMachineView(session: SessionController): MachineView {
  const view = new MachineView(byId("view3d"));
  session.on("session", (info) => view.attach(info));
  session.on("sample", (st) => view.show(st));
  // New machine data (travel, tools): rebuild the model, keep the toolpath.
  session.on("machine", (info) => {
    view.attach(info, { keepPath: true });
    if (session.latest) view.show(session.latest);
  });
  const views: Record<string, ViewName> = { "btn-view-iso": "iso", "btn-view-top": "top", "btn-view-front": "front" };
  for (const [id, name] of Object.entries(views)) byId(id).addEventListener("click", () => view.setView(name));
  byId("btn-view-path").addEventListener("click", () => view.zoomToPath());
  byId("btn-path-clear").addEventListener("click", () => view.clearPath());
  return view;
}

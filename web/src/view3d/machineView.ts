// The live 3D view: the machine's kinematic structure (from the session's machine data) moving
// with the MCS of the stream, the tool with its length from the tool data of the active T/D,
// the WCS at the active work offset, the executed toolpath (the tool tip traced on the
// workpiece) and the programmed path (POST .../preview), orbit and zoom.

import * as THREE from "three";
import type { AxisValues, PathHistory, State, StockWarning } from "../api/types";
import { byId, fmt, setText } from "../core/dom";
import { NcData } from "../core/ncdata";
import type { SessionController, SessionInfo } from "../core/session";
import { api } from "../api/client";
import { buildChainMachine, chainRecordFor } from "./chainModel";
import { parseChains } from "./kinChains";
import { axisLookup, isOrientationTrafo, readStructure, type Structure } from "./machineData";
import { buildMachine, type MachineModel } from "./machineModel";
import { Toolpath } from "./toolpath";
import { Viewport, type ViewName } from "./viewport";
import { StockView } from "./stock";
import { WcsTriad } from "./wcsTriad";
import { PathCheck, cartesianOf } from "./pathCheck";
import { wrapOnCylinder } from "./cylinderWrap";
import { activeSwivel } from "../swivel/activeSwivel";

const DEFAULT_TOOL_RADIUS = 5;
export const EXECUTED_COLOR = 0xffb02e;
export const PROGRAMMED_COLOR = 0x39c5cf;

/** Geometry axis values (X, Y, Z by name) as a point of the machine's Cartesian frame. */
function geometryPoint(values: AxisValues, out = new THREE.Vector3()): THREE.Vector3 {
  const v = (k: string) => (typeof values[k] === "number" ? values[k] : 0);
  return out.set(v("X"), v("Y"), v("Z"));
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

/** The programmed path: a fixed polyline of WCS points placed at the work offset. */
class ProgrammedPath {
  // Drawn over the solids: a path inside the workpiece or under the tool stays visible.
  readonly line = new THREE.Line(
    new THREE.BufferGeometry(),
    new THREE.LineBasicMaterial({ color: PROGRAMMED_COLOR, depthTest: false, transparent: true, opacity: 0.9 }),
  );
  count = 0;
  /** Per preview point: the index of its drawn vertex (a wrapped helix adds vertices). */
  private index: number[] = [];

  /**
   * `diameters[i]`: the TRACYL working diameter at point i (its X is radial, Y the arc length,
   * Z axial), wrapped onto the cylinder of `cylinder` when the model has one.
   */
  set(
    points: [number, number, number][],
    axes: string[],
    offset: THREE.Vector3,
    diameters: (number | null)[] = [],
    cylinder: Structure["cylinder"] = null,
  ): void {
    const cartesian = cartesianOf(axes);
    const out: number[] = [];
    this.index = [];
    points.forEach((p, i) => {
      const q = cartesian(p);
      const d = diameters[i];
      if (!cylinder || typeof d !== "number" || !(d > 0)) {
        out.push(q[0] + offset.x, q[1] + offset.y, q[2] + offset.z);
        this.index.push(out.length / 3 - 1);
        return;
      }
      // A straight segment on the unrolled surface is a helix on the cylinder: subdivide it
      // so that no step turns more than 2°.
      const prev = i > 0 && diameters[i - 1] === d ? cartesian(points[i - 1]!) : null;
      const turn = prev ? Math.abs(q[1] - prev[1]) / (d / 2) : 0;
      const steps = prev ? Math.min(720, Math.max(1, Math.ceil(turn / ((2 * Math.PI) / 180)))) : 1;
      for (let k = prev ? 1 : steps; k <= steps; k++) {
        const t = k / steps;
        const at = prev ? ([0, 1, 2].map((c) => prev[c]! + (q[c]! - prev[c]!) * t) as [number, number, number]) : q;
        out.push(...wrapOnCylinder(at, d, cylinder));
      }
      this.index.push(out.length / 3 - 1);
    });
    const data = new Float32Array(out);
    this.line.geometry.dispose();
    this.line.geometry = new THREE.BufferGeometry();
    this.line.geometry.setAttribute("position", new THREE.BufferAttribute(data, 3));
    this.line.geometry.computeBoundingSphere();
    this.count = data.length / 3;
  }

  /** Where preview point `i` is drawn (part frame); null outside the path. */
  pointAt(i: number, out = new THREE.Vector3()): THREE.Vector3 | null {
    const a = this.line.geometry.getAttribute("position");
    const k = this.index[i];
    if (!a || k === undefined || k < 0 || k >= a.count) return null;
    return out.set(a.getX(k), a.getY(k), a.getZ(k));
  }

  /** The drawn points (part frame), for the browser test. */
  points(): [number, number, number][] {
    const a = this.line.geometry.getAttribute("position");
    const out: [number, number, number][] = [];
    for (let i = 0; a && i < a.count; i++) out.push([a.getX(i), a.getY(i), a.getZ(i)]);
    return out;
  }

  clear(): void {
    this.line.geometry.dispose();
    this.line.geometry = new THREE.BufferGeometry();
    this.count = 0;
    this.index = [];
  }

  bounds(): THREE.Box3 {
    return this.count ? new THREE.Box3().setFromObject(this.line) : new THREE.Box3();
  }
}

export class MachineView {
  private readonly viewport: Viewport;
  private readonly toolpath = new Toolpath(EXECUTED_COLOR);
  readonly programmed = new ProgrammedPath();
  /** Tool axes, limit marks and the slider's marker along the programmed path. */
  readonly check = new PathCheck();
  private readonly tool = new ToolSolid();
  private readonly content = new THREE.Group(); // what belongs to the attached machine
  /** The cut stock (stock.ts), in the workpiece frame. */
  readonly stock = new StockView(() => this.viewport.invalidate());
  private structure: Structure | null = null;
  private model: MachineModel | null = null;
  private triad: WcsTriad | null = null;
  /** The WCS directions of the active frame chain (GET .../active-swivel), null: the BCS's. */
  private wcsAxes: [number, number, number][] | null = null;
  private ncData = new NcData("");
  private buildKey = "";
  private info: SessionInfo | null = null;
  /** The session's kinematic chain program (GET .../kinematic-chains), "" until fetched. */
  private chainText = "";
  private chainSerial = 0;
  private latest: State | null = null;
  /** Lathe: tool holder minus tool tip, measured while the BCS is Cartesian and untransformed. */
  private readonly latheOffset = new THREE.Vector3();
  private readonly holder = new THREE.Vector3();
  private readonly axis = new THREE.Vector3();
  private readonly tip = new THREE.Vector3();
  private readonly tipPart = new THREE.Vector3();
  private readonly bcs = new THREE.Vector3();
  private readonly wcs = new THREE.Vector3();
  /** Work offset (BCS − WCS of the geometry axes) of the latest state. */
  readonly workOffset = new THREE.Vector3();
  /**
   * Distance between the model's tool tip (on the workpiece) and the engine's BCS tool tip
   * while they are comparable (orientation transformation or none), for the browser test.
   */
  tipError: number | null = null;
  /** Points of the executed path that came from the session's history, for the browser test. */
  historyPoints = 0;
  /** Frame the working zone once the first state has placed the tool. */
  private framePending = false;

  constructor(
    host: HTMLElement,
    private readonly caption: HTMLElement,
  ) {
    this.viewport = new Viewport(host);
    this.viewport.scene.add(this.content);
  }

  attach(info: SessionInfo, opts: { keepPath?: boolean } = {}): void {
    this.info = info;
    this.ncData = new NcData(info.machine.machine_data);
    this.buildKey = ""; // rebuilt from the first state (it names the machine axes)
    if (!opts.keepPath) this.chainText = "";
    void this.fetchChains();
    if (!opts.keepPath) {
      this.toolpath.clear();
      this.programmed.clear();
      this.check.clear();
      void this.fetchHistory();
    }
  }

  /**
   * The executed path from before this view joined (GET .../path-history: the tool tip on the
   * workpiece, thinned by the server), put before the points the stream has added since once
   * the model is built (TRACYL points are wrapped onto its cylinder). Points the server could
   * not place on the part (a table turned by axes the kinematics do not describe) are left out
   * and counted in the caption rather than drawn where the tool was not.
   */
  private async fetchHistory(): Promise<void> {
    const id = this.info?.id;
    if (!id) return;
    this.pendingHistory = null;
    let history: PathHistory;
    try {
      history = await api.pathHistory(id);
    } catch {
      return; // an older server: the path starts now
    }
    if (id !== this.info?.id) return;
    this.pendingHistory = history;
    if (this.structure) this.applyHistory();
  }

  private pendingHistory: PathHistory | null = null;

  private applyHistory(): void {
    const history = this.pendingHistory;
    this.pendingHistory = null;
    if (!history) return;
    const cart = cartesianOf(history.axes);
    const cylinder = this.structure?.cylinder ?? null;
    const points: THREE.Vector3[] = [];
    let inexact = 0;
    history.points.forEach((p, i) => {
      if (history.exact?.[i] === false) {
        inexact++;
        return;
      }
      const d = history.tracyl_diameter?.[i];
      const q = cylinder && typeof d === "number" && d > 0 ? wrapOnCylinder(cart(p), d, cylinder) : cart(p);
      points.push(new THREE.Vector3(...q));
    });
    this.historyPoints = this.toolpath.prepend(points);
    this.historyInexact = inexact;
    const note = document.getElementById("view3d-history");
    if (note) {
      note.hidden = inexact === 0;
      note.textContent = inexact ? `earlier path: ${inexact} points not shown (table turned by axes the machine data do not describe)` : "";
    }
    this.viewport.invalidate();
  }

  /** Points of the fetched history left out (not known to be on the part). */
  historyInexact = 0;

  /** The TRACYL cylinder of the model (null: none, or no model yet). */
  cylinder(): Structure["cylinder"] {
    return this.structure?.cylinder ?? null;
  }

  show(st: State): void {
    const axes = Object.keys(st.positions.machine);
    const trafo = st.transformation ?? null;
    const oriSet = trafo && isOrientationTrafo(trafo.type) ? trafo.index : null;
    const key = `${axes.join(",")}|${oriSet ?? ""}`;
    this.latest = st;
    if (key !== this.buildKey) {
      this.build(axes, oriSet);
      // A chain transformation selected: its chains may be new (a program wrote $NK_ data).
      if (oriSet !== null && oriSet >= 100) void this.fetchChains();
    }
    const s = this.structure;
    const model = this.model;
    if (!s || !model) return;

    const polar = trafo !== null && trafo.type >= 256 && trafo.type <= 514; // TRANSMIT, TRACYL
    model.update(st.positions.machine, polar);
    model.holder(this.holder);
    geometryPoint(st.positions.basic, this.bcs);
    geometryPoint(st.positions.workpiece, this.wcs);
    this.workOffset.subVectors(this.bcs, this.wcs);

    if (s.kind === "mill") {
      model.toolAxis(this.axis);
      this.tip.copy(this.holder).addScaledVector(this.axis, -this.toolLength(st.tool.t, st.tool.d));
    } else {
      // The BCS is the Cartesian tool tip without a transformation and under TRAANG: the tool
      // offset is measured there; under TRANSMIT/TRACYL/TRACON it comes from the tool data.
      if (!trafo || trafo.type === 1024 || trafo.type === 1025) this.latheOffset.subVectors(this.holder, this.bcs);
      else this.latheToolOffset(st, this.latheOffset);
      this.tip.subVectors(this.holder, this.latheOffset);
    }
    this.tool.place(this.tip, this.holder, this.toolRadius(st.tool.t, st.tool.d));

    // The tip on the workpiece (the part frame turns with a rotary table or a C axis).
    this.content.updateMatrixWorld(true);
    this.tipPart.copy(this.tip);
    model.frame.localToWorld(this.tipPart);
    model.part.worldToLocal(this.tipPart);
    // Comparable: the BCS is the Cartesian tool tip on the workpiece (a mill without or with
    // TRAORI; a lathe under TRANSMIT, whose workpiece frame turns with C).
    const transmit = trafo !== null && (trafo.type === 256 || trafo.type === 257);
    const comparable = s.kind === "mill" ? !trafo || isOrientationTrafo(trafo.type) : transmit;
    this.tipError = comparable ? this.tipPart.distanceTo(this.bcs) : null;

    this.triad?.place(this.bcs, this.wcs);
    // A lathe's part ends at the WCS zero (its face, where turning programs put Z0).
    if (s.kind === "lathe" && !trafo) model.placePart?.(this.workOffset.z);
    this.toolpath.add(this.tipPart);
    if (this.framePending) {
      this.framePending = false;
      if (this.programmed.count > 0) this.frameProgram();
      else this.setView("iso");
    }
    this.viewport.invalidate();
  }

  /** A lathe's part end face (machine Z), null on other machines. */
  partEnd(): number | null {
    return this.model?.partEnd?.() ?? null;
  }

  /** Draws the scene again at the next frame. */
  redraw(): void {
    this.viewport.invalidate();
  }

  /** Turns the WCS triad with the frame chain (unit WCS axes in the BCS; null: not turned). */
  setWcsAxes(axes: [number, number, number][] | null): void {
    this.wcsAxes = axes;
    this.triad?.setAxes(axes);
    if (this.latest) this.show(this.latest);
    this.viewport.invalidate();
  }

  /**
   * The tool direction (tip → holder) relative to the workpiece in the WCS: the engine's under
   * an orientation transformation; otherwise the model's (the head's or table's rotary axes as
   * they stand, which the engine reports only under TRAORI), turned into the WCS by the frame.
   */
  toolVector(st: State): [number, number, number] | null {
    const trafo = st.transformation;
    if (trafo && isOrientationTrafo(trafo.type) && st.orientation) return st.orientation;
    if (!this.model || this.structure?.kind !== "mill") return null;
    this.content.updateMatrixWorld(true);
    const toPart = this.model.part.getWorldQuaternion(new THREE.Quaternion()).invert();
    const v = this.axis.clone().applyQuaternion(this.model.frame.getWorldQuaternion(new THREE.Quaternion())).applyQuaternion(toPart);
    const w = this.triad ? this.triad.toWcs(v) : v;
    return [w.x, w.y, w.z];
  }

  /** Where the triad's WCS axis `letter` points (part frame), for the browser test. */
  wcsDirection(letter: "X" | "Y" | "Z"): [number, number, number] | null {
    return this.triad?.direction(letter) ?? null;
  }

  /** Shows a programmed path (WCS points of the preview) at the current work offset. */
  setProgrammed(points: [number, number, number][], axes: string[], tracylDiameter: (number | null)[] = [], program = ""): void {
    // Framed on the first path of each program (another program, or the first path at all).
    const first = this.programmed.count === 0 || program !== this.framedProgram;
    this.framedProgram = program;
    // The points are BCS: the part frame is the BCS, no offset to add.
    this.programmed.set(points, axes, new THREE.Vector3(), tracylDiameter, this.structure?.cylinder ?? null);
    if (first && points.length) this.frameProgram();
    this.viewport.invalidate();
  }

  /**
   * Fits the camera to what a program check looks at: the programmed path, the stock (the
   * blank of WORKPIECE(...) or PUT .../stock), the executed path and the tool tip.
   */
  frameProgram(view: ViewName = "iso"): void {
    if (!this.model) return;
    this.content.updateMatrixWorld(true);
    const box = this.programmed.bounds();
    box.union(new THREE.Box3().setFromObject(this.stock.group));
    if (this.check.blank) box.union(this.check.blank.clone().applyMatrix4(this.model.part.matrixWorld));
    const exec = this.toolpath.bounds();
    if (!exec.isEmpty()) box.union(exec.applyMatrix4(this.model.part.matrixWorld));
    box.expandByPoint(this.model.frame.localToWorld(this.tip.clone()));
    if (box.isEmpty()) return;
    const size = box.getSize(new THREE.Vector3()).length();
    box.expandByScalar(Math.max(10, 0.12 * size));
    this.viewport.frameBox(box, view);
    this.framed = box.clone();
  }

  /**
   * The share of the programmed path's points the camera sees (inside the view frustum), for
   * the browser test: 1 when the path is framed.
   */
  programmedInView(): number {
    const pts = this.programmed.points();
    if (!pts.length || !this.model) return 0;
    this.content.updateMatrixWorld(true);
    const cam = this.viewport.camera;
    cam.updateMatrixWorld(true);
    const v = new THREE.Vector3();
    let inside = 0;
    for (const p of pts) {
      v.set(...p);
      this.model.part.localToWorld(v).project(cam);
      if (Math.abs(v.x) <= 1 && Math.abs(v.y) <= 1 && v.z >= -1 && v.z <= 1) inside++;
    }
    return inside / pts.length;
  }

  /** The program whose path was framed last (a key the preview gives). */
  private framedProgram = "";

  /** The box the last frameProgram fitted (world), for the browser test. */
  framed: THREE.Box3 | null = null;

  /** Looks at the working zone (tool, workpiece, paths) from a standard direction. */
  setView(view: ViewName): void {
    const box = this.workZone();
    if (!box.isEmpty()) this.viewport.frameBox(box, view);
  }

  /** The tool, the workpiece zero and the paths, with room for the axes around them. */
  private workZone(): THREE.Box3 {
    const box = new THREE.Box3();
    if (!this.model) return box;
    this.content.updateMatrixWorld(true);
    const world = (p: THREE.Vector3) => this.model!.frame.localToWorld(p.clone());
    box.expandByPoint(world(this.tip)).expandByPoint(world(this.holder));
    // The head above the holder (a mill's rotary axes sit there).
    box.expandByPoint(world(this.holder.clone().addScaledVector(this.axis, 300)));
    box.expandByPoint(this.model.part.localToWorld(new THREE.Vector3()));
    box.union(this.programmed.bounds());
    box.expandByScalar(100 + 0.1 * this.model.size);
    return box;
  }

  /** Zooms to the toolpaths (keeps the viewing direction). */
  zoomToPath(): void {
    const box = new THREE.Box3();
    const exec = this.toolpath.bounds();
    if (!exec.isEmpty() && this.model) {
      this.content.updateMatrixWorld(true);
      box.union(exec.applyMatrix4(this.model.part.matrixWorld));
    }
    box.union(this.programmed.bounds());
    if (box.isEmpty()) return;
    box.expandByScalar(20);
    const dir = this.viewport.camera.position.clone().sub(this.viewport.controls.target).normalize();
    this.viewport.frameBox(box, dir);
  }

  pathPoints(n: number): [number, number, number][] {
    return this.toolpath.lastPoints(n);
  }

  /**
   * How far the workpiece frame is turned about the unit machine direction `about` (degrees,
   * right-handed): the turn of a perpendicular vector, for the browser test.
   */
  partTurn(about: [number, number, number]): number | null {
    if (!this.model) return null;
    this.content.updateMatrixWorld(true);
    const axis = new THREE.Vector3(...about).normalize();
    const q = this.model.part.getWorldQuaternion(new THREE.Quaternion());
    const frame = this.model.frame.getWorldQuaternion(new THREE.Quaternion());
    q.premultiply(frame.invert()); // the part's turn in the machine frame
    const ref = Math.abs(axis.z) < 0.9 ? new THREE.Vector3(0, 0, 1) : new THREE.Vector3(1, 0, 0);
    ref.sub(axis.clone().multiplyScalar(ref.dot(axis))).normalize();
    const turned = ref.clone().applyQuaternion(q);
    return THREE.MathUtils.radToDeg(Math.atan2(axis.dot(ref.clone().cross(turned)), ref.dot(turned)));
  }

  /** Where the part frame's unit vector `v` points in the machine frame, for the browser test. */
  partDirection(v: [number, number, number]): [number, number, number] | null {
    if (!this.model) return null;
    this.content.updateMatrixWorld(true);
    const q = this.model.part.getWorldQuaternion(new THREE.Quaternion());
    q.premultiply(this.model.frame.getWorldQuaternion(new THREE.Quaternion()).invert());
    return new THREE.Vector3(...v).applyQuaternion(q).toArray();
  }

  clearPath(): void {
    this.toolpath.clear();
    this.programmed.clear();
    this.check.clear();
    this.viewport.invalidate();
  }

  /** Fetches the session's chain data; rebuilds the model when it changed. */
  private async fetchChains(): Promise<void> {
    const id = this.info?.id;
    if (!id) return;
    const mine = ++this.chainSerial;
    let text = "";
    try {
      text = await api.kinematicChains(id);
    } catch {
      return; // no chains to draw: the machine data model stays
    }
    if (mine !== this.chainSerial || id !== this.info?.id || typeof text !== "string" || text === this.chainText) return;
    this.chainText = text;
    this.buildKey = "";
    if (this.latest) this.show(this.latest);
  }

  private build(machineAxes: string[], oriSet: number | null): void {
    this.buildKey = `${machineAxes.join(",")}|${oriSet ?? ""}`;
    this.content.clear();
    const text = this.info?.machine.machine_data ?? "";
    let s = readStructure(text, machineAxes, oriSet);
    // A transformation defined by kinematic chains: the model follows its elements.
    const lookup = axisLookup(text, machineAxes);
    const chains = parseChains(this.chainText);
    const record = chainRecordFor(chains, oriSet, lookup);
    const chain = record ? buildChainMachine(chains, record, lookup) : null;
    if (chain) {
      s = { ...s, kind: "mill", head: [], table: [], summary: chain.summary };
      this.caption.dataset.chain = record!.name;
    } else {
      delete this.caption.dataset.chain;
    }
    this.structure = s;
    this.model = chain?.model ?? buildMachine(s);
    const letters = s.kind === "lathe" ? ["X", "Z", ...(s.linear.some((a) => a.letter === "Y") ? ["Y"] : [])] : ["X", "Y", "Z"];
    this.triad = new WcsTriad(Math.max(40, this.model.size * 0.08), letters);
    this.triad.setAxes(this.wcsAxes);
    this.programmed.line.renderOrder = 2;
    this.toolpath.line.renderOrder = 3;
    this.model.part.add(this.triad.group, this.toolpath.line, this.programmed.line, this.check.group);
    this.stock.mount(this.model.part, this.model.frame);
    this.model.frame.add(this.tool.mesh);
    this.content.add(this.model.root);
    this.model.update({}, false);
    this.caption.textContent = s.summary;
    this.caption.dataset.kind = s.kind;
    this.caption.dataset.head = String(chain ? chain.toolRotary : s.head.length);
    this.caption.dataset.table = String(chain ? chain.partRotary : s.table.length);
    this.framePending = true;
    if (this.pendingHistory) this.applyHistory();
  }

  private edge(t: number, d: number): string {
    return `${t},${d || 1}`;
  }

  private toolLength(t: number, d: number): number {
    if (t === 0) return 0;
    return this.ncData.number("$TC_DP3", this.edge(t, d)) ?? 0;
  }

  /**
   * Holder minus tip of a lathe's tool as the control compensates it: a turning tool (type
   * 500..599) by length 1 in X and length 2 in Z; a milling or drilling tool by length 1 along
   * the axis perpendicular to the working plane (G17 Z, G18 Y, G19 X).
   */
  private latheToolOffset(st: State, out: THREE.Vector3): THREE.Vector3 {
    const { t, d } = st.tool;
    out.set(0, 0, 0);
    if (t === 0 || d === 0) return out;
    const n = (k: number) => this.ncData.number(`$TC_DP${k}`, this.edge(t, d)) ?? 0;
    const type = n(1);
    if (type >= 500 && type < 600) return out.set(n(3), 0, n(4));
    const plane = st.gcodes.find((g) => g === "G17" || g === "G18" || g === "G19") ?? "G17";
    const l1 = n(3);
    return plane === "G17" ? out.set(0, 0, l1) : plane === "G18" ? out.set(0, l1, 0) : out.set(l1, 0, 0);
  }

  private toolRadius(t: number, d: number): number {
    if (t === 0) return DEFAULT_TOOL_RADIUS;
    return Math.max(3, this.ncData.number("$TC_DP6", this.edge(t, d)) || DEFAULT_TOOL_RADIUS);
  }
}

export function mountMachineView(session: SessionController): MachineView {
  const view = new MachineView(byId("view3d"), byId("view3d-caption"));
  session.on("session", (info) => {
    view.attach(info);
    view.stock.attach(info.id);
  });
  session.on("sample", (st) => {
    view.show(st);
    view.stock.show(st);
  });
  session.on("event", (ev) => {
    if (ev.event === "stock" && ev.warning) view.stock.mark(ev.warning as StockWarning);
  });
  session.on("stock", (push) => view.stock.apply(push));
  // New machine data (travel, tools): rebuild the model, keep the toolpath.
  session.on("machine", (info) => {
    view.attach(info, { keepPath: true });
    if (session.latest) view.show(session.latest);
  });
  activeSwivel.on("change", (sw) => view.setWcsAxes(sw?.wcs_axes ?? null));
  const caption = byId("view3d-caption");
  const toolVector = byId("tool-vector");
  session.on("state", (st) => {
    // The numeric tool vector on machines with two or more rotary axes (5-axis and more).
    const rotary = Number(caption.dataset.head ?? 0) + Number(caption.dataset.table ?? 0);
    const o = rotary >= 2 ? view.toolVector(st) : null;
    toolVector.hidden = !o;
    if (!toolVector.hidden && o) setText(toolVector, `tool vector ${o.map((c) => fmt(c, 3)).join(" ")}`);
  });
  const views: Record<string, ViewName> = { "btn-view-iso": "iso", "btn-view-top": "top", "btn-view-front": "front" };
  for (const [id, name] of Object.entries(views)) byId(id).addEventListener("click", () => view.setView(name));
  byId("btn-view-path").addEventListener("click", () => view.zoomToPath());
  byId("btn-path-clear").addEventListener("click", () => view.clearPath());
  // For the browser test and the curious: the model's tool tip against the engine's.
  (window as unknown as { __nctwin3d: unknown }).__nctwin3d = {
    tipError: () => view.tipError,
    /** The last `n` points of the executed path in the workpiece frame (machine directions). */
    pathPoints: (n: number) => view.pathPoints(n),
    /** The angle (degrees) the workpiece frame is turned about the machine axis `about`. */
    partTurn: (about: [number, number, number]) => view.partTurn(about),
    /** Where the part frame's vector `v` points in the machine frame (a tilted table). */
    partDirection: (v: [number, number, number]) => view.partDirection(v),
    programmedPoints: () => view.programmed.count,
    /** The programmed path as drawn (workpiece frame, TRACYL parts wrapped). */
    programmedPath: () => view.programmed.points(),
    /** Where the WCS triad's axis points (part frame): turned with a swivelled frame. */
    wcsDirection: (letter: "X" | "Y" | "Z") => view.wcsDirection(letter),
    /** Share of the programmed path's points inside the camera's view. */
    programmedInView: () => view.programmedInView(),
    /** Tool axis lines drawn along the programmed path (5-axis). */
    toolAxisLines: () => view.check.toolAxisCount,
    /** The limit marks drawn: kind, axis, line and position (part frame). */
    limitMarks: () => {
      const at = view.check.markPositions();
      return view.check.hits.map((h, i) => ({ kind: h.kind, axis: h.axis, line: h.line, basic: h.basic, at: at[i], exact: h.exact !== false }));
    },
    /** The slider's marker: visible and where (part frame). */
    marker: () => (view.check.marker.visible ? view.check.marker.position.toArray() : null),
    /** A lathe's part: the machine Z of its end face (at the WCS zero). */
    partEnd: () => view.partEnd(),
    /** The angle (degrees) the stock mesh is turned about the machine axis `about`. */
    stockTurn: (about: [number, number, number]) => view.stock.turn(about),
    /** The stock's meshes shown and their version; the check marks (check, line). */
    stockMeshes: () => view.stock.shownMeshes(),
    stockColors: () => view.stock.shownColors(),
    stockMarks: () => view.stock.markList(),
    /** The blank outline drawn (BCS min and max), null without one. */
    blank: () => (view.check.blank ? [view.check.blank.min.toArray(), view.check.blank.max.toArray()] : null),
    /** Executed path points that came from the session's history. */
    historyPoints: () => view.historyPoints,
    /** Points of the fetched history left out (a table turned outside the kinematics). */
    historyInexact: () => view.historyInexact,
  };
  setText(byId("view3d-caption"), "");
  return view;
}

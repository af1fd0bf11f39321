// The 3D machine model of a transformation defined by kinematic chains (K12): the element
// graph from the root, one scene group per element, moved the way the engine reads the
// elements (engine/src/machine_data/chains.rs): OFFSET translates by $NK_OFF_DIR, AXIS_LIN by
// (position + $NK_A_OFF) along it, AXIS_ROT turns about it through the frame origin by
// position − $NT_ROT_AX_OFFSET + $NK_A_OFF, ROT_CONST by $NK_A_OFF; $NK_NEXT starts in the
// element's output frame, $NK_PARALLEL in its input frame. The tool reference point is the
// output frame of $NT_T_CHAIN_LAST_ELEM, the workpiece (BCS origin) that of
// $NT_P_CHAIN_LAST_ELEM (none: the world frame).

import * as THREE from "three";
import type { AxisValues } from "../api/types";
import type { ChainElement, ChainRecord, KinChains } from "./kinChains";
import type { AxisLookup, Vec3 } from "./machineData";
import type { MachineModel } from "./machineModel";

const MATERIALS = {
  bed: new THREE.MeshLambertMaterial({ color: 0x59626d }),
  slide: new THREE.MeshLambertMaterial({ color: 0x3f7f91 }),
  rail: new THREE.MeshLambertMaterial({ color: 0x8a96a3 }),
  arm: new THREE.MeshLambertMaterial({ color: 0xc9d1d9 }),
  rotary: new THREE.MeshLambertMaterial({ color: 0x5b8f5b }),
  table: new THREE.MeshLambertMaterial({ color: 0x6f6a8a }),
  mark: new THREE.MeshLambertMaterial({ color: 0xd8a32b }),
  steel: new THREE.MeshLambertMaterial({ color: 0x9aa4ad }),
};

const v3 = (v: Vec3) => new THREE.Vector3(v[0], v[1], v[2]);
const Y_UP = new THREE.Vector3(0, 1, 0);

function cylinder(material: THREE.Material, radius: number, a: THREE.Vector3, b: THREE.Vector3, segments = 32): THREE.Mesh {
  const axis = b.clone().sub(a);
  const length = Math.max(axis.length(), 1e-3);
  const mesh = new THREE.Mesh(new THREE.CylinderGeometry(radius, radius, length, segments), material);
  mesh.position.copy(a).addScaledVector(axis, 0.5);
  mesh.quaternion.setFromUnitVectors(Y_UP, axis.divideScalar(length));
  return mesh;
}

/** Some direction perpendicular to unit `v`. */
function perpendicular(v: THREE.Vector3): THREE.Vector3 {
  const other = Math.abs(v.z) < 0.9 ? new THREE.Vector3(0, 0, 1) : new THREE.Vector3(1, 0, 0);
  return other.clone().sub(v.clone().multiplyScalar(other.dot(v))).normalize();
}

/**
 * The record the view draws: the active transformation's (data set 100 + n, the engine's
 * numbering of `$NT_[n]`) when it has a tool chain; else, when the machine data has no
 * orientation transformation of its own, the first TRAORI_DYN record.
 */
export function chainRecordFor(chains: KinChains, activeSet: number | null, lookup: AxisLookup): ChainRecord | null {
  const withTool = (r: ChainRecord) => r.toolLast !== "";
  if (activeSet !== null && activeSet >= 100) {
    const r = chains.records.find((r) => r.n === activeSet - 100);
    if (r && withTool(r)) return r;
  }
  if (lookup.hasOrientationTrafo) return null;
  return chains.records.find((r) => r.type === "TRAORI_DYN" && withTool(r)) ?? null;
}

/** One element in the scene: its input frame (the parent) and its output frame. */
interface Placed {
  element: ChainElement;
  out: THREE.Group;
  machineAxis: string | null;
  dir: THREE.Vector3;
  /** Constant part of the joint value (mm or degrees). */
  bias: number;
}

export interface ChainMachine {
  model: MachineModel;
  /** Elements placed in the scene (the ones reachable from the root). */
  elements: number;
  /** Rotary axis elements on the tool and on the workpiece chain. */
  toolRotary: number;
  partRotary: number;
  summary: string;
}

/** Builds the element graph of `chains` for `record`; null when the root or the tool end is missing. */
export function buildChainMachine(chains: KinChains, record: ChainRecord, lookup: AxisLookup): ChainMachine | null {
  const byName = new Map(chains.elements.map((e) => [e.name, e]));
  if (!byName.has(lookup.rootName)) return null;
  const root = new THREE.Group();
  const world = new THREE.Group();
  root.add(world);
  const placed = new Map<string, Placed>();
  const rotOffset = (name: string) => {
    const k = record.rotAxisNames.indexOf(name);
    return k >= 0 ? record.rotAxisOffset[k]! : 0;
  };

  // Walk from the root: NEXT in the output frame, PARALLEL in the input frame.
  const pending: [string, THREE.Group][] = [[lookup.rootName, world]];
  while (pending.length) {
    const [name, parent] = pending.pop()!;
    const e = byName.get(name);
    if (!e || placed.has(name)) continue; // the server checked the graph; stay safe on cycles
    const out = new THREE.Group();
    out.name = e.name;
    parent.add(out);
    const length = Math.hypot(...e.offDir);
    const dir = length > 1e-9 ? v3(e.offDir).divideScalar(length) : new THREE.Vector3(0, 0, 1);
    const isAxis = e.type === "AXIS_LIN" || e.type === "AXIS_ROT";
    const bias = e.type === "AXIS_ROT" ? e.aOff - rotOffset(e.name) : e.aOff;
    placed.set(name, { element: e, out, machineAxis: isAxis ? lookup.machineAxis(e.axis) : null, dir, bias });
    if (e.type === "OFFSET") out.position.copy(v3(e.offDir));
    if (e.type === "ROT_CONST") out.quaternion.setFromAxisAngle(dir, THREE.MathUtils.degToRad(e.aOff));
    if (e.next) pending.push([e.next, out]);
    if (e.parallel) pending.push([e.parallel, parent]);
  }
  const toolEnd = placed.get(record.toolLast);
  if (!toolEnd) return null;
  const partEnd = record.partLast ? placed.get(record.partLast) : undefined;
  if (record.partLast && !partEnd) return null;

  // Which elements lie on the way from the root to the tool end and to the part end.
  const parentOf = new Map<THREE.Object3D, Placed>();
  for (const p of placed.values()) parentOf.set(p.out, p);
  const wayTo = (end: Placed | undefined): Set<Placed> => {
    const way = new Set<Placed>();
    let o: THREE.Object3D | null = end?.out ?? null;
    while (o && o !== world) {
      const p = parentOf.get(o);
      if (p) way.add(p);
      o = o.parent;
    }
    return way;
  };
  const toolWay = wayTo(toolEnd);
  const partWay = wayTo(partEnd);

  // Solids: rails and slides for linear axes, housings (tool side) or round tables (workpiece
  // side) for rotary axes, arms for offsets.
  let span = 200;
  for (const p of placed.values()) {
    const e = p.element;
    const parent = p.out.parent!;
    if (e.type === "OFFSET" && Math.hypot(...e.offDir) > 1) {
      parent.add(cylinder(MATERIALS.arm, 30, new THREE.Vector3(), v3(e.offDir), 16));
    } else if (e.type === "AXIS_LIN") {
      const [lo, hi] = p.machineAxis ? lookup.travel(p.machineAxis) : [-500, 500];
      span = Math.max(span, hi - lo);
      const side = perpendicular(p.dir).multiplyScalar(-60);
      parent.add(cylinder(MATERIALS.rail, 18, p.dir.clone().multiplyScalar(lo + p.bias).add(side), p.dir.clone().multiplyScalar(hi + p.bias).add(side), 12));
      const carriage = new THREE.Mesh(new THREE.BoxGeometry(90, 90, 90), MATERIALS.slide);
      carriage.position.copy(side).multiplyScalar(0.5);
      p.out.add(carriage);
    } else if (e.type === "AXIS_ROT") {
      const up = p.dir.clone();
      if (partWay.has(p) && !toolWay.has(p)) {
        const disk = cylinder(MATERIALS.table, 220, up.clone().multiplyScalar(-50), new THREE.Vector3(), 48);
        const mark = cylinder(MATERIALS.mark, 10, new THREE.Vector3(), perpendicular(up).multiplyScalar(200), 8);
        p.out.add(disk, mark);
      } else {
        const housing = cylinder(MATERIALS.rotary, 70, up.clone().multiplyScalar(-80), up.clone().multiplyScalar(80));
        const mark = cylinder(MATERIALS.mark, 12, new THREE.Vector3(), perpendicular(up).multiplyScalar(110), 8);
        p.out.add(housing, mark);
      }
    }
  }
  const part = new THREE.Group();
  (partEnd?.out ?? world).add(part);
  const nose = new THREE.Group();
  toolEnd.out.add(nose);
  const base = v3(record.baseOrient);
  if (base.lengthSq() < 1e-12) base.set(0, 0, 1);
  base.normalize();
  nose.add(cylinder(MATERIALS.steel, 35, new THREE.Vector3(), base.clone().multiplyScalar(70)));
  // A floor below the workpiece zero so the scene has a ground.
  const grid = new THREE.GridHelper(span + 400, 16, 0x7d8894, 0x6a747f);
  grid.rotation.x = Math.PI / 2;
  grid.position.set(0, 0, -200);
  part.add(grid);

  const axes = [...placed.values()].filter((p) => p.machineAxis !== null);
  const q = new THREE.Quaternion();
  const value = (mcs: AxisValues, name: string | null) => {
    const v = name ? mcs[name] : undefined;
    return typeof v === "number" && Number.isFinite(v) ? v : 0;
  };
  const model: MachineModel = {
    root,
    frame: root,
    part,
    size: span,
    update(mcs) {
      for (const p of axes) {
        const x = value(mcs, p.machineAxis) + p.bias;
        if (p.element.type === "AXIS_LIN") p.out.position.copy(p.dir).multiplyScalar(x);
        else p.out.quaternion.setFromAxisAngle(p.dir, THREE.MathUtils.degToRad(x));
      }
    },
    holder(out) {
      root.updateMatrixWorld(true);
      return nose.getWorldPosition(out);
    },
    toolAxis(out) {
      root.updateMatrixWorld(true);
      return out.copy(base).applyQuaternion(nose.getWorldQuaternion(q)).normalize();
    },
  };
  const count = (way: Set<Placed>) => [...way].filter((p) => p.element.type === "AXIS_ROT").length;
  const toolRotary = count(toolWay);
  const partRotary = [...partWay].filter((p) => p.element.type === "AXIS_ROT" && !toolWay.has(p)).length;
  return {
    model,
    elements: placed.size,
    toolRotary,
    partRotary,
    summary: `kinematic chain "${record.name}" (${record.type || "no type"}, ${placed.size} elements, ${toolRotary} rotary on the tool, ${partRotary} on the workpiece)`,
  };
}

// The machine's kinematic structure as simple solids, built from the decoded machine data
// (`machineData.ts`): linear slides, the rotary axes of a swivel head and/or a rotary table at
// their pivots, a lathe's spindle with chuck and workpiece and its turret. Everything is in the
// machine's Cartesian frame (Z up for mills; a lathe's frame is turned so that its Z lies
// along the scene's x). `update` moves it to the machine axis positions of the stream.

import * as THREE from "three";
import type { AxisValues } from "../api/types";
import type { LinearAxis, RotaryAxis, Structure, Vec3 } from "./machineData";

export interface MachineModel {
  /** Scene root (holds the frame turn of a lathe). */
  readonly root: THREE.Group;
  /** The machine's Cartesian frame (the root for a mill; turned for a lathe). */
  readonly frame: THREE.Group;
  /** The frame the workpiece, the paths and the WCS live in (turns with a rotary table). */
  readonly part: THREE.Group;
  /** Moves the structure to these machine axis positions (MCS). */
  update(mcs: AxisValues, partTurns: boolean): void;
  /** Spindle nose (tool holder point) and unit tool direction (tip → holder), machine frame. */
  holder(out: THREE.Vector3): THREE.Vector3;
  toolAxis(out: THREE.Vector3): THREE.Vector3;
  /** Characteristic size (mm) for the triad and the camera. */
  readonly size: number;
  /**
   * A lathe's part: its end face put at the WCS zero `zeroZ` (machine Z of the work offset),
   * reaching back into the chuck; the part keeps its length when the zero is not in front of it.
   */
  placePart?(zeroZ: number): void;
  /** A lathe's part: the machine Z of its end face as drawn. */
  partEnd?(): number;
}

const MATERIALS = {
  bed: new THREE.MeshLambertMaterial({ color: 0x59626d }),
  frame: new THREE.MeshLambertMaterial({ color: 0x8a96a3 }),
  slide: new THREE.MeshLambertMaterial({ color: 0x3f7f91 }),
  head: new THREE.MeshLambertMaterial({ color: 0xc9d1d9 }),
  steel: new THREE.MeshLambertMaterial({ color: 0x9aa4ad }),
  rotary: new THREE.MeshLambertMaterial({ color: 0x5b8f5b }),
  table: new THREE.MeshLambertMaterial({ color: 0x6f6a8a }),
  mark: new THREE.MeshLambertMaterial({ color: 0xd8a32b }),
  work: new THREE.MeshLambertMaterial({ color: 0xb8c4cf, transparent: true, opacity: 0.55 }),
};

const v3 = (v: Vec3) => new THREE.Vector3(v[0], v[1], v[2]);

/** A box spanning [x0,x1] × [y0,y1] × [z0,z1]. */
function box(material: THREE.Material, x0: number, x1: number, y0: number, y1: number, z0: number, z1: number) {
  const mesh = new THREE.Mesh(new THREE.BoxGeometry(x1 - x0, y1 - y0, z1 - z0), material);
  mesh.position.set((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2);
  return mesh;
}

/** A cylinder of `radius` from point a to point b. */
function cylinder(material: THREE.Material, radius: number, a: THREE.Vector3, b: THREE.Vector3, segments = 32) {
  const axis = b.clone().sub(a);
  const length = Math.max(axis.length(), 1e-3);
  const mesh = new THREE.Mesh(new THREE.CylinderGeometry(radius, radius, length, segments), material);
  mesh.position.copy(a).addScaledVector(axis, 0.5);
  mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), axis.divideScalar(length));
  return mesh;
}

function group(...children: THREE.Object3D[]): THREE.Group {
  const g = new THREE.Group();
  if (children.length) g.add(...children);
  return g;
}

/** Some direction perpendicular to `v`. */
function perpendicular(v: THREE.Vector3): THREE.Vector3 {
  const other = Math.abs(v.z) < 0.9 ? new THREE.Vector3(0, 0, 1) : new THREE.Vector3(1, 0, 0);
  return other.clone().sub(v.clone().multiplyScalar(other.dot(v))).normalize();
}

function value(mcs: AxisValues, name: string | null | undefined): number {
  const v = name ? mcs[name] : undefined;
  return typeof v === "number" && Number.isFinite(v) ? v : 0;
}

/** A rotary axis: the pivot group (placed by the axis offset) and the turning group inside. */
interface Joint {
  axis: RotaryAxis;
  pivot: THREE.Group;
  turn: THREE.Group;
  dir: THREE.Vector3;
}

function joint(axis: RotaryAxis): Joint {
  const turn = new THREE.Group();
  const pivot = group(turn);
  pivot.position.copy(v3(axis.offset));
  return { axis, pivot, turn, dir: v3(axis.dir).normalize() };
}

function turnJoint(j: Joint, mcs: AxisValues): void {
  const angle = THREE.MathUtils.degToRad(value(mcs, j.axis.name) - j.axis.zero);
  j.turn.quaternion.setFromAxisAngle(j.dir, angle);
}

function linearOf(s: Structure, letter: "X" | "Y" | "Z"): LinearAxis | undefined {
  return s.linear.find((a) => a.letter === letter);
}

function range(s: Structure, letter: "X" | "Y" | "Z"): [number, number] {
  const a = linearOf(s, letter);
  return a ? [a.min, a.max] : [0, 0];
}

function slide(axis: LinearAxis | undefined, g: THREE.Group, mcs: AxisValues): void {
  if (!axis) return;
  g.position.copy(v3(axis.dir)).multiplyScalar(value(mcs, axis.name));
}

/** Mill: travelling column X, ram Y, head Z; swivel head and rotary table from TRAORI data. */
function buildMill(s: Structure): MachineModel {
  const [x0, x1] = range(s, "X");
  const [y0, y1] = range(s, "Y");
  const [z0, z1] = range(s, "Z");
  const span = Math.max(x1 - x0, y1 - y0, z1 - z0, 200);

  // ---- rotary table chain (fixed to the machine bed) ----
  const tableJoints = s.table.map(joint);
  let partParent: THREE.Group | null = null;
  const tableRoot = group();
  let parent = tableRoot;
  const pivotsWorld: THREE.Vector3[] = [];
  let at = new THREE.Vector3();
  for (const j of tableJoints) {
    parent.add(j.pivot);
    at = at.clone().add(v3(j.axis.offset));
    pivotsWorld.push(at.clone());
    parent = j.turn;
  }
  if (tableJoints.length) partParent = parent;
  const part = group();
  part.position.copy(v3(s.partOffset));
  (partParent ?? tableRoot).add(part);

  // Table top: under the lowest pivot of the table (or below the travel for a fixed table).
  const lowest = Math.min(0, ...pivotsWorld.map((p) => p.z));
  const tableTop = tableJoints.length ? lowest - 180 : -0.08 * (z1 - z0) - 20;
  const bed = box(MATERIALS.bed, x0 - 100, x1 + 100, y0 - 100, y1 + 100, tableTop - 100, tableTop);
  const grid = new THREE.GridHelper(Math.min(x1 - x0, y1 - y0) + 200, 16, 0x7d8894, 0x6a747f);
  grid.rotation.x = Math.PI / 2; // GridHelper lies in the xz plane
  grid.position.set((x0 + x1) / 2, (y0 + y1) / 2, tableTop + 0.5);

  // Visuals of the table axes: the inner one a round table (its top on the part zero), the
  // outer one a cradle carrying it, with two supports on the bed.
  tableJoints.forEach((j, i) => {
    const inner = i === tableJoints.length - 1;
    const dir = j.dir;
    if (inner) {
      // In the turning frame: the part zero lies at partOffset; the disk ends there.
      const top = v3(s.partOffset);
      const up = dir.clone().multiplyScalar(Math.sign(dir.dot(new THREE.Vector3(0, 0, 1))) || 1);
      const axisPoint = dir.clone().multiplyScalar(top.dot(dir));
      const disk = cylinder(MATERIALS.table, 220, axisPoint.clone().addScaledVector(up, -50), axisPoint, 48);
      const mark = box(MATERIALS.mark, 0, 200, -12, 12, -4, 2);
      mark.position.add(axisPoint);
      mark.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), up);
      const slots = [-1, 0, 1].map((k) => {
        const slot = box(MATERIALS.steel, -210, 210, -6, 6, -3, 1);
        slot.position.copy(axisPoint).add(perpendicular(up).multiplyScalar(k * 90));
        return slot;
      });
      j.turn.add(disk, mark, ...slots);
      if (i === 0 && Math.abs(up.z) > 0.9) {
        // A table standing alone (the 7th axis of a generic 7-axis machine): a pedestal on the bed.
        const bottom = pivotsWorld[0]!.clone().add(axisPoint).addScaledVector(up, -50);
        tableRoot.add(cylinder(MATERIALS.frame, 160, new THREE.Vector3(bottom.x, bottom.y, tableTop), bottom, 48));
      }
    } else {
      // Cradle: a plate under the next axis and two cheeks on this axis.
      const next = v3(tableJoints[i + 1]!.axis.offset);
      const side = dir.clone();
      const plate = box(MATERIALS.rotary, -260, 260, -170, 170, -30, 30);
      plate.quaternion.setFromUnitVectors(new THREE.Vector3(1, 0, 0), side);
      plate.position.copy(next).add(new THREE.Vector3(0, 0, -90));
      const cheeks = [-1, 1].map((k) => cylinder(MATERIALS.rotary, 110, side.clone().multiplyScalar(k * 250), side.clone().multiplyScalar(k * 300)));
      j.turn.add(plate, ...cheeks);
      const supports = [-1, 1].map((k) => {
        const c = pivotsWorld[i]!.clone().addScaledVector(side, k * 350);
        return box(MATERIALS.frame, c.x - 50, c.x + 50, c.y - 130, c.y + 130, tableTop, c.z + 120);
      });
      tableRoot.add(...supports, cylinder(MATERIALS.steel, 60, pivotsWorld[i]!.clone().addScaledVector(side, -330), pivotsWorld[i]!.clone().addScaledVector(side, 330)));
    }
  });

  // ---- column, ram, head ----
  const back = y1 + 150; // front face of the column
  const rails = box(MATERIALS.bed, x0 - 300, x1 + 300, back, back + 300, tableTop - 100, tableTop - 40);
  const headJoints = s.head.map(joint);
  const headTop = headJoints.reduce((z, j) => z + Math.max(0, j.axis.offset[2]), 0) + 70;
  const column = box(MATERIALS.frame, -130, 130, back + 20, back + 280, tableTop - 40, z1 + headTop + 380);
  const ram = box(MATERIALS.slide, -90, 90, -120, back + 280 - y0, z1 + headTop + 190, z1 + headTop + 350);
  const headBody = box(MATERIALS.head, -80, 80, -80, 80, headTop, z1 - z0 + headTop + 260);
  const zSlide = group(headBody); // origin: the machine position (tool reference at zero angles)

  // Head chain: housing per axis, then the spindle nose.
  parent = zSlide;
  headJoints.forEach((j, i) => {
    parent.add(j.pivot);
    const next = i + 1 < headJoints.length ? v3(headJoints[i + 1]!.axis.offset) : v3(s.toolOffset);
    const housing = cylinder(MATERIALS.rotary, 75, j.dir.clone().multiplyScalar(-85), j.dir.clone().multiplyScalar(85));
    // Arm from this pivot to the next (or to the nose), offset sideways for a fork.
    const arm = cylinder(MATERIALS.head, 45, new THREE.Vector3(), next);
    // A mark on the housing shows the turn (an axis about the tool's own axis turns nothing else).
    const mark = cylinder(MATERIALS.mark, 12, new THREE.Vector3(), perpendicular(j.dir).multiplyScalar(110), 8);
    j.turn.add(housing, arm, mark);
    parent = j.turn;
  });
  const nose = group();
  nose.position.copy(headJoints.length ? v3(s.toolOffset) : new THREE.Vector3());
  parent.add(nose);
  const tdir = v3(s.toolDir).normalize();
  nose.add(cylinder(MATERIALS.steel, 35, new THREE.Vector3(), tdir.clone().multiplyScalar(70)));
  if (!headJoints.length) zSlide.add(cylinder(MATERIALS.steel, 35, new THREE.Vector3(), new THREE.Vector3(0, 0, 70)));

  const ySlide = group(ram, zSlide);
  const xSlide = group(column, ySlide);
  const root = group(bed, grid, rails, tableRoot, xSlide);
  const X = linearOf(s, "X");
  const Y = linearOf(s, "Y");
  const Z = linearOf(s, "Z");
  const toolAxisLocal = tdir.clone();
  const q = new THREE.Quaternion();
  return {
    root,
    frame: root,
    part,
    size: span,
    update(mcs) {
      slide(X, xSlide, mcs);
      slide(Y, ySlide, mcs);
      slide(Z, zSlide, mcs);
      for (const j of [...headJoints, ...tableJoints]) turnJoint(j, mcs);
    },
    holder(out) {
      root.updateMatrixWorld(true);
      return nose.getWorldPosition(out);
    },
    toolAxis(out) {
      root.updateMatrixWorld(true);
      return out.copy(toolAxisLocal).applyQuaternion(nose.getWorldQuaternion(q)).normalize();
    },
  };
}

/**
 * Lathe in machine coordinates (X radial and up, Z along the spindle): a spindle with chuck and
 * workpiece turned by the spindle / C axis, a carriage in Z, a cross slide in X (inclined for
 * TRAANG), a Y slide when there is one, and the turret on it.
 */
function buildLathe(s: Structure): MachineModel {
  const [, x1] = range(s, "X");
  const [z0, z1] = range(s, "Z");
  const chuckR = Math.min(160, Math.max(60, x1 * 0.5));
  const face = z0 - 40; // chuck face on Z
  const bedTop = -chuckR - 80; // below the spindle (machine X is up)
  const workR = Math.min(chuckR * 0.6, 50);
  const workL = Math.min(220, Math.max(80, (z1 - z0) * 0.3));

  // Bed and headstock (X up, Z along, Y = X × Z towards the viewer's back).
  const bed = box(MATERIALS.bed, bedTop - 140, bedTop, -260, 260, face - 450, z1 + 250);
  const headstock = box(MATERIALS.frame, bedTop, chuckR + 120, -220, 220, face - 450, face - 130);

  const chuckBody = cylinder(MATERIALS.steel, chuckR, new THREE.Vector3(0, 0, face - 130), new THREE.Vector3(0, 0, face - 20), 48);
  const jaws = [0, 1, 2].map((i) => {
    const jaw = box(MATERIALS.head, workR, chuckR * 0.95, -14, 14, face - 20, face);
    const holder = group(jaw);
    holder.rotation.z = (i * 2 * Math.PI) / 3;
    return holder;
  });
  const work = cylinder(MATERIALS.work, workR, new THREE.Vector3(0, 0, face - 20), new THREE.Vector3(0, 0, face + workL), 48);
  const flat = box(MATERIALS.mark, workR - 2, workR + 1, -8, 8, face, face + workL); // shows the turn
  // The part stretched along Z about the chuck face (placePart): inner shifts the face to 0.
  const inner = group(work, flat);
  inner.position.z = -face;
  const stretch = group(inner);
  stretch.position.z = face;
  const spindle = group(chuckBody, ...jaws, stretch);
  const part = group();
  spindle.add(part);

  const X = linearOf(s, "X");
  const Y = linearOf(s, "Y");
  const Z = linearOf(s, "Z");
  const xDir = X ? v3(X.dir) : new THREE.Vector3(1, 0, 0);
  // The carriage stands behind the spindle (machine −Y, away from the operator's view).
  const saddle = box(MATERIALS.slide, bedTop, bedTop + 50, -260, 240, -110, 110);
  const upright = box(MATERIALS.frame, bedTop, x1 + 260, -260, -160, -80, 80);
  // The cross slide's guide along its (maybe inclined) direction.
  const back = new THREE.Vector3(0, -200, 0);
  const guide = cylinder(MATERIALS.slide, 30, xDir.clone().multiplyScalar(-40).add(back), xDir.clone().multiplyScalar(x1 + 200).add(back));
  const turret = cylinder(MATERIALS.head, 90, new THREE.Vector3(0, -60, 0), new THREE.Vector3(0, -170, 0), 8);
  const post = box(MATERIALS.head, 20, 120, -60, 40, -40, 40);
  const ySlide = group(turret, post); // origin: the tool holder reference (MCS point)
  const xSlide = group(ySlide);
  const zSlide = group(saddle, upright, guide, xSlide);
  const frame = group(bed, headstock, spindle, zSlide);
  // Machine X → scene z (up), Y → scene −y, Z → scene x.
  frame.quaternion.setFromRotationMatrix(new THREE.Matrix4().makeBasis(new THREE.Vector3(0, 0, 1), new THREE.Vector3(0, -1, 0), new THREE.Vector3(1, 0, 0)));
  const root = group(frame);
  const spindleAxis = s.spindle;
  return {
    root,
    frame,
    part,
    size: Math.max(z1 - z0, x1, 200),
    update(mcs, partTurns) {
      slide(Z, zSlide, mcs);
      slide(X, xSlide, mcs);
      slide(Y, ySlide, mcs);
      const turn = s.spindleSign * THREE.MathUtils.degToRad(value(mcs, spindleAxis));
      spindle.rotation.z = turn;
      // The paths turn with the workpiece only while TRANSMIT/TRACYL make C a path axis.
      part.rotation.z = partTurns ? 0 : -turn;
    },
    holder(out) {
      return out.copy(zSlide.position).add(xSlide.position).add(ySlide.position);
    },
    toolAxis(out) {
      return out.set(0, 0, 1);
    },
    placePart(zeroZ) {
      // At least 10 mm out of the jaws; the default length when the zero lies behind that.
      const length = zeroZ - face;
      stretch.scale.z = Number.isFinite(length) && length >= 10 ? length / workL : 1;
    },
    partEnd() {
      return face + workL * stretch.scale.z;
    },
  };
}

export function buildMachine(s: Structure): MachineModel {
  return s.kind === "mill" ? buildMill(s) : buildLathe(s);
}

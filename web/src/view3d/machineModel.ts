// The machine's kinematic structure as simple solids, one group per linear axis, each group a
// child of the axis it rides on. Two layouts: a travelling-column mill (the table stays put, so
// the workpiece and the toolpath do too) and a flat-bed lathe.

import * as THREE from "three";
import type { AxisValues } from "../api/types";
import type { Kinematics } from "./kinematics";

export interface MachineModel {
  readonly root: THREE.Group;
  /** Moves the structure to these machine axis positions (MCS). */
  update(mcs: AxisValues): void;
}

const MATERIALS = {
  bed: new THREE.MeshLambertMaterial({ color: 0x59626d }),
  frame: new THREE.MeshLambertMaterial({ color: 0x8a96a3 }),
  slide: new THREE.MeshLambertMaterial({ color: 0x3f7f91 }),
  head: new THREE.MeshLambertMaterial({ color: 0xc9d1d9 }),
  steel: new THREE.MeshLambertMaterial({ color: 0x9aa4ad }),
};

/** A box spanning [x0,x1] × [y0,y1] × [z0,z1]. */
function box(material: THREE.Material, x0: number, x1: number, y0: number, y1: number, z0: number, z1: number) {
  const mesh = new THREE.Mesh(new THREE.BoxGeometry(x1 - x0, y1 - y0, z1 - z0), material);
  mesh.position.set((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2);
  return mesh;
}

/** A cylinder along the scene's z from z0 to z1. */
function cylinderZ(material: THREE.Material, radius: number, z0: number, z1: number) {
  const mesh = new THREE.Mesh(new THREE.CylinderGeometry(radius, radius, z1 - z0, 32), material);
  mesh.rotation.x = Math.PI / 2;
  mesh.position.z = (z0 + z1) / 2;
  return mesh;
}

function group(...children: THREE.Object3D[]): THREE.Group {
  const g = new THREE.Group();
  if (children.length) g.add(...children);
  return g;
}

function axisValue(k: Kinematics, mcs: AxisValues, letter: "X" | "Y" | "Z"): number {
  const name = k.linear.get(letter)?.name;
  const v = name ? mcs[name] : undefined;
  return typeof v === "number" ? v : 0;
}

/** Vertical mill with a column travelling in X, a ram in Y and a spindle head in Z. */
function buildMill(k: Kinematics): MachineModel {
  const [x0, x1] = k.range("X");
  const [y0, y1] = k.range("Y");
  const [z0, z1] = k.range("Z");
  const tableTop = -0.08 * (z1 - z0) - 20;
  const back = y1 + 150; // front face of the column

  const table = box(MATERIALS.bed, x0 - 100, x1 + 100, y0 - 100, y1 + 100, tableTop - 100, tableTop);
  const grid = new THREE.GridHelper(Math.min(x1 - x0, y1 - y0) + 200, 16, 0x7d8894, 0x6a747f);
  grid.rotation.x = Math.PI / 2; // GridHelper lies in the xz plane
  grid.position.set((x0 + x1) / 2, (y0 + y1) / 2, tableTop + 0.5);
  const rails = box(MATERIALS.bed, x0 - 300, x1 + 300, back, back + 300, tableTop - 100, tableTop - 40);

  const column = box(MATERIALS.frame, -130, 130, back + 20, back + 280, tableTop - 40, z1 + 450);
  const ram = box(MATERIALS.slide, -90, 90, -120, back + 280 - y0, z1 + 260, z1 + 420);
  const head = box(MATERIALS.head, -80, 80, -80, 80, 70, z1 - z0 + 330);
  const nose = cylinderZ(MATERIALS.steel, 35, 0, 70);

  const zSlide = group(head, nose); // origin: the spindle nose, where the MCS point is
  const ySlide = group(ram, zSlide);
  const xSlide = group(column, ySlide);
  const root = group(table, grid, rails, xSlide);
  return {
    root,
    update(mcs) {
      xSlide.position.x = axisValue(k, mcs, "X");
      ySlide.position.y = axisValue(k, mcs, "Y");
      zSlide.position.z = axisValue(k, mcs, "Z");
    },
  };
}

/** Lathe: chuck on the scene's x axis, a carriage in Z, a cross slide in X (upwards). */
function buildLathe(k: Kinematics): MachineModel {
  const [, x1] = k.range("X");
  const [z0, z1] = k.range("Z");
  const chuckR = Math.min(160, Math.max(60, x1 * 0.5));
  const face = z0 - 40; // chuck face on the scene's x
  const bedTop = -chuckR - 80;

  const bed = box(MATERIALS.bed, face - 450, z1 + 250, -260, 260, bedTop - 140, bedTop);
  const headstock = box(MATERIALS.frame, face - 450, face - 130, -220, 220, bedTop, chuckR + 120);
  const chuckBody = new THREE.Mesh(new THREE.CylinderGeometry(chuckR, chuckR, 110, 48), MATERIALS.steel);
  chuckBody.rotation.z = Math.PI / 2; // along the scene's x
  chuckBody.position.x = face - 55 - 20;
  const jaws = [0, 1, 2].map((i) => {
    const jaw = box(MATERIALS.head, face - 20, face, -14, 14, chuckR * 0.25, chuckR * 0.95);
    const holder = group(jaw);
    holder.rotation.x = (i * 2 * Math.PI) / 3;
    return holder;
  });
  const chuck = group(chuckBody, ...jaws);

  const upright = box(MATERIALS.frame, -80, 80, 160, 260, bedTop, x1 + 260);
  const saddle = box(MATERIALS.slide, -110, 110, -240, 260, bedTop, bedTop + 50);
  const arm = box(MATERIALS.slide, -45, 45, 30, 170, 70, 130);
  const post = box(MATERIALS.head, -40, 40, -40, 40, 40, 140);

  const xSlide = group(arm, post); // origin: the tool holder reference point (MCS point)
  const zSlide = group(saddle, upright, xSlide);
  const root = group(bed, headstock, chuck, zSlide);
  return {
    root,
    update(mcs) {
      zSlide.position.x = axisValue(k, mcs, "Z");
      xSlide.position.z = axisValue(k, mcs, "X");
      const turn = k.rotary ? mcs[k.rotary] : undefined;
      chuck.rotation.x = typeof turn === "number" ? THREE.MathUtils.degToRad(turn) : 0;
    },
  };
}

export function buildMachine(k: Kinematics): MachineModel {
  return k.kind === "mill" ? buildMill(k) : buildLathe(k);
}

// What the 3D view needs to know about a machine's axes: which machine axes are linear and
// along which direction, their travel, and where the machine frame lies in the scene.

import * as THREE from "three";
import type { AxisValues } from "../api/types";
import { NcData } from "../core/ncdata";

export type Letter = "X" | "Y" | "Z";

export interface LinearAxis {
  name: string; // machine axis name, e.g. "X1"
  letter: Letter;
  min: number;
  max: number;
}

/** "mill": Z vertical, table below the tool. "lathe": Z along the spindle, X radial. */
export type LayoutKind = "mill" | "lathe";

const DEFAULT_TRAVEL = 500; // mm either side when the machine data gives no usable limit
const LETTERS: Letter[] = ["X", "Y", "Z"];

/** A software limit, unless missing or so large it is a "no limit" default. */
function sane(v: number | undefined, fallback: number): number {
  return v !== undefined && Math.abs(v) < 1e4 ? v : fallback;
}

export class Kinematics {
  readonly kind: LayoutKind;
  readonly linear = new Map<Letter, LinearAxis>();
  /** Machine axis name -> letter, for the linear axes. */
  private readonly letterOf = new Map<string, Letter>();
  /** The first rotary machine axis (a lathe's main spindle or C axis), if any. */
  readonly rotary: string | null;
  /** Scene direction of each machine direction. */
  private readonly dirs: Record<Letter, THREE.Vector3>;

  constructor(machineAxes: string[], machineData: string) {
    const data = new NcData(machineData);
    let rotary: string | null = null;
    for (const [i, name] of machineAxes.entries()) {
      const no = i + 1;
      const letter = name[0]?.toUpperCase() as Letter;
      if (data.axisFlag("$MA_IS_ROT_AX", name, no)) {
        rotary ??= name;
        continue;
      }
      if (!LETTERS.includes(letter) || this.linear.has(letter)) continue;
      const min = sane(data.axisNumber("$MA_POS_LIMIT_MINUS", name, no), -DEFAULT_TRAVEL);
      const max = sane(data.axisNumber("$MA_POS_LIMIT_PLUS", name, no), DEFAULT_TRAVEL);
      this.linear.set(letter, { name, letter, min: Math.min(min, max), max: Math.max(min, max) });
      this.letterOf.set(name, letter);
    }
    this.rotary = rotary;
    this.kind = this.linear.has("Y") || !this.linear.has("Z") ? "mill" : "lathe";
    // The scene is Z-up. A lathe lies with its spindle (Z) along the scene's x and X upwards
    // (right-handed: Y then points to the scene's -y).
    this.dirs =
      this.kind === "mill"
        ? { X: new THREE.Vector3(1, 0, 0), Y: new THREE.Vector3(0, 1, 0), Z: new THREE.Vector3(0, 0, 1) }
        : { X: new THREE.Vector3(0, 0, 1), Y: new THREE.Vector3(0, -1, 0), Z: new THREE.Vector3(1, 0, 0) };
  }

  dir(letter: Letter): THREE.Vector3 {
    return this.dirs[letter];
  }

  range(letter: Letter): [number, number] {
    const a = this.linear.get(letter);
    return a ? [a.min, a.max] : [0, 0];
  }

  /** Scene position of the machine axes' values (MCS, linear axes only). */
  machinePoint(mcs: AxisValues, out = new THREE.Vector3()): THREE.Vector3 {
    out.set(0, 0, 0);
    for (const [name, letter] of this.letterOf) {
      const v = mcs[name];
      if (typeof v === "number") out.addScaledVector(this.dirs[letter], v);
    }
    return out;
  }

  /** Scene position of geometry-axis values (BCS or WCS: axes named X, Y, Z). */
  geometryPoint(values: AxisValues, out = new THREE.Vector3()): THREE.Vector3 {
    out.set(0, 0, 0);
    for (const letter of LETTERS) {
      const v = values[letter];
      if (typeof v === "number") out.addScaledVector(this.dirs[letter], v);
    }
    return out;
  }
}

// The program selected for AUTO: what Cycle start runs and the machine screen shows.

import { Emitter } from "../core/emitter";

export interface SelectedProgram {
  name: string;
  /** The text; empty for a stored program too large to load into the page (`stored`). */
  text: string;
  /** A stored program of the session: Cycle start runs it by name (its text stays on the server). */
  stored?: boolean;
}

export const DEMO_PROGRAM: SelectedProgram = {
  name: "DEMO",
  text: [
    "; Demo: a square and a circle at Z-2",
    "G54 G17 G90 T1 D1",
    "G0 X-60 Y-60 Z50",
    "G0 Z2",
    "G1 Z-2 F1000",
    "G1 X60 F3000",
    "Y60",
    "X-60",
    "Y-60",
    "G0 Z10",
    "G0 X40 Y0",
    "G1 Z-2 F1000",
    "G2 X40 Y0 I-40 J0 F3000",
    "G0 Z50",
    "M30",
    "",
  ].join("\n"),
};

/** The demo for machines without a Y geometry axis (lathes): a shaft turned with T1. */
export const TURNING_DEMO: SelectedProgram = {
  name: "DEMO",
  text: [
    "; Demo: face and turn a shaft (radius programming)",
    "G18 G90 G54 T1 D1",
    "G0 X30 Z5",
    "G1 Z0 F300",
    "X-0.8",
    "G0 Z2",
    "X25",
    "G1 Z-40 F400",
    "X30 Z-45",
    "G0 X40",
    "Z5",
    "M30",
    "",
  ].join("\n"),
};

/**
 * The demo of the TRACYL lathe-mill (tracyl-xyzc): a groove around a 40 mm cylinder on the C
 * axis (the milling demo's X-60 is outside its XM travel of -50..200: alarm 10720). Under
 * TRACYL(40) Y is the unrolled arc length: Y60 turns C by 60 / 20 rad = 171.9°.
 */
export const TRACYL_DEMO: SelectedProgram = {
  name: "DEMO",
  text: [
    "; Demo: a groove around a 40 mm cylinder with TRACYL (Y is the unrolled arc length)",
    "T1 D1 G19 G90",
    "G0 X60 Z-20",
    "TRACYL(40)",
    "G1 X20 Y0 Z-20 F3000",
    "G1 Y60",
    "G1 Z-40",
    "G1 Y0",
    "G1 X30",
    "TRAFOOF",
    "G0 X60",
    "M30",
    "",
  ].join("\n"),
};

/**
 * The demo of the trunnion-table mill with TRACYL (tracyl-xyzac): A−90 lays the table's C
 * axis onto +Y, as its TRACYL data assume; then a groove around a 60 mm cylinder (under
 * TRACYL(60) X is radial, Y the arc length, Z along the cylinder), and the table back to A0.
 */
export const TRACYL_TABLE_DEMO: SelectedProgram = {
  name: "DEMO",
  text: [
    "; Demo: A-90 lays the table's C axis onto +Y, then a groove around a 60 mm cylinder with TRACYL",
    "T1 D1 G17 G90",
    "G0 X0 Y-20 Z150",
    "G0 A-90 C0",
    "G19 TRACYL(60)",
    "G1 X30 Y0 Z-20 F3000",
    "G1 Y60",
    "G1 Z-40",
    "G1 Y0",
    "G1 X45",
    "TRAFOOF",
    "G17 G0 Z150",
    "G0 A0",
    "M30",
    "",
  ].join("\n"),
};

/** Presets whose machine the general demos do not fit, by preset id. */
const PRESET_DEMOS: Record<string, SelectedProgram> = { "tracyl-xyzc": TRACYL_DEMO, "tracyl-xyzac": TRACYL_TABLE_DEMO };

/**
 * The demo that fits a machine: its preset's own, else the turning demo when it has no Y
 * geometry axis, else the milling demo.
 */
export function demoFor(machineData: string, preset = ""): SelectedProgram {
  const own = PRESET_DEMOS[preset];
  if (own) return own;
  const withoutY = /\$MC_AXCONF_GEOAX_ASSIGN_TAB\[1\]\s*=\s*0\b/.test(machineData);
  return withoutY ? TURNING_DEMO : DEMO_PROGRAM;
}

class Selection extends Emitter<{ change: SelectedProgram; mda: string }> {
  private program: SelectedProgram = DEMO_PROGRAM;
  /** The blocks last sent in MDA mode (block lines in MDA refer to them). */
  mdaText = "";

  get current(): SelectedProgram {
    return this.program;
  }

  select(program: SelectedProgram): void {
    this.program = { ...program };
    this.emit("change", this.program);
  }

  /** A new session: an untouched demo becomes the demo for its machine. */
  adoptDemo(machineData: string, preset = ""): void {
    const demo = demoFor(machineData, preset);
    if (this.program.name === "DEMO" && this.program.text !== demo.text) this.select(demo);
  }

  setMda(text: string): void {
    this.mdaText = text;
    this.emit("mda", text);
  }
}

export const selection = new Selection();

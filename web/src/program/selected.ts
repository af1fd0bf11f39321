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

/** The demo that fits a machine's NC data: the turning demo when it has no Y geometry axis. */
export function demoFor(machineData: string): SelectedProgram {
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
  adoptDemo(machineData: string): void {
    const demo = demoFor(machineData);
    if (this.program.name === "DEMO" && this.program.text !== demo.text) this.select(demo);
  }

  setMda(text: string): void {
    this.mdaText = text;
    this.emit("mda", text);
  }
}

export const selection = new Selection();

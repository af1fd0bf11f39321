// The programmed path's slider: moves a marker along the preview's path and names the block at
// the marker (its line, the subprogram it is in, and the line's text). The text of the
// channel's loaded program comes line by line from GET .../active-program (activeProgram's
// bounded cache, so a CAM program costs the same as a short one); of a selected program not yet
// run, from the selection's own text (main program lines only). Keyboard: the slider is a range
// input (arrows step point by point, PgUp/PgDn in tenths).

import type { PreviewResponse } from "../api/types";
import { byId, setText } from "../core/dom";
import { activeProgram } from "../program/active";
import type { MachineView } from "./machineView";

/** Where the previewed program's text is. */
export type ScrubSource = { active: true; serial: number } | { active: false; text: string };

export class PathScrub {
  private readonly slider = byId<HTMLInputElement>("path-scrub");
  private readonly label = byId("path-scrub-label");
  private preview: PreviewResponse | null = null;
  private source: ScrubSource = { active: false, text: "" };
  private textLines: string[] = [];

  constructor(private readonly view: MachineView) {
    this.slider.addEventListener("input", () => this.show());
    // Lines of the active program arrive after they were asked for.
    activeProgram.on("lines", () => this.preview && this.showLabel());
    this.set(null, this.source);
  }

  /** A new preview (null: none): the slider spans its points, the marker at the start. */
  set(r: PreviewResponse | null, source: ScrubSource): void {
    this.preview = r && r.points.length ? r : null;
    this.source = source;
    this.textLines = source.active ? [] : source.text.split(/\r?\n/);
    const n = this.preview?.points.length ?? 0;
    this.slider.max = String(Math.max(0, n - 1));
    this.slider.value = "0";
    this.slider.disabled = n === 0;
    this.show();
  }

  private show(): void {
    const i = Number(this.slider.value);
    const p = this.preview ? this.view.programmed.pointAt(i) : null;
    this.view.check.mark(p);
    this.view.redraw();
    this.showLabel();
  }

  private showLabel(): void {
    const r = this.preview;
    if (!r) {
      setText(this.label, "no programmed path");
      delete this.label.dataset.line;
      return;
    }
    const i = Number(this.slider.value);
    const line = r.lines[i] ?? 0;
    const k = r.line_program?.[i] ?? 0;
    const program = k > 0 ? (r.programs?.[k - 1] ?? null) : null;
    this.label.dataset.line = String(line);
    this.label.dataset.program = program ?? "";
    if (line === 0) {
      // The first sample is taken before the first block, the last after the program end.
      setText(this.label, `point ${i + 1}/${r.points.length}: ${i === 0 ? "before the first block" : "program end"}`);
      return;
    }
    let text: string | undefined;
    if (this.source.active) text = activeProgram.line({ serial: this.source.serial, program }, line);
    else if (!program) text = this.textLines[line - 1];
    const where = program ? `line ${line} of ${program}` : `line ${line}`;
    setText(this.label, `point ${i + 1}/${r.points.length} · ${where}: ${text?.trim() ?? "…"}`);
  }
}

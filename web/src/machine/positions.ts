// The coordinate display: one frame at a time (MCS, WCS or BCS), switched like Operate's
// "Act. values MCS" softkey.

import type { AxisValues, State } from "../api/types";
import { byId, el, fmt, setText } from "../core/dom";
import type { SessionController } from "../core/session";
import { rotaryAxisNames } from "../view3d/machineData";
import { showPositioning } from "./positioningMark";

export type Frame = "machine" | "workpiece" | "basic";

const TITLES: Record<Frame, string> = {
  machine: "Machine coordinates (MCS)",
  workpiece: "Workpiece coordinates (WCS)",
  basic: "Basic coordinates (BCS)",
};

export class PositionsView {
  private frame: Frame = "workpiece";
  private rowsKey = "";
  private cells = new Map<string, HTMLElement>();
  /** The reference point symbol cell of each row. */
  private refCells = new Map<string, HTMLElement>();
  /** The positioning-axis badge beside each row's axis name. */
  private posMarks = new Map<string, HTMLElement>();
  private latest: State | null = null;
  /** NC data text of the machine (which axes are rotary). */
  private machineData = "";
  private rotary = new Set<string>();

  constructor() {
    for (const b of document.querySelectorAll<HTMLButtonElement>("#coords-toggle [data-frame]")) {
      b.addEventListener("click", () => this.setFrame(b.dataset.frame as Frame));
    }
    this.setFrame(this.frame);
  }

  setFrame(frame: Frame): void {
    this.frame = frame;
    setText(byId("coords-title"), TITLES[frame]);
    byId("positions").dataset.frame = frame;
    for (const b of document.querySelectorAll<HTMLElement>("#coords-toggle [data-frame]")) {
      b.classList.toggle("active", b.dataset.frame === frame);
    }
    this.rowsKey = "";
    if (this.latest) this.render(this.latest);
  }

  setMachineData(text: string): void {
    this.machineData = text;
    this.rotary.clear();
    this.rowsKey = "";
  }

  render(st: State): void {
    this.latest = st;
    if (!this.rotary.size && this.machineData) this.rotary = rotaryAxisNames(this.machineData, Object.keys(st.positions.machine));
    const values: AxisValues = st.positions[this.frame] ?? {};
    const axes = Object.keys(values);
    const key = `${this.frame}:${axes.join(",")}`;
    if (key !== this.rowsKey) this.buildRows(axes, key, st.spindles);
    for (const [axis, value] of Object.entries(values)) {
      const td = this.cells.get(axis);
      if (td) setText(td, fmt(value));
    }
    this.showReferenced(st, axes);
    showPositioning(st, axes, this.posMarks);
  }

  /**
   * The reference point symbol beside each axis, as Operate shows it: ⊕ referenced, a warning
   * "not ref." otherwise. The state names machine axes; a WCS/BCS row takes the machine axis of
   * the same name, else the one at the same place (no transformation: the same order).
   */
  private showReferenced(st: State, axes: string[]): void {
    const referenced = st.referenced ?? {};
    const machine = Object.keys(st.positions.machine);
    axes.forEach((axis, i) => {
      const td = this.refCells.get(axis);
      if (!td) return;
      const name = axis in referenced ? axis : machine.length === axes.length ? machine[i] : undefined;
      const known = name !== undefined && name in referenced;
      const ok = known && referenced[name!] === true;
      const state = !known ? "" : ok ? "yes" : "no";
      if (td.dataset.referenced === state) return;
      td.dataset.referenced = state;
      setText(td, !known ? "" : ok ? "⊕" : "not ref.");
      td.title = !known ? "" : ok ? `${name} is referenced` : `${name} is not referenced: JOG → Ref. point`;
      td.setAttribute("aria-label", td.title);
    });
  }

  /** Rotary axes and spindles count in degrees, everything else in mm. */
  private buildRows(axes: string[], key: string, spindles: Record<string, number>): void {
    this.rowsKey = key;
    this.cells.clear();
    this.refCells.clear();
    this.posMarks.clear();
    const rows = axes.map((axis) => {
      const value = el("td", { class: "num value", "data-frame": this.frame, "data-axis": axis });
      this.cells.set(axis, value);
      const tr = el("tr");
      const ref = el("td", { class: "ref", "data-ref-axis": axis });
      this.refCells.set(axis, ref);
      const mark = el("span", { class: "pos-mark" });
      this.posMarks.set(axis, mark);
      const name = el("th", { class: "axis" }, axis);
      name.append(mark);
      tr.append(ref, name, value, el("td", { class: "unit" }, axis in spindles || this.rotary.has(axis) ? "°" : "mm"));
      return tr;
    });
    byId<HTMLTableElement>("positions").tBodies[0]!.replaceChildren(...rows);
  }
}

export function mountPositions(session: SessionController): PositionsView {
  const view = new PositionsView();
  session.on("session", (info) => view.setMachineData(info.machine.machine_data));
  session.on("machine", (info) => view.setMachineData(info.machine.machine_data));
  session.on("state", (st) => view.render(st));
  return view;
}

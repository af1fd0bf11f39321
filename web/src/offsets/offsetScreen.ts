// Work offsets (Operate's "Parameter > Work offset"): the settable frames G500, G54..G57 and
// G505.. as MD28080 defines them, with the offset (TR) of every channel axis and the rotations
// (RT) about X, Y, Z, editable, the active one marked. Read from GET .../machine-data and
// written back as `$P_UIFR` lines with PUT .../machine-data (reset state only, like the
// control's offsets while no program runs). Below them the overview of the active frame chain
// (GET .../frames): basic frames, settable frame, programmable frame, any other link in use,
// and the total, refreshed when the program stops or ends and when the work offset changes.

import { api } from "../api/client";
import type { FrameChain, State } from "../api/types";
import { el, fmt } from "../core/dom";
import { showMessage } from "../core/message";
import type { SessionController } from "../core/session";
import { component, frameCount, frameLine, frameName, parseFrames, type Frame } from "./offsetText";

const ROTATIONS = ["X", "Y", "Z"];

/** The links the overview always shows, with Operate's names; others only when in use. */
const CHAIN_NAMES: Record<string, string> = {
  $P_ACTBFRAME: "Basic frames",
  $P_IFRAME: "Settable frame",
  $P_PFRAME: "Programmable frame",
  $P_ACTFRAME: "Total",
};

export class OffsetScreen {
  private frames = new Map<number, Frame>();
  private count = 5;
  private axes: string[] = [];
  private active = "";
  /** Edits not yet sent: "n/axis/comp" → value. */
  private edits = new Map<string, number>();
  readonly node: HTMLDivElement;
  private readonly table: HTMLTableElement;
  private readonly chainTable: HTMLTableElement;
  private status = "";

  constructor(private readonly session: SessionController) {
    this.node = el("div", { id: "offsets-view", class: "offsets-view" });
    this.table = el("table", { id: "offset-list", class: "md-table offset-list" });
    this.table.append(el("thead"), el("tbody"));
    this.table.tBodies[0].addEventListener("change", (ev) => this.edited(ev.target as HTMLInputElement));
    this.chainTable = el("table", { id: "frame-chain", class: "md-table offset-list frame-chain" });
    this.chainTable.append(el("caption", {}, "Active frame chain"), el("thead"), el("tbody"));
    this.node.append(this.table, this.chainTable);
    session.on("session", () => {
      this.edits.clear();
      this.axes = [];
    });
    session.on("state", (st) => this.observe(st));
  }

  /** Unapplied edits, for the area's "pending" note. */
  get pending(): number {
    return this.edits.size;
  }

  async load(): Promise<void> {
    const id = this.session.id;
    if (!id) return;
    try {
      const { text } = await api.machineData(id);
      this.frames = parseFrames(text);
      this.count = frameCount(text);
      this.render();
      await this.loadChain();
    } catch (e) {
      showMessage(`work offsets: ${(e as Error).message}`);
    }
  }

  /** Reads and shows the active frame chain. */
  async loadChain(): Promise<void> {
    const id = this.session.id;
    if (!id) return;
    try {
      this.renderChain(await api.frames(id));
    } catch (e) {
      showMessage(`frame chain: ${(e as Error).message}`);
    }
  }

  private renderChain(chain: FrameChain): void {
    const head = el("tr");
    head.append(el("th", {}, "Frame"));
    for (const a of chain.axes) head.append(el("th", {}, a));
    for (const a of ROTATIONS) head.append(el("th", {}, `Rot ${a}`));
    this.chainTable.tHead!.replaceChildren(head);
    const rows = chain.links
      .filter((l) => l.name in CHAIN_NAMES || !l.neutral)
      .map((l) => {
        const tr = el("tr", { "data-link": l.name, title: l.name });
        if (l.name === "$P_ACTFRAME") tr.classList.add("total");
        tr.append(el("td", { class: "frame-name" }, CHAIN_NAMES[l.name] ?? l.name));
        for (let k = 0; k < chain.axes.length; k++) tr.append(el("td", { class: "num" }, fmt(l.trans[k] ?? NaN, 3)));
        for (let g = 0; g < 3; g++) tr.append(el("td", { class: "num" }, l.rot ? fmt(l.rot[g], 3) : "–"));
        return tr;
      });
    this.chainTable.tBodies[0].replaceChildren(...rows);
  }

  dropEdits(): void {
    this.edits.clear();
  }

  /** Sends the edited components; true when they were taken. */
  async apply(): Promise<boolean> {
    if (this.edits.size === 0) return true;
    const text = [...this.edits].map(([key, v]) => {
      const [n, axis, comp] = key.split("/");
      return frameLine(Number(n), axis, comp, v);
    });
    const answer = await this.session.act((id) => api.putMachineData(id, text.join("\n") + "\n"));
    if (!answer) return false;
    this.edits.clear();
    await this.load();
    return true;
  }

  private observe(st: State): void {
    const axes = Object.keys(st.positions.basic);
    const active = st.gcodes.find((g) => /^G(500|5[4-7]|5\d\d)$/.test(g)) ?? "";
    if (axes.join() !== this.axes.join()) {
      this.axes = axes;
      this.render();
    }
    if (st.status !== this.status) {
      // A program that stops or ends leaves its frames: show the chain it left.
      const settled = st.status !== "running";
      this.status = st.status;
      if (settled && this.node.isConnected) void this.loadChain();
    }
    if (active !== this.active) {
      this.active = active;
      if (this.node.isConnected) void this.loadChain();
      for (const tr of this.table.tBodies[0].rows) tr.classList.toggle("active", tr.dataset.frame === active);
    }
  }

  private render(): void {
    const rot = ROTATIONS.filter((a) => this.axes.includes(a));
    const head = el("tr");
    head.append(el("th", {}, "Work offset"));
    for (const a of this.axes) head.append(el("th", {}, a));
    for (const a of rot) head.append(el("th", {}, `Rot ${a}`));
    this.table.tHead!.replaceChildren(head);
    const rows: HTMLTableRowElement[] = [];
    for (let n = 0; n < this.count; n++) {
      const name = frameName(n);
      const tr = el("tr", { "data-frame": name });
      if (name === this.active) tr.classList.add("active");
      tr.append(el("td", { class: "frame-name" }, name));
      for (const a of this.axes) tr.append(this.cell(n, a, "TR"));
      for (const a of rot) tr.append(this.cell(n, a, "RT"));
      rows.push(tr);
    }
    this.table.tBodies[0].replaceChildren(...rows);
  }

  private cell(n: number, axis: string, comp: string): HTMLTableCellElement {
    const key = `${n}/${axis}/${comp}`;
    const td = el("td", { class: "num" });
    const input = el("input", {
      type: "number",
      step: "any",
      value: fmt(this.edits.get(key) ?? component(this.frames, n, axis, comp), 3),
      "data-edit": key,
      "aria-label": `${frameName(n)} ${comp === "RT" ? "rotation" : "offset"} ${axis}`,
    });
    if (this.edits.has(key)) input.classList.add("changed");
    // Frame 0 (G500) is the neutral frame on most machines, but the control lets it be set.
    td.append(input);
    return td;
  }

  private edited(input: HTMLInputElement): void {
    const key = input.dataset.edit;
    if (!key) return;
    const value = Number(input.value);
    if (input.value.trim() === "" || !Number.isFinite(value)) {
      showMessage(`${input.getAttribute("aria-label")}: "${input.value}" is no number`);
      return;
    }
    this.edits.set(key, value);
    input.classList.add("changed");
  }
}

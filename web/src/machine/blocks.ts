// The program display of the machine screen: the program the channel runs (from the server,
// whoever started it) with the current block highlighted and kept in view. A block inside a
// subprogram or cycle shows that program's text, as Operate does, with the calling line named.
//
// The list is virtualized: only the rows in view (plus a margin) exist, the rest is margin of
// the list's fixed row height, and the lines come in chunks from the server (`active.ts`), so
// a program of 200,000 blocks scrolls and follows its block as a short one does.
//
// Before the channel has loaded any program, and in reset state after Execute selected another
// one, the selection (what Cycle start will run) is shown, marked as selected.

import type { ChannelStatus, State } from "../api/types";
import { byId, el, setText } from "../core/dom";
import type { SessionController } from "../core/session";
import { activeName, activeProgram } from "../program/active";
import { highlightLine } from "../program/highlight";
import { selection } from "../program/selected";

const ROW_PX = 18; // the list's line height (program.css .code-view)
const OVERSCAN = 30; // rows rendered above and below the visible ones
const MAX_ROWS = 200; // rows rendered at most, whatever the list's height claims

const PROGRAM_STATUS: Record<ChannelStatus, string> = {
  idle: "RESET",
  running: "ACTIVE",
  stopped: "STOPPED",
  alarm: "INTERRUPTED",
};

/** Where the shown lines come from. */
type Source =
  | { kind: "active"; serial: number; program: string | null }
  | { kind: "selected"; lines: string[] }
  | { kind: "mda"; lines: string[] };

class BlocksView {
  private source: Source = { kind: "selected", lines: [] };
  private current: number | null = null;
  private renderedFirst = 0;
  private renderedLast = -1;
  private follow = true;
  /** The current line is past the lines known so far: scroll to it when they arrive. */
  private scrollPending = false;
  private lastState: State | null = null;
  /** Execute selected a program after the channel loaded its last one (reset state only). */
  selectedSinceLoad = false;
  private readonly list = byId<HTMLOListElement>("blocks");

  constructor() {
    this.list.addEventListener("scroll", () => this.renderRows(false), { passive: true });
    new ResizeObserver(() => this.renderRows(false)).observe(this.list);
  }

  /** Picks the text to show from the state and what the server and the selection hold. */
  render(st: State): void {
    this.lastState = st;
    const status = byId("program-status");
    status.dataset.status = st.status;
    setText(status, PROGRAM_STATUS[st.status]);

    const meta = activeProgram.meta;
    const inSub = st.block?.program ?? null;
    let source: Source;
    let name: string;
    const stale = meta !== null && st.program_serial !== undefined && meta.serial !== st.program_serial;
    if (stale && st.status !== "idle") {
      // The channel has loaded another program whose name and text are still being read:
      // nothing of the old one is shown meanwhile.
      source = { kind: "selected", lines: [] };
      name = "loading the active program …";
    } else if (meta && !(st.status === "idle" && this.selectedSinceLoad)) {
      source = { kind: "active", serial: meta.serial, program: inSub };
      name = inSub ? `${inSub}  (called by ${activeName(meta)})` : activeName(meta);
    } else if (st.mode === "MDA" && !meta) {
      source = { kind: "mda", lines: splitLines(selection.mdaText) };
      name = "MDA";
    } else {
      source = { kind: "selected", lines: splitLines(selection.current.text) };
      name = `${selection.current.name} (selected)`;
    }
    setText(byId("blocks-name"), name);
    this.list.dataset.source = source.kind;
    if (!sameSource(source, this.source)) {
      this.source = source;
      this.current = null;
      this.renderRows(true);
    }
    // Until the text of a newly loaded program is known, no line of the old one is marked.
    const fresh = source.kind !== "active" || source.serial === (st.program_serial ?? source.serial);
    const line = fresh && st.block && (source.kind === "active" || !inSub) ? st.block.line : null;
    this.highlight(line);
  }

  /** Shows the selection again (Execute, new MDA blocks) or newly arrived lines. */
  refresh(): void {
    if (this.lastState) {
      this.source = { kind: "selected", lines: [] }; // forces a new render
      this.render(this.lastState);
    } else {
      this.source = { kind: "selected", lines: splitLines(selection.current.text) };
      setText(byId("blocks-name"), `${selection.current.name} (selected)`);
      this.renderRows(true);
    }
  }

  /** Lines arrived from the server: fill the rows still waiting for them. */
  linesArrived(): void {
    this.renderRows(true);
    // A subprogram's length is known only with its first lines: bring the block into view now
    // (once: later arrivals are for rows the operator scrolled to).
    const line = this.current;
    if (!this.scrollPending || line == null || this.count() < line) return;
    this.scrollPending = false;
    this.scrollTo(line);
    this.renderRows(false);
  }

  private scrollTo(line: number): void {
    // Keep the current block in the upper third, as Operate does.
    this.list.scrollTop = Math.max(0, (line - 1) * ROW_PX - this.list.clientHeight / 3);
  }

  private count(): number {
    const s = this.source;
    if (s.kind !== "active") return s.lines.length;
    return activeProgram.lineCount(s.program) ?? activeProgram.meta?.lineCount ?? 0;
  }

  private text(n: number): string | undefined {
    const s = this.source;
    if (s.kind !== "active") return s.lines[n - 1];
    return activeProgram.line({ serial: s.serial, program: s.program }, n);
  }

  private highlight(line: number | null): void {
    if (line === this.current) return;
    this.current = line;
    // The padding must be there before the list can scroll to the line.
    this.renderRows(true);
    if (line != null && this.follow) this.scrollTo(line);
    this.scrollPending = line != null && this.count() < line;
    this.renderRows(false);
  }

  /** Renders the rows in view; `force` also when the same range is rendered already. */
  private renderRows(force: boolean): void {
    const total = this.count();
    const height = this.list.clientHeight || 300;
    const first = Math.max(1, Math.floor(this.list.scrollTop / ROW_PX) + 1 - OVERSCAN);
    const last = Math.min(total, Math.ceil((this.list.scrollTop + height) / ROW_PX) + OVERSCAN, first + MAX_ROWS - 1);
    if (!force && first === this.renderedFirst && last === this.renderedLast) return;
    this.renderedFirst = first;
    this.renderedLast = last;
    const rows: HTMLElement[] = [];
    for (let n = first; n <= last; n++) {
      const text = this.text(n);
      const li = el("li", { "data-line": String(n) });
      if (n === this.current) li.classList.add("current");
      li.append(el("span", { class: "line-no" }, String(n)));
      const code = el("span", { class: "line-code" });
      if (text === undefined) {
        code.classList.add("loading");
        code.textContent = "…";
      } else {
        code.innerHTML = highlightLine(text) || " ";
      }
      li.append(code);
      rows.push(li);
    }
    // The rows not rendered are margins of the first and last row (scrollable overflow, which
    // the list's `contain: size` keeps out of its own height, as padding would not be).
    rows[0]?.style.setProperty("margin-top", `${(first - 1) * ROW_PX}px`);
    rows.at(-1)?.style.setProperty("margin-bottom", `${Math.max(0, total - last) * ROW_PX}px`);
    this.list.replaceChildren(...rows);
    this.list.dataset.lines = String(total);
  }
}

function splitLines(text: string): string[] {
  const lines = text.split("\n").map((l) => l.replace(/\r$/, ""));
  if (lines.at(-1) === "") lines.pop();
  return lines;
}

function sameSource(a: Source, b: Source): boolean {
  if (a.kind !== b.kind) return false;
  if (a.kind === "active" && b.kind === "active") return a.serial === b.serial && a.program === b.program;
  return a.kind !== "active" && b.kind !== "active" && a.lines.length === b.lines.length && a.lines.every((l, i) => l === b.lines[i]);
}

export function mountBlocks(session: SessionController): BlocksView {
  const view = new BlocksView();
  view.refresh();
  selection.on("change", () => {
    view.selectedSinceLoad = true;
    view.refresh();
  });
  selection.on("mda", () => view.refresh());
  activeProgram.on("change", () => {
    view.selectedSinceLoad = false;
    view.refresh();
  });
  activeProgram.on("lines", () => view.linesArrived());
  session.on("state", (st) => view.render(st));
  return view;
}

// The program display of the machine screen: the active program's text with the current block
// highlighted and kept in view. Renders a window of lines around the current block, so long
// programs cost no more than short ones.

import type { ChannelStatus, State } from "../api/types";
import { byId, el, setText } from "../core/dom";
import type { SessionController } from "../core/session";
import { highlightLine } from "../program/highlight";
import { selection } from "../program/selected";

const WINDOW = 400; // lines rendered at once
const MARGIN = 50; // re-window when the current line comes this close to an edge

const PROGRAM_STATUS: Record<ChannelStatus, string> = {
  idle: "RESET",
  running: "ACTIVE",
  stopped: "STOPPED",
  alarm: "INTERRUPTED",
};

class BlocksView {
  private lines: string[] = [];
  private first = 1; // line number of the first rendered line
  private current: number | null = null;
  private shownMda = false;
  private readonly list = byId<HTMLOListElement>("blocks");

  /** Shows the program the block lines refer to: the MDA blocks in MDA, else the selection. */
  refresh(): void {
    const { name, text } = this.shownMda ? { name: "MDA", text: selection.mdaText } : selection.current;
    setText(byId("blocks-name"), name);
    this.lines = text.split("\n");
    if (this.lines.at(-1) === "") this.lines.pop();
    this.renderWindow(1);
  }

  render(st: State): void {
    const status = byId("program-status");
    status.dataset.status = st.status;
    setText(status, PROGRAM_STATUS[st.status]);

    const mda = st.mode === "MDA";
    if (mda !== this.shownMda) {
      this.shownMda = mda;
      this.refresh();
    }
    // The list shows the main program: a block inside a subprogram has a line of another text.
    this.highlight(st.block && !st.block.program ? st.block.line : null);
  }

  private highlight(line: number | null): void {
    if (line === this.current) return;
    this.list.querySelector(".current")?.classList.remove("current");
    if (line != null && line >= 1 && line <= this.lines.length) {
      const last = this.first + this.list.children.length - 1;
      const above = line < this.first || (line < this.first + MARGIN && this.first > 1);
      const below = line > last || (line > last - MARGIN && last < this.lines.length);
      if (above || below) this.renderWindow(Math.max(1, line - MARGIN));
    }
    this.current = line;
    if (line == null) return;
    const li = this.list.children[line - this.first] as HTMLElement | undefined;
    if (!li) return;
    li.classList.add("current");
    // Keep the current block in the upper third, as Operate does.
    const top = li.offsetTop - this.list.clientHeight / 3;
    this.list.scrollTop = Math.max(0, top);
  }

  private renderWindow(first: number): void {
    this.first = first;
    const end = Math.min(this.lines.length, first + WINDOW - 1);
    const items: HTMLElement[] = [];
    for (let n = first; n <= end; n++) {
      const li = el("li", { "data-line": String(n) });
      li.append(el("span", { class: "line-no" }, String(n)));
      const code = el("span", { class: "line-code" });
      code.innerHTML = highlightLine(this.lines[n - 1] ?? "") || " ";
      li.append(code);
      items.push(li);
    }
    this.list.replaceChildren(...items);
    this.current = null;
  }
}

export function mountBlocks(session: SessionController): void {
  const view = new BlocksView();
  view.refresh();
  selection.on("change", () => view.refresh());
  selection.on("mda", () => view.refresh());
  session.on("state", (st) => view.render(st));
}

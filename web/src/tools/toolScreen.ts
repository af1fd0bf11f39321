// The Parameter area, like Operate's "Tool list", "Magazine" and "Work offset" (offsets/): one row per cutting
// edge (place, type symbol and short name, tool name, duplo, D, length, radius, wear, state,
// remaining life) and a view of the magazines' places. Fed by GET .../tools; the geometry and
// wear cells are editable and sent back whole with PUT .../tools (reset state only, as on the
// control). The list is read again when the tool in the spindle, the prepared tool or the
// channel status changes, and every two seconds while a program runs (remaining life).
//
// The area builds its own DOM (section and softkey) so index.html and the shared area list stay
// untouched but for the area's name.

import type { State } from "../api/types";
import { el, fmt } from "../core/dom";
import { showMessage } from "../core/message";
import type { SessionController } from "../core/session";
import { areaChanged, currentArea, showArea } from "../ui/areas";
import { toolsApi, type Magazine, type ToolEdge, type ToolEntry, type ToolList } from "./toolsApi";
import { placeText, remainingLife, stateOf, typeOf } from "./toolText";
import { OffsetScreen } from "../offsets/offsetScreen";
import "./tools.css";

/** The editable cells: field of the edge and how it is shown. */
const EDITABLE = [
  { key: "length", label: "Length", get: (e: ToolEdge) => e.lengths[0], set: (e: ToolEdge, v: number) => (e.lengths[0] = v) },
  { key: "radius", label: "Radius", get: (e: ToolEdge) => e.radius, set: (e: ToolEdge, v: number) => (e.radius = v) },
  {
    key: "wear_length",
    label: "Δ Length",
    get: (e: ToolEdge) => e.wear_lengths[0],
    set: (e: ToolEdge, v: number) => (e.wear_lengths[0] = v),
  },
  { key: "wear_radius", label: "Δ Radius", get: (e: ToolEdge) => e.wear_radius, set: (e: ToolEdge, v: number) => (e.wear_radius = v) },
] as const;

const REFRESH_RUNNING_MS = 2000;

type Tab = "list" | "magazine" | "offsets";

class ToolScreen {
  private list: ToolList | null = null;
  /** Edits not yet sent: "T/D/key" → value. */
  private edits = new Map<string, number>();
  private lastKey = "";
  private stale = true;
  private loading = false;
  private lastLoad = 0;
  private running = false;
  private tab: Tab = "list";
  private readonly offsets: OffsetScreen;
  private readonly body: HTMLTableSectionElement;
  private readonly magazineView: HTMLDivElement;
  private readonly table: HTMLTableElement;
  private readonly pending: HTMLSpanElement;
  private readonly note: HTMLParagraphElement;

  constructor(private readonly session: SessionController) {
    const section = el("section", { id: "area-tools", class: "area tools-area", "data-area": "tools" });
    section.hidden = true;
    const bar = el("div", { class: "editor-bar" });
    const tabs = el("div", { class: "toggle", role: "tablist", "aria-label": "Tool views" });
    for (const [tab, label] of [
      ["list", "Tool list"],
      ["magazine", "Magazine"],
      ["offsets", "Work offsets"],
    ] as const) {
      const b = el("button", { type: "button", "data-tools-tab": tab }, label);
      b.addEventListener("click", () => this.showTab(tab));
      tabs.append(b);
    }
    this.pending = el("span", { id: "tools-pending", class: "muted" });
    const reload = el("button", { id: "btn-tools-reload", type: "button", title: "Read the tool list again and drop unapplied changes" }, "Reload");
    reload.addEventListener("click", () => {
      if (this.tab === "offsets") {
        this.offsets.dropEdits();
        void this.offsets.load();
        return;
      }
      this.edits.clear();
      void this.load();
    });
    const apply = el(
      "button",
      { id: "btn-tools-apply", type: "button", class: "primary", title: "Send the changed offsets (reset state only)" },
      "Apply",
    );
    apply.addEventListener("click", () => void (this.tab === "offsets" ? this.offsets.apply() : this.apply()));
    bar.append(tabs, el("div", { class: "spacer" }), this.pending, reload, apply);

    this.table = el("table", { id: "tool-list", class: "md-table tool-list" });
    const head = el("tr");
    for (const h of ["Place", "Type", "Tool name", "DP", "D", ...EDITABLE.map((c) => c.label), "State", "Remaining life"]) {
      head.append(el("th", {}, h));
    }
    this.table.append(el("thead"), el("tbody"));
    this.table.tHead!.append(head);
    this.body = this.table.tBodies[0];
    this.body.addEventListener("change", (ev) => this.edited(ev.target as HTMLInputElement));
    this.note = el("p", { id: "tools-note", class: "muted" });
    this.note.hidden = true;
    this.magazineView = el("div", { id: "magazine-view", class: "magazine-view" });
    this.magazineView.hidden = true;
    this.offsets = new OffsetScreen(session);
    const content = el("div", { class: "md-body" });
    content.append(this.note, this.table, this.magazineView, this.offsets.node);
    section.append(bar, content);
    const areas = document.querySelector("[data-area='data']");
    if (areas?.parentElement) areas.after(section);
    else document.body.append(section);

    const key = el("button", { type: "button", "data-goto": "tools", title: "Tool list, magazine, work offsets" }, "Parameter");
    key.addEventListener("click", () => showArea("tools"));
    const softkeys = document.querySelector("nav.softkeys");
    const before = softkeys?.querySelector("[data-goto='sessions']");
    if (before) before.before(key);
    else softkeys?.append(key);

    this.showTab("list");
    session.on("session", () => {
      this.list = null;
      this.edits.clear();
      this.lastKey = "";
      this.markStale();
    });
    session.on("state", (st) => this.observe(st));
    areaChanged.on("change", (area) => {
      if (area !== "tools") return;
      if (this.stale) void this.load();
      if (this.tab === "offsets") void this.offsets.load();
    });
  }

  private visible(): boolean {
    return currentArea() === "tools";
  }

  /** Reads the list again when the tool or the status changed (or life is being counted). */
  private observe(st: State): void {
    this.running = st.status === "running";
    const key = `${st.tool.t}/${st.tool.d}/${st.tool.prepared}/${st.status}`;
    const changed = key !== this.lastKey;
    this.lastKey = key;
    if (changed) this.markStale();
    else if (this.running && this.visible() && Date.now() - this.lastLoad > REFRESH_RUNNING_MS) void this.load();
  }

  private markStale(): void {
    this.stale = true;
    if (this.visible()) void this.load();
  }

  private async load(): Promise<void> {
    const id = this.session.id;
    if (!id || this.loading) return;
    this.loading = true;
    this.lastLoad = Date.now();
    try {
      this.list = await toolsApi.get(id);
      this.stale = false;
      this.render();
    } catch (e) {
      showMessage(`tool list: ${(e as Error).message}`);
    } finally {
      this.loading = false;
    }
  }

  private showTab(tab: Tab): void {
    this.tab = tab;
    for (const b of document.querySelectorAll<HTMLElement>("[data-tools-tab]")) {
      b.classList.toggle("active", b.dataset.toolsTab === tab);
    }
    this.table.hidden = tab !== "list";
    this.magazineView.hidden = tab !== "magazine";
    this.offsets.node.hidden = tab !== "offsets";
    if (tab === "offsets" && this.visible()) void this.offsets.load();
  }

  private render(): void {
    const list = this.list;
    if (!list) return;
    this.renderTable(list);
    this.renderMagazines(list);
    this.pending.textContent = this.edits.size ? `${this.edits.size} unapplied change(s)` : "";
    const auto = list.tools.filter((t) => t.auto_placed).map((t) => t.name || `T${t.number}`);
    this.note.hidden = auto.length === 0;
    this.note.textContent = auto.length ? `Put into a free magazine place when the data were activated: ${auto.join(", ")}` : "";
  }

  private renderTable(list: ToolList): void {
    const rows: HTMLTableRowElement[] = [];
    for (const tool of sortedTools(list)) {
      const edges = tool.edges.length ? tool.edges : [null];
      edges.forEach((edge, i) => rows.push(this.row(list, tool, edge, i === 0)));
    }
    this.body.replaceChildren(...rows);
  }

  private row(list: ToolList, tool: ToolEntry, edge: ToolEdge | null, first: boolean): HTMLTableRowElement {
    const tr = el("tr", { "data-tool": String(tool.number), "data-d": String(edge?.d ?? 0) });
    if (tool.in_spindle) tr.classList.add("in-spindle");
    else if (list.prepared === tool.number) tr.classList.add("prepared");
    const state = stateOf(tool.state);
    if (state.disabled) tr.classList.add("disabled");
    const type = typeOf(edge?.type ?? 0);
    const symbol = el("span", { class: `tool-symbol tool-${type.family}`, title: `${type.long} (type ${edge?.type ?? 0})` }, type.symbol);
    const typeCell = el("td", { class: "tool-type" });
    typeCell.append(symbol, document.createTextNode(` ${type.short}`));
    const cells: HTMLElement[] = [
      el("td", { class: "tool-place" }, first ? placeText(tool) : ""),
      typeCell,
      el("td", { class: "tool-name" }, first ? tool.name || `T${tool.number}` : ""),
      el("td", { class: "num" }, first ? String(tool.duplo) : ""),
      el("td", { class: "num tool-d" }, edge ? String(edge.d) : "–"),
    ];
    for (const c of EDITABLE) {
      const td = el("td", { class: "num" });
      if (edge) {
        const editKey = `${tool.number}/${edge.d}/${c.key}`;
        const value = this.edits.get(editKey) ?? c.get(edge);
        const input = el("input", {
          type: "number",
          step: "any",
          value: fmt(value, 3),
          "data-edit": editKey,
          "aria-label": `${c.label} of ${tool.name || `T${tool.number}`} D${edge.d}`,
        });
        if (this.edits.has(editKey)) input.classList.add("changed");
        td.append(input);
      }
      cells.push(td);
    }
    const stateCell = el("td", { class: "tool-state", title: `$TC_TP8 = ${tool.state}` }, first ? state.text : "");
    if (state.disabled) stateCell.classList.add("state-disabled");
    else if (state.prewarning) stateCell.classList.add("state-prewarning");
    cells.push(stateCell, el("td", { class: "num tool-life" }, edge ? remainingLife(tool, edge) : ""));
    tr.append(...cells);
    return tr;
  }

  private renderMagazines(list: ToolList): void {
    const byNumber = new Map(list.tools.map((t) => [t.number, t]));
    const label = (t: number | null | undefined) => {
      if (!t) return "";
      const tool = byNumber.get(t);
      return tool?.name ? `${tool.name} (${tool.duplo})` : `T${t}`;
    };
    const nodes: HTMLElement[] = [];
    const spindle = el("div", { class: "magazine spindle-place", id: "spindle-place" });
    spindle.append(el("h3", {}, "Spindle"), el("div", { class: "place in-spindle" }, list.spindle ? label(list.spindle) : "empty"));
    if (list.prepared && list.prepared !== list.spindle) spindle.append(el("p", { class: "muted" }, `prepared: ${label(list.prepared)}`));
    nodes.push(spindle);
    for (const mag of list.magazines.filter(shownMagazine)) {
      const box = el("div", { class: "magazine", "data-magazine": String(mag.number) });
      box.append(el("h3", {}, `${mag.name || magazineKind(mag)} (magazine ${mag.number})`));
      const grid = el("ol", { class: "places" });
      for (const p of mag.places) {
        const tool = p.tool ? byNumber.get(p.tool) : undefined;
        const li = el("li", { class: "place", "data-place": String(p.number) });
        li.append(el("span", { class: "place-number" }, String(p.number)), el("span", { class: "place-tool" }, label(p.tool)));
        if (p.state & 1) li.classList.add("place-disabled");
        if (tool && stateOf(tool.state).disabled) li.classList.add("disabled");
        if (p.tool && p.tool === list.prepared) li.classList.add("prepared");
        grid.append(li);
      }
      box.append(grid);
      nodes.push(box);
    }
    this.magazineView.replaceChildren(...nodes);
  }

  private edited(input: HTMLInputElement): void {
    const key = input.dataset.edit;
    if (!key || !this.list) return;
    const value = Number(input.value);
    if (!Number.isFinite(value)) {
      showMessage(`${input.getAttribute("aria-label")}: "${input.value}" is no number`);
      return;
    }
    this.edits.set(key, value);
    input.classList.add("changed");
    this.pending.textContent = `${this.edits.size} unapplied change(s)`;
  }

  /** Sends the whole list with the edited values (the server refuses it while a program runs). */
  private async apply(): Promise<void> {
    if (!this.list || this.edits.size === 0) return;
    const list: ToolList = structuredClone(this.list);
    for (const [key, value] of this.edits) {
      const [t, d, field] = key.split("/");
      const edge = list.tools.find((x) => x.number === Number(t))?.edges.find((e) => e.d === Number(d));
      const cell = EDITABLE.find((c) => c.key === field);
      if (edge && cell) cell.set(edge, value);
    }
    const answer = await this.session.act((id) => toolsApi.put(id, list));
    if (answer) {
      this.edits.clear();
      this.list = answer;
      this.render();
    }
  }
}

function sortedTools(list: ToolList): ToolEntry[] {
  // Magazine order as Operate lists it: by magazine and place, unplaced tools last.
  const place = (t: ToolEntry) => (t.place ? t.place.magazine * 1000 + t.place.place : Number.MAX_SAFE_INTEGER);
  return [...list.tools].sort((a, b) => place(a) - place(b) || a.number - b.number);
}

function shownMagazine(m: Magazine): boolean {
  // The buffer magazine 9998 is shown as the spindle; the loading magazine only if it holds tools.
  if (m.number === 9998) return false;
  if (m.number === 9999) return m.places.some((p) => p.tool);
  return true;
}

function magazineKind(m: Magazine): string {
  return { 1: "Chain magazine", 3: "Turret", 5: "Box magazine", 7: "Buffer", 9: "Loading magazine" }[m.kind] ?? "Magazine";
}

/** Mounts the Tools area. */
export function mountTools(session: SessionController): void {
  new ToolScreen(session);
}

// The Machine data area: general, channel and axis machine data and the tool table as forms,
// and all NC data as text (import/export in the control's syntax).
//
// Edits are collected as assignments ("$MA_MAX_AX_VELO[AX1]=8000") and sent together with
// "Activate" (PUT .../machine-data: all-or-nothing, reset state only). The server names the
// line of the first bad assignment; since every pending field is one line, that line leads
// back to the field, which shows the error.

import { api, ApiError } from "../api/client";
import type { MachineDatumDef } from "../api/types";
import { byId, el, setText } from "../core/dom";
import { clearMessage, showMessage } from "../core/message";
import type { SessionController } from "../core/session";
import { CodeEditor } from "../program/codeEditor";
import { areaChanged, currentArea } from "../ui/areas";

type Tab = "nck" | "channel" | "axis" | "tools" | "text";

/** Tool offset columns of the table: $TC_DPn. */
const TOOL_PARAMS: { p: number; label: string }[] = [
  { p: 1, label: "Type" },
  { p: 2, label: "Edge pos." },
  { p: 3, label: "Length 1" },
  { p: 4, label: "Length 2" },
  { p: 5, label: "Length 3" },
  { p: 6, label: "Radius" },
];
const TOOL_PARAM_COUNT = 25;
/** Tool types ($TC_DP1) by their numbers in the Siemens tool lists. */
const TOOL_TYPES: Record<number, string> = {
  100: "milling tool",
  110: "ball end mill",
  111: "conical ball end mill",
  120: "end mill",
  121: "end mill, corner rounding",
  130: "angle head cutter",
  140: "face mill",
  145: "thread cutter",
  150: "side mill",
  155: "bevelled cutter",
  200: "twist drill",
  205: "solid drill",
  210: "boring bar",
  220: "center drill",
  230: "countersink",
  240: "tap",
  500: "roughing tool",
  510: "finishing tool",
  520: "plunge cutter",
  530: "parting tool",
  540: "threading tool",
  580: "3D probe, turning",
  700: "slotting saw",
  710: "3D probe, milling",
};
const NEW_TOOL_TYPE = "120"; // end mill
/** Arrays longer than this show their set elements and the next one, not all of them. */
const SHORT_ARRAY = 4;

/** One field: where it shows and what it writes. */
interface Field {
  key: string; // the assignment's left side, normalised: "$MA_MAX_AX_VELO[AX1]"
  tab: Tab;
  axis?: string; // "AX1" for axis data
}

export class MachineDataArea {
  private defs: MachineDatumDef[] = [];
  private values = new Map<string, string>(); // key -> value as the server wrote it
  private order: string[] = []; // keys in the server's text order
  private serverText = "";
  private pending = new Map<string, { value: string; field: Field }>();
  private errorKey: string | null = null;
  private errorText = "";
  private tab: Tab = "nck";
  private axes: string[] = []; // machine axis names, AX1 first
  private axis = "AX1";
  private readonly text: CodeEditor;
  private textEdited = false;
  private loadedFor: string | null = null;

  constructor(private readonly session: SessionController) {
    this.text = new CodeEditor(byId("md-text"), "NC data text");
    this.text.onInput(() => {
      this.textEdited = this.text.text !== this.serverText;
      this.updatePending();
    });
    for (const b of document.querySelectorAll<HTMLButtonElement>("[data-md-tab]")) {
      b.addEventListener("click", () => this.setTab(b.dataset.mdTab as Tab));
    }
    byId<HTMLSelectElement>("md-axis").addEventListener("change", (ev) => {
      this.axis = (ev.target as HTMLSelectElement).value;
      this.render();
    });
    byId("md-filter").addEventListener("input", () => this.render());
    byId("btn-md-reload").addEventListener("click", () => void this.load(true));
    byId("btn-md-apply").addEventListener("click", () => void this.apply());
    byId("btn-md-export").addEventListener("click", () => this.exportText());
    byId("btn-md-import").addEventListener("click", () => byId<HTMLInputElement>("md-import-file").click());
    byId<HTMLInputElement>("md-import-file").addEventListener("change", (ev) => void this.importFile(ev));
    byId("btn-tool-new").addEventListener("click", () => this.newTool());
    byId("md-table").addEventListener("change", (ev) => this.onFieldChange(ev));
    byId("tool-table").addEventListener("change", (ev) => this.onFieldChange(ev));
    byId("tool-table").addEventListener("click", (ev) => this.onToolClick(ev));
    byId("md-diagnostics").addEventListener("click", (ev) => {
      const li = (ev.target as HTMLElement).closest<HTMLElement>("li[data-line]");
      if (li) this.text.goToLine(Number(li.dataset.line));
    });
    areaChanged.on("change", (area) => {
      if (area === "data" && this.loadedFor !== this.session.id) void this.load(false);
    });
    session.on("session", () => {
      this.loadedFor = null;
      this.pending.clear();
      this.clearError();
      if (currentArea() === "data") void this.load(false);
    });
    this.setTab("nck");
  }

  /** Reads the registry (once) and the session's data; drops pending changes when asked. */
  async load(dropPending: boolean): Promise<void> {
    const id = this.session.id;
    if (!id) return;
    try {
      if (!this.defs.length) this.defs = await api.machineDataDefinitions();
      const { text } = await api.machineData(id);
      this.loadedFor = id;
      this.setServerText(text);
      this.session.setMachineData(text);
      if (dropPending) {
        this.pending.clear();
        this.clearError();
      }
      this.axes = Object.keys(this.session.latest?.positions.machine ?? (await api.state(id)).positions.machine);
      this.fillAxes();
      this.render();
    } catch (e) {
      showMessage(`machine data: ${(e as Error).message}`);
    }
  }

  setTab(tab: Tab): void {
    this.tab = tab;
    for (const b of document.querySelectorAll<HTMLElement>("[data-md-tab]")) {
      b.classList.toggle("active", b.dataset.mdTab === tab);
    }
    byId("md-table").hidden = !(tab === "nck" || tab === "channel" || tab === "axis");
    byId("tool-table").hidden = tab !== "tools";
    byId("md-text").hidden = tab !== "text";
    byId("md-axis-label").hidden = tab !== "axis";
    byId("md-filter").hidden = !(tab === "nck" || tab === "channel" || tab === "axis");
    byId("btn-tool-new").hidden = tab !== "tools";
    if (tab !== "text") this.showDiagnostics([]);
    this.render();
  }

  // ---------------------------------------------------------------- reading the text

  private setServerText(text: string): void {
    this.serverText = text;
    this.values.clear();
    this.order = [];
    for (const raw of text.split("\n")) {
      const a = parseAssignment(raw);
      if (!a) continue;
      if (!this.values.has(a.key)) this.order.push(a.key);
      this.values.set(a.key, a.value);
    }
    this.text.text = text;
    this.textEdited = false;
  }

  private fillAxes(): void {
    const select = byId<HTMLSelectElement>("md-axis");
    const options = this.axes.map((name, i) => el("option", { value: `AX${i + 1}` }, `AX${i + 1}  ${name}`));
    select.replaceChildren(...options);
    if (!this.axes.some((_, i) => `AX${i + 1}` === this.axis)) this.axis = "AX1";
    select.value = this.axis;
  }

  // ---------------------------------------------------------------- rendering

  private render(): void {
    if (this.tab === "tools") this.renderTools();
    else if (this.tab !== "text") this.renderData(this.tab);
    this.updatePending();
  }

  private renderData(scope: "nck" | "channel" | "axis"): void {
    const filter = byId<HTMLInputElement>("md-filter").value.trim().toUpperCase();
    const rows: HTMLTableRowElement[] = [];
    for (const def of this.defs) {
      if (def.scope !== scope) continue;
      if (filter && !def.name.includes(filter) && !String(def.number).startsWith(filter)) continue;
      for (const index of this.indicesOf(def, scope)) {
        const key = `${def.name}${index}`;
        rows.push(this.dataRow(def, key, index, { key, tab: scope, ...(scope === "axis" ? { axis: this.axis } : {}) }));
      }
    }
    byId<HTMLTableElement>("md-table").tBodies[0]!.replaceChildren(...rows);
  }

  /** The index suffixes shown for a datum: "" for scalars, "[i]", "[AXn]", "[i,AXn]". */
  private indicesOf(def: MachineDatumDef, scope: "nck" | "channel" | "axis"): string[] {
    const axis = scope === "axis" ? this.axis : null;
    const suffix = (i: number | null) =>
      axis ? (i == null ? `[${axis}]` : `[${i},${axis}]`) : i == null ? "" : `[${i}]`;
    if (def.len <= 1) return [suffix(null)];
    let count = def.len;
    if (def.len > SHORT_ARRAY) {
      let highest = -1;
      for (let i = 0; i < def.len; i++) {
        const k = `${def.name}${suffix(i)}`;
        if (this.values.has(k) || this.pending.has(k)) highest = i;
      }
      count = Math.min(def.len, highest + 2);
    }
    return Array.from({ length: count }, (_, i) => suffix(i));
  }

  private dataRow(def: MachineDatumDef, key: string, index: string, field: Field): HTMLTableRowElement {
    const tr = el("tr", { "data-key": key });
    const stored = this.values.get(key);
    const element = Number(/^\[(\d+)/.exec(index)?.[1] ?? 0);
    const dflt = def.defaults[element] ?? def.defaults[0] ?? "";
    const value = this.pending.get(key)?.value ?? stored ?? dflt;
    const input = this.input(key, value, field, def.kind === "string" ? "text" : "value");
    input.dataset.original = stored ?? dflt;
    const cell = el("td", { class: "md-value" });
    cell.append(input);
    this.decorate(tr, cell, key, stored !== undefined);
    const range =
      def.min != null || def.max != null ? `${def.min ?? "−∞"} … ${def.max ?? "∞"}` : def.kind === "bool" ? "TRUE/FALSE" : "";
    tr.append(
      el("td", { class: "num" }, def.number ? String(def.number) : ""),
      el("td", { class: "mono md-name" }, `${def.name}${index}`),
      cell,
      el("td", { class: "mono muted" }, dflt),
      el("td", { class: "mono muted" }, range),
    );
    return tr;
  }

  private renderTools(): void {
    const edges = new Map<string, { t: number; d: number }>();
    const note = (key: string) => {
      const m = /^\$TC_DP\d+\[(\d+),(\d+)\]$/.exec(key);
      if (m) edges.set(`${m[1]},${m[2]}`, { t: Number(m[1]), d: Number(m[2]) });
    };
    for (const key of this.values.keys()) note(key);
    for (const key of this.pending.keys()) note(key);
    const sorted = [...edges.values()].sort((a, b) => a.t - b.t || a.d - b.d);
    const rows = sorted.map(({ t, d }) => {
      const tr = el("tr", { "data-tool": String(t), "data-edge": String(d) });
      tr.append(el("td", { class: "num" }, String(t)), el("td", { class: "num" }, String(d)));
      let deleted = true;
      for (let p = 1; p <= TOOL_PARAM_COUNT; p++) {
        const key = `$TC_DP${p}[${t},${d}]`;
        const v = this.pending.get(key)?.value ?? this.values.get(key) ?? "0";
        if (Number(v) !== 0) deleted = false;
      }
      for (const { p } of TOOL_PARAMS) {
        const key = `$TC_DP${p}[${t},${d}]`;
        const stored = this.values.get(key);
        const input = this.input(key, this.pending.get(key)?.value ?? stored ?? "0", { key, tab: "tools" }, "value");
        input.dataset.original = stored ?? "0";
        const cell = el("td", { class: "md-value" });
        cell.append(input);
        if (p === 1) {
          const type = TOOL_TYPES[Number(input.value)];
          cell.append(el("span", { class: "tool-type" }, type ?? ""));
        }
        this.decorate(tr, cell, key, stored !== undefined);
        tr.append(cell);
      }
      const actions = el("td", { class: "actions" });
      actions.append(el("button", { type: "button", "data-action": "delete-edge", title: "Set every offset of this edge to 0" }, "Delete"));
      tr.append(actions);
      tr.classList.toggle("deleted", deleted);
      return tr;
    });
    const body = byId<HTMLTableElement>("tool-table").tBodies[0]!;
    if (!rows.length) {
      const tr = el("tr");
      tr.append(el("td", { colspan: "9", class: "muted" }, "No tool offsets yet: New tool adds one."));
      rows.push(tr);
    }
    body.replaceChildren(...rows);
  }

  private input(key: string, value: string, field: Field, kind: "text" | "value"): HTMLInputElement {
    const input = el("input", {
      type: "text",
      class: `md-input ${kind}`,
      value,
      spellcheck: "false",
      autocomplete: "off",
      "data-key": key,
      "aria-label": key,
    });
    inputFields.set(input, field);
    return input;
  }

  /** Marks a row's field as pending or in error (with the message under the field). */
  private decorate(tr: HTMLTableRowElement, cell: HTMLElement, key: string, stored: boolean): void {
    const input = cell.querySelector("input")!;
    if (this.pending.has(key)) {
      input.classList.add("modified");
      tr.classList.add("modified");
    }
    if (stored) tr.classList.add("set");
    if (this.errorKey === key) {
      input.classList.add("invalid");
      input.setAttribute("aria-invalid", "true");
      cell.append(el("div", { class: "field-error", role: "alert" }, this.errorText));
      tr.classList.add("invalid");
    }
  }

  private updatePending(): void {
    const n = this.pending.size;
    const parts: string[] = [];
    if (n) parts.push(`${n} change${n === 1 ? "" : "s"} not active yet`);
    if (this.textEdited) parts.push("text edited");
    setText(byId("md-pending"), parts.join(", "));
  }

  // ---------------------------------------------------------------- editing

  private onFieldChange(ev: Event): void {
    const input = ev.target as HTMLInputElement;
    const field = inputFields.get(input);
    if (!field) return;
    const value = input.value.trim();
    if (value === input.dataset.original) this.pending.delete(field.key);
    else this.pending.set(field.key, { value, field });
    if (this.errorKey === field.key) this.clearError();
    input.classList.toggle("modified", this.pending.has(field.key));
    input.closest("tr")?.classList.toggle("modified", this.pending.has(field.key));
    this.updatePending();
  }

  private newTool(): void {
    let t = 0;
    for (const key of [...this.values.keys(), ...this.pending.keys()]) {
      const m = /^\$TC_DP\d+\[(\d+),\d+\]$/.exec(key);
      if (m) t = Math.max(t, Number(m[1]));
    }
    const key = `$TC_DP1[${t + 1},1]`;
    this.pending.set(key, { value: NEW_TOOL_TYPE, field: { key, tab: "tools" } });
    this.render();
  }

  private onToolClick(ev: Event): void {
    const button = (ev.target as HTMLElement).closest<HTMLButtonElement>("button[data-action='delete-edge']");
    const tr = button?.closest<HTMLElement>("tr[data-tool]");
    if (!tr) return;
    const { tool, edge } = tr.dataset;
    for (let p = 1; p <= TOOL_PARAM_COUNT; p++) {
      const key = `$TC_DP${p}[${tool},${edge}]`;
      if (this.values.has(key)) this.pending.set(key, { value: "0", field: { key, tab: "tools" } });
      else this.pending.delete(key);
    }
    this.render();
  }

  /** Activate: the edited text in the Text view, else the pending fields. */
  async apply(): Promise<void> {
    const id = this.session.id;
    if (!id) return;
    if (this.tab === "text") return this.applyText(id);
    const entries = [...this.pending.values()];
    if (!entries.length) {
      showMessage("nothing to activate: change a value first", "info");
      return;
    }
    const text = entries.map((e) => `${e.field.key}=${e.value}`).join("\n") + "\n";
    clearMessage();
    this.clearError();
    try {
      this.session.accept(await api.putMachineData(id, text));
      this.pending.clear();
      await this.load(false);
      showMessage(`${entries.length} value${entries.length === 1 ? "" : "s"} activated`, "info");
    } catch (e) {
      const err = e as Error;
      const line = err instanceof ApiError ? err.line : null;
      const bad = line != null ? entries[line - 1] : undefined;
      showMessage(`nothing activated: ${err.message}`);
      if (bad) this.showFieldError(bad.field, stripLine(err.message));
    }
  }

  private async applyText(id: string): Promise<void> {
    clearMessage();
    this.showDiagnostics([]);
    try {
      this.session.accept(await api.putMachineData(id, this.text.text));
      await this.load(false); // fields changed but not activated stay pending
      showMessage("NC data text activated", "info");
    } catch (e) {
      const err = e as Error;
      showMessage(`nothing activated: ${err.message}`);
      if (err instanceof ApiError && err.line != null) {
        this.showDiagnostics([{ line: err.line, message: stripLine(err.message) }]);
        this.text.goToLine(err.line);
      }
    }
  }

  private showFieldError(field: Field, message: string): void {
    this.errorKey = field.key;
    this.errorText = message;
    if (field.axis) {
      this.axis = field.axis;
      byId<HTMLSelectElement>("md-axis").value = field.axis;
    }
    byId<HTMLInputElement>("md-filter").value = "";
    this.setTab(field.tab);
    const input = document.querySelector<HTMLInputElement>(`.md-input[data-key="${cssEscape(field.key)}"]`);
    input?.focus();
    input?.scrollIntoView({ block: "center" });
  }

  private clearError(): void {
    this.errorKey = null;
    this.errorText = "";
    for (const n of document.querySelectorAll(".md-table .field-error")) n.remove();
    for (const n of document.querySelectorAll(".md-table .invalid")) {
      n.classList.remove("invalid");
      n.removeAttribute("aria-invalid");
    }
  }

  private showDiagnostics(list: { line: number; message: string }[]): void {
    this.text.setMarks(list);
    byId("md-diagnostics").replaceChildren(
      ...list.map((d) => {
        const li = el("li", { "data-line": String(d.line) });
        li.append(el("span", { class: "diag-pos" }, `line ${d.line}`), el("span", {}, d.message));
        return li;
      }),
    );
  }

  // ---------------------------------------------------------------- import / export

  private exportText(): void {
    const id = this.session.id ?? "session";
    const machine = this.session.info?.machine.id ?? "";
    const header = `; NCTwin NC data of session ${id} (${machine}): values that differ from the defaults\n`;
    const body = this.tab === "text" ? this.text.text : this.serverText;
    const url = URL.createObjectURL(new Blob([header + body], { type: "text/plain" }));
    const a = el("a", { href: url, download: `${id}-nc-data.txt` });
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 1000);
  }

  private async importFile(ev: Event): Promise<void> {
    const input = ev.target as HTMLInputElement;
    const file = input.files?.[0];
    input.value = "";
    if (!file) return;
    const text = await file.text();
    this.setTab("text");
    this.text.text = text;
    this.textEdited = text !== this.serverText;
    this.updatePending();
    showMessage(`${file.name} loaded into the Text view: Activate applies it`, "info");
  }
}

/** Which field an input edits (kept beside the DOM, not in it). */
const inputFields = new WeakMap<HTMLInputElement, Field>();

/** "$MA_X[ AX1 ] = 5 ; c" -> key "$MA_X[AX1]", value "5"; null for other lines. */
export function parseAssignment(raw: string): { key: string; value: string } | null {
  const line = raw.replace(/;.*$/, "").trim();
  const m = /^(\$[A-Z0-9_]+)\s*(\[[^\]]*\])?\s*=\s*(.+)$/i.exec(line);
  if (!m) return null;
  const [, name = "", index = "", value = ""] = m;
  return { key: `${name.toUpperCase()}${index.replace(/\s+/g, "").toUpperCase()}`, value: value.trim() };
}

/** "machine data: line 2: $MA_X: value ..." -> "$MA_X: value ..." (the field names the line). */
function stripLine(message: string): string {
  return message.replace(/^.*?\bline \d+:\s*/, "");
}

function cssEscape(s: string): string {
  return s.replace(/["\\]/g, "\\$&");
}

export function mountMachineData(session: SessionController): MachineDataArea {
  return new MachineDataArea(session);
}

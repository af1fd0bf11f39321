// The Program manager: the session's stored programs; open, select for execution, delete, new.

import { api } from "../api/client";
import type { StoredProgram } from "../api/types";
import { byId, el } from "../core/dom";
import { showMessage } from "../core/message";
import type { SessionController } from "../core/session";
import { areaChanged, showArea } from "../ui/areas";
import type { EditorArea } from "./editorArea";
import { selection } from "./selected";

/** Stored programs larger than this are not loaded into the page on Execute. */
const LOAD_LIMIT_BYTES = 256 * 1024;

export class ProgramManager {
  constructor(
    private readonly session: SessionController,
    private readonly editor: EditorArea,
  ) {
    byId("btn-programs-refresh").addEventListener("click", () => void this.refresh());
    const upload = byId<HTMLInputElement>("programs-upload-file");
    byId("btn-programs-upload").addEventListener("click", () => upload.click());
    upload.addEventListener("change", () => {
      const file = upload.files?.[0];
      upload.value = "";
      if (file) void this.upload(file);
    });
    byId("btn-programs-new").addEventListener("click", () => {
      this.editor.open("NEW", "");
      showArea("program");
    });
    byId("programs").addEventListener("click", (ev) => void this.onClick(ev));
    areaChanged.on("change", (area) => area === "manager" && void this.refresh());
    session.on("session", () => byId<HTMLTableElement>("programs").tBodies[0]!.replaceChildren());
  }

  async refresh(): Promise<void> {
    const id = this.session.id;
    if (!id) return;
    const note = byId("programs-note");
    let programs: StoredProgram[];
    try {
      programs = await api.programs(id);
    } catch (e) {
      note.hidden = false;
      note.textContent = `The program store is not available: ${(e as Error).message}`;
      return;
    }
    note.hidden = programs.length > 0;
    note.textContent = "No stored programs yet: write one in the Program area and save it.";
    byId<HTMLTableElement>("programs").tBodies[0]!.replaceChildren(...programs.map((p) => this.row(p)));
  }

  /** Uploads an archive file into the session's store (all or nothing) and says what it held. */
  async upload(file: File): Promise<void> {
    const id = this.session.id;
    if (!id) return;
    try {
      const result = await api.importArchive(id, file);
      const stored = result.programs.map((p) => p.name).join(", ") || "none";
      const data = result.nc_data.length ? `; NC data loaded: ${result.nc_data.map((d) => d.name).join(", ")}` : "";
      const skipped = result.skipped.length
        ? `; skipped: ${result.skipped.map((s) => `${s.name} (${s.reason})`).join(", ")}`
        : "";
      showMessage(`${file.name}: stored ${stored}${data}${skipped}`, "info");
    } catch (e) {
      showMessage(`${file.name}: ${(e as Error).message}`);
    }
    await this.refresh();
  }

  private row(p: StoredProgram): HTMLTableRowElement {
    const tr = el("tr", { "data-program": p.name, "data-size": String(p.size) });
    const actions = el("td", { class: "actions" });
    actions.append(
      el("button", { type: "button", "data-action": "open" }, "Open"),
      el("button", { type: "button", "data-action": "execute" }, "Execute"),
      el("button", { type: "button", "data-action": "delete" }, "Delete"),
    );
    tr.append(el("td", { class: "mono" }, p.name), el("td", { class: "num" }, `${p.size} B`), actions);
    return tr;
  }

  private async onClick(ev: Event): Promise<void> {
    const button = (ev.target as HTMLElement).closest<HTMLButtonElement>("button[data-action]");
    const name = button?.closest<HTMLElement>("tr[data-program]")?.dataset.program;
    const id = this.session.id;
    if (!button || !name || !id) return;
    try {
      switch (button.dataset.action) {
        case "open": {
          const { text } = await api.program(id, name);
          this.editor.open(name, text);
          showArea("program");
          break;
        }
        case "execute": {
          // A CAM-size program stays on the server: it runs by name and the program display
          // reads its lines from there once it runs.
          const size = Number(button.closest<HTMLElement>("tr[data-program]")?.dataset.size ?? "0");
          const text = size > LOAD_LIMIT_BYTES ? "" : (await api.program(id, name)).text;
          selection.select({ name, text, stored: true });
          // As Operate's "Select": the program is for AUTO, so AUTO is selected (in reset state).
          const st = this.session.latest;
          if (st && st.mode !== "AUTO" && st.status === "idle") await this.session.act((sid) => api.setMode(sid, "AUTO"));
          showArea("machine");
          break;
        }
        case "delete":
          if (!confirm(`Delete program ${name}?`)) return;
          await api.deleteProgram(id, name);
          await this.refresh();
          break;
      }
    } catch (e) {
      showMessage(`${name}: ${(e as Error).message}`);
    }
  }
}

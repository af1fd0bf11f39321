// The Program area: edit a program, check it (errors at their lines), save it in the session's
// program store, select it for execution. The check is the server's (POST .../check): syntax,
// and names that are not defined (12550), unknown G functions (12470), called programs that do
// not exist (14011) and missing jump destinations (14080), each with its alarm number.
// Check and Execute then make a trial run on a copy of the channel (POST .../preview), kept
// only for what no static check can find because it depends on the values the program
// computes and the machine it runs on: a software limit (10720), a working-area limit, an
// arithmetic alarm, a tool that is not there, an alarm the program raises with SETAL. New/Open
// ask before they drop unsaved text.

import { api, ApiError } from "../api/client";
import type { Diagnostic } from "../api/types";
import { byId, el, setText } from "../core/dom";
import { clearMessage, showMessage } from "../core/message";
import type { SessionController } from "../core/session";
import { showArea } from "../ui/areas";
import { CodeEditor } from "./codeEditor";
import { selection } from "./selected";

const CHECK_DELAY_MS = 600; // check this long after the last keystroke
/**
 * The longest text the check and the trial run take: their JSON body (newlines escaped) may be
 * 1 MiB at most (the server's limit for all but program uploads, `413` beyond). A longer
 * program (a CAM program) is saved and run by name from the store, where the run finds errors.
 */
const CHECK_LIMIT_CHARS = 900_000;

export class EditorArea {
  readonly editor = new CodeEditor(byId("editor"));
  private savedText = "";
  private checkTimer: ReturnType<typeof setTimeout> | undefined;
  private checkSeq = 0;
  private readonly nameInput = byId<HTMLInputElement>("editor-name");

  constructor(private readonly session: SessionController) {
    this.editor.onInput(() => {
      this.updateDirty();
      clearTimeout(this.checkTimer);
      if (!this.tooLargeToCheck) this.checkTimer = setTimeout(() => void this.check(), CHECK_DELAY_MS);
    });
    byId("btn-editor-new").addEventListener("click", () => this.open("NEW", ""));
    byId("btn-editor-save").addEventListener("click", () => void this.save());
    byId("btn-editor-check").addEventListener("click", () => void this.checkAll());
    byId("btn-editor-execute").addEventListener("click", () => void this.execute());
    byId("diagnostics").addEventListener("click", (ev) => {
      const li = (ev.target as HTMLElement).closest<HTMLElement>("li[data-line]");
      if (li) this.editor.goToLine(Number(li.dataset.line), Number(li.dataset.column) || 1);
    });
    this.open(selection.current.name, selection.current.text);
  }

  /** Whether the text is beyond what the check takes (see [`CHECK_LIMIT_CHARS`]). */
  get tooLargeToCheck(): boolean {
    return this.editor.text.length > CHECK_LIMIT_CHARS;
  }

  get name(): string {
    return this.nameInput.value.trim().toUpperCase();
  }

  /** Whether the editor holds text that is not saved. */
  get dirty(): boolean {
    return this.editor.text !== this.savedText;
  }

  /**
   * Loads a program into the editor (saved state = as given); asks first when that would drop
   * unsaved text. False when the user kept the text.
   */
  open(name: string, text: string): boolean {
    if (this.dirty && !confirm(`${this.name || "The program"} has unsaved changes. Drop them and open ${name}?`)) return false;
    this.nameInput.value = name;
    this.editor.text = text;
    this.savedText = text;
    this.showDiagnostics([]);
    this.updateDirty();
    return true;
  }

  /**
   * The server's check (syntax and names), then a trial run when it finds nothing; shows and
   * returns the errors.
   */
  async checkAll(): Promise<Diagnostic[]> {
    const errors = await this.check();
    if (errors.length) return errors;
    const trial = await this.trialRun();
    if (trial.length) this.showDiagnostics(trial);
    return trial;
  }

  /**
   * Runs the text on a copy of the channel (the preview, no motion on the machine): its alarm
   * at its line, or nothing (also when the trial is cut short by the server's limits or cannot
   * run). Only what the run finds beyond the check: see the head of this file.
   */
  private async trialRun(): Promise<Diagnostic[]> {
    const id = this.session.id;
    if (!id || this.tooLargeToCheck) return [];
    try {
      const r = await api.preview(id, { program: this.editor.text, max_points: 2 });
      if (r.outcome !== "alarm" || !r.alarm) return [];
      const line = r.alarm.line ?? 1;
      return [{ line, column: 1, alarm: r.alarm.number, message: `${r.alarm.message} (trial run)` }];
    } catch {
      return [];
    }
  }

  /**
   * The server's check (syntax and undefined names, POST .../check); shows and returns the
   * errors (none if it cannot check).
   */
  async check(): Promise<Diagnostic[]> {
    clearTimeout(this.checkTimer);
    const id = this.session.id;
    if (!id) return [];
    if (this.tooLargeToCheck) {
      showMessage(`${this.name || "the program"} is too large to check here (more than about 1 MB): save it and run it from the program manager`, "info");
      return [];
    }
    const seq = ++this.checkSeq;
    try {
      const { diagnostics } = await api.check(id, this.editor.text);
      if (seq === this.checkSeq) this.showDiagnostics(diagnostics);
      return diagnostics;
    } catch (e) {
      if (seq === this.checkSeq) showMessage(`check: ${(e as Error).message}`);
      return [];
    }
  }

  async save(): Promise<boolean> {
    const name = this.name;
    if (!name) {
      showMessage("give the program a name first");
      return false;
    }
    const id = this.session.id;
    if (!id) return false;
    const text = this.editor.text;
    try {
      await api.saveProgram(id, name, text);
      this.savedText = text;
      this.updateDirty();
      showMessage(`${name} saved`, "info");
      return true;
    } catch (e) {
      this.showServerError(e);
      return false;
    }
  }

  /** Checks, then selects the program for AUTO and switches to the machine screen. */
  async execute(): Promise<void> {
    if (this.tooLargeToCheck) {
      showMessage(`${this.name || "the program"} is too large to select from the editor (more than about 1 MB): save it and Execute it in the program manager`);
      return;
    }
    const errors = await this.checkAll();
    if (errors.length) {
      showMessage(`${this.name || "the program"} has ${errors.length} error(s): not selected`);
      const first = errors[0]!;
      this.editor.goToLine(first.line, first.column ?? 1);
      return;
    }
    clearMessage();
    selection.select({ name: this.name || "NONAME", text: this.editor.text });
    showArea("machine");
  }

  private showDiagnostics(diagnostics: Diagnostic[]): void {
    this.editor.setMarks(diagnostics);
    byId("diagnostics").replaceChildren(
      ...diagnostics.map((d) => {
        const li = el("li", { "data-line": String(d.line), "data-column": String(d.column ?? "") });
        li.append(
          el("span", { class: "diag-pos" }, `line ${d.line}${d.column != null ? `:${d.column}` : ""}`),
          el("span", {}, d.alarm != null ? `alarm ${d.alarm}: ${d.message}` : d.message),
        );
        return li;
      }),
    );
  }

  private showServerError(e: unknown): void {
    const err = e as Error;
    if (err instanceof ApiError && err.line != null) {
      this.showDiagnostics([{ line: err.line, message: err.message }]);
    }
    showMessage(err.message);
  }

  private updateDirty(): void {
    setText(byId("editor-dirty"), this.dirty ? "modified" : "");
  }
}

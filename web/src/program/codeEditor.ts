// A small code editor: a plain <textarea> for input (so typing, undo, selection and form filling
// behave natively) over a highlighted copy of its text, with a line-number gutter that marks
// lines with errors. No wrapping: one block is one line, as on the control.

import { el } from "../core/dom";
import { escapeHtml, highlightLine } from "./highlight";

export interface LineMark {
  line: number; // 1-based
  column?: number | null;
  message: string;
}

export class CodeEditor {
  readonly input: HTMLTextAreaElement;
  private readonly gutter: HTMLElement;
  private readonly code: HTMLElement;
  private marks = new Map<number, string>(); // line -> message
  private frame = 0;
  private readonly listeners = new Set<() => void>();

  constructor(host: HTMLElement) {
    this.gutter = el("div", { class: "code-gutter", "aria-hidden": "true" });
    const pre = el("pre", { class: "code-highlight", "aria-hidden": "true" });
    this.code = el("code");
    pre.append(this.code);
    this.input = el("textarea", {
      class: "code-input",
      spellcheck: "false",
      autocomplete: "off",
      autocapitalize: "off",
      wrap: "off",
      "aria-label": "Program text",
    });
    const body = el("div", { class: "code-body" });
    body.append(pre, this.input);
    host.append(this.gutter, body);

    this.input.addEventListener("input", () => {
      this.scheduleRender();
      for (const fn of this.listeners) fn();
    });
    this.input.addEventListener("scroll", () => this.syncScroll(pre));
    this.render();
  }

  get text(): string {
    return this.input.value;
  }

  set text(value: string) {
    this.input.value = value;
    this.render();
  }

  onInput(fn: () => void): void {
    this.listeners.add(fn);
  }

  /** Marks lines with errors (replaces earlier marks). */
  setMarks(marks: LineMark[]): void {
    this.marks = new Map();
    for (const m of marks) {
      const text = m.column != null ? `${m.column}: ${m.message}` : m.message;
      const prev = this.marks.get(m.line);
      this.marks.set(m.line, prev ? `${prev}\n${text}` : text);
    }
    this.render();
  }

  /** Puts the caret at the start of a line and scrolls it into view. */
  goToLine(line: number, column = 1): void {
    const lines = this.input.value.split("\n");
    let offset = 0;
    for (let i = 0; i < Math.min(line - 1, lines.length); i++) offset += (lines[i]?.length ?? 0) + 1;
    offset += Math.max(0, column - 1);
    this.input.focus();
    this.input.setSelectionRange(offset, offset);
    const lineHeight = parseFloat(getComputedStyle(this.input).lineHeight) || 18;
    this.input.scrollTop = Math.max(0, (line - 3) * lineHeight);
  }

  private scheduleRender(): void {
    if (this.frame) return;
    this.frame = requestAnimationFrame(() => {
      this.frame = 0;
      this.render();
    });
  }

  private render(): void {
    const lines = this.input.value.split("\n");
    this.code.innerHTML =
      lines
        .map((line, i) => {
          const html = highlightLine(line);
          const mark = this.marks.get(i + 1);
          return mark ? `<span class="code-line error">${html || " "}</span>` : html;
        })
        .join("\n") + "\n"; // a trailing newline keeps the last line's height
    const numbers = lines.map((_, i) => {
      const mark = this.marks.get(i + 1);
      return mark
        ? `<div class="error" title="${escapeHtml(mark)}">${i + 1}</div>`
        : `<div>${i + 1}</div>`;
    });
    this.gutter.innerHTML = numbers.join("");
  }

  private syncScroll(pre: HTMLElement): void {
    pre.scrollTop = this.input.scrollTop;
    pre.scrollLeft = this.input.scrollLeft;
    this.gutter.scrollTop = this.input.scrollTop;
  }
}

// A small code editor: a plain <textarea> for input (so typing, undo, selection and form filling
// behave natively) over a highlighted copy of its text, with a line-number gutter that marks
// lines with errors. No wrapping: one block is one line, as on the control.
//
// Only the lines in view (and a margin around them) are highlighted and numbered: a CAM program
// of 200,000 blocks costs a keystroke or a scroll the same few hundred lines as a short one.
// Padding above and below the drawn lines keeps the layer as tall as the textarea's text, so
// the two scroll together.

import { el } from "../core/dom";
import { escapeHtml, highlightLine } from "./highlight";

export interface LineMark {
  line: number; // 1-based
  column?: number | null;
  message: string;
}

/** Lines drawn beyond the visible ones on each side: scrolling within them needs no redraw. */
const MARGIN_LINES = 60;
/** The line height when the style cannot tell (the editor's CSS sets 19 px). */
const FALLBACK_LINE_HEIGHT_PX = 19;

export class CodeEditor {
  readonly input: HTMLTextAreaElement;
  private readonly gutter: HTMLElement;
  private readonly code: HTMLElement;
  private readonly numbers: HTMLElement;
  private marks = new Map<number, string>(); // line -> message
  private frame = 0;
  private readonly listeners = new Set<() => void>();
  /** The text split into lines, kept until the text changes. */
  private lines: string[] = [""];
  private linesStale = true;
  /** The drawn lines: [first, end) as 0-based indices. */
  private drawn = { first: 0, end: 0 };

  constructor(host: HTMLElement) {
    this.gutter = el("div", { class: "code-gutter", "aria-hidden": "true" });
    this.numbers = el("div");
    this.gutter.append(this.numbers);
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
      this.linesStale = true;
      this.scheduleRender();
      for (const fn of this.listeners) fn();
    });
    this.input.addEventListener("scroll", () => {
      if (!this.inView(this.drawn)) this.render();
      this.syncScroll(pre);
    });
    this.render();
  }

  get text(): string {
    return this.input.value;
  }

  set text(value: string) {
    this.input.value = value;
    this.linesStale = true;
    this.render();
  }

  /** How many lines are highlighted in the page now (bounded whatever the program's length). */
  get drawnLines(): number {
    return this.drawn.end - this.drawn.first;
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

  private lineHeight(): number {
    return parseFloat(getComputedStyle(this.input).lineHeight) || FALLBACK_LINE_HEIGHT_PX;
  }

  /** The lines in view, as 0-based [first, end). */
  private visible(): { first: number; end: number } {
    const height = this.lineHeight();
    const first = Math.floor(this.input.scrollTop / height);
    const rows = Math.ceil((this.input.clientHeight || window.innerHeight) / height) + 1;
    return { first, end: Math.min(this.lines.length, first + rows) };
  }

  /** Whether the lines in view are among the drawn ones. */
  private inView(drawn: { first: number; end: number }): boolean {
    const seen = this.visible();
    return seen.first >= drawn.first && seen.end <= drawn.end;
  }

  private render(): void {
    if (this.linesStale) {
      this.lines = this.input.value.split("\n");
      this.linesStale = false;
      let longest = 0;
      for (const line of this.lines) longest = Math.max(longest, line.length);
      // The layer as wide as the longest line, so it scrolls sideways with the textarea.
      this.code.style.minWidth = `${longest + 1}ch`;
      // Room for the largest line number.
      this.gutter.style.width = `${String(this.lines.length).length + 2}ch`;
    }
    const seen = this.visible();
    const first = Math.max(0, seen.first - MARGIN_LINES);
    const end = Math.min(this.lines.length, seen.end + MARGIN_LINES);
    this.drawn = { first, end };
    const height = this.lineHeight();
    const above = `${first * height}px`;
    const below = `${(this.lines.length - end) * height}px`;
    const shown = this.lines.slice(first, end);
    this.code.style.paddingTop = above;
    this.code.style.paddingBottom = below;
    this.code.innerHTML =
      shown
        .map((line, i) => {
          const html = highlightLine(line);
          const mark = this.marks.get(first + i + 1);
          return mark ? `<span class="code-line error">${html || " "}</span>` : html;
        })
        .join("\n") + "\n"; // a trailing newline keeps the last line's height
    this.numbers.style.paddingTop = above;
    this.numbers.style.paddingBottom = below;
    this.numbers.innerHTML = shown
      .map((_, i) => {
        const n = first + i + 1;
        const mark = this.marks.get(n);
        return mark ? `<div class="error" title="${escapeHtml(mark)}">${n}</div>` : `<div>${n}</div>`;
      })
      .join("");
  }

  private syncScroll(pre: HTMLElement): void {
    pre.scrollTop = this.input.scrollTop;
    pre.scrollLeft = this.input.scrollLeft;
    this.gutter.scrollTop = this.input.scrollTop;
  }
}

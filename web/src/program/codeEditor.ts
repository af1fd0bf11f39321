// The program editor: CodeMirror 6, which keeps the text in a tree of lines and draws only the
// lines in view, so a CAM program of 200,000 blocks opens, scrolls and takes a keystroke as
// fast as a short one (a <textarea> lays out all of its text on every change). One block per
// line, no wrapping, line numbers with the lines that have errors marked, undo/redo, NC
// colouring (ncHighlight.ts). Tab inserts a tab (or indents the selected lines, Shift+Tab
// outdents); Escape then Tab leaves the editor, as CodeMirror's keyboard-trap escape.

import { Compartment, EditorState, type Extension, type Text } from "@codemirror/state";
import { drawSelection, EditorView, keymap, lineNumbers } from "@codemirror/view";
import { defaultKeymap, history, historyKeymap, indentLess, insertTab } from "@codemirror/commands";
import { errorMarks, type LineMark, setLineMarks } from "./errorMarks";
import { ncHighlighting } from "./ncHighlight";
import { lockReason, onLockChange } from "../ui/lock";

export type { LineMark } from "./errorMarks";

/** Colours and metrics of the editor (dark, as the rest of the HMI; text >= 12 px, contrast >= 4.5:1). */
const theme = EditorView.theme(
  {
    "&": { flex: "1", minWidth: "0", height: "100%", color: "var(--text)", backgroundColor: "#1a1f25" },
    "&.cm-focused": { outline: "none" },
    ".cm-scroller": { fontFamily: "var(--mono)", fontSize: "13px", lineHeight: "19px" },
    ".cm-content": { padding: "6px 0", caretColor: "#fff" },
    ".cm-line": { padding: "0 8px" },
    ".cm-cursor, .cm-dropCursor": { borderLeftColor: "#fff" },
    "&.cm-focused > .cm-scroller > .cm-selectionLayer .cm-selectionBackground, .cm-selectionBackground":
      { backgroundColor: "rgba(47, 164, 185, 0.35)" },
    // #929daa on #1e242b: 5.6:1.
    ".cm-gutters": { color: "#929daa", backgroundColor: "#1e242b", borderRight: "1px solid var(--line)" },
    ".cm-lineNumbers .cm-gutterElement": { minWidth: "3ch", padding: "0 8px 0 6px" },
    ".cm-lineNumbers .cm-gutterElement.error": { color: "#fff", backgroundColor: "var(--bad)" },
  },
  { dark: true },
);

/** Tab inserts a tab at the caret (indents a selection); Shift+Tab outdents. */
const tabKeys = keymap.of([{ key: "Tab", run: insertTab, shift: indentLess }]);

/** Typing allowed or not (a locked editor still scrolls, selects and copies). */
function editable(on: boolean): Extension {
  return [EditorView.editable.of(on), EditorState.readOnly.of(!on)];
}

export class CodeEditor {
  private readonly view: EditorView;
  private readonly extensions: Extension;
  /** Editable or read-only: read-only while the page's controls are locked (ui/lock.ts). */
  private readonly access = new Compartment();
  private readonly listeners = new Set<() => void>();
  /** The text of `textOf` as one string: built once per document version, not per read. */
  private textOf: Text | null = null;
  private textCache = "";

  /** `label`: the accessible name of the text ("Program text" by default). */
  constructor(host: HTMLElement, label = "Program text") {
    this.extensions = [
      lineNumbers(),
      history(),
      drawSelection(),
      EditorState.tabSize.of(4),
      EditorView.contentAttributes.of({ "aria-label": label, spellcheck: "false", autocapitalize: "off", autocorrect: "off" }),
      ncHighlighting,
      errorMarks,
      tabKeys,
      keymap.of([...defaultKeymap, ...historyKeymap]),
      theme,
      EditorView.updateListener.of((update) => {
        if (update.docChanged) for (const fn of this.listeners) fn();
      }),
    ];
    this.view = new EditorView({ parent: host, state: this.stateOf("") });
    onLockChange((why) => this.view.dispatch({ effects: this.access.reconfigure(editable(why === null)) }));
  }

  get text(): string {
    const doc = this.view.state.doc;
    if (doc !== this.textOf) {
      this.textCache = doc.toString();
      this.textOf = doc;
    }
    return this.textCache;
  }

  /** Replaces the text: a fresh start (no undo back into the previous text, no marks). */
  set text(value: string) {
    this.view.setState(this.stateOf(value));
  }

  /** Called after every change of the text by the user (typing, paste, undo); not on `text =`. */
  onInput(fn: () => void): void {
    this.listeners.add(fn);
  }

  /** Marks lines with errors (replaces earlier marks). */
  setMarks(marks: LineMark[]): void {
    this.view.dispatch({ effects: setLineMarks.of(marks) });
  }

  /** Puts the caret at a line and column (1-based, clamped to the text) and scrolls it into view. */
  goToLine(line: number, column = 1): void {
    const doc = this.view.state.doc;
    const target = doc.line(Math.min(Math.max(1, Math.trunc(line) || 1), doc.lines));
    const pos = target.from + Math.min(Math.max(0, Math.trunc(column) - 1 || 0), target.length);
    this.view.dispatch({ selection: { anchor: pos }, effects: EditorView.scrollIntoView(pos, { y: "center" }) });
    this.view.focus();
  }

  private stateOf(text: string): EditorState {
    return EditorState.create({ doc: text, extensions: [this.extensions, this.access.of(editable(lockReason() === null))] });
  }
}

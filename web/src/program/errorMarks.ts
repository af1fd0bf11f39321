// Error lines in the CodeMirror editor: the line underlined, its number in the gutter marked
// (the message as the marker's title). The marks move with the text while it is edited, until
// the next check replaces them.

import { type EditorState, type Extension, RangeSet, StateEffect, StateField } from "@codemirror/state";
import { Decoration, type DecorationSet, EditorView, GutterMarker, lineNumberMarkers } from "@codemirror/view";

export interface LineMark {
  line: number; // 1-based
  column?: number | null;
  message: string;
}

/** Replaces the marks (lines out of the text are dropped). */
export const setLineMarks = StateEffect.define<LineMark[]>();

/** A marked line: its underline, carrying the message for its gutter marker. */
function errorLine(message: string): Decoration {
  return Decoration.line({ class: "code-line error", message });
}

/** The line's number drawn in the gutter (instead of the plain one), marked, with the message. */
class ErrorNumber extends GutterMarker {
  override elementClass = "error";
  constructor(
    readonly number: number,
    readonly message: string,
  ) {
    super();
  }
  override eq(other: GutterMarker): boolean {
    return other instanceof ErrorNumber && other.number === this.number && other.message === this.message;
  }
  override toDOM(): Node {
    const span = document.createElement("span");
    span.textContent = String(this.number);
    span.title = this.message;
    return span;
  }
}

/** One message per line (several marks on a line joined), as line decorations. */
function decorate(state: EditorState, list: LineMark[]): DecorationSet {
  const byLine = new Map<number, string>();
  for (const m of list) {
    if (!Number.isInteger(m.line) || m.line < 1 || m.line > state.doc.lines) continue;
    const text = m.column != null ? `${m.column}: ${m.message}` : m.message;
    const prev = byLine.get(m.line);
    byLine.set(m.line, prev ? `${prev}\n${text}` : text);
  }
  const lines = [...byLine.keys()].sort((a, b) => a - b);
  return Decoration.set(lines.map((n) => errorLine(byLine.get(n)!).range(state.doc.line(n).from)));
}

const marksField = StateField.define<DecorationSet>({
  create: () => Decoration.none,
  update(marks, tr) {
    let next = marks.map(tr.changes);
    for (const effect of tr.effects) if (effect.is(setLineMarks)) next = decorate(tr.state, effect.value);
    return next;
  },
  provide: (field) => EditorView.decorations.from(field),
});

/** Gutter markers for the marked lines, numbered by where the lines are now. */
const numbers = lineNumberMarkers.compute([marksField], (state) => {
  const markers: ReturnType<ErrorNumber["range"]>[] = [];
  const cursor = state.field(marksField).iter();
  for (; cursor.value; cursor.next()) {
    const message = String(cursor.value.spec.message ?? "");
    markers.push(new ErrorNumber(state.doc.lineAt(cursor.from).number, message).range(cursor.from));
  }
  return RangeSet.of(markers);
});

/** The editor extension holding the error marks ([`setLineMarks`] sets them). */
export const errorMarks: Extension = [marksField, numbers];

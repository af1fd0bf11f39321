// NC syntax colouring for the CodeMirror editor: the tokens of highlight.ts (the program
// display's) as `tok-KIND` marks, so both views colour alike from one stylesheet. Only the lines
// drawn are tokenized, after each edit or scroll: a 200,000-block program costs what a short one
// does. NC lines are lexed one at a time (no state carries over a line break), so no parse of
// the whole text is needed.

import { RangeSetBuilder } from "@codemirror/state";
import { Decoration, type DecorationSet, type EditorView, ViewPlugin, type ViewUpdate } from "@codemirror/view";
import { type TokenKind, tokenizeLine } from "./highlight";

const marks = new Map<TokenKind, Decoration>();

function markFor(kind: TokenKind): Decoration {
  let mark = marks.get(kind);
  if (!mark) {
    mark = Decoration.mark({ class: `tok-${kind}` });
    marks.set(kind, mark);
  }
  return mark;
}

/** The colour marks of the lines in view. */
function colourVisible(view: EditorView): DecorationSet {
  const builder = new RangeSetBuilder<Decoration>();
  const doc = view.state.doc;
  let done = -1; // end of the last line coloured (visible ranges may share a line)
  for (const { from, to } of view.visibleRanges) {
    for (let pos = from; pos <= to; ) {
      const line = doc.lineAt(pos);
      pos = line.to + 1;
      if (line.from <= done) continue;
      done = line.to;
      let at = line.from;
      for (const token of tokenizeLine(line.text)) {
        const end = at + token.text.length;
        if (token.kind !== "text") builder.add(at, end, markFor(token.kind));
        at = end;
      }
    }
  }
  return builder.finish();
}

/** The editor extension that colours NC words (G/M codes, axes, keywords, comments …). */
export const ncHighlighting = ViewPlugin.fromClass(
  class {
    decorations: DecorationSet;
    constructor(view: EditorView) {
      this.decorations = colourVisible(view);
    }
    update(update: ViewUpdate) {
      if (update.docChanged || update.viewportChanged) this.decorations = colourVisible(update.view);
    }
  },
  { decorations: (plugin) => plugin.decorations },
);

// Syntax highlighting of the NC language (SINUMERIK dialect), one line at a time.
// Lexical only: it colours what a word looks like, the server's /check says what is wrong.

export type TokenKind =
  | "comment"
  | "blocknum"
  | "label"
  | "gcode"
  | "mcode"
  | "tool"
  | "feed"
  | "axis"
  | "keyword"
  | "sysvar"
  | "param"
  | "string"
  | "number"
  | "operator"
  | "text";

export interface Token {
  kind: TokenKind;
  text: string;
}

const KEYWORDS = new Set(
  (
    "IF ELSE ENDIF WHILE ENDWHILE FOR TO ENDFOR REPEAT UNTIL LOOP ENDLOOP CASE OF DEFAULT " +
    "GOTO GOTOF GOTOB GOTOC DEF REAL INT BOOL CHAR STRING AXIS FRAME PROC RET AND OR NOT XOR " +
    "DIV MOD B_AND B_OR B_NOT B_XOR TRUE FALSE MSG STOPRE TRANS ATRANS ROT AROT SCALE ASCALE " +
    "MIRROR AMIRROR TRAORI TRANSMIT TRACYL TRAANG TRAFOOF SUPA DIAMON DIAMOF DIAM90 AC IC DC ACP " +
    "ACN CR AR RND RNDM CHF CHR TURN SPOS SPOSA SETMS CYCLE800 CYCLE832 CALL EXTERN SAVE DISPLOF " +
    "SIN COS TAN ASIN ACOS ATAN2 SQRT ABS POT TRUNC ROUND LN EXP MINVAL MAXVAL DEFINE AS SET REP EXECSTRING"
  ).split(" "),
);

/** Address letters of axes and arc parameters. */
const AXIS_LETTERS = new Set("XYZABCUVWIJKQ".split(""));

// One alternative per token kind, tried in this order at each position.
const TOKEN = new RegExp(
  [
    "(?<comment>;.*$)",
    '(?<string>"[^"]*"?)',
    "(?<sysvar>\\$[A-Za-z_][A-Za-z0-9_]*)",
    // A word, with the value of an address glued to it: "X10.5", "G01", "CYCLE800".
    "(?<word>[A-Za-z_][A-Za-z0-9_]*(?:\\.\\d*)?)",
    "(?<number>(?:\\d+\\.?\\d*|\\.\\d+)(?:[eE][+-]?\\d+)?)",
    "(?<hex>'[HB][0-9A-Fa-f]+')",
    "(?<operator>==|<>|<=|>=|[=+\\-*/<>()\\[\\],:])",
    "(?<space>\\s+)",
    "(?<other>.)",
  ].join("|"),
  "gy",
);

function classifyWord(word: string, atLineStart: boolean, next: string): TokenKind {
  const upper = word.toUpperCase();
  if (KEYWORDS.has(upper)) return "keyword";
  const [, letters = "", value = ""] = /^([A-Z_]+)([\d.]*)$/.exec(upper) ?? [];
  if (atLineStart && letters === "N" && value) return "blocknum";
  if (atLineStart && next.startsWith(":") && !next.startsWith(":=")) return "label";
  switch (letters) {
    case "G":
      return value ? "gcode" : "text";
    case "M":
      return "mcode";
    case "T":
    case "D":
      return "tool";
    case "F":
    case "S":
      return "feed";
    case "R":
      return value ? "param" : "text";
  }
  if (letters.length === 1 && AXIS_LETTERS.has(letters)) return "axis";
  return "text";
}

/** Splits one line into coloured tokens; their texts concatenate to the line. */
export function tokenizeLine(line: string): Token[] {
  const tokens: Token[] = [];
  let atLineStart = true;
  TOKEN.lastIndex = 0;
  let m: RegExpExecArray | null;
  while (TOKEN.lastIndex < line.length && (m = TOKEN.exec(line))) {
    const g = m.groups ?? {};
    const text = m[0];
    let kind: TokenKind;
    if (g.comment !== undefined) kind = "comment";
    else if (g.string !== undefined) kind = "string";
    else if (g.sysvar !== undefined) kind = "sysvar";
    else if (g.word !== undefined) {
      kind = classifyWord(text, atLineStart, line.slice(TOKEN.lastIndex));
    } else if (g.number !== undefined || g.hex !== undefined) kind = "number";
    else if (g.operator !== undefined) kind = "operator";
    else kind = "text";
    const prev = tokens.at(-1);
    if (prev && prev.kind === kind && kind === "text") prev.text += text;
    else tokens.push({ kind, text });
    if (g.space === undefined) atLineStart = false;
  }
  return tokens;
}

const ESCAPES: Record<string, string> = { "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" };

export function escapeHtml(text: string): string {
  return text.replace(/[&<>"]/g, (c) => ESCAPES[c] ?? c);
}

/** One line as HTML: `<span class="tok-KIND">` per token (plain text for spaces). */
export function highlightLine(line: string): string {
  return tokenizeLine(line)
    .map((t) => (t.kind === "text" ? escapeHtml(t.text) : `<span class="tok-${t.kind}">${escapeHtml(t.text)}</span>`))
    .join("");
}

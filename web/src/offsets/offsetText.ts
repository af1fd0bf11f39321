// The settable work offsets in the NC data text (GET/PUT .../machine-data): `$P_UIFR[n,AX,C]`
// lines (C = TR offset, FI fine offset, RT rotation, SC scale, MI mirror) and their number,
// MD28080 $MC_MM_NUM_USER_FRAMES (default 5: G500 and G54..G57). Pure functions.

/** Component values of one settable frame by axis: TR, FI, RT, ... */
export type Frame = Map<string, Map<string, number>>;

const LINE = /^\$P_UIFR\[\s*(\d+)\s*,\s*([A-Z_][A-Z0-9_]*)\s*,\s*(TR|FI|RT|SC|MI)\s*\]\s*=\s*(-?[\d.eE+-]+)\s*$/i;

/** Every $P_UIFR value of the text, by frame number. */
export function parseFrames(text: string): Map<number, Frame> {
  const frames = new Map<number, Frame>();
  for (const raw of text.split("\n")) {
    const m = LINE.exec(raw.trim());
    if (!m) continue;
    const n = Number(m[1]);
    const axis = m[2].toUpperCase();
    const frame = frames.get(n) ?? new Map<string, Map<string, number>>();
    frames.set(n, frame);
    const comps = frame.get(axis) ?? new Map<string, number>();
    frame.set(axis, comps);
    comps.set(m[3].toUpperCase(), Number(m[4]));
  }
  return frames;
}

/** MD28080 from the text, else its default 5. */
export function frameCount(text: string): number {
  const m = /^\$MC_MM_NUM_USER_FRAMES\s*=\s*(\d+)/m.exec(text);
  return m ? Math.max(5, Math.min(100, Number(m[1]))) : 5;
}

/** G500 for frame 0, G54..G57 for 1..4, G505..G599 for 5..99. */
export function frameName(n: number): string {
  if (n === 0) return "G500";
  if (n <= 4) return `G${53 + n}`;
  return `G5${String(n).padStart(2, "0")}`;
}

/** One component of a frame (0 where the text sets none). */
export function component(frames: Map<number, Frame>, n: number, axis: string, comp: string): number {
  return frames.get(n)?.get(axis)?.get(comp) ?? 0;
}

/** The NC data line that sets one component. */
export function frameLine(n: number, axis: string, comp: string, value: number): string {
  return `$P_UIFR[${n},${axis},${comp}]=${value}`;
}

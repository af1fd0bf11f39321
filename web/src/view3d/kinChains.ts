// Kinematic chain data ($NK_ elements, $NT_ transformation records, K12) as the session's
// GET .../kinematic-chains program writes it, read into plain records for the 3D view.
// Lenient like `NcData`: lines it does not understand are skipped (the server validated them).

import type { Vec3 } from "./machineData";

export type ElementType = "OFFSET" | "AXIS_LIN" | "AXIS_ROT" | "ROT_CONST";

/** One chain element `$NK_…[i]`. */
export interface ChainElement {
  name: string;
  type: ElementType | string;
  /** `$NK_NEXT`: starts in this element's output frame. */
  next: string;
  /** `$NK_PARALLEL`: starts in this element's input frame (a branch beside it). */
  parallel: string;
  offDir: Vec3;
  /** `$NK_AXIS`: the machine or channel axis an axis element follows. */
  axis: string;
  /** `$NK_A_OFF`: axis offset (mm or degrees), the angle of a ROT_CONST. */
  aOff: number;
}

/** One transformation record `$NT_…[n]`. */
export interface ChainRecord {
  n: number;
  name: string;
  type: string;
  toolFirst: string;
  toolLast: string;
  partFirst: string;
  partLast: string;
  rotAxisNames: [string, string, string];
  rotAxisOffset: Vec3;
  /** `$NT_BASE_ORIENT`, tool direction (tip → holder) in the tool reference frame; default +Z. */
  baseOrient: Vec3;
}

export interface KinChains {
  elements: ChainElement[];
  records: ChainRecord[];
}

const LINE = /^\s*(?:N\d+\s+)?\$(NK|NT)_([A-Z0-9_]+)\[\s*(\d+)\s*(?:,\s*(\d+)\s*)?\]\s*=\s*(.+?)\s*$/i;

/** The value text up to a comment outside quotes, without its quotes. */
function literal(raw: string): string {
  let quoted = false;
  let end = raw.length;
  for (let i = 0; i < raw.length; i++) {
    if (raw[i] === '"') quoted = !quoted;
    else if (raw[i] === ";" && !quoted) {
      end = i;
      break;
    }
  }
  const v = raw.slice(0, end).trim();
  return v.length >= 2 && v.startsWith('"') && v.endsWith('"') ? v.slice(1, -1) : v;
}

/** Reads the chain program text (the lines `$NK_…[i]=…` and `$NT_…[n,k]=…`). */
export function parseChains(text: string): KinChains {
  const nk = new Map<number, Map<string, string>>();
  const nt = new Map<number, Map<string, string>>();
  for (const line of text.split("\n")) {
    const m = LINE.exec(line);
    if (!m) continue;
    const [, family = "", name = "", index = "0", comp, value = ""] = m;
    const table = family.toUpperCase() === "NK" ? nk : nt;
    const i = Number(index);
    if (!table.has(i)) table.set(i, new Map());
    table.get(i)!.set(comp === undefined ? name.toUpperCase() : `${name.toUpperCase()}.${comp}`, literal(value));
  }
  const str = (r: Map<string, string>, k: string) => r.get(k) ?? "";
  const num = (r: Map<string, string>, k: string, fallback = 0) => {
    const v = Number(r.get(k));
    return r.has(k) && Number.isFinite(v) ? v : fallback;
  };
  const vec = (r: Map<string, string>, k: string, fallback: Vec3 = [0, 0, 0]): Vec3 => {
    if (![0, 1, 2].some((c) => r.has(`${k}.${c}`))) return fallback;
    return [0, 1, 2].map((c) => num(r, `${k}.${c}`)) as Vec3;
  };
  const elements = [...nk.entries()]
    .sort(([a], [b]) => a - b)
    .map(([, r]) => ({
      name: str(r, "NAME"),
      type: str(r, "TYPE").toUpperCase(),
      next: str(r, "NEXT"),
      parallel: str(r, "PARALLEL"),
      offDir: vec(r, "OFF_DIR"),
      axis: str(r, "AXIS"),
      aOff: num(r, "A_OFF"),
    }))
    .filter((e) => e.name !== "");
  const records = [...nt.entries()]
    .sort(([a], [b]) => a - b)
    .map(([n, r]) => ({
      n,
      name: str(r, "NAME"),
      type: str(r, "TRAFO_TYPE").toUpperCase(),
      toolFirst: str(r, "T_CHAIN_FIRST_ELEM"),
      toolLast: str(r, "T_CHAIN_LAST_ELEM"),
      partFirst: str(r, "P_CHAIN_FIRST_ELEM"),
      partLast: str(r, "P_CHAIN_LAST_ELEM"),
      rotAxisNames: [0, 1, 2].map((k) => str(r, `ROT_AX_NAME.${k}`)) as [string, string, string],
      rotAxisOffset: vec(r, "ROT_AX_OFFSET"),
      baseOrient: vec(r, "BASE_ORIENT", [0, 0, 1]),
    }))
    .filter((r) => r.name !== "" || r.type !== "");
  return { elements, records };
}

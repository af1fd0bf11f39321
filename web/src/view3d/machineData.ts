// What the 3D view reads from a machine's NC data: which machine axes are linear (and along
// which direction), which are rotary, where the rotary axes sit (TRAORI data sets: head, table
// or mixed), which axis turns a lathe's workpiece, and the inclined axis of TRAANG. Decoded the
// way the engine decodes them (engine/src/machine_data/traori.rs); nothing keyed on preset names.

import { NcData } from "../core/ncdata";

export type Vec3 = [number, number, number];
export type Letter = "X" | "Y" | "Z";
export const LETTERS: Letter[] = ["X", "Y", "Z"];
const UNIT: Vec3[] = [
  [1, 0, 0],
  [0, 1, 0],
  [0, 0, 1],
];

/** `$MC_TRAFO_TYPE` codes of the orientation transformations (TRAORI). */
export function isOrientationTrafo(type: number | null | undefined): boolean {
  return typeof type === "number" && type >= 16 && type < 256;
}
const isTransmit = (t: number) => t === 256 || t === 257;
const isTracyl = (t: number) => t >= 512 && t <= 514;
const isTraang = (t: number) => t === 1024 || t === 1025;

export interface LinearAxis {
  name: string; // machine axis name
  letter: Letter;
  min: number;
  max: number;
  /** Direction in the machine's Cartesian frame (inclined for a TRAANG axis). */
  dir: Vec3;
}

export interface RotaryAxis {
  name: string; // machine axis name
  /** Axis direction; the part is turned by +angle about it (sign and DIN reversal included). */
  dir: Vec3;
  /** Offset from the previous element of its chain to this axis (see `Structure`). */
  offset: Vec3;
  /** Axis position of the kinematic zero position (degrees). */
  zero: number;
}

export interface Structure {
  kind: "mill" | "lathe";
  linear: LinearAxis[];
  /**
   * Rotary axes that turn the tool, outer first. The first offset is from the machine position
   * (the tool reference point at zero angles) to axis 1, the next from axis to axis;
   * `toolOffset` leads from the last axis to the spindle nose.
   */
  head: RotaryAxis[];
  toolOffset: Vec3;
  /**
   * Rotary axes that turn the workpiece, outer first. The first offset is from the machine zero
   * to axis 1, the next from axis to axis; `partOffset` leads from the last one to the part
   * zero (the BCS origin).
   */
  table: RotaryAxis[];
  partOffset: Vec3;
  /** Tool direction (tip → holder) in the zero position. */
  toolDir: Vec3;
  /** Lathe: the machine axis that turns the workpiece (main spindle / C axis). */
  spindle: string | null;
  /**
   * The workpiece turns by `spindleSign` × the axis position about +Z: −1 as TRANSMIT/TRACYL
   * map a point at angle C onto the tool (C = atan2(y, x)), +1 with ROT_SIGN_IS_PLUS = FALSE.
   */
  spindleSign: number;
  /** Machine axes named in $MA_IS_ROT_AX that no chain above uses. */
  otherRotary: string[];
  /**
   * TRACYL: the machine directions of the radial axis (TRAFO_AXES_IN_n[0]) and of the axis
   * parallel to the rotary axis ([2]) in the workpiece frame; the cylinder axis runs through
   * the workpiece frame's origin along `parallel`. Null without TRACYL data.
   */
  cylinder: { radial: Vec3; parallel: Vec3 } | null;
  /** Data set number n of the orientation transformation the model follows, if any. */
  traori: number | null;
  /** A one-line summary for the view's caption. */
  summary: string;
}

const SEQUENCES: [number, number][] = [
  [0, 1],
  [0, 2],
  [1, 0],
  [1, 2],
  [2, 0],
  [2, 1],
];
const AXIS_NAMES = "ABC";

type OriMachine = "tool" | "part" | "mixed";

function decodeOri(t: number): { machine: OriMachine; generic: boolean; letters: [number, number]; toolDir: number } | null {
  if (t >= 16 && t <= 21) return { machine: "tool", generic: false, letters: SEQUENCES[t - 16]!, toolDir: 2 };
  if (t >= 32 && t <= 37) return { machine: "part", generic: false, letters: SEQUENCES[t - 32]!, toolDir: 2 };
  if (t >= 48 && t <= 53) return { machine: "mixed", generic: false, letters: SEQUENCES[t - 48]!, toolDir: 2 };
  if (t === 24 || t === 40 || t === 56) {
    const machine = t === 24 ? "tool" : t === 40 ? "part" : "mixed";
    return { machine, generic: true, letters: [2, 0], toolDir: 2 };
  }
  if (t >= 128 && t <= 255) {
    const seq = t & 7;
    const dir = (t >> 3) & 3;
    const moving = (t >> 5) & 3;
    if (seq > 5 || dir > 2 || moving > 2) return null;
    return { machine: (["tool", "part", "mixed"] as const)[moving]!, generic: false, letters: SEQUENCES[seq]!, toolDir: dir };
  }
  return null;
}

const scale = (v: Vec3, s: number): Vec3 => [v[0] * s, v[1] * s, v[2] * s];
const add = (a: Vec3, b: Vec3): Vec3 => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
function unit(v: Vec3, fallback: Vec3): Vec3 {
  const n = Math.hypot(...v);
  return n > 1e-9 ? scale(v, 1 / n) : fallback;
}

/** The names and data of one machine, with the control's defaults for what the text omits. */
class Md {
  constructor(
    readonly data: NcData,
    /** Machine axis names in machine axis order (as the MCS of the state lists them). */
    readonly machineAxes: string[],
  ) {}

  num(name: string, index = "", fallback = 0): number {
    return this.data.number(name, index) ?? fallback;
  }

  vec(name: string, fallback: Vec3 = [0, 0, 0]): Vec3 {
    const v = [0, 1, 2].map((i) => this.data.number(name, String(i)));
    return v.every((x) => x === undefined) ? fallback : (v.map((x) => x ?? 0) as Vec3);
  }

  /** Machine axis name of channel axis k (1-based), via $MC_AXCONF_MACHAX_USED. */
  machineOfChannel(k: number): string | null {
    if (k <= 0) return null;
    const m = this.num("$MC_AXCONF_MACHAX_USED", String(k - 1), k <= 6 ? k : 0);
    if (m <= 0) return null;
    const named = this.data.raw("$MN_AXCONF_MACHAX_NAME_TAB", String(m - 1))?.replace(/"/g, "");
    if (named && this.machineAxes.includes(named)) return named;
    // The state lists the machine axes in machine axis order: the m-th used one is a fair guess.
    return this.machineAxes[m - 1] ?? named ?? null;
  }

  /** Axial datum of a machine axis (the text indexes by name or by AXn). */
  axis(name: string, datum: string): number | undefined {
    const no = this.machineNumber(name);
    return this.data.axisNumber(datum, name, no);
  }

  axisFlag(name: string, datum: string): boolean {
    return this.data.axisFlag(datum, name, this.machineNumber(name));
  }

  private machineNumber(name: string): number {
    for (let m = 1; m <= 31; m++) {
      const named = this.data.raw("$MN_AXCONF_MACHAX_NAME_TAB", String(m - 1))?.replace(/"/g, "");
      if (named === name) return m;
    }
    return this.machineAxes.indexOf(name) + 1;
  }

  /** Transformation data sets: [n, type] for every $MC_TRAFO_TYPE_n set. */
  trafos(): [number, number][] {
    const out: [number, number][] = [];
    for (let n = 1; n <= 10; n++) {
      const t = this.data.number(`$MC_TRAFO_TYPE_${n}`);
      if (t) out.push([n, t]);
    }
    return out;
  }

  /** The k-th data set of a kind (TRAORI 1 and 2 have their own TRAFO5 data, TRAANG_ANGLE_k ...). */
  ordinal(n: number, same: (t: number) => boolean): number {
    return this.trafos().filter(([m, t]) => m <= n && same(t)).length;
  }

  /** Channel axis number of role `i` of data set n ($MC_TRAFO_AXES_IN_n[i], default i+1 for i<5). */
  axesIn(n: number, i: number): number {
    return this.num(`$MC_TRAFO_AXES_IN_${n}`, String(i), i < 5 ? i + 1 : 0);
  }
}

/** Software limit, unless missing or so large it is a "no limit" default. */
function travel(v: number | undefined, fallback: number): number {
  return v !== undefined && Math.abs(v) < 1e4 ? v : fallback;
}

const DEFAULT_TRAVEL = 500;

/**
 * Reads the structure from NC data text and the machine axis names of the state (MCS).
 * `activeTrafo`: the data set number of the active transformation, preferred when it is an
 * orientation transformation.
 */
export function readStructure(text: string, machineAxes: string[], activeTrafo: number | null = null): Structure {
  const md = new Md(new NcData(text), machineAxes);
  const trafos = md.trafos();

  // Geometry axes without transformation: $MC_AXCONF_GEOAX_ASSIGN_TAB (default 1, 2, 3).
  const linear: LinearAxis[] = [];
  LETTERS.forEach((letter, g) => {
    const name = md.machineOfChannel(md.num("$MC_AXCONF_GEOAX_ASSIGN_TAB", String(g), g + 1));
    if (!name || md.axisFlag(name, "$MA_IS_ROT_AX") || linear.some((a) => a.name === name)) return;
    const lo = travel(md.axis(name, "$MA_POS_LIMIT_MINUS"), -DEFAULT_TRAVEL);
    const hi = travel(md.axis(name, "$MA_POS_LIMIT_PLUS"), DEFAULT_TRAVEL);
    linear.push({ name, letter, min: Math.min(lo, hi), max: Math.max(lo, hi), dir: UNIT[g]! });
  });

  // TRAANG: the inclined axis moves along X·cos α + Z·sin α (engine kinematics/traang.rs).
  for (const [n, t] of trafos) {
    if (!isTraang(t)) continue;
    const inclined = md.machineOfChannel(md.axesIn(n, 0));
    const alpha = md.num(`$MC_TRAANG_ANGLE_${md.ordinal(n, isTraang)}`) * (Math.PI / 180);
    const axis = linear.find((a) => a.name === inclined);
    if (axis && alpha) axis.dir = [Math.cos(alpha), 0, Math.sin(alpha)];
  }

  const rotary = machineAxes.filter((a) => md.axisFlag(a, "$MA_IS_ROT_AX"));
  const hasY = linear.some((a) => a.letter === "Y");
  // A lathe turns the workpiece with a spindle; TRACYL on a milling machine's rotary table
  // (X-Y-Z-A-C) does not make it one.
  const spindleTurnsPart = (n: number) =>
    (md.axis(md.machineOfChannel(md.axesIn(n, 1)) ?? "", "$MA_SPIND_ASSIGN_TO_MACHAX") ?? 0) > 0;
  const turning = trafos.some(
    ([n, t]) => ((isTransmit(t) || isTracyl(t)) && spindleTurnsPart(n)) || isTraang(t) || t === 8192,
  );
  const kind: Structure["kind"] = !hasY || (turning && !trafos.some(([, t]) => isOrientationTrafo(t))) ? "lathe" : "mill";

  const s: Structure = {
    kind,
    linear,
    head: [],
    toolOffset: [0, 0, 0],
    table: [],
    partOffset: [0, 0, 0],
    toolDir: [0, 0, 1],
    spindle: null,
    spindleSign: -1,
    otherRotary: [],
    cylinder: null,
    traori: null,
    summary: "",
  };

  // Orientation transformation: the active one, else the first one defined.
  const oris = trafos.filter(([, t]) => isOrientationTrafo(t));
  const ori = oris.find(([n]) => n === activeTrafo) ?? oris[0];
  const used = new Set<string>();
  if (ori && kind === "mill") {
    const [n, t] = ori;
    const d = decodeOri(t);
    const k = md.ordinal(n, isOrientationTrafo) === 2 ? 2 : 1;
    const names = [md.machineOfChannel(md.axesIn(n, 3)), md.machineOfChannel(md.axesIn(n, 4))];
    // Generic 6-/7-axis head (type 24): a 3rd rotary axis turns the tool about its own axis
    // (TRAFO_AXES_IN_n[5]), a 7th axis turns the workpiece (TRAFO_AXES_IN_n[6]).
    const genericHead = d?.generic === true && d.machine === "tool";
    const third = genericHead ? md.machineOfChannel(md.axesIn(n, 5)) : null;
    const seventh = genericHead ? md.machineOfChannel(md.axesIn(n, 6)) : null;
    if (third) names.push(third);
    if (d && names[0] && names[1]) {
      s.traori = n;
      const sign = (i: number) => {
        const raw = md.data.raw(`$MC_TRAFO5_ROT_SIGN_IS_PLUS_${k}`, String(i));
        return raw !== undefined && /^(FALSE|0)$/i.test(raw) ? -1 : 1;
      };
      const onPart = (i: number) => d.machine === "part" || (d.machine === "mixed" && i === 1);
      const dir = (i: number): Vec3 => {
        const base = d.generic
          ? unit(md.vec(`$MC_TRAFO5_AXIS${i + 1}_${k}`, i === 0 || i === 2 ? [0, 0, 1] : [1, 0, 0]), [0, 0, 1])
          : onPart(i)
            ? scale(UNIT[d.letters[i]!]!, -1) // DIN: a table axis turns the part the other way
            : UNIT[d.letters[i]!]!;
        return scale(base, sign(i));
      };
      const zero = (i: number) => md.num(`$MC_TRAFO5_ROT_AX_OFFSET_${k}`, String(i));
      const base = md.vec(`$MC_TRAFO5_BASE_TOOL_${k}`);
      const joint = md.vec(`$MC_TRAFO5_JOINT_OFFSET_${k}`);
      const jointPart = md.vec(`$MC_TRAFO5_JOINT_OFFSET_PART_${k}`);
      const part = md.vec(`$MC_TRAFO5_PART_OFFSET_${k}`);
      const axis = (i: number, offset: Vec3): RotaryAxis => ({ name: names[i]!, dir: dir(i), offset, zero: zero(i) });
      // The offset vectors on the chain (engine traori.rs): tool l1 = PART_OFFSET, l2 =
      // JOINT_OFFSET, l3 = BASE_TOOL; part l2 = BASE_TOOL, l3 = JOINT_OFFSET, l4 = PART_OFFSET;
      // mixed l1 = JOINT_OFFSET, l2 = BASE_TOOL, l3 = JOINT_OFFSET_PART, l4 = PART_OFFSET.
      if (d.machine === "tool") {
        // 6-axis: l23 = JOINT_OFFSET_2_3 leads from axis 2 to axis 3 (engine orient/chain.rs).
        s.head = [axis(0, part), axis(1, joint), ...(third ? [axis(2, md.vec(`$MC_TRAFO6_JOINT_OFFSET_2_3_${k}`))] : [])];
        s.toolOffset = base;
        if (seventh) {
          // The 7th axis runs through the BCS zero point (the machine zero of a tool chain)
          // and turns the workpiece right-handedly about TRAFO7_EXT_AXIS1 by the position
          // minus TRAFO7_EXT_ROT_AX_OFFSET (engine kinematics/seventh.rs).
          s.table = [
            {
              name: seventh,
              dir: unit(md.vec(`$MC_TRAFO7_EXT_AXIS1_${k}`, [0, 0, 1]), [0, 0, 1]),
              offset: [0, 0, 0],
              zero: md.num(`$MC_TRAFO7_EXT_ROT_AX_OFFSET_${k}`),
            },
          ];
          used.add(seventh);
        }
      } else if (d.machine === "part") {
        s.table = [axis(0, base), axis(1, joint)];
        s.partOffset = part;
      } else {
        s.head = [axis(0, joint)];
        s.toolOffset = base;
        s.table = [axis(1, jointPart)];
        s.partOffset = part;
      }
      s.toolDir = d.generic ? unit(md.vec(`$MC_TRAFO5_BASE_ORIENT_${k}`, [0, 0, 1]), [0, 0, 1]) : UNIT[d.toolDir]!;
      names.forEach((a) => a && used.add(a));
      const where = { tool: "swivel head", part: "rotary table", mixed: "head + table" }[d.machine];
      const seq = d.generic ? "" : ` ${AXIS_NAMES[d.letters[0]]}${AXIS_NAMES[d.letters[1]]}`;
      const count = 5 + (third ? 1 : 0) + (s.table.length && seventh ? 1 : 0);
      const extra = seventh ? ` + rotary table ${seventh}` : "";
      s.summary = `${count}-axis ${where}${seq}${extra} (TRAORI type ${t}, data set ${n})`;
    }
  }

  // TRACYL on a milling machine (no orientation transformation holds the rotary axis): the
  // rotary axis turns the cylinder about the axis parallel to it (TRAFO_AXES_IN_n[2]), through
  // the machine zero, the way the lathe's spindle turns it (see `spindleSign`).
  const tracyl = trafos.find(([, t]) => isTracyl(t));
  if (tracyl) {
    const role = (i: number) => linear.find((a) => a.name === md.machineOfChannel(md.axesIn(tracyl[0], i)));
    const [radial, parallel] = [role(0), role(2)];
    if (radial && parallel) s.cylinder = { radial: radial.dir, parallel: parallel.dir };
  }
  if (kind === "mill" && !s.table.length && !s.head.length && tracyl) {
    // The table as the engine turns the blank on it (channel/stock_table.rs): C about the
    // table's Z through the machine zero by the TRACYL sign and offset, carried by the
    // channel's other rotary non-spindle axis named A (about machine X) or B (about Y).
    const [n] = tracyl;
    const k = md.ordinal(n, isTracyl);
    const rot = md.machineOfChannel(md.axesIn(n, 1));
    const parallel = linear.find((a) => a.name === md.machineOfChannel(md.axesIn(n, 2)));
    const raw = md.data.raw(`$MC_TRACYL_ROT_SIGN_IS_PLUS_${k}`);
    const sign = raw !== undefined && /^(FALSE|0)$/i.test(raw) ? 1 : -1;
    const tilt = tiltAxis(md, rot);
    if (rot && parallel && (tilt || Math.abs(parallel.dir[2]) > 0.999)) {
      const turn: RotaryAxis = { name: rot, dir: [0, 0, sign], offset: [0, 0, 0], zero: md.num(`$MC_TRACYL_ROT_AX_OFFSET_${k}`) };
      s.table = tilt ? [{ name: tilt.name, dir: UNIT[tilt.about]!, offset: [0, 0, 0], zero: 0 }, turn] : [turn];
      used.add(rot);
      if (tilt) used.add(tilt.name);
      // The TRACYL data describe the machine with C along `parallel`: the tilt that lays the
      // table's Z there takes the radial and parallel directions into the table's frame.
      const angle = tilt ? tiltTo(tilt.about, parallel.dir) : 0;
      if (s.cylinder && angle !== null) {
        s.cylinder = { radial: rotateAbout(tilt?.about ?? 0, -angle, s.cylinder.radial), parallel: rotateAbout(tilt?.about ?? 0, -angle, s.cylinder.parallel) };
      }
      const carried = tilt ? ` carried by ${tilt.name}` : "";
      const along = tilt && angle !== null ? `, ${rot} along ${parallel.letter} at ${tilt.name} ${angle}°` : "";
      s.summary = `${linear.length}-axis mill, cylinder on ${rot}${carried} (TRACYL, data set ${n}${along})`;
    }
  }

  if (kind === "lathe") {
    // The axis that turns the workpiece: the rotary axis of TRANSMIT/TRACYL, else the first
    // spindle ($MA_SPIND_ASSIGN_TO_MACHAX = 1), else the first rotary axis.
    const polar = trafos.find(([, t]) => isTransmit(t) || isTracyl(t));
    const fromTrafo = polar ? md.machineOfChannel(md.axesIn(polar[0], 1)) : null;
    const main = rotary.find((a) => md.axis(a, "$MA_SPIND_ASSIGN_TO_MACHAX") === 1);
    s.spindle = fromTrafo ?? main ?? rotary[0] ?? null;
    if (polar) {
      const kind = isTransmit(polar[1]) ? "TRANSMIT" : "TRACYL";
      const k = md.ordinal(polar[0], isTransmit(polar[1]) ? isTransmit : isTracyl);
      const raw = md.data.raw(`$MC_${kind}_ROT_SIGN_IS_PLUS_${k}`);
      if (raw !== undefined && /^(FALSE|0)$/i.test(raw)) s.spindleSign = 1;
    }
    if (s.spindle) used.add(s.spindle);
    const names = trafos
      .map(([, t]) => (isTransmit(t) ? "TRANSMIT" : isTracyl(t) ? "TRACYL" : isTraang(t) ? "TRAANG" : t === 8192 ? "TRACON" : ""))
      .filter(Boolean);
    s.summary = `lathe${s.spindle ? `, workpiece on ${s.spindle}` : ""}${names.length ? ` (${[...new Set(names)].join(", ")})` : ""}`;
  } else if (!s.summary) {
    s.summary = `${linear.length}-axis mill`;
  }
  // The unrolled path is wrapped in the workpiece frame only where that frame turns with the
  // TRACYL rotary axis: a lathe's spindle, or the cylinder axis built above on a mill.
  const tracylRot = tracyl ? md.machineOfChannel(md.axesIn(tracyl[0], 1)) : null;
  const turnsWithTracyl = kind === "lathe" ? s.spindle === tracylRot : s.table.at(-1)?.name === tracylRot;
  if (!turnsWithTracyl) s.cylinder = null;
  s.otherRotary = rotary.filter((a) => !used.has(a));
  return s;
}

/**
 * The tilting axis of a TRACYL/TRANSMIT rotary table (engine channel/stock_table.rs): the
 * first channel axis named A (about machine X) or B (about Y) that is rotary, no spindle and
 * not the table's own rotary axis `rot`.
 */
function tiltAxis(md: Md, rot: string | null): { name: string; about: 0 | 1 } | null {
  const defaults = ["X", "Y", "Z", "A", "B", "C", "U", "V"];
  for (let k = 1; k <= 20; k++) {
    const name = md.machineOfChannel(k);
    if (!name || name === rot || !md.axisFlag(name, "$MA_IS_ROT_AX")) continue;
    if ((md.axis(name, "$MA_SPIND_ASSIGN_TO_MACHAX") ?? 0) > 0) continue;
    const chan = md.data.raw("$MC_AXCONF_CHANAX_NAME_TAB", String(k - 1))?.replace(/"/g, "") ?? defaults[k - 1];
    if (chan === "A") return { name, about: 0 };
    if (chan === "B") return { name, about: 1 };
  }
  return null;
}

/** `v` turned right-handedly by `deg` degrees about machine axis `about` (0 X, 1 Y, 2 Z). */
export function rotateAbout(about: number, deg: number, v: Vec3): Vec3 {
  const [s, c] = [Math.sin((deg * Math.PI) / 180), Math.cos((deg * Math.PI) / 180)];
  const [x, y, z] = v;
  const r: Vec3 = about === 0 ? [x, c * y - s * z, s * y + c * z] : about === 1 ? [c * x + s * z, y, -s * x + c * z] : [c * x - s * y, s * x + c * y, z];
  return r.map((e) => (Math.abs(e) < 1e-12 ? 0 : e)) as Vec3;
}

/** The tilt (degrees) about `about` that turns the table's +Z onto `dir`; null if none does. */
function tiltTo(about: 0 | 1, dir: Vec3): number | null {
  // R_x(θ)·Z = (0, −sin θ, cos θ); R_y(θ)·Z = (sin θ, 0, cos θ).
  if (Math.abs(dir[about]) > 1e-9) return null;
  const deg = about === 0 ? Math.atan2(-dir[1], dir[2]) : Math.atan2(dir[0], dir[2]);
  return Math.round(((deg * 180) / Math.PI) * 1e9) / 1e9;
}

export { add as addVec, scale as scaleVec };

/**
 * Names of the rotary axes of a machine, both as machine axes (MCS) and as channel axes
 * ($MC_AXCONF_CHANAX_NAME_TAB, for the WCS/BCS display), for showing degrees instead of mm.
 */
export function rotaryAxisNames(text: string, machineAxes: string[]): Set<string> {
  const md = new Md(new NcData(text), machineAxes);
  const out = new Set(machineAxes.filter((a) => md.axisFlag(a, "$MA_IS_ROT_AX")));
  for (let k = 1; k <= 20; k++) {
    const machine = md.machineOfChannel(k);
    if (!machine || !out.has(machine)) continue;
    const defaults = ["X", "Y", "Z", "A", "B", "C", "U", "V"];
    const name = md.data.raw("$MC_AXCONF_CHANAX_NAME_TAB", String(k - 1))?.replace(/"/g, "") ?? defaults[k - 1];
    if (name) out.add(name);
  }
  return out;
}

/** What the chain model needs of the machine data: axis names resolved, travel, the root name. */
export interface AxisLookup {
  /** The machine axis (MCS name) a `$NK_AXIS` entry follows: a machine or a channel axis name. */
  machineAxis(name: string): string | null;
  /** Software limits of a machine axis (a default span when none are set). */
  travel(machineAxis: string): [number, number];
  /** `$MN_ROOT_KIN_ELEM_NAME` (default "ROOT"). */
  rootName: string;
  /** Whether the machine data defines an orientation transformation of its own. */
  hasOrientationTrafo: boolean;
}

export function axisLookup(text: string, machineAxes: string[]): AxisLookup {
  const md = new Md(new NcData(text), machineAxes);
  const defaults = ["X", "Y", "Z", "A", "B", "C", "U", "V"];
  return {
    machineAxis(name) {
      if (machineAxes.includes(name)) return name;
      for (let k = 1; k <= 20; k++) {
        const chan = md.data.raw("$MC_AXCONF_CHANAX_NAME_TAB", String(k - 1))?.replace(/"/g, "") ?? defaults[k - 1];
        if (chan === name) return md.machineOfChannel(k);
      }
      return null;
    },
    travel(axis) {
      const lo = travel(md.axis(axis, "$MA_POS_LIMIT_MINUS"), -DEFAULT_TRAVEL);
      const hi = travel(md.axis(axis, "$MA_POS_LIMIT_PLUS"), DEFAULT_TRAVEL);
      return [Math.min(lo, hi), Math.max(lo, hi)];
    },
    rootName: md.data.raw("$MN_ROOT_KIN_ELEM_NAME")?.replace(/"/g, "") || "ROOT",
    hasOrientationTrafo: md.trafos().some(([, t]) => isOrientationTrafo(t)),
  };
}

// Wire types of the NCTwin server (see /api/v1/openapi.json).

export type ChannelStatus = "idle" | "running" | "stopped" | "alarm";
export type OpMode = "JOG" | "MDA" | "AUTO";
export type Pace = "realtime" | "fast";

/** Axis name -> value (mm or degrees), in the machine's axis order. */
export type AxisValues = Record<string, number>;

export interface Positions {
  machine: AxisValues; // MCS: every machine axis
  basic: AxisValues; // BCS: channel axes by program name
  workpiece: AxisValues; // WCS
}

export interface Alarm {
  number: number;
  message: string;
  line?: number | null;
}

export interface Block {
  line: number; // 1-based line in the text of the program the block is in
  text: string;
  program?: string | null; // the subprogram the block is in; null: the main program
}

export interface Transformation {
  name: string;
  type: number;
  index: number;
}

export interface State {
  status: ChannelStatus;
  mode: OpMode;
  time: number;
  tick: number;
  positions: Positions;
  orientation?: [number, number, number] | null;
  transformation?: Transformation | null;
  block?: Block | null;
  alarms: Alarm[];
  /** Tool in the spindle (T, D, its $TC_TP2 name) and the programmed (prepared) tool. */
  tool: { t: number; d: number; name: string; prepared: number };
  path_velocity: number;
  /** Counts the programs the channel loaded: when it changes, the active program is another. */
  program_serial?: number;
  /** Path length still to go of the block in execution (mm). */
  distance_to_go?: number;
  /** Programmed path feed of the block in execution (mm/min); null for rapid or no motion. */
  programmed_feed?: number | null;
  /** The program stands at a preprocessing stop waiting for the main run (absent: no). */
  preprocessing_stop_wait?: boolean;
  /** Workpiece counters ($AC_REQUIRED_PARTS, $AC_TOTAL_PARTS, $AC_ACTUAL_PARTS, $AC_SPECIAL_PARTS). */
  parts?: { required: number; total: number; actual: number; special: number };
  /** Program runtimes in seconds ($AC_OPERATING_TIME, $AC_CYCLE_TIME, $AC_CUTTING_TIME). */
  runtimes?: { operating: number; cycle: number; cutting: number };
  spindles: Record<string, number>;
  /** Each spindle's mode (M3/M4/M5/SPOS), angle in degrees and master flag, by the names of `spindles`. */
  spindle_info?: Record<string, SpindleInfo>;
  /** Axes travelling on their own interpolators (POS/POSA/POSP, command axes); absent when none. */
  positioning?: PositioningState[];
  /** The program's last MSG text. */
  message?: string | null;
  overrides: Overrides;
  single_block: boolean;
  optional_stop: boolean;
  /** Dry-run feed (DRY) selected. */
  dry_run?: boolean;
  /** Active skip levels (SKP), ascending; `/` is level 0. */
  skip_levels?: number[];
  /** Active G functions of the block in execution, one per displayed G group. */
  gcodes: string[];
  /** Reference point state by machine axis name. */
  referenced?: Record<string, boolean>;
  /** The program was interrupted and axes moved by JOG: NC start repositions first (REPOS). */
  repos_pending?: boolean;
  /** Active synchronized actions, by ID then block-modal (absent when none). */
  synchronized_actions?: SyncActionState[];
  /** Material removal: volumes and checks (absent without a blank). */
  stock?: StockSummary;
}

/** A check of material removal: rapid_into_stock, no_spindle, depth_of_cut or holder_collision. */
export interface StockWarning {
  check: string;
  line: number;
  volume: number;
  depth: number;
  /** Where the segment that cut began (tool tip, BCS mm). */
  position: [number, number, number];
}

/** The state's stock summary (GET .../stock for the list of checks). */
export interface StockSummary {
  model: "milling" | "turning";
  resolution: number;
  initial_volume: number;
  volume: number;
  removed: number;
  warnings: number;
  last_warning: StockWarning | null;
  /** Grows with every cut: the tiles changed since the version shown are fetched again. */
  version: number;
  /**
   * Where the stock's frame lies in the machine's Cartesian frame now, rows of [R | t]
   * (machine = R·p + t): the pose of the table carrying the blank; null (or absent, an older
   * server) where the blank does not move.
   */
  frame?: [number, number, number, number][] | null;
}

/** A positioning axis: machine axis name, end point (null: endless MOV), mm/min or deg/min. */
export interface PositioningState {
  axis: string;
  target: number | null;
  velocity: number;
  kind: "POS" | "POSA" | "POSP" | "OS" | "command" | "MOV";
  waiting: boolean;
}

/** A synchronized action as the state lists it. */
export interface SyncActionState {
  id: number | null;
  kind: "block" | "modal" | "static";
  trigger: string;
  condition: string;
  fired: boolean;
  locked: boolean;
  line: number;
}

/** GET/PUT .../io: the inputs and outputs, element 0 is signal 1. */
export interface IoImage {
  inputs: boolean[];
  outputs: boolean[];
  analog_inputs: number[];
  analog_outputs: number[];
  /** The PLC data area ($A_DBB[0]..) up to its last non-zero byte. */
  plc_data: number[];
}

/** PUT .../io: signals to change. */
export interface IoChange {
  inputs?: { signal: number; value: boolean }[];
  analog_inputs?: { signal: number; value: number }[];
  plc_data?: { offset: number; bytes: number[] }[];
}

/** Override switches in percent. */
export interface Overrides {
  feed: number; // 0..120
  rapid: number; // 0..100
  spindle: number; // 50..120
}

export interface ProgramOptions {
  single_block?: boolean;
  optional_stop?: boolean;
  dry_run?: boolean;
  /** The active skip levels 0..9 (`[]`: none). */
  skip_levels?: number[];
}

/** One datum of the server's machine-data registry. */
export interface MachineDatumDef {
  name: string; // "$MA_MAX_AX_VELO"
  number: number;
  scope: "nck" | "channel" | "axis";
  kind: "bool" | "int" | "real" | "string";
  len: number;
  defaults: string[]; // per element, in NC data syntax
  min?: number | null;
  max?: number | null;
}

export interface MachineSummary {
  id: string;
  name: string;
  description: string;
}

export interface MachineDetail extends MachineSummary {
  machine_data: string; // the preset as NC data text
}

export interface SessionSummary {
  id: string;
  machine: string;
  status: ChannelStatus;
  mode: OpMode;
}

export interface Session {
  id: string;
  machine: string;
  state: State;
}

export interface StoredProgram {
  name: string;
  size: number;
}

/** Answer of `POST /sessions/{id}/program-archive`: the programs stored (names with their
 * directory when the archive gave one), the NC data sections loaded and the sections skipped. */
export interface ArchiveImport {
  programs: { name: string; type: string; directory: string; size: number }[];
  nc_data: { name: string; line: number }[];
  skipped: { name: string; line: number; reason: string }[];
}

export interface Diagnostic {
  line: number;
  column?: number | null;
  /** The alarm the control would give (12080 syntax, 12550 unknown name, ...), when known. */
  alarm?: number | null;
  message: string;
}

/** An event message of the stream: {"type": "event", "event": "...", ...details}. */
export interface StreamEvent {
  type: "event";
  event: string;
  [detail: string]: unknown;
}

export interface JogCommand {
  axis: string;
  direction: 1 | -1;
  increment?: number;
  rapid?: boolean;
}

/** Body of POST .../swivel: the CYCLE800 parameters by name. */
export interface SwivelCommand {
  data_set?: string;
  retract: number;
  additive: boolean;
  tracking: boolean;
  mode: "axis_by_axis" | "solid_angle" | "projection_angle" | "direct";
  sequence: string;
  x0: number;
  y0: number;
  z0: number;
  a: number;
  b: number;
  c: number;
  x1: number;
  y1: number;
  z1: number;
  direction: 1 | -1;
  wait: boolean;
}

/** Who holds control of a session (GET .../control). */
export interface ControlState {
  auth: boolean; // the server requires tokens
  role: "owner" | "operator" | "observer"; // the caller's
  holder?: "owner" | "operator" | "observer" | null;
  you_hold_control: boolean;
}

/** Body of POST .../preview: a program text or a stored program's name. */
export interface PreviewRequest {
  program?: string;
  name?: string;
  /** The program the channel runs or ran last (GET .../active-program). */
  active?: boolean;
  max_points?: number;
  max_time?: number;
}

/** The programmed toolpath of a preview run (throwaway copy of the channel, fast pace). */
export interface PreviewResponse {
  axes: [string, string, string];
  points: [number, number, number][]; // WCS
  basic: [number, number, number][]; // BCS
  lines: number[];
  /** Per point: the program its line is in (0 the main program, k `programs[k-1]`). */
  line_program?: number[];
  /** The subprograms the path passed through, by stored name. */
  programs?: string[];
  /** Per point: the TRACYL working diameter while TRACYL was active (unrolled Y), else null. */
  tracyl_diameter?: (number | null)[];
  /** Per point: the unit tool direction (tip → holder) in the BCS under TRAORI, else null. */
  tool_direction?: ([number, number, number] | null)[];
  /** Where an axis reached its velocity or acceleration limit in feed motion (first 200). */
  limit_hits?: LimitHit[];
  limit_hits_total?: number;
  /** The blank the program defined with WORKPIECE(...) (BCS box; turned: a cylinder about Z). */
  blank?: { turning: boolean; min: [number, number, number]; max: [number, number, number] } | null;
  outcome: "ended" | "alarm" | "limit";
  alarm?: Alarm | null;
  time: number;
  samples: number;
}

/** An axis at its velocity or acceleration limit in a preview. */
export interface LimitHit {
  axis: string;
  kind: "velocity" | "acceleration";
  value: number;
  limit: number;
  line: number;
  /**
   * Tool tip on the workpiece (geometry axes as the preview's `axes`): the BCS, or on a table
   * turned without TRAORI the tip through the kinematics; under TRACYL unrolled.
   */
  basic: [number, number, number];
  /** The TRACYL working diameter when the hit was under TRACYL (`basic` is unrolled). */
  tracyl_diameter?: number | null;
  /** false: a rotary axis the kinematics do not describe had turned the workpiece. */
  exact?: boolean;
  time: number;
}

/** GET .../active-swivel: the active swivel data set, its angles and the turned WCS. */
export interface ActiveSwivel {
  /** 0: no swivel data set active. */
  data_set: number;
  name: string;
  /** Rotary axes 1 and 2 of the data set in degrees ($P_TCANG[1], [2]). */
  axis_angles: [number, number];
  /** The swivelled plane's rotation about X, Y, Z in degrees. */
  plane: [number, number, number];
  /** Unit directions of WCS X, Y, Z in the BCS. */
  wcs_axes: [[number, number, number], [number, number, number], [number, number, number]];
}

/**
 * GET .../path-history: the executed path since the session started (the tool tip on the
 * workpiece, thinned by geometry to 0.01 mm).
 */
export interface PathHistory {
  axes: [string, string, string];
  points: [number, number, number][];
  lines: number[];
  /** Per point: the TRACYL working diameter (the point is unrolled), else null. */
  tracyl_diameter?: (number | null)[];
  /** Per point: false where the table was turned by axes the kinematics do not describe. */
  exact?: boolean[];
  halvings: number;
  recorded: number;
}

/** One link of GET .../frames: a frame of the active chain as frame data. */
export interface FrameLink {
  name: string;
  neutral: boolean;
  trans: number[];
  rot: [number, number, number] | null;
  scale: number[];
  mirror: boolean[];
}

/** GET .../frames: the active frame chain (BCS towards WCS), the total last. */
export interface FrameChain {
  axes: string[];
  links: FrameLink[];
}

/** One spindle in the state's `spindle_info`. */
export interface SpindleInfo {
  number: number;
  speed: number;
  mode: "M3" | "M4" | "M5" | "SPOS";
  position: number;
  master: boolean;
  /** The gear stage engaged (M40..M45); null without gear stages. Absent from older servers. */
  gear?: number | null;
  /** The spindle load symbol: the master spindle cuts (feed motion removing stock). */
  cutting?: boolean;
}

/** One level of the call stack of the block in execution (program null: the main program). */
export interface CallLevel {
  program: string | null;
  line: number;
}

/** GET .../active-program: the channel's loaded program and a range of its lines. */
export interface ActiveProgramRange {
  serial: number;
  name: string | null;
  directory: string | null;
  mode: OpMode;
  sha256: string;
  line_count: number;
  bytes: number;
  /** The program the lines are from (null: the main program). */
  program: string | null;
  program_line_count: number;
  from: number;
  lines: string[];
  call_stack: CallLevel[];
}

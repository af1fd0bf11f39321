// REST client for the NCTwin server (prefix /api/v1, JSON in and out).

import { identityHeaders, viewOnly } from "./identity";
import { rememberTokens, sessionOfPath, tokenFor, type Tokens } from "./tokens";
import type {
  ActiveProgramRange,
  ActiveSwivel,
  ArchiveImport,
  ControlState,
  Diagnostic,
  FrameChain,
  IoChange,
  IoImage,
  JogCommand,
  MachineDatumDef,
  MachineDetail,
  MachineSummary,
  OpMode,
  PathHistory,
  PreviewRequest,
  PreviewResponse,
  Overrides,
  Pace,
  ProgramOptions,
  Session,
  SessionSummary,
  State,
  StoredProgram,
  SwivelCommand,
} from "./types";

const BASE = "/api/v1";

/** An error answer of the server ({"error", "line"?}) or a network failure (status 0). */
export class ApiError extends Error {
  readonly status: number;
  readonly line: number | null;

  constructor(status: number, error: string, line: number | null = null) {
    // "line 3: ..." unless the server's text names the line already.
    const named = line != null && new RegExp(`\\bline ${line}\\b`).test(error);
    super(line != null && !named ? `line ${line}: ${error}` : error);
    this.name = "ApiError";
    this.status = status;
    this.line = line;
  }
}

/** `tokenOf`: the session whose token to present when the path names none. */
export async function request<T>(method: string, path: string, body?: unknown, tokenOf?: string | null): Promise<T> {
  const headers: Record<string, string> = { Accept: "application/json", ...identityHeaders() };
  const session = sessionOfPath(path) ?? tokenOf;
  const token = session ? tokenFor(session) : undefined;
  if (token) headers.Authorization = `Bearer ${token}`;
  const init: RequestInit = { method, headers };
  if (body instanceof Blob) {
    // A file as it is (an archive: the server detects its encoding).
    headers["Content-Type"] = "text/plain";
    init.body = body;
  } else if (body !== undefined) {
    headers["Content-Type"] = "application/json";
    init.body = JSON.stringify(body);
  }
  let res: Response;
  try {
    res = await fetch(BASE + path, init);
  } catch (e) {
    throw new ApiError(0, `server not reachable (${(e as Error).message})`);
  }
  const text = await res.text();
  let data: unknown = null;
  if (text) {
    try {
      data = JSON.parse(text);
    } catch {
      data = text;
    }
  }
  if (!res.ok) {
    const obj = data && typeof data === "object" ? (data as { error?: unknown; line?: unknown }) : null;
    const error =
      (obj && typeof obj.error === "string" && obj.error) ||
      (typeof data === "string" && data.trim()) ||
      `${res.status} ${res.statusText}`;
    const line = obj && typeof obj.line === "number" ? obj.line : null;
    throw new ApiError(res.status, error, line);
  }
  return data as T;
}

const s = (id: string) => `/sessions/${encodeURIComponent(id)}`;
const p = (id: string, name: string) => `${s(id)}/programs/${encodeURIComponent(name)}`;

export const api = {
  machines: () => request<MachineSummary[]>("GET", "/machines"),
  machine: (id: string) => request<MachineDetail>("GET", `/machines/${encodeURIComponent(id)}`),

  /** With `--auth required` the server lists the sessions of the token presented (`tokenOf`'s). */
  sessions: (tokenOf?: string | null) => request<SessionSummary[]>("GET", "/sessions", undefined, tokenOf),
  session: (id: string) => request<Session>("GET", s(id)),
  createSession: async (machine: string, machineData?: string) => {
    const created = await request<Session & { tokens?: Tokens }>(
      "POST",
      "/sessions",
      machineData ? { machine, machine_data: machineData } : { machine },
    );
    if (created.tokens) rememberTokens(created.id, created.tokens);
    return created;
  },
  deleteSession: (id: string) => request<null>("DELETE", s(id)),

  state: (id: string) => request<State>("GET", `${s(id)}/state`),
  run: (id: string, program: string, pace: Pace, name?: string) =>
    request<State>("POST", `${s(id)}/run`, name ? { program, pace, name } : { program, pace }),
  /** Runs the stored program `name` in AUTO (its text is not sent). */
  runStored: (id: string, name: string, pace: Pace) => request<State>("POST", `${s(id)}/run`, { name, pace }),
  /** Lines `from`.. of the loaded program, or of `program` (a subprogram of its call stack). */
  activeProgram: (id: string, from = 1, count = 1, program?: string | null) => {
    const q = new URLSearchParams({ from: String(from), count: String(count) });
    if (program) q.set("program", program);
    return request<ActiveProgramRange>("GET", `${s(id)}/active-program?${q}`);
  },
  /** NC start; `repos`: where and how a repositioning after JOG returns (RMI.., REPOSL..). */
  start: (id: string, pace: Pace, repos?: { repos: string; approach: string; disr?: number } | null) =>
    request<State>("POST", `${s(id)}/start`, { pace, ...(repos ?? {}) }),
  stop: (id: string) => request<State>("POST", `${s(id)}/stop`, {}),
  reset: (id: string) => request<State>("POST", `${s(id)}/reset`, {}),
  cancel: (id: string) => request<State>("POST", `${s(id)}/cancel`, {}),
  mda: (id: string, program: string, pace: Pace) => request<State>("POST", `${s(id)}/mda`, { program, pace }),
  setMode: (id: string, mode: OpMode) => request<State>("PUT", `${s(id)}/mode`, { mode }),
  jog: (id: string, jog: JogCommand) => request<State>("POST", `${s(id)}/jog`, jog),
  swivel: (id: string, swivel: SwivelCommand) => request<State>("POST", `${s(id)}/swivel`, swivel),
  jogStop: (id: string) => request<State>("POST", `${s(id)}/jog/stop`, {}),
  /** Ref. point: references every unreferenced axis (JOG mode, reset state). */
  reference: (id: string) => request<State>("POST", `${s(id)}/reference`, {}),
  /** Handwheel detents on `axis` (INC1..INC1000 per detent). */
  handwheel: (id: string, hw: { axis: string; pulses: number; inc: number; coordinates: string }) =>
    request<State>("POST", `${s(id)}/jog/handwheel`, hw),
  /** Set WO: the active work offset so that `axis` reads `value` in the WCS. */
  setWorkOffset: (id: string, axis: string, value: number) => request<State>("POST", `${s(id)}/set-wo`, { axis, value }),
  setOverrides: (id: string, o: Partial<Overrides>) => request<State>("PUT", `${s(id)}/overrides`, o),
  setOptions: (id: string, o: ProgramOptions) => request<State>("PUT", `${s(id)}/options`, o),
  /** Workpiece counts (required, total, actual, special); absent ones keep their value. */
  setParts: (id: string, parts: Partial<Record<"required" | "total" | "actual" | "special", number>>) =>
    request<State>("PUT", `${s(id)}/parts`, parts),
  io: (id: string) => request<IoImage>("GET", `${s(id)}/io`),
  setIo: (id: string, change: IoChange) => request<IoImage>("PUT", `${s(id)}/io`, change),

  machineData: (id: string) => request<{ text: string }>("GET", `${s(id)}/machine-data`),
  /** The active frame chain link by link and its total. */
  frames: (id: string) => request<FrameChain>("GET", `${s(id)}/frames`),
  /** The chain data ($NK_/$NT_) as a part program (plain text). */
  kinematicChains: (id: string) => request<string>("GET", `${s(id)}/kinematic-chains`),
  putMachineData: (id: string, text: string) => request<State>("PUT", `${s(id)}/machine-data`, { text }),
  machineDataDefinitions: () => request<MachineDatumDef[]>("GET", "/machine-data/definitions"),

  programs: (id: string) => request<StoredProgram[]>("GET", `${s(id)}/programs`),
  program: (id: string, name: string) => request<{ text: string }>("GET", p(id, name)),
  saveProgram: (id: string, name: string, text: string) => request<unknown>("PUT", p(id, name), { text }),
  deleteProgram: (id: string, name: string) => request<unknown>("DELETE", p(id, name)),
  /** Stores every program of an archive file (`%_N_NAME_MPF` headers), all or nothing. */
  importArchive: (id: string, file: Blob) => request<ArchiveImport>("POST", `${s(id)}/program-archive`, file),
  control: (id: string) => request<ControlState>("GET", `${s(id)}/control`),
  viewers: (id: string) => request<{ streams: number }>("GET", `${s(id)}/viewers`),
  takeControl: (id: string) => request<ControlState>("POST", `${s(id)}/control/take`, {}),
  releaseControl: (id: string) => request<ControlState>("POST", `${s(id)}/control/release`, {}),

  preview: (id: string, body: PreviewRequest) => request<PreviewResponse>("POST", `${s(id)}/preview`, body),
  /** The active swivel (CYCLE800/TCARR data set, angles, the WCS directions). */
  activeSwivel: (id: string) => request<ActiveSwivel>("GET", `${s(id)}/active-swivel`),
  /** The executed path since the session started (BCS, thinned by the server). */
  pathHistory: (id: string) => request<PathHistory>("GET", `${s(id)}/path-history`),
  check: (id: string, program: string) =>
    request<{ diagnostics: Diagnostic[] }>("POST", `${s(id)}/check`, { program }),
};

/** WebSocket address of a session's stream. */
export function streamUrl(id: string, periodMs = 50): string {
  const proto = location.protocol === "https:" ? "wss:" : "ws:";
  const token = tokenFor(id);
  const auth = token ? `&token=${encodeURIComponent(token)}` : "";
  const watch = viewOnly() ? "&view_only=1" : "";
  return `${proto}//${location.host}${BASE}${s(id)}/stream?period_ms=${periodMs}${auth}${watch}`;
}

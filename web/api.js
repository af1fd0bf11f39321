// REST client for the NCTwin server (prefix /api/v1, JSON in and out).

const BASE = "/api/v1";

/** An error answer of the server ({"error", "line"?}) or a network failure. */
export class ApiError extends Error {
  constructor(status, error, line = null) {
    // "line 3: ..." unless the server's text names the line already.
    const named = line != null && new RegExp(`\\bline ${line}\\b`).test(error);
    super(line != null && !named ? `line ${line}: ${error}` : error);
    this.name = "ApiError";
    this.status = status; // 0 when the server could not be reached
    this.line = line;
  }
}

async function request(method, path, body) {
  const init = { method, headers: { Accept: "application/json" } };
  if (body !== undefined) {
    init.headers["Content-Type"] = "application/json";
    init.body = JSON.stringify(body);
  }
  let res;
  try {
    res = await fetch(BASE + path, init);
  } catch (e) {
    throw new ApiError(0, `server not reachable (${e.message})`);
  }
  const text = await res.text();
  let data = null;
  if (text) {
    try {
      data = JSON.parse(text);
    } catch {
      data = text;
    }
  }
  if (!res.ok) {
    const error =
      (data && typeof data === "object" && data.error) ||
      (typeof data === "string" && data.trim()) ||
      `${res.status} ${res.statusText}`;
    const line = data && typeof data === "object" && data.line != null ? data.line : null;
    throw new ApiError(res.status, error, line);
  }
  return data;
}

const s = (id) => `/sessions/${encodeURIComponent(id)}`;

export const api = {
  health: () => request("GET", "/health"),
  machines: () => request("GET", "/machines"),
  createSession: (machine) => request("POST", "/sessions", machine ? { machine } : {}),
  deleteSession: (id) => request("DELETE", s(id)),
  state: (id) => request("GET", `${s(id)}/state`),
  run: (id, program, pace = "realtime") => request("POST", `${s(id)}/run`, { program, pace }),
  start: (id, pace = "realtime") => request("POST", `${s(id)}/start`, { pace }),
  stop: (id) => request("POST", `${s(id)}/stop`, {}),
  reset: (id) => request("POST", `${s(id)}/reset`, {}),
  cancel: (id) => request("POST", `${s(id)}/cancel`, {}),
  mda: (id, program) => request("POST", `${s(id)}/mda`, { program }),
  setMode: (id, mode) => request("PUT", `${s(id)}/mode`, { mode }),
  /** jog: {axis, direction: 1|-1, increment?, rapid?} */
  jog: (id, jog) => request("POST", `${s(id)}/jog`, jog),
  jogStop: (id) => request("POST", `${s(id)}/jog/stop`, {}),
};

/** WebSocket address of a session's state stream. */
export function streamUrl(id, periodMs = 50) {
  const proto = location.protocol === "https:" ? "wss:" : "ws:";
  return `${proto}//${location.host}${BASE}${s(id)}/stream?period_ms=${periodMs}`;
}

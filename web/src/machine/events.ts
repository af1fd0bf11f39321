// The event log: what the stream reported (alarms, block changes, program end, mode changes),
// newest first, with the simulated time it arrived at.

import type { StreamEvent } from "../api/types";
import { byId, el, fmt } from "../core/dom";
import type { SessionController } from "../core/session";

const MAX_EVENTS = 200;

/** The action log's commands in the words of the screen. */
const ACTIONS: Record<string, string> = {
  "POST start": "Cycle start",
  "POST stop": "Cycle stop",
  "POST reset": "Reset",
  "POST cancel": "cancel alarm",
  "PUT mode": "operating mode",
  "POST run": "program start (Execute)",
  "POST mda": "MDA start",
  "POST jog": "JOG",
  "POST jog/stop": "JOG stop",
  "POST jog/handwheel": "handwheel",
  "POST reference": "Ref. point",
  "POST set-wo": "Set WO",
  "PUT overrides": "override",
  "PUT options": "program control (SBL/M01)",
  "PUT machine-data": "machine data",
  "PUT tools": "tool data",
  "POST swivel": "swivel (CYCLE800)",
  "POST search": "block search",
};

function describe(ev: StreamEvent): string {
  const { type: _type, event: _event, ...rest } = ev;
  if (ev.event === "operator_action") {
    const who = typeof rest.name === "string" && rest.name ? `${rest.name} (${String(rest.role)})` : String(rest.role);
    const action = String(rest.action ?? "");
    return `${who}: ${ACTIONS[action] ?? action}`;
  }
  const alarm = rest.alarm as { number?: number; message?: string; line?: number | null } | undefined;
  if (alarm && typeof alarm === "object") {
    return `${alarm.number}${alarm.line != null ? ` (line ${alarm.line})` : ""}: ${alarm.message ?? ""}`;
  }
  if (typeof rest.line === "number" && typeof rest.text === "string") return `line ${rest.line}: ${rest.text}`;
  const warning = rest.warning as { check?: string; line?: number; volume?: number; depth?: number } | undefined;
  if (warning && typeof warning === "object") {
    const what = (warning.check ?? "").replace(/_/g, " ");
    return `${what} at line ${warning.line}: ${fmt(warning.volume ?? 0, 1)} mm³, depth ${fmt(warning.depth ?? 0, 2)} mm`;
  }
  return Object.entries(rest)
    .map(([k, v]) => `${k}=${typeof v === "object" ? JSON.stringify(v) : String(v)}`)
    .join(" ");
}

export function mountEvents(session: SessionController): void {
  const list = byId("events");
  session.on("session", () => list.replaceChildren());
  session.on("event", (ev) => {
    const time = session.latest ? fmt(session.latest.time, 2) : "";
    const li = el("li", { "data-event": ev.event });
    li.append(
      el("span", { class: "event-time" }, time),
      el("span", { class: "event-name" }, ev.event.replace(/_/g, " ")),
      el("span", { class: "event-detail" }, describe(ev)),
    );
    list.prepend(li);
    while (list.children.length > MAX_EVENTS) list.lastElementChild?.remove();
  });
}

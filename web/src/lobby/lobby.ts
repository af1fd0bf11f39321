// The Sessions area, also the start page at `/`: the user's display name, machine presets,
// creating a session, and the class view: every running session with its status, alarms and
// current block, to join (drive), watch (view only) or end (after a confirmation).

import { api } from "../api/client";
import { displayName, setDisplayName, setViewOnly } from "../api/identity";
import { forgetTokens } from "../api/tokens";
import type { MachineSummary, SessionSummary, State } from "../api/types";
import { byId, el, setText } from "../core/dom";
import { clearMessage, showMessage } from "../core/message";
import type { SessionController } from "../core/session";
import { areaChanged, showArea } from "../ui/areas";

const REFRESH_MS = 2000;

export class Lobby {
  private machines: MachineSummary[] = [];
  private timer: ReturnType<typeof setInterval> | undefined;

  constructor(private readonly session: SessionController) {
    byId("new-session-form").addEventListener("submit", (ev) => {
      ev.preventDefault();
      void this.create();
    });
    byId("preset-select").addEventListener("change", () => this.describePreset());
    const name = byId<HTMLInputElement>("display-name");
    name.value = displayName();
    name.addEventListener("change", () => setDisplayName(name.value));
    byId("btn-sessions-refresh").addEventListener("click", () => void this.refresh());
    byId("sessions").addEventListener("click", (ev) => this.onListClick(ev));
    // Keep the list current while it is on screen.
    areaChanged.on("change", (area) => {
      clearInterval(this.timer);
      if (area !== "sessions") return;
      void this.refresh();
      this.timer = setInterval(() => void this.refresh(), REFRESH_MS);
    });
  }

  async loadMachines(preferred: string): Promise<void> {
    this.machines = await api.machines();
    const select = byId<HTMLSelectElement>("preset-select");
    select.replaceChildren(...this.machines.map((m) => el("option", { value: m.id }, m.name)));
    if (this.machines.some((m) => m.id === preferred)) select.value = preferred;
    this.describePreset();
  }

  /** Creates a session on the chosen preset and opens the machine screen on it. */
  async create(machine = byId<HTMLSelectElement>("preset-select").value): Promise<void> {
    const machineData = byId<HTMLTextAreaElement>("new-machine-data").value.trim();
    try {
      setDisplayName(byId<HTMLInputElement>("display-name").value);
      const created = await api.createSession(machine, machineData || undefined);
      clearMessage();
      setViewOnly(false);
      await this.session.attach(created.id, created.machine);
      showArea("machine");
    } catch (e) {
      showMessage(`new session: ${(e as Error).message}`);
    }
  }

  async refresh(): Promise<void> {
    let sessions: SessionSummary[];
    try {
      sessions = await api.sessions(this.session.id);
    } catch (e) {
      showMessage(`session list: ${(e as Error).message}`);
      return;
    }
    const names = new Map(this.machines.map((m) => [m.id, m.name]));
    // The class view: each session's alarms and current block from its state (a session whose
    // state this page may not read shows dashes).
    const states = await Promise.all(sessions.map((s) => api.state(s.id).catch((): State | null => null)));
    byId<HTMLTableElement>("sessions").tBodies[0]!.replaceChildren(
      ...sessions.map((s, i) => {
        const st = states[i];
        const tr = el("tr", { "data-session": s.id });
        if (s.id === this.session.id) tr.classList.add("attached");
        const status = el("td", {}, s.status);
        status.append(el("span", { class: "dot", "data-status": s.status }));
        const alarms = st?.alarms.map((a) => String(a.number)).join(", ") ?? "–";
        const alarmCell = el("td", { class: "class-alarms", title: st?.alarms.map((a) => `${a.number}: ${a.message}`).join("\n") ?? "" }, alarms);
        if (st?.alarms.length) alarmCell.classList.add("has-alarm");
        const block = st?.block ? `${st.block.line}: ${st.block.text}` : "–";
        const actions = el("td", { class: "actions" });
        actions.append(
          el("button", { type: "button", "data-open": s.id, "data-machine": s.machine, title: "Join: operate this session" }, s.id === this.session.id ? "Shown" : "Join"),
          el("button", { type: "button", "data-watch": s.id, "data-machine": s.machine, title: "Watch: view only, controls off" }, "Watch"),
          el("button", { type: "button", "data-delete": s.id, title: "End this session (asks first)" }, "End"),
        );
        tr.append(
          el("td", {}, s.id),
          el("td", {}, names.get(s.machine) ?? s.machine),
          el("td", {}, s.mode),
          status,
          alarmCell,
          el("td", { class: "class-block mono" }, block),
          actions,
        );
        return tr;
      }),
    );
  }

  private describePreset(): void {
    const id = byId<HTMLSelectElement>("preset-select").value;
    setText(byId("preset-description"), this.machines.find((m) => m.id === id)?.description ?? "");
  }

  private onListClick(ev: Event): void {
    const button = (ev.target as HTMLElement).closest<HTMLButtonElement>("button");
    if (!button) return;
    const { open, watch, machine, delete: del } = button.dataset;
    const target = open ?? watch;
    if (target && machine) {
      setDisplayName(byId<HTMLInputElement>("display-name").value);
      setViewOnly(watch !== undefined);
      void this.session.attach(target, machine).then(
        () => showArea("machine"),
        (e: Error) => showMessage(`session ${target}: ${e.message}`),
      );
    } else if (del) {
      if (!confirm(`End session ${del}? Its program, position and data are gone for everyone in it.`)) return;
      void api.deleteSession(del).then(
        () => {
          forgetTokens(del);
          return this.refresh();
        },
        (e: Error) => showMessage(`end session ${del}: ${e.message}`),
      );
    }
  }
}

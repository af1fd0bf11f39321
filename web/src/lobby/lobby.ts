// The Sessions area: machine presets, creating a session, and the list of running sessions
// to join or end.

import { api } from "../api/client";
import { forgetTokens } from "../api/tokens";
import type { MachineSummary, SessionSummary } from "../api/types";
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
      const created = await api.createSession(machine, machineData || undefined);
      clearMessage();
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
    byId<HTMLTableElement>("sessions").tBodies[0]!.replaceChildren(
      ...sessions.map((s) => {
        const tr = el("tr", { "data-session": s.id });
        if (s.id === this.session.id) tr.classList.add("attached");
        const status = el("td", {}, s.status);
        status.append(el("span", { class: "dot", "data-status": s.status }));
        const actions = el("td", { class: "actions" });
        actions.append(
          el("button", { type: "button", "data-open": s.id, "data-machine": s.machine }, s.id === this.session.id ? "Shown" : "Open"),
          el("button", { type: "button", "data-delete": s.id }, "End"),
        );
        tr.append(el("td", {}, s.id), el("td", {}, names.get(s.machine) ?? s.machine), el("td", {}, s.mode), status, actions);
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
    const { open, machine, delete: del } = button.dataset;
    if (open && machine) {
      void this.session.attach(open, machine).then(
        () => showArea("machine"),
        (e: Error) => showMessage(`session ${open}: ${e.message}`),
      );
    } else if (del) {
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

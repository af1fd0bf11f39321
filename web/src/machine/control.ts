// Multi-user: how many clients watch the session; the caller's role and who holds control,
// with take/release, in the header; and links to share the session with an operator or an
// observer. Roles and control are only shown when the server requires tokens
// (`--auth required`); with auth off every client is the owner.

import { api } from "../api/client";
import { rememberTokens, tokensOf, type Role } from "../api/tokens";
import type { ControlState } from "../api/types";
import { byId, el, setText } from "../core/dom";
import { showMessage } from "../core/message";
import type { SessionController } from "../core/session";

const POLL_MS = 3000;

export class ControlView {
  private timer: ReturnType<typeof setInterval> | undefined;
  private state: ControlState | null = null;

  constructor(private readonly session: SessionController) {
    byId("btn-control").addEventListener("click", () => void this.toggle());
    session.on("session", () => void this.start());
    session.on("connection", (conn) => conn === "online" && this.session.id && void this.refreshViewers(this.session.id));
  }

  private async start(): Promise<void> {
    clearInterval(this.timer);
    this.state = null;
    this.render();
    await this.refresh();
    this.timer = setInterval(() => void this.refresh(), POLL_MS);
  }

  private async refreshViewers(id: string): Promise<void> {
    const node = byId("viewers");
    try {
      const { streams } = await api.viewers(id);
      node.hidden = false;
      node.dataset.count = String(streams);
      setText(node, `${streams} watching`);
    } catch {
      node.hidden = true; // a server without the endpoint
    }
  }

  private async refresh(): Promise<ControlState | null> {
    const id = this.session.id;
    if (!id) return null;
    void this.refreshViewers(id);
    if (this.state && !this.state.auth) return this.state; // nothing changes with auth off
    try {
      this.state = await api.control(id);
      // A token from a link is stored as an observer's until the server names its role.
      const tokens = tokensOf(id);
      const token = tokens.owner ?? tokens.operator ?? tokens.observer;
      if (token && !tokens[this.state.role]) rememberTokens(id, { [this.state.role]: token, observer: undefined });
    } catch {
      this.state = null;
    }
    this.render();
    return this.state;
  }

  private async toggle(): Promise<void> {
    const id = this.session.id;
    const st = this.state;
    if (!id || !st) return;
    try {
      this.state = st.you_hold_control ? await api.releaseControl(id) : await api.takeControl(id);
    } catch (e) {
      showMessage(`control: ${(e as Error).message}`);
    }
    this.render();
  }

  private render(): void {
    const st = this.state;
    const box = byId("control");
    box.hidden = !st?.auth;
    renderShare(this.session.id, st);
    if (!st?.auth) return;
    const holder = st.holder ? (st.holder === st.role ? "you" : st.holder) : "free";
    setText(byId("control-text"), `${st.role} · control: ${holder}`);
    box.dataset.control = st.you_hold_control ? "mine" : st.holder ? "other" : "free";
    const button = byId<HTMLButtonElement>("btn-control");
    button.hidden = st.role === "observer";
    setText(button, st.you_hold_control ? "Release" : "Take control");
  }
}

/** The Sessions area's share links (operator, observer) of the attached session, when known. */
function renderShare(id: string | null, st: ControlState | null): void {
  const panel = byId("share-panel");
  const tokens = id ? tokensOf(id) : {};
  const roles: Role[] = ["operator", "observer"];
  const known = roles.filter((r) => tokens[r]);
  panel.hidden = !id || !st?.auth || known.length === 0;
  if (panel.hidden || !id) return;
  byId("share-links").replaceChildren(
    ...known.map((role) => {
      const url = new URL(location.href);
      url.search = "";
      url.searchParams.set("session", id);
      url.searchParams.set("token", tokens[role]!);
      const row = el("label", { class: "stacked" }, `${role[0]!.toUpperCase()}${role.slice(1)} link`);
      row.append(el("input", { type: "text", readonly: "", value: url.toString(), "data-share": role }));
      return row;
    }),
  );
}

export function mountControl(session: SessionController): ControlView {
  return new ControlView(session);
}

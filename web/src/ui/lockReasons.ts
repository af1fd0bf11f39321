// Why the controls are off, in plain words: a watch link (view only), an observer's token, an
// operator while another role holds control (`--auth required`). Read from the page's view
// mode and the session's control state.

import { api } from "../api/client";
import { viewOnly } from "../api/identity";
import type { ControlState } from "../api/types";
import type { SessionController } from "../core/session";
import { lockControls } from "./lock";

const POLL_MS = 3000;

/** The reason for `control` (null: this page may drive). */
export function lockReasonOf(watching: boolean, control: ControlState | null): string | null {
  if (watching) return "View only: you are watching this session (watch link). Controls are off; Join it from the Sessions area to operate.";
  if (!control?.auth) return null;
  if (control.role === "observer") return "View only: you joined as an observer. Controls are off.";
  if (control.you_hold_control) return null;
  if (!control.holder) return "Nobody has control: press Take control in the header to operate.";
  const who = control.holder === "owner" ? "the trainer (owner)" : `the ${control.holder}`;
  return `Controls are off: ${who} has control. Take control once it is released.`;
}

export function mountLock(session: SessionController): void {
  let control: ControlState | null = null;
  let timer: ReturnType<typeof setInterval> | undefined;
  const apply = () => lockControls(session.id ? lockReasonOf(viewOnly(), control) : null);
  const poll = async () => {
    const id = session.id;
    if (!id) return;
    control = await api.control(id).catch(() => null);
    if (control && !control.auth) clearInterval(timer); // nothing changes with auth off
    apply();
  };
  session.on("session", () => {
    control = null;
    apply();
    clearInterval(timer);
    void poll();
    timer = setInterval(() => void poll(), POLL_MS);
  });
}

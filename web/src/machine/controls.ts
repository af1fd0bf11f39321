// Program control (Cycle start / Cycle stop / Reset, pace) and the MDA line.

import { api } from "../api/client";
import type { Pace } from "../api/types";
import { byId } from "../core/dom";
import type { SessionController } from "../core/session";
import { reposFields } from "../jog/jog";
import { selection } from "../program/selected";

function pace(): Pace {
  return byId<HTMLSelectElement>("pace").value === "fast" ? "fast" : "realtime";
}

/** Cycle start: continues a stopped program, otherwise loads and starts the selected one. */
function cycleStart(session: SessionController): void {
  const st = session.latest;
  if (st && st.status === "stopped" && st.mode === "AUTO") {
    // After JOG in the interrupted program: the REPOS choice of the JOG panel.
    const repos = st.repos_pending ? reposFields() : null;
    void session.act((id) => api.start(id, pace(), repos));
  } else if (st && st.mode === "MDA") {
    void session.act((id) => api.mda(id, selection.mdaText, pace()));
  } else {
    void session.act((id) => api.run(id, selection.current.text, pace()));
  }
}

export function mountControls(session: SessionController): void {
  byId("btn-cycle-start").addEventListener("click", () => cycleStart(session));
  byId("btn-cycle-stop").addEventListener("click", () => session.act((id) => api.stop(id)));
  byId("btn-reset").addEventListener("click", () => session.act((id) => api.reset(id)));

  byId("mda-form").addEventListener("submit", (ev) => {
    ev.preventDefault();
    const text = byId<HTMLInputElement>("mda-input").value.trim();
    if (!text) return;
    selection.setMda(text);
    void session.act((id) => api.mda(id, text, pace()));
  });
}

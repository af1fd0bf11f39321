// Program control (Cycle start / Cycle stop / Reset, pace) and the MDA line.

import { api } from "../api/client";
import type { Pace, State } from "../api/types";
import { byId, setText } from "../core/dom";
import { showMessage } from "../core/message";
import type { SessionController } from "../core/session";
import { reposFields } from "../jog/jog";
import { activeName, activeProgram } from "../program/active";
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
    const text = mdaBuffer();
    if (!text) {
      showMessage("MDA: the buffer is empty; enter blocks in the MDA panel first");
      return;
    }
    selection.setMda(text);
    void session.act((id) => api.mda(id, text, pace()));
  } else {
    const { name, text, stored } = selection.current;
    void session.act((id) => (stored ? api.runStored(id, name, pace()) : api.run(id, text, pace(), name)));
  }
}

/** The MDA buffer: the blocks typed in the MDA panel, else the ones sent last. */
function mdaBuffer(): string {
  return byId<HTMLTextAreaElement>("mda-input").value.trim() || selection.mdaText.trim();
}

/** What Cycle start will start now, named beside the key. */
export function cycleStartTarget(st: State | null): string {
  if (!st) return "";
  if (st.status === "running") return "running";
  if (st.status === "alarm") return "alarm: reset first";
  if (st.mode === "JOG") return st.status === "stopped" ? "JOG: select AUTO or MDA to continue" : "JOG: select AUTO or MDA";
  if (st.status === "stopped") return `continues ${activeName(activeProgram.meta)}`;
  if (st.mode === "MDA") {
    const first = mdaBuffer().split("\n")[0] ?? "";
    return first ? `starts MDA: ${first}` : "MDA buffer empty";
  }
  return `starts ${selection.current.name}`;
}

export function mountControls(session: SessionController): void {
  const target = byId("cycle-start-what");
  const show = () => setText(target, cycleStartTarget(session.latest));
  session.on("state", show);
  selection.on("change", show);
  selection.on("mda", show);
  activeProgram.on("change", show);
  const mda = byId<HTMLTextAreaElement>("mda-input");
  mda.addEventListener("input", show);
  // The MDA editor takes several blocks (Enter: a new line); Ctrl+Enter starts them.
  mda.addEventListener("keydown", (ev) => {
    if (ev.key === "Enter" && (ev.ctrlKey || ev.metaKey)) {
      ev.preventDefault();
      byId<HTMLFormElement>("mda-form").requestSubmit();
    }
  });
  byId("btn-cycle-start").addEventListener("click", () => cycleStart(session));
  byId("btn-cycle-stop").addEventListener("click", () => session.act((id) => api.stop(id)));
  byId("btn-reset").addEventListener("click", () => session.act((id) => api.reset(id)));

  byId("mda-form").addEventListener("submit", (ev) => {
    ev.preventDefault();
    const text = byId<HTMLTextAreaElement>("mda-input").value.trim();
    if (!text) return;
    selection.setMda(text);
    void session.act((id) => api.mda(id, text, pace()));
  });
}

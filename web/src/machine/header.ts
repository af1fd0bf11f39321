// The header line: session, machine, mode, channel status, newest alarm, stream connection.

import { api } from "../api/client";
import type { Connection } from "../api/stream";
import type { OpMode, State } from "../api/types";
import { byId, setText } from "../core/dom";
import type { SessionController } from "../core/session";
import { activeName, activeProgram } from "../program/active";
import { selection } from "../program/selected";

function renderState(st: State): void {
  const badge = byId("status");
  badge.dataset.status = st.status;
  setText(badge, st.status);

  for (const b of document.querySelectorAll<HTMLElement>("[data-set-mode]")) {
    b.classList.toggle("active", b.dataset.setMode === st.mode);
  }

  // Operate shows the newest alarm in the header on every screen.
  const line = byId("alarm-line");
  const newest = st.alarms.at(-1);
  line.hidden = !newest;
  setText(line, newest ? `${newest.number}  ${newest.message}` : "");
}

function renderConnection(conn: Connection): void {
  const node = byId("connection");
  node.dataset.conn = conn;
  setText(node, conn);
}

export function mountHeader(session: SessionController): void {
  session.on("session", (info) => {
    setText(byId("session-id"), info.id);
    setText(byId("machine-name"), info.machine.name);
  });
  session.on("state", renderState);
  session.on("connection", renderConnection);
  // The program the channel has loaded; the selection only until the channel has one.
  const showProgram = () => {
    const meta = activeProgram.meta;
    setText(byId("header-program"), meta ? activeName(meta) : `${selection.current.name} (selected)`);
  };
  selection.on("change", showProgram);
  activeProgram.on("change", showProgram);
  showProgram();

  for (const b of document.querySelectorAll<HTMLButtonElement>("[data-set-mode]")) {
    b.addEventListener("click", () => session.act((id) => api.setMode(id, b.dataset.setMode as OpMode)));
  }
}

// The alarm list: number, program line, text.

import { api } from "../api/client";
import type { Alarm } from "../api/types";
import { byId, el } from "../core/dom";
import type { SessionController } from "../core/session";

let shownKey = "";

function render(alarms: Alarm[]): void {
  const key = JSON.stringify(alarms);
  if (key === shownKey) return;
  shownKey = key;
  const table = byId<HTMLTableElement>("alarms");
  table.tBodies[0]!.replaceChildren(
    ...alarms.map((a) => {
      const tr = el("tr", { "data-alarm": String(a.number) });
      tr.append(
        el("td", { class: "num" }, String(a.number)),
        el("td", { class: "num" }, a.line != null ? String(a.line) : ""),
        el("td", {}, a.message),
      );
      return tr;
    }),
  );
  table.classList.toggle("has-alarms", alarms.length > 0);
}

export function mountAlarms(session: SessionController): void {
  session.on("state", (st) => render(st.alarms));
  byId("btn-cancel").addEventListener("click", () => session.act((id) => api.cancel(id)));
}

// The times and workpiece counter panel, as Operate's "Times, counter" window: the program
// runtimes ($AC_CYCLE_TIME, $AC_CUTTING_TIME, $AC_OPERATING_TIME) and the required and actual
// workpiece counts, which the operator sets between batches (PUT .../parts). The fields show
// the state's counts except while the operator edits them.

import { api } from "../api/client";
import type { State } from "../api/types";
import { byId, setText } from "../core/dom";
import type { SessionController } from "../core/session";
import { clockTime } from "./statusLine";

const FIELDS = ["required", "actual"] as const;

export function mountCounters(session: SessionController): void {
  const form = byId<HTMLFormElement>("parts-form");
  const input = (name: (typeof FIELDS)[number]) => byId<HTMLInputElement>(`parts-${name}`);
  let editing = false;
  form.addEventListener("focusin", () => {
    editing = true;
  });
  form.addEventListener("focusout", (e) => {
    if (!form.contains(e.relatedTarget as Node | null)) editing = false;
  });
  form.addEventListener("submit", (e) => {
    e.preventDefault();
    const body: Record<string, number> = {};
    for (const name of FIELDS) {
      const value = input(name).valueAsNumber;
      if (Number.isInteger(value)) body[name] = value;
    }
    editing = false;
    void session.act((id) => api.setParts(id, body));
  });
  session.on("state", (st: State) => {
    const t = st.runtimes;
    if (t) {
      setText(
        byId("runtimes"),
        `Cycle ${clockTime(t.cycle)} · Cutting ${clockTime(t.cutting)} · Operating ${clockTime(t.operating)}`,
      );
    }
    if (editing || !st.parts) return;
    for (const name of FIELDS) {
      const shown = String(st.parts[name]);
      if (input(name).value !== shown) input(name).value = shown;
    }
  });
}

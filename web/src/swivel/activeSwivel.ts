// The active swivel beside T, F, S (as Operate shows the active swivel data set): the data set's
// name and number, the positions of its rotary axes and the swivelled plane's rotation, or
// "none". Read from GET .../active-swivel when the session is attached or comes back, when the
// NC data change, and whenever the channel changes mode, status or program (a swivel only
// happens through a program or MDA block, CYCLE800 or TCARR, and a reset may deselect it).
// Listeners (the 3D view's WCS triad) get each new answer.

import { api } from "../api/client";
import type { ActiveSwivel, State } from "../api/types";
import { byId, fmt, setText } from "../core/dom";
import { Emitter } from "../core/emitter";
import type { SessionController } from "../core/session";
import { swivelDataSets } from "./swivel";

/** The rotary axis names of each swivel data set ($TC_CARR35/36), by data set number. */
export function carrierAxisNames(machineData: string): Map<number, [string, string]> {
  const out = new Map<number, [string, string]>();
  for (const m of machineData.matchAll(/^\s*\$TC_CARR(35|36)\[(\d+)\]\s*=\s*"([^"]*)"/gm)) {
    const n = Number(m[2]);
    const names = out.get(n) ?? ["1", "2"];
    names[m[1] === "35" ? 0 : 1] = (m[3] ?? "").trim() || names[m[1] === "35" ? 0 : 1]!;
    out.set(n, names);
  }
  return out;
}

/** The display text of an active swivel: "none", or name (number), axis angles and plane. */
export function swivelText(s: ActiveSwivel, axisNames?: [string, string]): string {
  if (s.data_set === 0) return "none";
  const [a1, a2] = axisNames ?? ["1", "2"];
  const title = s.name ? `${s.name} (${s.data_set})` : `TC${s.data_set}`;
  const axes = `${a1} ${fmt(s.axis_angles[0], 1)}° ${a2} ${fmt(s.axis_angles[1], 1)}°`;
  const turned = s.plane.some((v) => Math.abs(v) > 1e-6);
  const plane = turned ? `plane X ${fmt(s.plane[0], 1)}° Y ${fmt(s.plane[1], 1)}° Z ${fmt(s.plane[2], 1)}°` : "plane not turned";
  return `${title}: ${axes} · ${plane}`;
}

class ActiveSwivelStore extends Emitter<{ change: ActiveSwivel | null }> {
  current: ActiveSwivel | null = null;
}

/** The active swivel of the attached session (null before the first answer). */
export const activeSwivel = new ActiveSwivelStore();

export function mountActiveSwivel(session: SessionController): void {
  const row = byId("swivel-active-row");
  const text = byId("swivel-active");
  let names = new Map<number, [string, string]>();
  let key = "";
  let serial = 0;
  const show = () => {
    const s = activeSwivel.current;
    setText(text, s ? swivelText(s, names.get(s.data_set)) : "–");
    text.dataset.dataSet = String(s?.data_set ?? "");
  };
  const refresh = async () => {
    const id = session.id;
    if (!id) return;
    const mine = ++serial;
    try {
      const s = await api.activeSwivel(id);
      if (mine !== serial || id !== session.id) return;
      activeSwivel.current = s;
    } catch {
      if (mine !== serial) return;
      activeSwivel.current = null; // an older server, or the session is gone
    }
    show();
    activeSwivel.emit("change", activeSwivel.current);
  };
  const machine = (data: string) => {
    names = carrierAxisNames(data);
    row.hidden = swivelDataSets(data).length === 0;
    show();
  };
  session.on("session", (info) => {
    key = "";
    activeSwivel.current = null;
    machine(info.machine.machine_data);
  });
  session.on("machine", (info) => {
    machine(info.machine.machine_data);
    void refresh();
  });
  session.on("reconnected", () => void refresh());
  session.on("state", (st: State) => {
    const next = `${st.mode}|${st.status}|${st.program_serial ?? ""}`;
    if (next === key) return;
    key = next;
    void refresh();
  });
}

// The swivel form: CYCLE800's fields grouped as on the Operate screen (swivel data set,
// retraction, swivel mode and axis sequence, reference point, angles, zero point, direction),
// sent as POST .../swivel. The server runs the cycle as one MDA block and returns to JOG, also
// after an alarm (shown under the form with the reason; the alarm stays until RESET).
// The swivel data set is a list of the machine's `$TC_CARR` data sets (by `$TC_CARR34` name,
// else by number), the first one chosen; machines without swivel data do not show the screen.

import { api } from "../api/client";
import type { SwivelCommand } from "../api/types";
import { byId, el, setText } from "../core/dom";
import { showMessage } from "../core/message";
import type { SessionController } from "../core/session";

function command(form: HTMLFormElement): SwivelCommand {
  const data = new FormData(form);
  const num = (name: string): number => Number(data.get(name) ?? 0) || 0;
  const tc = String(data.get("data_set") ?? "").trim();
  return {
    ...(tc ? { data_set: tc } : {}),
    retract: num("retract"),
    additive: data.get("additive") === "on",
    tracking: data.get("tracking") === "on",
    mode: String(data.get("mode")) as SwivelCommand["mode"],
    sequence: String(data.get("sequence") ?? "XYZ"),
    x0: num("x0"),
    y0: num("y0"),
    z0: num("z0"),
    a: num("a"),
    b: num("b"),
    c: num("c"),
    x1: num("x1"),
    y1: num("y1"),
    z1: num("z1"),
    direction: num("direction") < 0 ? -1 : 1,
    wait: true,
  };
}

/** The swivel data sets of NC data text: number and `$TC_CARR34` name, in number order. */
export function swivelDataSets(machineData: string): { n: number; name: string }[] {
  const sets = new Map<number, string>();
  for (const m of machineData.matchAll(/^\s*\$TC_CARR(\d+)\[(\d+)\]\s*=\s*(.*)$/gm)) {
    const n = Number(m[2]);
    if (!sets.has(n)) sets.set(n, "");
    if (m[1] === "34") sets.set(n, (/"([^"]*)"/.exec(m[3] ?? "")?.[1] ?? "").trim());
  }
  return [...sets].sort((a, b) => a[0] - b[0]).map(([n, name]) => ({ n, name }));
}

function showDataSets(machineData: string): void {
  const sets = swivelDataSets(machineData);
  byId("swivel-panel").hidden = sets.length === 0;
  const select = byId<HTMLSelectElement>("swivel-tc");
  const keep = select.value;
  select.replaceChildren(
    ...sets.map((s) => el("option", { value: s.name || String(s.n) }, s.name ? `${s.name} (${s.n})` : `data set ${s.n}`)),
  );
  if ([...select.options].some((o) => o.value === keep)) select.value = keep;
}

export function mountSwivel(session: SessionController): void {
  const form = byId<HTMLFormElement>("swivel-form");
  session.on("session", (info) => showDataSets(info.machine.machine_data));
  session.on("machine", (info) => showDataSets(info.machine.machine_data));
  const outcome = byId("swivel-outcome");
  const swivel = async (cmd: SwivelCommand) => {
    setText(outcome, "swivelling …");
    delete outcome.dataset.failed;
    const st = await session.act((id) => api.swivel(id, cmd));
    if (!st) {
      setText(outcome, "");
      return;
    }
    const alarm = st.alarms[0];
    if (alarm) {
      // The server ran CYCLE800 as an MDA block and went back to JOG; the alarm stays.
      const why = `swivel not done: alarm ${alarm.number} ${alarm.message}`;
      setText(outcome, `${why} – the channel is in ${st.mode} again; RESET clears the alarm`);
      outcome.dataset.failed = "true";
      showMessage(why);
    } else {
      setText(outcome, cmd.data_set === "0" ? "swivel deselected" : `swivelled (${st.mode})`);
    }
  };
  form.addEventListener("submit", (ev) => {
    ev.preventDefault();
    void swivel(command(form));
  });
  byId("btn-swivel-off").addEventListener("click", () => void swivel({ ...command(form), data_set: "0" }));
}

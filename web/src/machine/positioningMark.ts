// The positioning-axis mark in the coordinate display: an axis travelling on its own
// interpolator (POS, POSA, POSP of the program, a synchronized action's command axis or MOV)
// gets a small badge beside its name, its tooltip the end point, speed and whether the
// program waits for it. The state names machine axes; a WCS/BCS row takes the machine axis of
// the same name, else the one at the same place (as the reference symbol does).

import type { PositioningState, State } from "../api/types";
import { fmt, setText } from "../core/dom";

/** Updates the badge of each row's axis cell (`marks`: row axis name -> badge element). */
export function showPositioning(st: State, axes: string[], marks: Map<string, HTMLElement>): void {
  const list = st.positioning ?? [];
  const machine = Object.keys(st.positions.machine);
  axes.forEach((axis, i) => {
    const badge = marks.get(axis);
    if (!badge) return;
    const name = list.some((p) => p.axis === axis) || machine.length !== axes.length ? axis : machine[i];
    const p = list.find((q) => q.axis === name);
    setText(badge, p ? p.kind : "");
    const tip = p ? describe(p) : "";
    if (badge.title !== tip) {
      badge.title = tip;
      badge.dataset.waiting = p?.waiting ? "yes" : "no";
      if (tip) badge.setAttribute("aria-label", tip);
      else badge.removeAttribute("aria-label");
    }
  });
}

function describe(p: PositioningState): string {
  const to = p.target === null ? "endless motion" : `to ${fmt(p.target)}`;
  const wait = p.waiting ? ", the program waits for it" : "";
  const what = p.kind === "OS" ? "oscillating axis" : `positioning axis (${p.kind})`;
  return `${p.axis}: ${what} ${to} at ${fmt(Math.abs(p.velocity), 0)}/min${wait}`;
}

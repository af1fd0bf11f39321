// The T, F, S window: active tool and edge, path feed, spindle speeds, transformation, active
// G functions, time.

import type { SpindleInfo, State } from "../api/types";
import { byId, fmt, setText } from "../core/dom";
import type { SessionController } from "../core/session";

function spindleText(name: string, rpm: number, info?: SpindleInfo): string {
  if (info?.mode === "SPOS") return `${name} SPOS ${fmt(info.position, 1)}°`;
  const dir = info ? info.mode : rpm > 0 ? "M3" : rpm < 0 ? "M4" : "M5";
  // The gear stage as Operate shows it beside the speed (M40..M45 select it).
  const gear = info?.gear ? ` GS${info.gear}` : "";
  return `${name} ${fmt(Math.abs(rpm), 0)} rpm ${dir}${gear}`;
}

function render(st: State): void {
  const named = st.tool.name ? `T="${st.tool.name}"` : `T${st.tool.t}`;
  const prepared = st.tool.prepared !== st.tool.t ? `  (prepared T${st.tool.prepared})` : "";
  setText(byId("tool"), `${named}  D${st.tool.d}${prepared}`);
  setText(byId("path-feed"), fmt(st.path_velocity, 1));
  const spindles = Object.entries(st.spindles);
  setText(byId("spindles"), spindles.length ? spindles.map(([n, rpm]) => spindleText(n, rpm, st.spindle_info?.[n])).join("   ") : "–");
  byId("spindle-load").hidden = !Object.values(st.spindle_info ?? {}).some((s) => s.cutting);
  const tr = st.transformation;
  setText(byId("transformation"), tr ? `${tr.name} (${tr.index})` : "none");
  setText(byId("gcodes"), st.gcodes.length ? st.gcodes.join(" ") : "–");
  setText(byId("sim-time"), fmt(st.time, 2));
}

export function mountTfs(session: SessionController): void {
  session.on("state", render);
}

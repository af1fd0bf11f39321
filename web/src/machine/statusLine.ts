// The channel status line under the program display, as Operate shows it: why the channel
// stands or what it does, the active program-control options, and the actual path feed.
//
// Read from the state alone. Why a stopped program stands is told by the state's flags and the
// block in execution: REPOS pending (JOG in the interrupted program), an M0/M1 in the current
// block, single block, else NC stop. Distance to go and programmed feed are the block's (under
// DRY the programmed feed is the dry-run feed the block was prepared with). The options show as
// Operate abbreviates them: SBL M01 DRY SKP. A preprocessing stop (STOPRE, a read of main-run
// values) is shown only while the path stands at it for something else of the main run (a
// POSA axis travelling: the state's `preprocessing_stop_wait`); behind the path's own blocks
// it ends in the cycle they end, and the channel never stands. The workpiece count (against
// the setpoint when one is set) and the running program's cycle time close the line, as
// Operate's program status shows them.

import type { State } from "../api/types";
import { byId, fmt, setText } from "../core/dom";
import type { SessionController } from "../core/session";

/** The reason the channel stands (or what it does), in Operate's words. */
export function channelReason(st: State): string {
  switch (st.status) {
    case "alarm": {
      const a = st.alarms.at(-1);
      return a ? `Alarm ${a.number}: the channel stands until a reset` : "Alarm: the channel stands until a reset";
    }
    case "stopped": {
      if (st.repos_pending) return "Stop: program interrupted by JOG, NC start repositions (REPOS)";
      const text = (st.block?.text ?? "").replace(/;.*$/, "").toUpperCase();
      if (/(^|[^A-Z0-9_])M0*0(?![0-9])/.test(text)) return "Stop: M0 programmed stop";
      if (/(^|[^A-Z0-9_])M0*1(?![0-9])/.test(text) && st.optional_stop) return "Stop: M1 optional stop";
      if (st.single_block) return "Stop: block ended in single block";
      return "Stop: NC stop";
    }
    case "running": {
      if (st.preprocessing_stop_wait) {
        const axes = (st.positioning ?? []).map((p) => p.axis);
        const what = axes.length > 0 ? ` for positioning axis ${axes.join(", ")}` : "";
        return `Wait: preprocessing stop, the main run finishes${what}`;
      }
      return st.mode === "JOG" ? "JOG motion" : `Program running (${st.mode})`;
    }
    case "idle": {
      const missing = Object.entries(st.referenced ?? {})
        .filter(([, ok]) => !ok)
        .map(([axis]) => axis);
      if (missing.length > 0) return `Reference point missing: ${missing.join(", ")}`;
      return "Reset";
    }
  }
}

/** Seconds as H:MM:SS (whole seconds, as Operate shows a runtime). */
export function clockTime(seconds: number): string {
  const s = Math.max(0, Math.floor(seconds));
  const two = (n: number) => String(n).padStart(2, "0");
  return `${Math.floor(s / 3600)}:${two(Math.floor(s / 60) % 60)}:${two(s % 60)}`;
}

/** "Parts 3/5 · Cycle 0:01:23": the actual count (of the setpoint, if set) and cycle time. */
export function partsAndTime(st: State): string {
  const p = st.parts;
  if (!p) return "";
  const count = p.required > 0 ? `${p.actual}/${p.required}` : `${p.actual}`;
  return `Parts ${count} · Cycle ${clockTime(st.runtimes?.cycle ?? 0)}`;
}

function render(st: State): void {
  const line = byId("channel-status");
  line.dataset.status = st.status;
  setText(byId("channel-reason"), channelReason(st));
  const options = [
    st.single_block ? "SBL" : "",
    st.optional_stop ? "M01" : "",
    st.dry_run ? "DRY" : "",
    (st.skip_levels ?? []).length > 0 ? "SKP" : "",
  ].filter(Boolean);
  setText(byId("channel-options"), options.join(" "));
  const programmed = st.programmed_feed == null ? (st.distance_to_go ? "rapid" : "–") : fmt(st.programmed_feed, 0);
  setText(byId("channel-feed"), `F prog ${programmed} act ${fmt(st.path_velocity, 0)} mm/min`);
  setText(byId("channel-dtg"), `DTG ${fmt(st.distance_to_go ?? 0, 3)}`);
  setText(byId("channel-times"), partsAndTime(st));
}

export function mountStatusLine(session: SessionController): void {
  session.on("state", render);
}

// Program progress, run time and remaining-time estimate of the AUTO program.
//
// Like Operate, the estimate comes from the last complete run of the same program (on the same
// machine): remaining = that run's duration - time run so far. Before a program has run once,
// it is extrapolated from the position of the current block in the program text, which is only
// a rough guide for programs with loops or subprogram calls (the tooltip says which it is).
// Times are simulated seconds, so the estimate holds in both paces.

import type { State } from "../api/types";
import { byId, fmt, setText } from "../core/dom";
import type { SessionController } from "../core/session";
import { activeProgram } from "../program/active";

const STORE_PREFIX = "nctwin.runtime.";
const MIN_LINE_FRACTION = 0.02; // below this, extrapolating from the line says nothing

interface Run {
  serial: number; // the program serial of the run (its text is read from the server)
  key: string | null; // machine and SHA-256 of the program, once the server named it
  start: number; // simulated time at cycle start
  fromStart: boolean; // seen from its start (else joined while running: no record)
  lines: number;
  previous: number | null; // duration of the last complete run of this program
}

export class ProgressView {
  private run: Run | null = null;
  private lastStatus: State["status"] | null = null;
  private finished: { duration: number } | null = null;
  private machine = "";

  setMachine(id: string): void {
    this.machine = id;
    this.run = null;
    this.finished = null;
    this.lastStatus = null;
  }

  /** Called for every sample, so that no start or end is missed between two frames. */
  sample(st: State): void {
    this.resolve();
    const prev = this.lastStatus;
    this.lastStatus = st.status;
    const auto = st.mode === "AUTO";
    if (auto && st.status === "running" && prev !== "running" && prev !== "stopped") {
      this.begin(st, prev !== null);
    } else if (this.run && st.status === "idle" && (prev === "running" || prev === "stopped")) {
      const duration = st.time - this.run.start;
      if (this.run.fromStart && this.run.key && st.alarms.length === 0 && auto) {
        try {
          localStorage.setItem(STORE_PREFIX + this.run.key, String(duration));
        } catch {
          // private mode or full: the estimate falls back to the program line
        }
      }
      this.finished = { duration };
      this.run = null;
    } else if (st.status === "alarm" || (!auto && st.status === "running")) {
      this.run = null;
      this.finished = null;
    }
  }

  render(st: State): void {
    this.resolve();
    const bar = byId("progress-bar");
    const box = byId("progress");
    const remaining = byId("remaining-time");
    let fraction: number | null = null;
    let runTime: number | null = null;
    let rest: number | null = null;
    let how = "";
    const run = this.run;
    if (run) {
      runTime = Math.max(0, st.time - run.start);
      if (run.previous != null && run.previous > 0) {
        fraction = Math.min(0.99, runTime / run.previous);
        rest = Math.max(0, run.previous - runTime);
        how = `from the last complete run (${fmt(run.previous, 1)} s)`;
      } else if (st.block && !st.block.program && run.lines > 0) {
        fraction = Math.min(1, Math.max(0, (st.block.line - 1) / run.lines));
        rest = fraction >= MIN_LINE_FRACTION && runTime > 0 ? (runTime * (1 - fraction)) / fraction : null;
        how = "extrapolated from the current line (no complete run yet)";
      }
    } else if (this.finished && st.status === "idle") {
      fraction = 1;
      runTime = this.finished.duration;
      rest = 0;
      how = "program ended";
    }
    bar.style.width = fraction == null ? "0" : `${(fraction * 100).toFixed(1)}%`;
    box.setAttribute("aria-valuenow", fraction == null ? "0" : (fraction * 100).toFixed(0));
    setText(byId("run-time"), runTime == null ? "–" : `${fmt(runTime, 1)} s`);
    setText(remaining, rest == null ? "–" : `${run?.previous != null || rest === 0 ? "" : "≈ "}${fmt(rest, 1)} s`);
    remaining.title = how;

    const msg = byId("program-msg");
    msg.hidden = !st.message;
    setText(msg, st.message ? `MSG  ${st.message}` : "");
  }

  private begin(st: State, seenStart: boolean): void {
    const serial = st.program_serial ?? 0;
    this.run = { serial, key: null, start: st.time, fromStart: seenStart, lines: 0, previous: null };
    this.finished = null;
    this.resolve();
  }

  /** Names the run's program once the server's active program is the one the run started. */
  private resolve(): void {
    const run = this.run;
    const meta = activeProgram.meta;
    if (!run || run.key || !meta || meta.serial !== run.serial) return;
    run.key = `${this.machine}.${meta.sha256}`;
    run.lines = meta.lineCount;
    try {
      const v = Number(localStorage.getItem(STORE_PREFIX + run.key));
      run.previous = Number.isFinite(v) && v > 0 ? v : null;
    } catch {
      run.previous = null;
    }
  }
}

export function mountProgress(session: SessionController): ProgressView {
  const view = new ProgressView();
  session.on("session", (info) => view.setMachine(info.machine.id));
  session.on("sample", (st) => view.sample(st));
  session.on("state", (st) => view.render(st));
  return view;
}

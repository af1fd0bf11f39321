// uPlot charts over the last seconds of simulated time: the WCS axis positions, or the axis
// velocities (differences of successive stream samples, in mm/min or °/min), each with the
// path feed. Switched by the two keys in the plot's corner.

import uPlot from "uplot";
import "uplot/dist/uPlot.min.css";
import type { State } from "../api/types";
import { byId } from "../core/dom";
import type { SessionController } from "../core/session";

const WINDOW_S = 30; // seconds of simulated time shown
const REDRAW_MS = 100;
/** The stream sends only while something changes: a longer gap means the axes stood still. */
const REST_GAP_S = 0.25;
const COLORS = ["#e5534b", "#57ab5a", "#539bf5", "#d8a32b", "#b083f0", "#39c5cf"];
const AXIS_STYLE = { stroke: "#8b96a3", grid: { stroke: "#333b44", width: 1 }, ticks: { stroke: "#333b44" } };

export type PlotMode = "position" | "velocity";

export class AxisPlot {
  private plot: uPlot | null = null;
  private axes: string[] = [];
  private rotary = new Set<string>();
  private time: number[] = [];
  private pos: number[][] = []; // one per axis
  private vel: number[][] = []; // one per axis, per minute
  private feed: number[] = [];
  private timer: ReturnType<typeof setTimeout> | undefined;
  private mode: PlotMode = "position";

  constructor(private readonly host: HTMLElement) {
    new ResizeObserver(() => this.resize()).observe(host);
  }

  reset(): void {
    this.plot?.destroy();
    this.plot = null;
    this.axes = [];
    this.time = [];
    this.pos = [];
    this.vel = [];
    this.feed = [];
  }

  setMode(mode: PlotMode): void {
    if (mode === this.mode) return;
    this.mode = mode;
    if (this.axes.length) this.build();
  }

  add(st: State): void {
    const values = st.positions.workpiece;
    const axes = Object.keys(values).filter((a) => !(a in st.spindles));
    const last = this.time.at(-1) ?? -Infinity;
    if (axes.join(",") !== this.axes.join(",") || st.time < last) this.create(axes);
    if (st.time === this.time.at(-1)) return;
    const prevTime = this.time.at(-1);
    if (prevTime !== undefined && st.time - prevTime > REST_GAP_S) {
      // At rest until just before this sample.
      this.push(st.time - 0.05, axes.map((_, i) => this.pos[i]!.at(-1) ?? NaN), axes.map(() => 0), 0);
    }
    const t0 = this.time.at(-1);
    const p = axes.map((a) => values[a] ?? NaN);
    const v = axes.map((_, i) => {
      const before = this.pos[i]!.at(-1);
      return t0 === undefined || before === undefined ? 0 : ((p[i]! - before) / (st.time - t0)) * 60;
    });
    this.push(st.time, p, v, st.path_velocity);
    // Drop what left the window (in chunks, not one by one).
    const cut = this.time.findIndex((t) => t >= st.time - WINDOW_S);
    if (cut > 256) {
      this.time.splice(0, cut);
      this.feed.splice(0, cut);
      for (const s of [...this.pos, ...this.vel]) s.splice(0, cut);
    }
    this.scheduleRedraw();
  }

  private push(t: number, p: number[], v: number[], f: number): void {
    this.time.push(t);
    p.forEach((x, i) => this.pos[i]!.push(x));
    v.forEach((x, i) => this.vel[i]!.push(x));
    this.feed.push(f);
  }

  private create(axes: string[]): void {
    this.reset();
    this.axes = axes;
    // The state does not say which channel axes are rotary: by the usual names A, B, C.
    this.rotary = new Set(axes.filter((a) => /^[ABC]\d*$/.test(a)));
    this.pos = axes.map(() => []);
    this.vel = axes.map(() => []);
    this.build();
  }

  private build(): void {
    this.plot?.destroy();
    const { width, height } = this.size();
    const velocity = this.mode === "velocity";
    const unit = (a: string) => (this.rotary.has(a) ? (velocity ? "°/min" : "°") : velocity ? "mm/min" : "mm");
    const opts: uPlot.Options = {
      width,
      height,
      legend: { show: true, live: false },
      cursor: { show: false },
      scales: {
        // At least one second: a few samples close together would otherwise fill the width.
        x: { time: false, range: (_u, min, max) => (min == null || max == null || max - min < 1 ? [min ?? 0, (min ?? 0) + 1] : [min, max]) },
        y: { auto: true },
        feed: { auto: true },
      },
      axes: [
        { ...AXIS_STYLE, size: 30, values: (_u, ticks) => ticks.map((t) => `${+t.toFixed(2)} s`) },
        { ...AXIS_STYLE, scale: "y", size: 60 },
        { ...AXIS_STYLE, scale: "feed", side: 1, size: 60, grid: { show: false } },
      ],
      series: [
        {},
        ...this.axes.map((a, i) => ({
          label: `${velocity ? "v" : ""}${a} ${unit(a)}`,
          scale: "y",
          stroke: COLORS[i % COLORS.length],
          width: 1.5,
          points: { show: false },
        })),
        { label: "F mm/min", scale: velocity ? "y" : "feed", stroke: "#8b96a3", width: 1, dash: [4, 4], points: { show: false } },
      ],
    };
    this.plot = new uPlot(opts, this.data(), this.host);
    this.host.dataset.mode = this.mode;
  }

  private data(): uPlot.AlignedData {
    return [this.time, ...(this.mode === "velocity" ? this.vel : this.pos), this.feed];
  }

  private scheduleRedraw(): void {
    if (this.timer !== undefined) return;
    this.timer = setTimeout(() => {
      this.timer = undefined;
      this.plot?.setData(this.data());
    }, REDRAW_MS);
  }

  private size(): { width: number; height: number } {
    const legend = this.plot?.root.querySelector(".u-legend")?.clientHeight ?? 24;
    return { width: Math.max(100, this.host.clientWidth), height: Math.max(60, this.host.clientHeight - legend) };
  }

  private resize(): void {
    if (this.plot) this.plot.setSize(this.size());
  }
}

export function mountAxisPlot(session: SessionController): AxisPlot {
  const plot = new AxisPlot(byId("plot"));
  session.on("session", () => plot.reset());
  session.on("sample", (st) => plot.add(st));
  const keys = document.querySelectorAll<HTMLButtonElement>("#plot-mode [data-plot]");
  const select = (mode: PlotMode) => {
    plot.setMode(mode);
    for (const k of keys) k.classList.toggle("active", k.dataset.plot === mode);
  };
  for (const k of keys) k.addEventListener("click", () => select(k.dataset.plot as PlotMode));
  select("position");
  return plot;
}

// A uPlot chart of the WCS axis positions and the path feed over the last seconds of
// simulated time.

import uPlot from "uplot";
import "uplot/dist/uPlot.min.css";
import type { State } from "../api/types";
import { byId } from "../core/dom";
import type { SessionController } from "../core/session";

const WINDOW_S = 30; // seconds of simulated time shown
const REDRAW_MS = 100;
const COLORS = ["#e5534b", "#57ab5a", "#539bf5", "#d8a32b", "#b083f0", "#39c5cf"];
const AXIS_STYLE = { stroke: "#8b96a3", grid: { stroke: "#333b44", width: 1 }, ticks: { stroke: "#333b44" } };

export class AxisPlot {
  private plot: uPlot | null = null;
  private axes: string[] = [];
  private time: number[] = [];
  private series: number[][] = []; // one per axis, then the path feed
  private timer: ReturnType<typeof setTimeout> | undefined;

  constructor(private readonly host: HTMLElement) {
    new ResizeObserver(() => this.resize()).observe(host);
  }

  reset(): void {
    this.plot?.destroy();
    this.plot = null;
    this.axes = [];
    this.time = [];
    this.series = [];
  }

  add(st: State): void {
    const axes = Object.keys(st.positions.workpiece).filter((a) => !(a in st.spindles));
    if (axes.join(",") !== this.axes.join(",") || st.time < (this.time.at(-1) ?? -Infinity)) this.create(axes);
    if (st.time === this.time.at(-1)) return;
    this.time.push(st.time);
    axes.forEach((a, i) => this.series[i]!.push(st.positions.workpiece[a] ?? NaN));
    this.series[axes.length]!.push(st.path_velocity);
    // Drop what left the window (in chunks, not one by one).
    const cut = this.time.findIndex((t) => t >= st.time - WINDOW_S);
    if (cut > 256) {
      this.time.splice(0, cut);
      for (const s of this.series) s.splice(0, cut);
    }
    this.scheduleRedraw();
  }

  private create(axes: string[]): void {
    this.reset();
    this.axes = axes;
    this.series = [...axes, "F"].map(() => []);
    const { width, height } = this.size();
    const opts: uPlot.Options = {
      width,
      height,
      legend: { show: true, live: false },
      cursor: { show: false },
      scales: { x: { time: false }, mm: { auto: true }, feed: { auto: true } },
      axes: [
        { ...AXIS_STYLE, size: 30, values: (_u, ticks) => ticks.map((t) => `${+t.toFixed(2)} s`) },
        { ...AXIS_STYLE, scale: "mm", size: 56 },
        { ...AXIS_STYLE, scale: "feed", side: 1, size: 60, grid: { show: false } },
      ],
      series: [
        {},
        ...axes.map((a, i) => ({
          label: `${a} mm`,
          scale: "mm",
          stroke: COLORS[i % COLORS.length],
          width: 1.5,
          points: { show: false },
        })),
        { label: "F mm/min", scale: "feed", stroke: "#8b96a3", width: 1, dash: [4, 4], points: { show: false } },
      ],
    };
    this.plot = new uPlot(opts, this.data(), this.host);
  }

  private data(): uPlot.AlignedData {
    return [this.time, ...this.series];
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
  return plot;
}

// The JOG area's functions beside the axis keys, as Operate's JOG softkeys: "Ref. point"
// (reference every unreferenced axis), handwheel selection (which axis handwheel 1 moves; a
// detent is one INC step), and "Set WO" (the axis reads the typed value; the difference goes
// into the active work offset).

import { api } from "../api/client";
import type { State } from "../api/types";
import { byId, el } from "../core/dom";
import { showMessage } from "../core/message";
import type { SessionController } from "../core/session";
import type { JogPanel } from "./jog";

/** Detents of one mouse-wheel notch over the handwheel keys. */
const WHEEL_DETENTS = 1;

export class JogFunctions {
  private axesKey = "";

  constructor(
    private readonly session: SessionController,
    private readonly jog: JogPanel,
  ) {
    byId("btn-ref-point").addEventListener("click", () => void this.reference());
    byId("set-wo-form").addEventListener("submit", (ev) => {
      ev.preventDefault();
      void this.setWorkOffset();
    });
    const axis = byId<HTMLSelectElement>("handwheel-axis");
    axis.addEventListener("change", () => this.showHandwheel());
    for (const [id, dir] of [
      ["handwheel-minus", -1],
      ["handwheel-plus", 1],
    ] as const) {
      const key = byId<HTMLButtonElement>(id);
      key.addEventListener("click", () => void this.turn(dir));
      key.addEventListener(
        "wheel",
        (ev) => {
          ev.preventDefault();
          void this.turn(ev.deltaY < 0 ? WHEEL_DETENTS : -WHEEL_DETENTS);
        },
        { passive: false },
      );
    }
    session.on("session", () => (this.axesKey = ""));
    session.on("state", (st) => this.show(st));
  }

  /** The handwheel's axis ("" when off). */
  get handwheelAxis(): string {
    return byId<HTMLSelectElement>("handwheel-axis").value;
  }

  private show(st: State): void {
    const axes = Object.keys(st.positions.workpiece);
    const machine = Object.keys(st.positions.machine);
    const key = `${axes.join(",")}|${machine.join(",")}`;
    if (key !== this.axesKey) {
      this.axesKey = key;
      fill(byId<HTMLSelectElement>("set-wo-axis"), axes, false);
      fill(byId<HTMLSelectElement>("handwheel-axis"), [...new Set([...axes, ...machine])], true);
      this.showHandwheel();
    }
    const unreferenced = Object.entries(st.referenced ?? {}).filter(([, r]) => !r).map(([a]) => a);
    const ref = byId<HTMLButtonElement>("btn-ref-point");
    ref.classList.toggle("attention", unreferenced.length > 0);
    ref.title = unreferenced.length
      ? `Ref. point: reference ${unreferenced.join(", ")} (not referenced: NC start is refused with alarm 16905)`
      : "Ref. point: every axis is referenced";
  }

  private showHandwheel(): void {
    const on = this.handwheelAxis !== "";
    byId("handwheel-minus").hidden = !on;
    byId("handwheel-plus").hidden = !on;
  }

  private async reference(): Promise<void> {
    if (this.session.latest?.mode !== "JOG") {
      showMessage("Ref. point: select JOG mode first");
      return;
    }
    await this.session.act((id) => api.reference(id));
  }

  /** Turns handwheel 1 by `pulses` detents: one INC step each (INC1 when JOG is continuous). */
  async turn(pulses: number): Promise<void> {
    const axis = this.handwheelAxis;
    if (!axis) return;
    if (this.session.latest?.mode !== "JOG") {
      showMessage("handwheel: select JOG mode first");
      return;
    }
    const coordinates = this.jog.coordinates;
    if (coordinates === "TCS") {
      showMessage("handwheel: choose MCS, BCS or WCS (the handwheel does not move in the TCS)");
      return;
    }
    const choice = byId<HTMLSelectElement>("jog-increment").value;
    const inc = ["1", "10", "100", "1000"].includes(choice) ? Number(choice) : 1;
    await this.session.act((id) => api.handwheel(id, { axis, pulses, inc, coordinates }), { keepMessage: true });
  }

  private async setWorkOffset(): Promise<void> {
    const axis = byId<HTMLSelectElement>("set-wo-axis").value;
    const input = byId<HTMLInputElement>("set-wo-value");
    const value = Number(input.value);
    if (!axis || input.value.trim() === "" || !Number.isFinite(value)) {
      showMessage(`Set WO: "${input.value}" is no position`);
      return;
    }
    await this.session.act((id) => api.setWorkOffset(id, axis, value));
  }
}

function fill(select: HTMLSelectElement, axes: string[], withOff: boolean): void {
  const keep = select.value;
  const options = axes.map((a) => el("option", { value: a }, a));
  select.replaceChildren(...(withOff ? [el("option", { value: "" }, "off"), ...options] : options));
  if ([...select.options].some((o) => o.value === keep)) select.value = keep;
}

export function mountJogFunctions(session: SessionController, jog: JogPanel): JogFunctions {
  return new JogFunctions(session, jog);
}

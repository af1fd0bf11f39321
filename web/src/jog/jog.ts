// The JOG panel: a -/+ key pair per channel axis. Continuous JOG moves while the key is held
// (jog/stop on release, when the pointer leaves the key or the window loses focus); with an
// increment selected, each press moves by that increment.

import { api } from "../api/client";
import type { JogCommand } from "../api/types";
import { byId, el } from "../core/dom";
import type { SessionController } from "../core/session";

export class JogPanel {
  private held: HTMLButtonElement | null = null;
  private call: Promise<unknown> = Promise.resolve();
  private axesKey = "";
  private readonly box = byId("jog-axes");

  constructor(private readonly session: SessionController) {
    this.box.addEventListener("pointerdown", (ev) => this.press(ev));
    this.box.addEventListener("pointerup", () => this.release());
    this.box.addEventListener("pointercancel", () => this.release());
    this.box.addEventListener("pointerleave", (ev) => ev.target === this.held && this.release(), true);
    this.box.addEventListener("contextmenu", (ev) => ev.preventDefault());
    window.addEventListener("blur", () => this.release());
  }

  /** One key pair per channel axis (as the program names them). */
  setAxes(axes: string[]): void {
    const key = axes.join(",");
    if (key === this.axesKey) return;
    this.axesKey = key;
    this.box.replaceChildren(
      ...axes.map((axis) => {
        const row = el("div", { class: "jog-axis" });
        row.append(
          el("button", { type: "button", "data-jog-axis": axis, "data-dir": "-1", title: `${axis} −` }, "−"),
          el("span", { class: "jog-name" }, axis),
          el("button", { type: "button", "data-jog-axis": axis, "data-dir": "1", title: `${axis} +` }, "+"),
        );
        return row;
      }),
    );
  }

  private press(ev: PointerEvent): void {
    const button = (ev.target as HTMLElement).closest<HTMLButtonElement>("button[data-jog-axis]");
    if (!button || ev.button !== 0 || !this.session.id) return;
    ev.preventDefault();
    const increment = byId<HTMLSelectElement>("jog-increment").value;
    const jog: JogCommand = {
      axis: button.dataset.jogAxis ?? "",
      direction: button.dataset.dir === "-1" ? -1 : 1,
    };
    if (increment) jog.increment = Number(increment);
    if (byId<HTMLInputElement>("jog-rapid").checked) jog.rapid = true;
    if (!increment) {
      this.held = button;
      button.classList.add("pressed");
    }
    this.call = this.session.act((id) => api.jog(id, jog));
  }

  private release(): void {
    const button = this.held;
    if (!button) return;
    button.classList.remove("pressed");
    this.held = null;
    // After the jog request has been answered, so the stop cannot overtake it. Keeps the
    // message bar, which may show why the jog was refused.
    this.call = this.call.then(() => this.session.act((id) => api.jogStop(id), { keepMessage: true }));
  }
}

export function mountJog(session: SessionController): void {
  const panel = new JogPanel(session);
  session.on("state", (st) => panel.setAxes(Object.keys(st.positions.workpiece)));
}

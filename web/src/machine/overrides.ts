// Override switches (feed 0-120 %, rapid 0-100 %, spindle 50-120 %) and the program control
// keys single block (SBL1), optional stop (M01), dry-run feed (DRY) and skip level /0 (SKP; the
// key leaves other levels set through the API as they are). The sliders send on every step (the server
// applies overrides at once, also to a running program); what they show afterwards is what the
// state reports, except while the operator is dragging one.

import { api } from "../api/client";
import type { Overrides, State } from "../api/types";
import { byId, setText } from "../core/dom";
import type { SessionController } from "../core/session";

type OverrideName = keyof Overrides;
const NAMES: OverrideName[] = ["feed", "rapid", "spindle"];
const SEND_DELAY_MS = 80; // coalesce the steps of one drag

export class OverridePanel {
  private readonly inputs = new Map<OverrideName, HTMLInputElement>();
  private dragging: OverrideName | null = null;
  private pending: Partial<Overrides> = {};
  private timer: ReturnType<typeof setTimeout> | undefined;

  constructor(private readonly session: SessionController) {
    for (const name of NAMES) {
      const input = byId<HTMLInputElement>(`ovr-${name}`);
      this.inputs.set(name, input);
      input.addEventListener("input", () => {
        this.dragging = name;
        this.showValue(name, Number(input.value));
        this.pending[name] = Number(input.value);
        clearTimeout(this.timer);
        this.timer = setTimeout(() => this.send(), SEND_DELAY_MS);
      });
      input.addEventListener("change", () => {
        clearTimeout(this.timer);
        this.send();
      });
    }
    byId("btn-sbl").addEventListener("click", () => this.toggle("single_block"));
    byId("btn-m1").addEventListener("click", () => this.toggle("optional_stop"));
    byId("btn-dry").addEventListener("click", () => this.toggle("dry_run"));
    byId("btn-skp").addEventListener("click", () => this.toggleSkipLevel0());
  }

  render(st: State): void {
    const o = st.overrides;
    if (o) {
      for (const name of NAMES) {
        if (name === this.dragging) continue;
        const input = this.inputs.get(name)!;
        if (Number(input.value) !== o[name]) input.value = String(o[name]);
        this.showValue(name, o[name]);
      }
      setText(byId("feed-ovr"), `${fmtPercent(o.feed)}`);
      setText(byId("spindle-ovr"), Object.keys(st.spindles).length ? fmtPercent(o.spindle) : "");
      byId("feed-ovr").classList.toggle("changed", o.feed !== 100);
    }
    setPressed(byId("btn-sbl"), st.single_block);
    setPressed(byId("btn-m1"), st.optional_stop);
    setPressed(byId("btn-dry"), st.dry_run ?? false);
    setPressed(byId("btn-skp"), (st.skip_levels ?? []).includes(0));
  }

  private showValue(name: OverrideName, value: number): void {
    setText(byId(`ovr-${name}-value`), fmtPercent(value));
  }

  private send(): void {
    const body = this.pending;
    this.pending = {};
    if (!Object.keys(body).length) return;
    void this.session.act((id) => api.setOverrides(id, body)).finally(() => {
      if (!Object.keys(this.pending).length) this.dragging = null;
    });
  }

  private toggleSkipLevel0(): void {
    const levels = this.session.latest?.skip_levels ?? [];
    const next = levels.includes(0) ? levels.filter((l) => l !== 0) : [0, ...levels];
    void this.session.act((id) => api.setOptions(id, { skip_levels: next }));
  }

  private toggle(option: "single_block" | "optional_stop" | "dry_run"): void {
    const current = this.session.latest?.[option] ?? false;
    void this.session.act((id) => api.setOptions(id, { [option]: !current }));
  }
}

function fmtPercent(v: number): string {
  return `${Math.round(v)} %`;
}

function setPressed(button: HTMLElement, on: boolean): void {
  const value = String(on);
  if (button.getAttribute("aria-pressed") !== value) button.setAttribute("aria-pressed", value);
  button.classList.toggle("active", on);
}

export function mountOverrides(session: SessionController): OverridePanel {
  const panel = new OverridePanel(session);
  session.on("state", (st) => panel.render(st));
  return panel;
}

// The JOG panel: a -/+ key pair per axis, the coordinate system (MCS/BCS/WCS/TCS), the
// increment (continuous, INC1..INC1000, INCvar), the rapid overlay key and, while an orientation
// transformation is active, the orientation keys A2/B2/C2.
//
// JOG keys go over the session's WebSocket with the server's dead-man: a held key sends `jog`,
// then `jog_keepalive` every KEEPALIVE_MS while it stays held, and `jog_stop` when it is
// released, the pointer is lost, the window loses focus or the page is hidden. Without a live
// stream the panel falls back to REST (`POST .../jog`, `.../jog/stop`).

import { api } from "../api/client";
import type { StreamReply } from "../api/stream";
import type { JogCommand, State } from "../api/types";
import { byId, el, setText } from "../core/dom";
import { showMessage } from "../core/message";
import type { SessionController } from "../core/session";
import { isOrientationTrafo } from "../view3d/machineData";

/** Keep-alive period while a key is held: well inside the server's 400 ms dead-man. */
export const KEEPALIVE_MS = 100;

export type JogCoords = "MCS" | "BCS" | "WCS" | "TCS";
const ORIENTATION_AXES = ["A2", "B2", "C2"];

/** The `jog` client message of the stream (and the body of `POST .../jog`). */
export interface JogMessage extends JogCommand {
  coordinates: JogCoords;
  inc?: number;
}

/**
 * Fields beyond axis, direction, increment and system: for the orientation keys the rotation
 * kind when one is chosen (absent: the server takes SD42660 ORI_JOG_MODE). The stream rejects
 * unknown fields, so only fields the server knows go here.
 */
export function extraJogFields(axis: string): Record<string, unknown> {
  if (!ORIENTATION_AXES.includes(axis)) return {};
  const rotation = byId<HTMLSelectElement>("jog-rotation").value;
  return rotation ? { rotation } : {};
}

/** The REPOS choice for NC start while `repos_pending` (body fields of `POST .../start`). */
export function reposFields(): { repos: string; approach: string; disr?: number } | null {
  if (byId("jog-repos-opts").hidden) return null;
  const approach = byId<HTMLSelectElement>("repos-approach").value;
  const fields: { repos: string; approach: string; disr?: number } = {
    repos: byId<HTMLSelectElement>("repos-mode").value,
    approach,
  };
  if (approach === "REPOSQ" || approach === "REPOSH") fields.disr = Number(byId<HTMLInputElement>("repos-disr").value);
  return fields;
}

/** The increment selector's value as message fields: {} continuous, `inc` or `increment`. */
export function incrementFields(choice: string, variable: number): Pick<JogMessage, "inc" | "increment"> | null {
  if (!choice) return {};
  if (choice === "var") return Number.isFinite(variable) && variable > 0 ? { increment: variable } : null;
  return { inc: Number(choice) };
}

export class JogPanel {
  private held: HTMLButtonElement | null = null;
  private keepalive: ReturnType<typeof setInterval> | undefined;
  /** Whether the held key's motion went over the stream (else REST). */
  private heldOnStream = false;
  private call: Promise<unknown> = Promise.resolve();
  private axesKey = "";
  private coords: JogCoords = "WCS";
  /** The axis the keyboard's + / − keys move (chosen with 1..9, as Operate's axis keys). */
  private keyAxis = "";
  private readonly box = byId("jog-axes");
  private readonly oriBox = byId("jog-ori");
  private readonly rapidKey = byId<HTMLButtonElement>("jog-rapid");

  constructor(private readonly session: SessionController) {
    for (const host of [this.box, this.oriBox]) {
      host.addEventListener("pointerdown", (ev) => this.press(ev));
      host.addEventListener("pointerup", () => this.release());
      host.addEventListener("pointercancel", () => this.release());
      host.addEventListener("lostpointercapture", () => this.release());
      host.addEventListener("contextmenu", (ev) => ev.preventDefault());
    }
    window.addEventListener("blur", () => this.release());
    window.addEventListener("keydown", (ev) => this.onKey(ev, true));
    window.addEventListener("keyup", (ev) => this.onKey(ev, false));
    document.addEventListener("visibilitychange", () => document.hidden && this.release());
    session.on("reply", (r) => this.onReply(r));
    session.on("connection", (c) => c !== "online" && this.release());
    session.on("session", () => {
      this.release();
      this.axesKey = "";
    });

    for (const b of document.querySelectorAll<HTMLButtonElement>("#jog-coords [data-jog-coords]")) {
      b.addEventListener("click", () => this.setCoords(b.dataset.jogCoords as JogCoords));
    }
    this.setCoords("WCS");
    this.rapidKey.addEventListener("click", () => {
      this.rapidKey.setAttribute("aria-pressed", String(this.rapidKey.getAttribute("aria-pressed") !== "true"));
    });
    const inc = byId<HTMLSelectElement>("jog-increment");
    const showVar = () => (byId("jog-var").hidden = inc.value !== "var");
    inc.addEventListener("change", showVar);
    showVar();
  }

  /** The coordinate system the JOG keys (and the handwheel) move in. */
  get coordinates(): JogCoords {
    return this.coords;
  }

  setCoords(coords: JogCoords): void {
    this.coords = coords;
    for (const b of document.querySelectorAll<HTMLButtonElement>("#jog-coords [data-jog-coords]")) {
      b.classList.toggle("active", b.dataset.jogCoords === coords);
    }
    this.axesKey = ""; // the keys name machine axes in the MCS, channel axes otherwise
    if (this.session.latest) this.show(this.session.latest);
  }

  /** Keys for the axes of this state and coordinate system; orientation keys with TRAORI. */
  show(st: State): void {
    const axes = Object.keys(this.coords === "MCS" ? st.positions.machine : st.positions.workpiece);
    const ori = isOrientationTrafo(st.transformation?.type);
    const key = `${this.coords}|${axes.join(",")}|${ori}`;
    setText(byId("jog-mode-hint"), st.mode === "JOG" ? "" : "select JOG mode to move the axes");
    byId("jog-repos").hidden = !st.repos_pending;
    byId("jog-repos-opts").hidden = !st.repos_pending;
    if (key === this.axesKey) return;
    this.axesKey = key;
    this.box.replaceChildren(...axes.map((a) => keyRow(a)));
    if (!axes.includes(this.keyAxis)) this.keyAxis = "";
    for (const r of this.box.querySelectorAll<HTMLElement>(".jog-axis")) r.classList.toggle("selected", r.dataset.axis === this.keyAxis);
    this.oriBox.hidden = !ori;
    byId("jog-rotation-label").hidden = !ori;
    this.oriBox.replaceChildren(...(ori ? ORIENTATION_AXES.map((a) => keyRow(a, this.coords === "MCS")) : []));
  }

  private message(button: HTMLButtonElement): JogMessage | null {
    const choice = byId<HTMLSelectElement>("jog-increment").value;
    const step = incrementFields(choice, Number(byId<HTMLInputElement>("jog-var").value));
    if (!step) {
      showMessage("enter a positive variable increment (INCvar)");
      return null;
    }
    const jog: JogMessage = {
      axis: button.dataset.jogAxis ?? "",
      direction: button.dataset.dir === "-1" ? -1 : 1,
      coordinates: this.coords,
      ...step,
    };
    if (this.rapidKey.getAttribute("aria-pressed") === "true") jog.rapid = true;
    return { ...jog, ...extraJogFields(jog.axis) };
  }

  private press(ev: PointerEvent): void {
    const button = (ev.target as HTMLElement).closest<HTMLButtonElement>("button[data-jog-axis]");
    if (!button || button.disabled || ev.button !== 0 || !this.session.id) return;
    ev.preventDefault();
    // Keep the pointer's events on this key even when it slides off (release stays reliable).
    button.setPointerCapture?.(ev.pointerId);
    this.pressKey(button);
  }

  /**
   * Keyboard, in JOG mode while the Machine area shows and no text field has the focus: the
   * arrow keys are X−/X+ (left/right) and Y−/Y+ (down/up), Page Down/Up Z−/Z+; the digits 1..9
   * select the n-th axis (as Operate's axis keys) and + / − move it, for every axis; Space or
   * Enter on a focused JOG key acts as pressing it. All held like the JOG keys.
   */
  onKey(ev: KeyboardEvent, down: boolean): void {
    const target = ev.target as HTMLElement | null;
    if (target?.closest("input, textarea, select, [contenteditable]") || byId("area-machine").hidden) return;
    if (this.session.latest?.mode !== "JOG") return;
    const focusedKey = target?.closest<HTMLButtonElement>("button[data-jog-axis]");
    if (focusedKey && (ev.key === " " || ev.key === "Enter")) {
      ev.preventDefault();
      if (!down) return this.release();
      if (!ev.repeat && !focusedKey.disabled) this.pressKey(focusedKey);
      return;
    }
    if (/^[1-9]$/.test(ev.key)) {
      if (down) this.selectKeyAxis(Number(ev.key) - 1);
      return;
    }
    const map: Record<string, [string, string]> = {
      ArrowLeft: ["X", "-1"],
      ArrowRight: ["X", "1"],
      ArrowDown: ["Y", "-1"],
      ArrowUp: ["Y", "1"],
      PageDown: ["Z", "-1"],
      PageUp: ["Z", "1"],
    };
    if (this.keyAxis) {
      map["+"] = [this.keyAxis, "1"];
      map["-"] = [this.keyAxis, "-1"];
    }
    const hit = map[ev.key];
    if (!hit) return;
    const button = this.box.querySelector<HTMLButtonElement>(`button[data-jog-axis="${hit[0]}"][data-dir="${hit[1]}"]`);
    if (!button) return;
    ev.preventDefault();
    if (!down) return this.release();
    if (!ev.repeat) this.pressKey(button);
  }

  /** Selects the `index`-th axis row for the + / − keys (marked in the panel). */
  private selectKeyAxis(index: number): void {
    const rows = [...this.box.querySelectorAll<HTMLElement>(".jog-axis")];
    const row = rows[index];
    if (!row) return;
    this.keyAxis = row.dataset.axis ?? "";
    for (const r of rows) r.classList.toggle("selected", r === row);
  }

  private pressKey(button: HTMLButtonElement): void {
    this.release();
    if (document.body.dataset.locked) return; // view only / no control: see ui/lock.ts
    const jog = this.message(button);
    if (!jog) return;
    const continuous = jog.inc === undefined && jog.increment === undefined;
    const onStream = this.session.send({ type: "jog", ...jog });
    if (!onStream) this.call = this.session.act((id) => api.jog(id, jog));
    if (!continuous) return;
    this.held = button;
    this.heldOnStream = onStream;
    button.classList.add("pressed");
    if (onStream) {
      this.keepalive = setInterval(() => this.session.send({ type: "jog_keepalive" }), KEEPALIVE_MS);
    }
  }

  /** Releases the held key (if any): `jog_stop`, the axis brakes. */
  release(): void {
    clearInterval(this.keepalive);
    this.keepalive = undefined;
    const button = this.held;
    if (!button) return;
    button.classList.remove("pressed");
    this.held = null;
    if (this.heldOnStream && this.session.send({ type: "jog_stop" })) return;
    // A closed socket stops the motion itself; over REST: after the jog request has been
    // answered, so the stop cannot overtake it. Keeps the message bar (why a jog was refused).
    this.call = this.call.then(() => this.session.act((id) => api.jogStop(id), { keepMessage: true }));
  }

  private onReply(reply: StreamReply): void {
    if (reply.type !== "error") return;
    // A refused or dead-man-stopped jog: the key no longer moves anything.
    if (reply.request === "jog") this.release();
    showMessage(reply.error ?? "JOG refused");
  }
}

function keyRow(axis: string, disabled = false): HTMLElement {
  const row = el("div", { class: "jog-axis", "data-axis": axis });
  const key = (dir: string, label: string) => {
    const b = el("button", { type: "button", "data-jog-axis": axis, "data-dir": dir, title: `${axis} ${label}` }, label);
    b.disabled = disabled;
    if (disabled) b.title = `${axis}: orientation JOG needs BCS, WCS or TCS`;
    return b;
  };
  row.append(key("-1", "−"), el("span", { class: "jog-name" }, axis), key("1", "+"));
  return row;
}

export function mountJog(session: SessionController): JogPanel {
  const panel = new JogPanel(session);
  session.on("state", (st) => panel.show(st));
  return panel;
}

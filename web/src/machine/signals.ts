// The simulated PLC's signals and the active synchronized actions: switches for the digital
// inputs $A_IN[1..16] (the default set; the channel has 40, the rest over REST), lamps
// for the outputs $A_OUT[1..16], the analog inputs $A_INA[1..4] with the outputs $A_OUTA[1..4]
// beside them, and the state's list of synchronized actions. A switched input goes to the
// server at once; the server acts on it in the next IPO cycle.

import { api } from "../api/client";
import type { IoImage, State, SyncActionState } from "../api/types";
import { byId, el, fmt, setText } from "../core/dom";
import type { SessionController } from "../core/session";

const SHOWN = 16;
const ANALOG = 4;
/** While something runs, the outputs are read again at most this often. */
const REFRESH_MS = 500;

let image: IoImage | null = null;
let lastRead = 0;
let shownActions = "";

function renderIo(io: IoImage): void {
  image = io;
  const inputs = byId("signal-inputs");
  const outputs = byId("signal-outputs");
  if (inputs.childElementCount !== SHOWN) {
    inputs.replaceChildren(
      ...Array.from({ length: SHOWN }, (_, i) => el("button", { type: "button", "data-signal": String(i + 1) }, String(i + 1))),
    );
    outputs.replaceChildren(...Array.from({ length: SHOWN }, (_, i) => el("span", {}, String(i + 1))));
  }
  for (let i = 0; i < SHOWN; i++) {
    const on = io.inputs[i] === true;
    const button = inputs.children[i] as HTMLElement;
    button.classList.toggle("on", on);
    button.setAttribute("aria-pressed", String(on));
    outputs.children[i]!.classList.toggle("on", io.outputs[i] === true);
  }
  const analog = byId("signal-analog");
  if (analog.childElementCount !== ANALOG) {
    analog.replaceChildren(
      ...Array.from({ length: ANALOG }, (_, i) => {
        const label = el("label", {}, `A${i + 1} `);
        const input = el("input", { type: "number", step: "any", "data-analog": String(i + 1), "aria-label": `$A_INA[${i + 1}]` });
        label.append(input, el("span", { class: "muted" }));
        return label;
      }),
    );
  }
  for (let i = 0; i < ANALOG; i++) {
    const label = analog.children[i]!;
    const input = label.querySelector("input")!;
    if (document.activeElement !== input) input.value = String(io.analog_inputs[i] ?? 0);
    setText(label.querySelector("span")!, ` → ${fmt(io.analog_outputs[i] ?? 0, 2)}`);
  }
}

function renderActions(actions: SyncActionState[]): void {
  const key = JSON.stringify(actions);
  if (key === shownActions) return;
  shownActions = key;
  byId<HTMLTableElement>("sync-actions").tBodies[0]!.replaceChildren(
    ...actions.map((a) => {
      const tr = el("tr", { class: a.fired ? "fired" : "", title: `line ${a.line}` });
      tr.append(
        el("td", { class: "num" }, a.id != null ? String(a.id) : "–"),
        el("td", {}, a.kind + (a.locked ? " (locked)" : "")),
        el("td", {}, `${a.trigger} ${a.condition}`.trim()),
        el("td", {}, a.fired ? "yes" : "no"),
      );
      return tr;
    }),
  );
}

export function mountSignals(session: SessionController): void {
  const read = (): void => {
    lastRead = Date.now();
    void session.act((id) => api.io(id), { keepMessage: true }).then((io) => io && renderIo(io));
  };
  session.on("session", read);
  session.on("event", (e) => {
    if (e.event === "digital_output" || e.event === "inputs_changed") read();
  });
  session.on("state", (st: State) => {
    renderActions(st.synchronized_actions ?? []);
    // Synchronized actions write analog outputs without an event: read while they are active.
    if ((st.synchronized_actions?.length ?? 0) > 0 && Date.now() - lastRead > REFRESH_MS) read();
  });
  byId("signal-inputs").addEventListener("click", (ev) => {
    const n = Number((ev.target as HTMLElement).dataset.signal);
    if (!n || !image) return;
    const value = !image.inputs[n - 1];
    void session
      .act((id) => api.setIo(id, { inputs: [{ signal: n, value }] }), { keepMessage: true })
      .then((io) => io && renderIo(io));
  });
  byId("signal-analog").addEventListener("change", (ev) => {
    const input = ev.target as HTMLInputElement;
    const n = Number(input.dataset.analog);
    const value = Number(input.value);
    if (!n || !Number.isFinite(value)) return;
    void session
      .act((id) => api.setIo(id, { analog_inputs: [{ signal: n, value }] }))
      .then((io) => io && renderIo(io));
  });
}

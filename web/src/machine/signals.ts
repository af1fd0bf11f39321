// The simulated PLC's signals and the active synchronized actions: switches for the digital
// inputs $A_IN[n], lamps for the outputs $A_OUT[n], the analog inputs $A_INA[n] with the outputs
// $A_OUTA[n] beside them (as many as the session's machine data configure: 16, 16 and 4 each by
// default), and the state's list of synchronized actions. A switched input goes to the server
// at once; the server acts on it in the next IPO cycle.

import { api } from "../api/client";
import type { IoImage, State, SyncActionState } from "../api/types";
import { byId, el, fmt, setText } from "../core/dom";
import type { SessionController } from "../core/session";

/** While something runs, the outputs are read again at most this often. */
const REFRESH_MS = 500;

let image: IoImage | null = null;
let lastRead = 0;
let shownActions = "";

function renderIo(io: IoImage): void {
  image = io;
  const inputs = byId("signal-inputs");
  const outputs = byId("signal-outputs");
  if (inputs.childElementCount !== io.inputs.length) {
    inputs.replaceChildren(
      ...io.inputs.map((_, i) => el("button", { type: "button", "data-signal": String(i + 1) }, String(i + 1))),
    );
  }
  if (outputs.childElementCount !== io.outputs.length) {
    outputs.replaceChildren(...io.outputs.map((_, i) => el("span", {}, String(i + 1))));
  }
  io.inputs.forEach((on, i) => {
    const button = inputs.children[i] as HTMLElement;
    button.classList.toggle("on", on);
    button.setAttribute("aria-pressed", String(on));
  });
  io.outputs.forEach((on, i) => outputs.children[i]!.classList.toggle("on", on));
  const analog = byId("signal-analog");
  const analogCount = io.analog_inputs.length;
  if (analog.childElementCount !== analogCount) {
    analog.replaceChildren(
      ...Array.from({ length: analogCount }, (_, i) => {
        const label = el("label", {}, `A${i + 1} `);
        const input = el("input", { type: "number", step: "any", "data-analog": String(i + 1), "aria-label": `$A_INA[${i + 1}]` });
        label.append(input, el("span", { class: "muted" }));
        return label;
      }),
    );
  }
  for (let i = 0; i < analogCount; i++) {
    const label = analog.children[i]!;
    const input = label.querySelector("input")!;
    if (document.activeElement !== input) input.value = String(io.analog_inputs[i] ?? 0);
    const out = io.analog_outputs[i];
    setText(label.querySelector("span")!, out === undefined ? "" : ` → ${fmt(out, 2)}`);
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

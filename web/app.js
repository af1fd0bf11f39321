// NCTwin operator screen: wires the buttons to the REST API and the stream to the page.

import { api, streamUrl } from "./api.js";
import { StateStream } from "./stream.js";
import * as view from "./render.js";

const DEFAULT_MACHINE = "mill-3axis";
const PACE = "realtime";
const DEMO_PROGRAM = ["G0 X0 Y0 Z50", "G1 X100 F6000", "G2 X0 Y0 I-50 J0", "G0 Z100", "M30", ""].join("\n");

const $ = (id) => document.getElementById(id);

let sessionId = null;
let stream = null;
let lastTime = -Infinity; // simulated time of the newest state shown
let pending = null; // state waiting for the next animation frame

// ---- state display --------------------------------------------------------

/** Show a state unless a newer one was shown already; at most once per frame. */
function showState(st) {
  if (!st || typeof st !== "object" || !st.status) return;
  if (typeof st.time === "number") {
    if (st.time < lastTime) return; // an answer that a stream message overtook
    lastTime = st.time;
  }
  const first = pending === null;
  pending = st;
  if (first) {
    requestAnimationFrame(() => {
      const s = pending;
      pending = null;
      view.renderState(s);
    });
  }
}

// ---- actions ----------------------------------------------------------------

/** Run one API call: clear the message bar, show a state answer, show an error answer. */
async function act(call, { keepMessage = false } = {}) {
  if (!sessionId) return undefined;
  if (!keepMessage) view.clearMessage();
  try {
    const result = await call(sessionId);
    showState(result);
    return result;
  } catch (e) {
    view.showMessage(e.message);
    return undefined;
  }
}

async function openSession(id) {
  const old = stream;
  sessionId = id;
  if (old) old.close();
  lastTime = -Infinity;
  view.renderSession(id);
  view.clearEvents();
  document.title = `NCTwin – ${id}`;
  const url = new URL(location.href);
  url.searchParams.set("session", id);
  history.replaceState(null, "", url);
  stream = new StateStream(streamUrl(id), {
    onState: showState,
    onEvent: view.addEvent,
    onConnection: (conn) => {
      view.renderConnection(conn);
      if (conn === "offline" && id === sessionId) checkSession(id);
    },
  });
  try {
    showState(await api.state(id));
  } catch (e) {
    view.showMessage(`session ${id}: ${e.message}`);
  }
}

/** After the stream dropped: stop reconnecting if the session is gone (deleted, server restart). */
async function checkSession(id) {
  try {
    await api.state(id);
  } catch (e) {
    if (e.status === 404 && id === sessionId && stream && !stream.closed) {
      stream.close();
      view.showMessage(`session ${id} no longer exists: click "New session"`);
    }
  }
}

async function newSession() {
  const machine = $("machine-select").value || DEFAULT_MACHINE;
  try {
    const created = await api.createSession(machine);
    view.clearMessage();
    await openSession(created.id);
  } catch (e) {
    view.showMessage(`new session: ${e.message}`);
  }
}

// ---- JOG: continuous while pressed (stops on release or when the pointer leaves the key),
// or one increment per press ---------------------------------------------------------------

let jogButton = null; // button held down in continuous jog
let jogCall = Promise.resolve();

function jogStart(ev) {
  const button = ev.target.closest("button[data-jog-axis]");
  if (!button || ev.button !== 0 || !sessionId) return;
  ev.preventDefault();
  const increment = $("jog-increment").value;
  const jog = { axis: button.dataset.jogAxis, direction: Number(button.dataset.dir) };
  if (increment) jog.increment = Number(increment);
  if ($("jog-rapid").checked) jog.rapid = true;
  if (!increment) {
    jogButton = button;
    button.classList.add("pressed");
  }
  jogCall = act((id) => api.jog(id, jog));
}

function jogEnd() {
  if (!jogButton) return;
  jogButton.classList.remove("pressed");
  jogButton = null;
  // After the jog request has been answered, so the stop cannot overtake it.
  // Keeps the message bar, which may show why the jog was refused.
  jogCall = jogCall.then(() => act((id) => api.jogStop(id), { keepMessage: true }));
}

// ---- wiring ---------------------------------------------------------------------

function wire() {
  $("program").value = DEMO_PROGRAM;
  $("btn-new-session").addEventListener("click", newSession);
  $("btn-start").addEventListener("click", () => act((id) => api.run(id, $("program").value, PACE)));
  $("btn-stop").addEventListener("click", () => act((id) => api.stop(id)));
  $("btn-continue").addEventListener("click", () => act((id) => api.start(id, PACE)));
  $("btn-reset").addEventListener("click", () => act((id) => api.reset(id)));
  $("btn-cancel").addEventListener("click", () => act((id) => api.cancel(id)));
  $("btn-message-close").addEventListener("click", view.clearMessage);
  for (const b of document.querySelectorAll("[data-set-mode]")) {
    b.addEventListener("click", () => act((id) => api.setMode(id, b.dataset.setMode)));
  }
  $("mda-form").addEventListener("submit", (ev) => {
    ev.preventDefault();
    const text = $("mda-input").value.trim();
    if (text) act((id) => api.mda(id, text));
  });
  const jogAxes = $("jog-axes");
  jogAxes.addEventListener("pointerdown", jogStart);
  jogAxes.addEventListener("pointerup", jogEnd);
  jogAxes.addEventListener("pointercancel", jogEnd);
  jogAxes.addEventListener("pointerleave", (ev) => ev.target === jogButton && jogEnd(), true);
  jogAxes.addEventListener("contextmenu", (ev) => ev.preventDefault());
  window.addEventListener("blur", jogEnd);
}

async function main() {
  wire();
  const params = new URLSearchParams(location.search);
  const wanted = params.get("machine") || DEFAULT_MACHINE;
  try {
    view.renderMachines(await api.machines(), wanted);
  } catch (e) {
    view.renderMachines([{ id: wanted, name: wanted }], wanted);
    view.showMessage(`machine list: ${e.message}`);
  }
  const given = params.get("session");
  if (given) {
    try {
      await api.state(given);
      await openSession(given);
      return;
    } catch (e) {
      await newSession();
      view.showMessage(`session ${given}: ${e.message}; opened a new session`);
      return;
    }
  }
  await newSession();
}

main();

// Everything that writes to the page. Reads nothing from the server itself.

const $ = (id) => document.getElementById(id);

function el(tag, attrs = {}, text) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}

function setText(node, text) {
  if (node.textContent !== text) node.textContent = text;
}

export function fmt(value, digits = 3) {
  if (typeof value !== "number" || !Number.isFinite(value)) return "–";
  const s = value.toFixed(digits);
  return /^-0\.?0*$/.test(s) ? s.slice(1) : s; // no "-0.000"
}

// ---- header -------------------------------------------------------------

export function renderSession(id) {
  setText($("session-id"), id || "–");
}

export function renderMachines(machines, selected) {
  const sel = $("machine-select");
  sel.replaceChildren(
    ...machines.map((m) => {
      const o = el("option", { value: m.id }, m.name || m.id);
      if (m.description) o.title = m.description;
      return o;
    }),
  );
  if (selected && machines.some((m) => m.id === selected)) sel.value = selected;
}

export function renderConnection(conn) {
  const node = $("connection");
  node.dataset.conn = conn;
  setText(node, conn);
}

// ---- message bar --------------------------------------------------------

export function showMessage(text, kind = "error") {
  const bar = $("message");
  bar.dataset.kind = kind;
  setText($("message-text"), text);
  bar.hidden = false;
}

export function clearMessage() {
  $("message").hidden = true;
  setText($("message-text"), "");
}

// ---- state --------------------------------------------------------------

let axesKey = null;
let alarmsKey = null;
let cells = {}; // "frame/axis" -> td

function renderPositions(positions) {
  const machine = Object.keys(positions.machine || {});
  const channel = Object.keys(positions.workpiece || positions.basic || {});
  const key = JSON.stringify([machine, channel]);
  if (key !== axesKey) {
    axesKey = key;
    cells = {};
    const rows = [];
    for (let i = 0; i < Math.max(machine.length, channel.length); i++) {
      const tr = el("tr");
      const cell = (frame, axis) => {
        const td = el("td", { class: "num" });
        if (axis !== undefined) {
          td.dataset.frame = frame;
          td.dataset.axis = axis;
          cells[`${frame}/${axis}`] = td;
        }
        return td;
      };
      tr.append(el("th", { class: "axis" }, machine[i] ?? ""), cell("machine", machine[i]));
      tr.append(el("th", { class: "axis" }, channel[i] ?? ""), cell("basic", channel[i]));
      tr.append(cell("workpiece", channel[i]));
      rows.push(tr);
    }
    $("positions").tBodies[0].replaceChildren(...rows);
    renderJogAxes(channel);
  }
  for (const frame of ["machine", "basic", "workpiece"]) {
    for (const [axis, value] of Object.entries(positions[frame] || {})) {
      const td = cells[`${frame}/${axis}`];
      if (td) setText(td, fmt(value));
    }
  }
}

function renderJogAxes(axes) {
  const box = $("jog-axes");
  box.replaceChildren(
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

function renderAlarms(alarms) {
  const key = JSON.stringify(alarms);
  if (key === alarmsKey) return;
  alarmsKey = key;
  const body = $("alarms").tBodies[0];
  body.replaceChildren(
    ...alarms.map((a) => {
      const tr = el("tr", { "data-alarm": String(a.number) });
      tr.append(
        el("td", { class: "num" }, String(a.number)),
        el("td", { class: "num" }, a.line != null ? String(a.line) : ""),
        el("td", {}, a.message || ""),
      );
      return tr;
    }),
  );
  $("alarms").classList.toggle("has-alarms", alarms.length > 0);
}

export function renderState(st) {
  const status = st.status || "";
  const badge = $("status");
  badge.dataset.status = status;
  setText(badge, status || "–");

  const mode = st.mode || "";
  const modeNode = $("mode");
  modeNode.dataset.mode = mode;
  setText(modeNode, mode || "–");
  for (const b of document.querySelectorAll("[data-set-mode]")) {
    b.classList.toggle("active", b.dataset.setMode === mode);
  }

  if (st.positions) renderPositions(st.positions);

  setText($("block-line"), st.block ? `N${st.block.line}` : "–");
  setText($("block-text"), st.block ? st.block.text : "");
  setText($("path-velocity"), fmt(st.path_velocity, 1));
  setText($("tool-t"), st.tool && st.tool.t != null ? String(st.tool.t) : "–");
  setText($("tool-d"), st.tool && st.tool.d != null ? String(st.tool.d) : "–");
  const spindles = Object.entries(st.spindles || {});
  setText(
    $("spindles"),
    spindles.length ? spindles.map(([name, rpm]) => `${name}: ${fmt(rpm, 0)} rpm`).join("  ") : "–",
  );
  const tr = st.transformation;
  setText($("transformation"), tr ? `${tr.name}${tr.index != null ? ` (${tr.index})` : ""}` : "none");
  setText($("sim-time"), fmt(st.time, 2));

  renderAlarms(st.alarms || []);
}

// ---- events -------------------------------------------------------------

const MAX_EVENTS = 30;

function describe(key, value) {
  if (key === "alarm" && value && typeof value === "object") {
    return `${value.number}${value.line != null ? ` (line ${value.line})` : ""}: ${value.message}`;
  }
  return `${key}=${typeof value === "object" ? JSON.stringify(value) : value}`;
}

export function addEvent(msg) {
  const list = $("events");
  const { type: _t, event, ...rest } = msg;
  const detail = Object.entries(rest)
    .map(([k, v]) => describe(k, v))
    .join(" ");
  const li = el("li", { "data-event": event || "" });
  li.append(el("span", { class: "event-name" }, event || "event"), document.createTextNode(` ${detail}`));
  list.prepend(li);
  while (list.children.length > MAX_EVENTS) list.lastElementChild.remove();
}

export function clearEvents() {
  $("events").replaceChildren();
}

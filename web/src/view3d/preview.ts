// The programmed path in the 3D view: the selected program run on a throwaway copy of the
// session's channel (POST .../preview), drawn in its own colour beside the executed path.
// Asked again when another program is selected, the session changes, or on the Preview key.

import { api } from "../api/client";
import { byId, setText } from "../core/dom";
import type { SessionController } from "../core/session";
import { selection } from "../program/selected";
import type { MachineView } from "./machineView";

/** Points asked for: enough for smooth arcs, small enough to draw at once. */
const MAX_POINTS = 8000;

export function mountPreview(session: SessionController, view: MachineView): void {
  const note = byId("view3d-preview");
  let serial = 0;
  const refresh = async () => {
    const id = session.id;
    if (!id) return;
    const mine = ++serial;
    const program = selection.current;
    setText(note, `preview ${program.name} …`);
    try {
      const r = await api.preview(id, { program: program.text, max_points: MAX_POINTS });
      if (mine !== serial || id !== session.id) return;
      view.setProgrammed(r.basic, r.axes, r.tracyl_diameter);
      const end =
        r.outcome === "alarm" && r.alarm ? ` – alarm ${r.alarm.number}${r.alarm.line ? ` in line ${r.alarm.line}` : ""}` : r.outcome === "limit" ? " – cut short" : "";
      setText(note, `programmed ${program.name}: ${r.time.toFixed(1)} s${end}`);
      note.dataset.points = String(r.points.length);
    } catch (e) {
      if (mine !== serial) return;
      view.setProgrammed([], ["X", "Y", "Z"]);
      setText(note, `no preview of ${program.name}: ${(e as Error).message}`);
      note.dataset.points = "0";
    }
  };
  let pending = false;
  // After the first state of a new session (the model needs its axes first).
  session.on("session", () => (pending = true));
  session.on("state", () => {
    if (!pending) return;
    pending = false;
    void refresh();
  });
  session.on("machine", () => void refresh());
  selection.on("change", () => void refresh());
  byId("btn-view-preview").addEventListener("click", () => void refresh());
}

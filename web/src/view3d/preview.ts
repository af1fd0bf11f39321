// The programmed path in the 3D view: the program the channel has loaded (or, before it has
// one, the selected program) run on a throwaway copy of the session's channel
// (POST .../preview), drawn in its own colour beside the executed path. The server thins the
// path to MAX_POINTS, so a CAM program of any size costs the browser the same. Asked again
// when the channel loads another program, another program is selected, the session changes,
// or on the Preview key.

import { api, ApiError } from "../api/client";
import { byId, setText } from "../core/dom";
import type { SessionController } from "../core/session";
import { activeName, activeProgram } from "../program/active";
import { selection } from "../program/selected";
import type { MachineView } from "./machineView";
import { PathScrub } from "./scrub";
import { showLimitHits } from "./limitCaption";

/** Points asked for: enough for smooth arcs, small enough to draw at once. */
const MAX_POINTS = 8000;
/** Simulated seconds of a loaded program's path (the server's largest). */
const ACTIVE_MAX_TIME_S = 3600;
/**
 * The server runs a few previews at once and answers 429 after a wait (a class previewing the
 * same CAM program): asked again this much later, this many times, before the note says so.
 */
const BUSY_RETRY_MS = 2000;
const BUSY_RETRIES = 5;

export function mountPreview(session: SessionController, view: MachineView): void {
  const note = byId("view3d-preview");
  const scrub = new PathScrub(view);
  let serial = 0;
  // The selection while it is newer than the loaded program, else the loaded program.
  let useSelection = true;
  const refresh = async (retries = BUSY_RETRIES) => {
    const id = session.id;
    if (!id) return;
    const mine = ++serial;
    const meta = activeProgram.meta;
    const active = meta && !useSelection;
    const program = active ? { name: activeName(meta) } : selection.current;
    setText(note, `preview ${program.name} …`);
    try {
      const body = active
        ? { active: true, max_points: MAX_POINTS, max_time: ACTIVE_MAX_TIME_S }
        : selection.current.stored
          ? { name: selection.current.name, max_points: MAX_POINTS }
          : { program: selection.current.text, max_points: MAX_POINTS };
      const r = await api.preview(id, body);
      if (mine !== serial || id !== session.id) return;
      view.check.set(r, view.cylinder()); // first: the framing of a new path includes the blank
      view.setProgrammed(r.basic, r.axes, r.tracyl_diameter, active ? `active ${meta.serial}` : `selected ${program.name}`);
      scrub.set(r, active ? { active: true, serial: meta.serial } : { active: false, text: selection.current.text });
      showLimitHits(r);
      const end =
        r.outcome === "alarm" && r.alarm ? ` – alarm ${r.alarm.number}${r.alarm.line ? ` in line ${r.alarm.line}` : ""}` : r.outcome === "limit" ? " – cut short" : "";
      setText(note, `programmed ${program.name}: ${r.time.toFixed(1)} s${end}`);
      note.dataset.points = String(r.points.length);
    } catch (e) {
      if (mine !== serial) return;
      if (e instanceof ApiError && e.status === 429 && retries > 0) {
        setText(note, `preview ${program.name}: the server is busy with other previews, asking again …`);
        setTimeout(() => {
          if (mine === serial && id === session.id) void refresh(retries - 1);
        }, BUSY_RETRY_MS);
        return;
      }
      view.setProgrammed([], ["X", "Y", "Z"]);
      view.check.clear();
      scrub.set(null, { active: false, text: "" });
      showLimitHits(null);
      setText(note, `no preview of ${program.name}: ${(e as Error).message}`);
      note.dataset.points = "0";
    }
  };
  // After the first state of a new session (the model needs its axes first). Until then a
  // change (the new session adopting its machine's demo) waits for it: one preview per new
  // session, not two racing each other.
  let shownFor: string | null = null;
  const ready = () => shownFor !== null && shownFor === session.id;
  session.on("session", () => (shownFor = null));
  session.on("state", () => {
    if (ready()) return;
    shownFor = session.id;
    void refresh();
  });
  session.on("machine", () => {
    if (ready()) void refresh();
  });
  selection.on("change", () => {
    useSelection = true;
    if (ready()) void refresh();
  });
  // MDA blocks (a swivel, a JOG-like move) do not replace the path of the AUTO program.
  activeProgram.on("change", (meta) => {
    if (!meta || meta.mode !== "AUTO") return;
    useSelection = false;
    void refresh();
  });
  byId("btn-view-preview").addEventListener("click", () => void refresh());
}

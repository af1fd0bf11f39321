// NCTwin HMI: mounts every view and attaches to a session (the one in the URL, or a new one).

import "./styles/base.css";
import "./styles/layout.css";
import "./styles/machine.css";
import "./styles/program.css";
import { api } from "./api/client";
import { rememberToken } from "./api/tokens";
import { showMessage, wireMessageBar } from "./core/message";
import { SessionController } from "./core/session";
import { selection } from "./program/selected";
import { activeProgram } from "./program/active";
import { mountCounters } from "./machine/counters";
import { mountStatusLine } from "./machine/statusLine";
import { mountJog } from "./jog/jog";
import { mountJogFunctions } from "./jog/jogFunctions";
import { mountSwivel } from "./swivel/swivel";
import { mountActiveSwivel } from "./swivel/activeSwivel";
import { Lobby } from "./lobby/lobby";
import { mountAlarms } from "./machine/alarms";
import { mountControl } from "./machine/control";
import { mountBlocks } from "./machine/blocks";
import { mountControls } from "./machine/controls";
import { mountEvents } from "./machine/events";
import { mountHeader } from "./machine/header";
import { mountOverrides } from "./machine/overrides";
import { mountPositions } from "./machine/positions";
import { mountProgress } from "./machine/progress";
import { mountSignals } from "./machine/signals";
import { mountTfs } from "./machine/tfs";
import { mountAxisPlot } from "./plot/axisPlot";
import { EditorArea } from "./program/editorArea";
import { ProgramManager } from "./program/manager";
import { mountMachineData } from "./setup/machineData";
import { mountTools } from "./tools/toolScreen";
import { showArea, wireAreas } from "./ui/areas";
import { mountLock } from "./ui/lockReasons";
import { mountMachineView } from "./view3d/machineView";
import { mountPreview } from "./view3d/preview";

const DEFAULT_MACHINE = "mill-3axis";

async function main(): Promise<void> {
  const session = new SessionController();
  // First listener: the views that follow read the demo chosen for the session's machine.
  session.on("session", (info) => selection.adoptDemo(info.machine.machine_data, info.machine.id));
  activeProgram.attach(session);
  wireMessageBar();
  wireAreas();
  mountHeader(session);
  mountControl(session);
  mountPositions(session);
  mountTfs(session);
  mountBlocks(session);
  mountProgress(session);
  mountStatusLine(session);
  mountOverrides(session);
  mountCounters(session);
  mountControls(session);
  mountJogFunctions(session, mountJog(session));
  mountSwivel(session);
  mountActiveSwivel(session);
  mountAlarms(session);
  mountSignals(session);
  mountEvents(session);
  mountPreview(session, mountMachineView(session));
  mountAxisPlot(session);
  const editor = new EditorArea(session);
  new ProgramManager(session, editor);
  mountMachineData(session);
  mountTools(session);
  const lobby = new Lobby(session);
  mountLock(session);
  showArea("machine");

  // `/` is the start page (running sessions and machines: join, watch or new); ?session=ID
  // joins that session (?view=watch: watches it); ?machine=PRESET opens a new session of it.
  const params = new URLSearchParams(location.search);
  const preset = params.get("machine");
  await lobby.loadMachines(preset ?? DEFAULT_MACHINE).catch((e: Error) => showMessage(`machine list: ${e.message}`));
  const wanted = params.get("session");
  if (!wanted) {
    if (preset) return lobby.create(preset);
    showArea("sessions");
    return;
  }
  // A shared link: keep its token, and keep it out of the address bar.
  const token = params.get("token");
  if (token) {
    rememberToken(wanted, token);
    const url = new URL(location.href);
    url.searchParams.delete("token");
    history.replaceState(null, "", url);
  }
  try {
    const existing = await api.session(wanted);
    await session.attach(existing.id, existing.machine);
  } catch (e) {
    // No new session behind the user's back: the start page, with the reason.
    const url = new URL(location.href);
    url.search = "";
    history.replaceState(null, "", url);
    showArea("sessions");
    showMessage(`session ${wanted} cannot be opened (${(e as Error).message}): join a running session or start a new one`);
  }
}

void main();

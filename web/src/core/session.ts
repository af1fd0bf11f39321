// The session the screen is attached to: its id, machine, live stream, and the newest state.
// Views subscribe to its events instead of talking to the stream themselves.

import { api, streamUrl } from "../api/client";
import { StateStream, type Connection, type StreamReply } from "../api/stream";
import type { StockPush } from "../api/stockPush";
import type { MachineDetail, State, StreamEvent } from "../api/types";
import { Emitter } from "./emitter";
import { clearMessage, showMessage } from "./message";

export interface SessionInfo {
  id: string;
  machine: MachineDetail;
}

type SessionEvents = {
  /** A new session was attached (views reset what belongs to the old one). */
  session: SessionInfo;
  /** Every new state, in order (for plots and toolpaths). */
  sample: State;
  /** The newest state, at most once per animation frame (for the DOM). */
  state: State;
  event: StreamEvent;
  connection: Connection;
  /** The session's NC data changed (new text in `info.machine.machine_data`). */
  machine: SessionInfo;
  /** The server's `ack`/`error` to a message this page sent on the stream. */
  reply: StreamReply;
  /** The stream is back after it was lost: what was read before may be stale. */
  reconnected: SessionInfo;
  /** The stock's changed tiles pushed on the stream. */
  stock: StockPush;
};

export class SessionController extends Emitter<SessionEvents> {
  info: SessionInfo | null = null;
  latest: State | null = null;
  private stream: StateStream | null = null;
  private lastTime = -Infinity;
  private framePending = false;
  /** The stream was lost and has not come back yet. */
  private lost = false;

  get id(): string | null {
    return this.info?.id ?? null;
  }

  /** Attaches the screen to an existing session. */
  async attach(id: string, machineId: string): Promise<void> {
    const preset = await api.machine(machineId).catch(
      (): MachineDetail => ({ id: machineId, name: machineId, description: "", machine_data: "" }),
    );
    // The session's own data (preset plus what was applied since), for the views that read
    // machine data (travel, axis types); the preset's when the server cannot tell.
    const own = await api.machineData(id).catch(() => null);
    const machine = own ? { ...preset, machine_data: own.text } : preset;
    this.stream?.close();
    this.info = { id, machine };
    this.latest = null;
    this.lastTime = -Infinity;
    this.lost = false;
    document.body.classList.remove("stale");
    this.emit("session", this.info);
    const url = new URL(location.href);
    url.searchParams.set("session", id);
    history.replaceState(null, "", url);
    document.title = `NCTwin – ${id}`;
    this.stream = new StateStream(streamUrl(id), {
      onState: (st) => this.accept(st),
      onEvent: (ev) => this.emit("event", ev),
      onReply: (reply) => this.emit("reply", reply),
      onStock: (push) => this.emit("stock", push),
      onConnection: (conn) => this.connectionChanged(id, conn),
    });
    this.accept(await api.state(id));
  }

  /**
   * While the stream is down the screen shows stale values (greyed). Back online, the first
   * state is taken whatever its time (a restarted server starts its session time afresh), the
   * active program is read again and the messages of before are cleared.
   */
  private connectionChanged(id: string, conn: Connection): void {
    const wasLost = this.lost;
    if (conn === "offline") this.lost = true;
    document.body.classList.toggle("stale", this.lost && conn !== "online");
    this.emit("connection", conn);
    if (conn === "offline") void this.checkAlive(id);
    if (conn === "online" && wasLost && this.info && id === this.info.id) {
      this.lost = false;
      this.lastTime = -Infinity;
      clearMessage();
      this.emit("reconnected", this.info);
    }
  }

  /** Whether client messages can go over the live stream now. */
  get streamOnline(): boolean {
    return this.stream?.online ?? false;
  }

  /** Sends a client message on the live stream (JOG keys); false when it is not connected. */
  send(message: object): boolean {
    return this.stream?.send(message) ?? false;
  }

  /** Takes the session's NC data text as read after a change, for the views that use it. */
  setMachineData(text: string): void {
    if (!this.info || this.info.machine.machine_data === text) return;
    this.info = { ...this.info, machine: { ...this.info.machine, machine_data: text } };
    this.emit("machine", this.info);
  }

  /** Shows a state unless a newer one was shown already (an answer a stream message overtook). */
  accept(st: State | null | undefined): void {
    if (!st || typeof st !== "object" || !st.status) return;
    if (st.time < this.lastTime) return;
    this.lastTime = st.time;
    this.latest = st;
    this.emit("sample", st);
    if (this.framePending) return;
    this.framePending = true;
    requestAnimationFrame(() => {
      this.framePending = false;
      if (this.latest) this.emit("state", this.latest);
    });
  }

  /**
   * Runs one API call on the attached session: clears the message bar, shows a state answer,
   * shows an error answer. Returns the answer, or undefined after an error.
   */
  async act<T>(call: (id: string) => Promise<T>, opts: { keepMessage?: boolean } = {}): Promise<T | undefined> {
    const id = this.id;
    if (!id) return undefined;
    if (!opts.keepMessage) clearMessage();
    try {
      const result = await call(id);
      if (result && typeof result === "object" && "status" in result) this.accept(result as unknown as State);
      return result;
    } catch (e) {
      showMessage((e as Error).message);
      return undefined;
    }
  }

  /** After the stream dropped: stop reconnecting if the session is gone. */
  private async checkAlive(id: string): Promise<void> {
    try {
      await api.state(id);
    } catch (e) {
      const status = (e as { status?: number }).status;
      if (status === 404 && id === this.id && this.stream && !this.stream.closed) {
        this.stream.close();
        showMessage(`session ${id} no longer exists: open the Sessions area to start a new one`);
      }
    }
  }
}

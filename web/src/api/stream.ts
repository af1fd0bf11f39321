// Live stream of one session over WebSocket, reconnecting with back-off when it drops.

import type { StockPush } from "./stockPush";
import type { State, StreamEvent } from "./types";

const MIN_DELAY_MS = 500;
const MAX_DELAY_MS = 5000;

export type Connection = "connecting" | "online" | "offline";

/** The server's answer to a client message: `ack`, or `error` with the REST status. */
export interface StreamReply {
  type: "ack" | "error";
  request?: string | null;
  error?: string;
  status?: number;
}

export interface StreamHandlers {
  onState(state: State): void;
  onEvent(event: StreamEvent): void;
  onConnection(conn: Connection): void;
  onReply?(reply: StreamReply): void;
  onStock?(push: StockPush): void;
}

export class StateStream {
  private ws: WebSocket | null = null;
  private retries = 0;
  private timer: ReturnType<typeof setTimeout> | undefined;
  closed = false;

  constructor(
    private readonly url: string,
    private readonly handlers: StreamHandlers,
  ) {
    this.connect();
  }

  private connect(): void {
    if (this.closed) return;
    this.handlers.onConnection("connecting");
    const ws = new WebSocket(this.url);
    this.ws = ws;
    ws.onopen = () => {
      this.retries = 0;
      this.handlers.onConnection("online");
    };
    ws.onmessage = (ev: MessageEvent<string>) => {
      let msg: { type?: string };
      try {
        msg = JSON.parse(ev.data);
      } catch {
        return; // not ours to show
      }
      if (msg.type === "state") this.handlers.onState(msg as unknown as State);
      else if (msg.type === "event") this.handlers.onEvent(msg as StreamEvent);
      else if (msg.type === "ack" || msg.type === "error") this.handlers.onReply?.(msg as StreamReply);
      else if (msg.type === "stock") this.handlers.onStock?.(msg as StockPush);
    };
    ws.onclose = () => {
      if (this.ws !== ws) return;
      this.ws = null;
      if (this.closed) return;
      this.handlers.onConnection("offline");
      const delay = Math.min(MAX_DELAY_MS, MIN_DELAY_MS * 2 ** this.retries++);
      this.timer = setTimeout(() => this.connect(), delay);
    };
    // An error is always followed by close, which schedules the reconnect.
    ws.onerror = () => {};
  }

  /** Whether the socket is open (client messages can be sent). */
  get online(): boolean {
    return this.ws?.readyState === WebSocket.OPEN;
  }

  /** Sends one client message (JSON); false when the socket is not open. */
  send(message: object): boolean {
    if (!this.ws || this.ws.readyState !== WebSocket.OPEN) return false;
    this.ws.send(JSON.stringify(message));
    return true;
  }

  close(): void {
    this.closed = true;
    clearTimeout(this.timer);
    const ws = this.ws;
    this.ws = null;
    ws?.close();
    this.handlers.onConnection("offline");
  }
}

// Live state stream of one session over WebSocket, reconnecting when it drops.

const MIN_DELAY_MS = 500;
const MAX_DELAY_MS = 5000;

export class StateStream {
  /**
   * @param {string} url WebSocket address
   * @param {{onState?: Function, onEvent?: Function, onConnection?: Function}} handlers
   *   onConnection receives "connecting" | "online" | "offline".
   */
  constructor(url, handlers) {
    this.url = url;
    this.handlers = handlers;
    this.ws = null;
    this.closed = false;
    this.retries = 0;
    this.timer = null;
    this.connect();
  }

  connect() {
    if (this.closed) return;
    this.emit("onConnection", "connecting");
    const ws = new WebSocket(this.url);
    this.ws = ws;
    ws.onopen = () => {
      this.retries = 0;
      this.emit("onConnection", "online");
    };
    ws.onmessage = (ev) => {
      let msg;
      try {
        msg = JSON.parse(ev.data);
      } catch {
        return; // not ours to show
      }
      if (msg.type === "state") this.emit("onState", msg);
      else if (msg.type === "event") this.emit("onEvent", msg);
    };
    ws.onclose = () => {
      if (this.ws !== ws) return;
      this.ws = null;
      if (this.closed) return;
      this.emit("onConnection", "offline");
      const delay = Math.min(MAX_DELAY_MS, MIN_DELAY_MS * 2 ** this.retries++);
      this.timer = setTimeout(() => this.connect(), delay);
    };
    // An error is always followed by close, which schedules the reconnect.
    ws.onerror = () => {};
  }

  emit(name, arg) {
    const fn = this.handlers[name];
    if (fn) fn(arg);
  }

  close() {
    this.closed = true;
    clearTimeout(this.timer);
    if (this.ws) {
      const ws = this.ws;
      this.ws = null;
      ws.close();
    }
    this.emit("onConnection", "offline");
  }
}

// The message bar under the header: errors of the last action, hints.

import { byId, setText } from "./dom";

export type MessageKind = "error" | "info";

export function showMessage(text: string, kind: MessageKind = "error"): void {
  const bar = byId("message");
  bar.dataset.kind = kind;
  setText(byId("message-text"), text);
  bar.hidden = false;
}

export function clearMessage(): void {
  byId("message").hidden = true;
  setText(byId("message-text"), "");
}

export function wireMessageBar(): void {
  byId("btn-message-close").addEventListener("click", clearMessage);
}

// Controls off, with the reason in plain words: for a page that only watches (a watch link),
// an observer, and an operator while someone else holds control. Everything that drives the
// machine or changes its data is disabled (mode keys, Cycle start/stop, Reset, JOG, MDA,
// overrides, the editor's and the data areas' writes); what only changes the view (coordinate
// system, 3D view, plot, area switch, the start page) stays usable.

import { byId, setText } from "../core/dom";

/** Where the driving controls are. */
const SCOPES = [".mode-buttons", ".machine-right", "#area-program", "#area-manager", "#area-data", "#area-tools"];
/** Controls inside those scopes that only change the view. */
const VIEW_ONLY_OK = "[data-tools-tab], [data-view-ok], #btn-message-close";
const CONTROLS = "button, input, select, textarea";

let reason: string | null = null;
let observer: MutationObserver | null = null;
/** Controls that are no form elements (the CodeMirror editors) and lock themselves. */
const listeners = new Set<(why: string | null) => void>();

/** Calls `fn` with the reason now and on every change (null: the controls are on). */
export function onLockChange(fn: (why: string | null) => void): void {
  listeners.add(fn);
  fn(reason);
}

/** The reason the controls are off (null: they are on). */
export function lockReason(): string | null {
  return reason;
}

/** Turns the controls off with `why`, or on again with null. */
export function lockControls(why: string | null): void {
  if (why === reason) return;
  const was = reason;
  reason = why;
  const banner = byId("lock-banner");
  banner.hidden = why === null;
  setText(banner, why ?? "");
  if (why === null) delete document.body.dataset.locked;
  else document.body.dataset.locked = "true";
  for (const fn of listeners) fn(why);
  if (why === null) {
    observer?.disconnect();
    observer = null;
    for (const node of document.querySelectorAll<HTMLElement>("[data-locked]")) unlock(node);
    return;
  }
  for (const scope of scopes()) lockWithin(scope);
  if (was === null) {
    // Views rebuild their keys (JOG axes, program lists): those come in locked too.
    // A view that enables a key again (Cycle start after a state change) is overruled.
    observer = new MutationObserver((records) => {
      for (const r of records) {
        for (const n of r.addedNodes) if (n instanceof HTMLElement) lockWithin(n);
        const t = r.target as HTMLButtonElement;
        if (r.type === "attributes" && t.dataset.locked && !t.disabled) {
          t.dataset.locked = "true";
          t.disabled = true;
        }
      }
    });
    for (const scope of scopes()) {
      observer.observe(scope, { childList: true, subtree: true, attributes: true, attributeFilter: ["disabled"] });
    }
  } else {
    for (const node of document.querySelectorAll<HTMLElement>("[data-locked]")) node.title = reason ?? "";
  }
}

function scopes(): HTMLElement[] {
  return SCOPES.flatMap((s) => [...document.querySelectorAll<HTMLElement>(s)]);
}

function lockWithin(root: HTMLElement): void {
  const nodes = root.matches(CONTROLS) ? [root] : [...root.querySelectorAll<HTMLElement>(CONTROLS)];
  for (const node of nodes) {
    if (node.matches(VIEW_ONLY_OK) || node.dataset.locked) continue;
    const control = node as HTMLButtonElement;
    node.dataset.locked = control.disabled ? "was-disabled" : "true";
    node.dataset.titleBefore = node.title;
    control.disabled = true;
    node.title = reason ?? "";
  }
}

function unlock(node: HTMLElement): void {
  (node as HTMLButtonElement).disabled = node.dataset.locked === "was-disabled";
  node.title = node.dataset.titleBefore ?? "";
  delete node.dataset.locked;
  delete node.dataset.titleBefore;
}

// Operating areas (Machine, Program, Program manager, Machine data, Tools, Sessions), switched by the softkey bar.

import { Emitter } from "../core/emitter";

export type Area = "machine" | "program" | "manager" | "data" | "tools" | "sessions";

export const areaChanged = new Emitter<{ change: Area }>();

let current: Area = "machine";

export function currentArea(): Area {
  return current;
}

export function showArea(area: Area): void {
  current = area;
  for (const node of document.querySelectorAll<HTMLElement>("[data-area]")) {
    node.hidden = node.dataset.area !== area;
  }
  for (const key of document.querySelectorAll<HTMLElement>("[data-goto]")) {
    key.classList.toggle("active", key.dataset.goto === area);
  }
  areaChanged.emit("change", area);
}

export function wireAreas(): void {
  for (const key of document.querySelectorAll<HTMLButtonElement>("[data-goto]")) {
    key.addEventListener("click", () => showArea(key.dataset.goto as Area));
  }
}

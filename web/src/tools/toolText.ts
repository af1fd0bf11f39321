// How the tool screens show a tool's data: type symbol and short name from $TC_DP1, state from
// $TC_TP8, place from $TC_MPP6, remaining life from $TC_MOP2/$TC_MOP4 (pure functions).

import { fmt } from "../core/dom";
import type { ToolEdge, ToolEntry } from "./toolsApi";

export interface ToolType {
  family: "mill" | "drill" | "grind" | "turn" | "special" | "none";
  symbol: string;
  short: string;
  long: string;
}

/** $TC_DP1 tool types (Function Manual W1, "Tool type") as Operate names them, short. */
const NAMED: Record<number, [string, string]> = {
  100: ["MILL", "Milling tool"],
  110: ["BALL", "Ball end mill"],
  111: ["BALL", "Conical ball end mill"],
  120: ["END MILL", "End mill"],
  121: ["END MILL R", "End mill with corner rounding"],
  130: ["ANGLE", "Angle head cutter"],
  140: ["FACE", "Face mill"],
  145: ["THREAD", "Thread cutter"],
  150: ["SIDE", "Side mill"],
  155: ["BEVEL", "Bevel cutter"],
  200: ["DRILL", "Twist drill"],
  205: ["DRILL", "Solid drill"],
  210: ["BORE", "Boring bar"],
  220: ["CENTER", "Centre drill"],
  230: ["COUNTERSINK", "Countersink"],
  240: ["TAP", "Tap"],
  250: ["REAMER", "Reamer"],
  500: ["ROUGH", "Roughing tool"],
  510: ["FINISH", "Finishing tool"],
  520: ["PLUNGE", "Plunge cutter"],
  530: ["PARTING", "Parting tool"],
  540: ["THREAD", "Threading tool"],
  550: ["BUTTON", "Button tool"],
  560: ["DRILL", "Rotary drill"],
  580: ["PROBE", "Turning probe"],
  700: ["SAW", "Slotting saw"],
  710: ["3D PROBE", "3D probe"],
  711: ["EDGE PROBE", "Edge probe"],
  730: ["STOP", "Stop"],
};

export function typeOf(dp1: number): ToolType {
  const t = Math.round(dp1);
  const [short, long] = NAMED[t] ?? ["", ""];
  if (t >= 100 && t < 200) return { family: "mill", symbol: "⌀", short: short || "MILL", long: long || "Milling tool" };
  if (t >= 200 && t < 300) return { family: "drill", symbol: "▽", short: short || "DRILL", long: long || "Drilling tool" };
  if (t >= 400 && t < 500) return { family: "grind", symbol: "◎", short: "GRIND", long: "Grinding tool" };
  if (t >= 500 && t < 600) return { family: "turn", symbol: "◇", short: short || "TURN", long: long || "Turning tool" };
  if (t >= 700) return { family: "special", symbol: "✱", short: short || "SPECIAL", long: long || "Special tool" };
  return { family: "none", symbol: "·", short: "–", long: "no type" };
}

export interface ToolStateText {
  disabled: boolean;
  prewarning: boolean;
  text: string;
}

/** $TC_TP8: bit 0 active, 1 enabled, 2 disabled, 3 measured, 4 prewarning. */
export function stateOf(tp8: number): ToolStateText {
  const disabled = (tp8 & 4) !== 0;
  const prewarning = (tp8 & 16) !== 0;
  const words: string[] = [];
  if (disabled) words.push("disabled");
  if (prewarning) words.push("prewarning");
  if (!disabled && tp8 & 2) words.push("enabled");
  if (tp8 & 1) words.push("active");
  if (tp8 & 8) words.push("measured");
  return { disabled, prewarning, text: words.join(", ") || "–" };
}

export function placeText(tool: ToolEntry): string {
  if (tool.in_spindle) return "Spindle";
  const p = tool.place;
  if (!p) return "–";
  if (p.magazine === 9999) return `unloaded (${p.place})`;
  return `${p.magazine}/${p.place}${tool.auto_placed ? " *" : ""}`;
}

/** $TC_TP9 bit 0: remaining minutes ($TC_MOP2); bit 1: remaining pieces ($TC_MOP4). */
export function remainingLife(tool: ToolEntry, edge: ToolEdge): string {
  const parts: string[] = [];
  if (tool.monitoring & 1) parts.push(`${fmt(edge.monitoring["2"] ?? 0, 2)} min`);
  if (tool.monitoring & 2) parts.push(`${fmt(edge.monitoring["4"] ?? 0, 0)} pcs`);
  return parts.join(" / ");
}

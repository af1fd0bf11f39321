// The swivel form: CYCLE800's fields grouped as on the Operate screen (swivel data set,
// retraction, swivel mode and axis sequence, reference point, angles, zero point, direction),
// sent as POST .../swivel. The server runs the cycle as one MDA block and returns to JOG.

import { api } from "../api/client";
import type { SwivelCommand } from "../api/types";
import { byId } from "../core/dom";
import type { SessionController } from "../core/session";

function command(form: HTMLFormElement): SwivelCommand {
  const data = new FormData(form);
  const num = (name: string): number => Number(data.get(name) ?? 0) || 0;
  const tc = String(data.get("data_set") ?? "").trim();
  return {
    ...(tc ? { data_set: tc } : {}),
    retract: num("retract"),
    additive: data.get("additive") === "on",
    tracking: data.get("tracking") === "on",
    mode: String(data.get("mode")) as SwivelCommand["mode"],
    sequence: String(data.get("sequence") ?? "XYZ"),
    x0: num("x0"),
    y0: num("y0"),
    z0: num("z0"),
    a: num("a"),
    b: num("b"),
    c: num("c"),
    x1: num("x1"),
    y1: num("y1"),
    z1: num("z1"),
    direction: num("direction") < 0 ? -1 : 1,
    wait: true,
  };
}

export function mountSwivel(session: SessionController): void {
  const form = byId<HTMLFormElement>("swivel-form");
  form.addEventListener("submit", (ev) => {
    ev.preventDefault();
    const cmd = command(form);
    void session.act((id) => api.swivel(id, cmd));
  });
  byId("btn-swivel-off").addEventListener("click", () => {
    const cmd = { ...command(form), data_set: "0" };
    void session.act((id) => api.swivel(id, cmd));
  });
}

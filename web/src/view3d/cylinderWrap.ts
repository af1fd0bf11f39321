// Wrapping a TRACYL point of the unrolled surface onto the cylinder of the machine model: the
// programmed path, the executed path a late viewer fetches and the limit marks use it alike.

import type { Structure } from "./machineData";

/**
 * A TRACYL point (X radial, Y arc length on diameter d, Z axial) on the cylinder: at X from
 * the axis, turned by Y / (d/2) from the radial direction towards parallel × radial (the way
 * the engine's TRACYL turns the workpiece under the tool), Z along the axis.
 */
export function wrapOnCylinder(p: [number, number, number], d: number, c: NonNullable<Structure["cylinder"]>): [number, number, number] {
  const [r, u] = [c.radial, c.parallel];
  const perp = [u[1] * r[2] - u[2] * r[1], u[2] * r[0] - u[0] * r[2], u[0] * r[1] - u[1] * r[0]];
  const theta = p[1] / (d / 2);
  const [cos, sin] = [Math.cos(theta), Math.sin(theta)];
  return [0, 1, 2].map((i) => r[i]! * p[0] * cos + perp[i]! * p[0] * sin + u[i]! * p[2]) as [number, number, number];
}

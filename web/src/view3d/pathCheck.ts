// What the 3D view adds to the programmed path for checking a program (from the preview,
// POST .../preview): on 5-axis machines the tool axis as short lines every few mm along the
// path (the preview's tool direction under TRAORI, interpolated between its points); the points
// where an axis reached its velocity (violet) or acceleration (yellow) limit in feed motion;
// the blank the program defines with WORKPIECE(...) as an outline (a box, or a cylinder about Z
// for a turned blank); and the position marker the path slider (scrub.ts) moves. All in the part frame (BCS mm), so
// they turn with a rotary table as the programmed path does. Bounded whatever the program's
// size: at most MAX_TOOL_AXES lines, the server's 200 limit hits, one marker.

import * as THREE from "three";
import type { LimitHit, PreviewResponse } from "../api/types";
import { wrapOnCylinder } from "./cylinderWrap";
import type { Structure } from "./machineData";

export const TOOL_AXIS_COLOR = 0x9be7a0;
export const VELOCITY_COLOR = 0xc77dff;
export const ACCEL_COLOR = 0xffd166;
/** A mark whose place on the part is not known (a table turned outside the kinematics). */
export const INEXACT_COLOR = 0x8a949e;
const MARKER_COLOR = 0xffffff;
const BLANK_COLOR = 0x9fb0c2;
/** Most tool axis lines drawn along a path. */
export const MAX_TOOL_AXES = 600;
/** Smallest spacing of the tool axis lines (mm). */
const MIN_SPACING = 1;

type P3 = [number, number, number];

/** Maps a preview's (axes-ordered) coordinates to the part frame's X, Y, Z. */
export function cartesianOf(axes: string[]): (p: P3) => P3 {
  const slot = axes.map((name) => ({ X: 0, Y: 1, Z: 2 })[name as "X" | "Y" | "Z"] ?? -1);
  return (p) => {
    const q: P3 = [0, 0, 0];
    slot.forEach((s, k) => s >= 0 && (q[s] = p[k] ?? 0));
    return q;
  };
}

/**
 * The tool axis lines of a path: every `spacing` mm along the polyline `points`, a line of
 * `length` from the tip along the tool direction (interpolated between the neighbouring
 * points' directions; none where a direction is missing). At most `max` lines.
 */
export function toolAxisLines(points: P3[], dirs: (P3 | null)[], length: number, max = MAX_TOOL_AXES): Float32Array {
  let total = 0;
  for (let i = 1; i < points.length; i++) total += dist(points[i - 1]!, points[i]!);
  if (!dirs.some((d) => d)) return new Float32Array(0);
  const spacing = Math.max(MIN_SPACING, total / max);
  const out: number[] = [];
  let next = 0; // distance along the path of the next line
  let along = 0;
  const emit = (p: P3, d: P3) => {
    const n = Math.hypot(d[0], d[1], d[2]);
    if (!(n > 0) || out.length / 6 >= max) return;
    out.push(p[0], p[1], p[2], p[0] + (d[0] / n) * length, p[1] + (d[1] / n) * length, p[2] + (d[2] / n) * length);
  };
  for (let i = 0; i < points.length; i++) {
    const a = points[i]!;
    if (i === 0) {
      if (dirs[0]) emit(a, dirs[0]);
      next = spacing;
      continue;
    }
    const b = points[i - 1]!;
    const seg = dist(b, a);
    const [db, da] = [dirs[i - 1], dirs[i]];
    while (seg > 0 && next <= along + seg) {
      const t = (next - along) / seg;
      if (db && da) emit(lerp(b, a, t), lerp(db, da, t));
      next += spacing;
    }
    along += seg;
  }
  return new Float32Array(out);
}

function dist(a: P3, b: P3): number {
  return Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

function lerp(a: P3, b: P3, t: number): P3 {
  return [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t];
}

export class PathCheck {
  readonly group = new THREE.Group();
  private readonly toolAxes = new THREE.LineSegments(
    new THREE.BufferGeometry(),
    new THREE.LineBasicMaterial({ color: TOOL_AXIS_COLOR, depthTest: false, transparent: true, opacity: 0.85 }),
  );
  private readonly limits = new THREE.Group();
  private readonly limitGeometry = new THREE.OctahedronGeometry(1);
  private readonly velocityMaterial = new THREE.MeshBasicMaterial({ color: VELOCITY_COLOR, depthTest: false });
  private readonly accelMaterial = new THREE.MeshBasicMaterial({ color: ACCEL_COLOR, depthTest: false });
  private readonly inexactMaterial = new THREE.MeshBasicMaterial({ color: INEXACT_COLOR, depthTest: false, wireframe: true });
  /** The slider's position on the programmed path. */
  readonly marker = new THREE.Mesh(new THREE.SphereGeometry(1, 16, 12), new THREE.MeshBasicMaterial({ color: MARKER_COLOR, depthTest: false }));
  /** The limit hits drawn, for the caption and the browser test. */
  hits: LimitHit[] = [];

  /** Where each of `hits` is drawn (part frame), for the browser test. */
  markPositions(): [number, number, number][] {
    return this.limits.children.map((m) => m.position.toArray() as [number, number, number]);
  }
  /** Tool axis lines drawn. */
  toolAxisCount = 0;
  /** The blank's outline (part frame), null without one. */
  private readonly blankOutline = new THREE.Group();
  /** The blank drawn (BCS box), for framing and the browser test. */
  blank: THREE.Box3 | null = null;

  constructor() {
    this.toolAxes.renderOrder = 4;
    this.limits.renderOrder = 5;
    this.marker.renderOrder = 6;
    this.marker.visible = false;
    this.group.add(this.toolAxes, this.limits, this.marker, this.blankOutline);
  }

  /**
   * Draws the tool axes and limit marks of a preview answer (BCS = part frame); a mark under
   * TRACYL is wrapped onto `cylinder` as the programmed path is. A mark the server could not
   * place on the part (`exact: false`) is drawn grey and hollow.
   */
  set(r: PreviewResponse, cylinder: Structure["cylinder"] = null): void {
    this.clear();
    const cart = cartesianOf(r.axes);
    const points = r.basic.map(cart);
    const box = new THREE.Box3();
    for (const p of points) box.expandByPoint(new THREE.Vector3(...p));
    const size = box.isEmpty() ? 100 : box.getSize(new THREE.Vector3()).length();
    const dirs = (r.tool_direction ?? []).map((d) => (d ? cart(d) : null));
    const lines = toolAxisLines(points, dirs, Math.min(50, Math.max(5, size * 0.05)));
    this.toolAxes.geometry.setAttribute("position", new THREE.BufferAttribute(lines, 3));
    this.toolAxes.geometry.computeBoundingSphere();
    this.toolAxisCount = lines.length / 6;
    const radius = Math.min(6, Math.max(0.8, size * 0.008));
    this.hits = r.limit_hits ?? [];
    for (const h of this.hits) {
      const material = h.exact === false ? this.inexactMaterial : h.kind === "velocity" ? this.velocityMaterial : this.accelMaterial;
      const mark = new THREE.Mesh(this.limitGeometry, material);
      const d = h.tracyl_diameter;
      mark.position.set(...(cylinder && typeof d === "number" && d > 0 ? wrapOnCylinder(cart(h.basic), d, cylinder) : cart(h.basic)));
      mark.scale.setScalar(radius * 1.4);
      mark.renderOrder = 5;
      this.limits.add(mark);
    }
    this.marker.scale.setScalar(radius * 1.2);
    if (r.blank) this.drawBlank(r.blank);
  }

  private drawBlank(b: NonNullable<PreviewResponse["blank"]>): void {
    const [min, max] = [new THREE.Vector3(...b.min), new THREE.Vector3(...b.max)];
    const size = max.clone().sub(min);
    const center = min.clone().add(max).multiplyScalar(0.5);
    const shape = b.turning
      ? new THREE.CylinderGeometry(size.x / 2, size.x / 2, size.z, 48, 1).rotateX(Math.PI / 2)
      : new THREE.BoxGeometry(size.x, size.y, size.z);
    const edges = new THREE.LineSegments(
      new THREE.EdgesGeometry(shape, 20),
      new THREE.LineBasicMaterial({ color: BLANK_COLOR, transparent: true, opacity: 0.8 }),
    );
    shape.dispose();
    edges.position.copy(center);
    this.blankOutline.add(edges);
    this.blank = new THREE.Box3(min, max);
  }

  /** Puts the marker at `p` (part frame); null hides it. */
  mark(p: THREE.Vector3 | null): void {
    this.marker.visible = p !== null;
    if (p) this.marker.position.copy(p);
  }

  clear(): void {
    this.toolAxes.geometry.dispose();
    this.toolAxes.geometry = new THREE.BufferGeometry();
    this.toolAxisCount = 0;
    this.limits.clear();
    this.hits = [];
    for (const c of this.blankOutline.children) (c as THREE.LineSegments).geometry.dispose();
    this.blankOutline.clear();
    this.blank = null;
    this.marker.visible = false;
  }
}

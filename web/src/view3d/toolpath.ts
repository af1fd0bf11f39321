// The executed toolpath: a polyline of visited tool tip positions in a growing buffer.

import * as THREE from "three";

const CAPACITY = 200_000; // points; the oldest half is dropped when full
const MIN_STEP = 0.01; // mm between two stored points

export class Toolpath {
  readonly line: THREE.Line;
  private readonly positions = new Float32Array(CAPACITY * 3);
  private readonly attribute = new THREE.BufferAttribute(this.positions, 3);
  private count = 0;
  private readonly last = new THREE.Vector3();

  constructor(color = 0xffb02e) {
    this.attribute.setUsage(THREE.DynamicDrawUsage);
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", this.attribute);
    geometry.setDrawRange(0, 0);
    // Drawn over the solids (the tool tip is often inside the workpiece or under the tool).
    this.line = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color, depthTest: false, transparent: true }));
    this.line.frustumCulled = false; // the bounding sphere would need recomputing on every point
  }

  /** Appends a point unless it is where the path already ends. Returns whether it did. */
  add(p: THREE.Vector3): boolean {
    if (this.count > 0 && p.distanceTo(this.last) < MIN_STEP) return false;
    if (this.count === CAPACITY) {
      const keep = CAPACITY / 2;
      this.positions.copyWithin(0, (CAPACITY - keep) * 3);
      this.count = keep;
      this.attribute.clearUpdateRanges(); // upload everything once
    } else {
      this.attribute.addUpdateRange(this.count * 3, 3); // upload only the new point
    }
    this.positions.set([p.x, p.y, p.z], this.count * 3);
    this.count++;
    this.last.copy(p);
    this.attribute.needsUpdate = true;
    this.line.geometry.setDrawRange(0, this.count);
    return true;
  }

  /**
   * Puts `points` (an earlier path, oldest first) before the stored ones, the oldest dropped
   * beyond the capacity. Returns how many of them were kept.
   */
  prepend(points: THREE.Vector3[]): number {
    const room = CAPACITY - this.count;
    const take = points.slice(Math.max(0, points.length - room));
    if (take.length === 0) return 0;
    this.positions.copyWithin(take.length * 3, 0, this.count * 3);
    take.forEach((p, i) => this.positions.set([p.x, p.y, p.z], i * 3));
    if (this.count === 0) this.last.copy(take[take.length - 1]!);
    this.count += take.length;
    this.attribute.clearUpdateRanges(); // upload everything once
    this.attribute.needsUpdate = true;
    this.line.geometry.setDrawRange(0, this.count);
    return take.length;
  }

  /** The box around the stored points (empty when there are none). */
  bounds(): THREE.Box3 {
    const box = new THREE.Box3();
    const p = new THREE.Vector3();
    for (let i = 0; i < this.count; i++) box.expandByPoint(p.fromArray(this.positions, i * 3));
    return box;
  }

  /** The last `n` stored points, oldest first. */
  lastPoints(n: number): [number, number, number][] {
    const out: [number, number, number][] = [];
    for (let i = Math.max(0, this.count - n); i < this.count; i++) {
      out.push([this.positions[i * 3]!, this.positions[i * 3 + 1]!, this.positions[i * 3 + 2]!]);
    }
    return out;
  }

  clear(): void {
    this.count = 0;
    this.line.geometry.setDrawRange(0, 0);
  }
}

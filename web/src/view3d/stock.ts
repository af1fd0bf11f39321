// The stock of material removal in the 3D view: the session's workpiece as the program has cut
// it so far, the server's binary STL (GET .../stock.stl, BCS mm) drawn in the workpiece frame.
// Fetched when the state's `stock.removed` changes: at once when the program rests, at most
// every REFRESH_MS while it cuts. The checks (rapid into stock, no spindle, depth of cut) are
// marked where their segment began: red for a rapid, orange for the others.

import * as THREE from "three";
import { tokenFor } from "../api/tokens";
import type { State, StockWarning } from "../api/types";

const REFRESH_MS = 1500;
const STOCK_COLOR = 0x9fb0c2;
const MAX_MARKS = 100;
const MARK_RADIUS = 2.5;

/** The triangles of a binary STL as a geometry with the file's facet normals. */
export function parseStl(buf: ArrayBuffer): THREE.BufferGeometry {
  const view = new DataView(buf);
  const count = buf.byteLength >= 84 ? view.getUint32(80, true) : 0;
  if (buf.byteLength < 84 + 50 * count) throw new Error(`STL of ${count} triangles is ${buf.byteLength} bytes`);
  const positions = new Float32Array(count * 9);
  const normals = new Float32Array(count * 9);
  for (let t = 0; t < count; t++) {
    const o = 84 + 50 * t;
    const n = [view.getFloat32(o, true), view.getFloat32(o + 4, true), view.getFloat32(o + 8, true)];
    for (let v = 0; v < 3; v++) {
      for (let c = 0; c < 3; c++) {
        positions[9 * t + 3 * v + c] = view.getFloat32(o + 12 + 12 * v + 4 * c, true);
        normals[9 * t + 3 * v + c] = n[c];
      }
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  g.setAttribute("normal", new THREE.BufferAttribute(normals, 3));
  g.computeBoundingBox();
  return g;
}

/** The stock mesh and the check marks; `show` on every state, `attach` for a new session. */
export class StockView {
  /** Mesh and marks, in the workpiece frame (the BCS). */
  readonly group = new THREE.Group();
  private readonly marks = new THREE.Group();
  private readonly markGeometry = new THREE.SphereGeometry(MARK_RADIUS, 12, 8);
  private readonly rapidMaterial = new THREE.MeshBasicMaterial({ color: 0xe53935 });
  private readonly otherMaterial = new THREE.MeshBasicMaterial({ color: 0xfb8c00 });
  readonly mesh = new THREE.Mesh(
    new THREE.BufferGeometry(),
    new THREE.MeshStandardMaterial({ color: STOCK_COLOR, metalness: 0.2, roughness: 0.7, side: THREE.DoubleSide }),
  );
  private session = "";
  private shown = Number.NaN;
  private lastFetch = -Infinity;
  private busy = false;

  constructor(private readonly redraw: () => void) {
    this.mesh.visible = false;
    this.mesh.renderOrder = 1;
    this.group.add(this.mesh, this.marks);
  }

  attach(id: string): void {
    this.session = id;
    this.shown = Number.NaN;
    this.mesh.visible = false;
    this.marks.clear();
    this.redraw();
  }

  /** Marks a check's place (the `stock` event's warning). */
  mark(w: StockWarning): void {
    if (!Array.isArray(w.position)) return;
    const material = w.check === "rapid_into_stock" ? this.rapidMaterial : this.otherMaterial;
    const m = new THREE.Mesh(this.markGeometry, material);
    m.position.set(w.position[0], w.position[1], w.position[2]);
    m.userData = { check: w.check, line: w.line };
    this.marks.add(m);
    while (this.marks.children.length > MAX_MARKS) this.marks.remove(this.marks.children[0]);
    this.redraw();
  }

  show(st: State, now = performance.now()): void {
    const stock = st.stock;
    if (!stock) {
      if (this.mesh.visible || this.marks.children.length) {
        this.mesh.visible = false;
        this.marks.clear();
        this.shown = Number.NaN;
        this.redraw();
      }
      return;
    }
    if (this.busy || stock.removed === this.shown) return;
    if (st.status === "running" && now - this.lastFetch < REFRESH_MS) return;
    this.lastFetch = now;
    void this.fetch(stock.removed);
  }

  private async fetch(removed: number): Promise<void> {
    const id = this.session;
    if (!id) return;
    this.busy = true;
    try {
      const token = tokenFor(id);
      const res = await fetch(`/api/v1/sessions/${encodeURIComponent(id)}/stock.stl`, {
        headers: token ? { Authorization: `Bearer ${token}` } : {},
      });
      if (!res.ok || id !== this.session) return;
      const geometry = parseStl(await res.arrayBuffer());
      this.mesh.geometry.dispose();
      this.mesh.geometry = geometry;
      this.mesh.visible = true;
      this.shown = removed;
      this.redraw();
    } catch {
      // A failed fetch is retried with the next state that shows a change.
    } finally {
      this.busy = false;
    }
  }
}

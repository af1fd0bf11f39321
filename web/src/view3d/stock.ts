// The stock of material removal in the 3D view: the session's workpiece as the program has cut
// it so far, drawn in the workpiece frame (BCS mm). A milled stock comes in tiles of 64 x 64
// dexel cells: when the state's `stock.version` changes, GET .../stock/changes?since= names the
// tiles cut since the version shown and only those are fetched again (GET .../stock/tiles/i/j,
// binary STL); each face is coloured by the tool that cut it (the pen in the STL's attribute
// bytes: 0 the blank's grey, then one colour per tool in the order they first cut). A turned
// stock is one STL (GET .../stock.stl). The stream pushes the changed tiles after each state
// with a new version (`stock` messages, `apply`), the first few meshes inline: applied when
// they continue the version shown, the tiles they only name fetched. REST is the fallback: at
// once when the program rests and nothing was pushed within PUSH_GRACE_MS, at most every
// REFRESH_MS while it cuts, and when a push says `reload`. The checks (rapid into stock, no spindle, depth of cut, holder
// collision) are marked where their segment began: red for a rapid, orange for the others.
// The stock lives in the frame of the table that carries it: where the state names that
// frame's pose (`stock.frame`, a blank on a rotary or trunnion table), the mesh hangs in the
// machine frame placed by it, so it turns with C and tilts with A/B as the engine cuts it;
// elsewhere it stays in the part frame (the BCS, a lathe's spindle).

import * as THREE from "three";
import { fromBase64, type StockPush } from "../api/stockPush";
import { tokenFor } from "../api/tokens";
import type { State, StockWarning } from "../api/types";

const REFRESH_MS = 1500;
/** How long a state ahead of the stock shown waits for the stream's push before REST. */
const PUSH_GRACE_MS = 300;
const STOCK_COLOR = 0x9fb0c2;
/** Colours of pens 1, 2, ... (the tools in the order they first cut), repeating. */
const PEN_COLORS = [0x4f8fd6, 0xd9a03f, 0x5cb85c, 0xb565c9, 0xd9534f, 0x3fb8b0, 0x8d6e63, 0xc0ca33];

/** The colour of a face cut by `pen` (0: the blank's own face). */
export function penColor(pen: number): THREE.Color {
  return new THREE.Color(pen === 0 ? STOCK_COLOR : PEN_COLORS[(pen - 1) % PEN_COLORS.length]);
}
const MAX_MARKS = 100;
const MARK_RADIUS = 2.5;

/** The triangles of a binary STL as a geometry with the file's facet normals. */
export function parseStl(buf: ArrayBuffer): THREE.BufferGeometry {
  const view = new DataView(buf);
  const count = buf.byteLength >= 84 ? view.getUint32(80, true) : 0;
  if (buf.byteLength < 84 + 50 * count) throw new Error(`STL of ${count} triangles is ${buf.byteLength} bytes`);
  const positions = new Float32Array(count * 9);
  const normals = new Float32Array(count * 9);
  const colors = new Float32Array(count * 9);
  const palette = new Map<number, THREE.Color>();
  for (let t = 0; t < count; t++) {
    const o = 84 + 50 * t;
    const n = [view.getFloat32(o, true), view.getFloat32(o + 4, true), view.getFloat32(o + 8, true)];
    const pen = view.getUint16(o + 48, true);
    let color = palette.get(pen);
    if (!color) {
      color = penColor(pen);
      palette.set(pen, color);
    }
    for (let v = 0; v < 3; v++) {
      for (let c = 0; c < 3; c++) {
        positions[9 * t + 3 * v + c] = view.getFloat32(o + 12 + 12 * v + 4 * c, true);
        normals[9 * t + 3 * v + c] = n[c];
      }
      colors[9 * t + 3 * v] = color.r;
      colors[9 * t + 3 * v + 1] = color.g;
      colors[9 * t + 3 * v + 2] = color.b;
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  g.setAttribute("normal", new THREE.BufferAttribute(normals, 3));
  g.setAttribute("color", new THREE.BufferAttribute(colors, 3));
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
  private readonly material = new THREE.MeshStandardMaterial({
    vertexColors: true,
    metalness: 0.2,
    roughness: 0.7,
    side: THREE.DoubleSide,
  });
  /** The stock's meshes: one per tile of a milled stock ("i,j"), one ("all") for a turned one. */
  private readonly tiles = new Map<string, THREE.Mesh>();
  private readonly meshes = new THREE.Group();
  private session = "";
  /** The stock shown: its blank (volume, resolution, model) and version. */
  private blankKey = "";
  private shown = 0;
  private lastFetch = -Infinity;
  private busy = false;
  /** The stock's model ("milling" or "turning") of the last state. */
  private model = "";
  /** When the state first showed a version ahead of the one shown (for PUSH_GRACE_MS). */
  private behindSince = -Infinity;
  /** Pushes arrive on this session's stream. */
  private pushed = false;
  /** The part frame (BCS) and the machine frame of the model the stock hangs in. */
  private part: THREE.Object3D | null = null;
  private machine: THREE.Object3D | null = null;
  private readonly pose = new THREE.Matrix4();

  constructor(private readonly redraw: () => void) {
    this.meshes.renderOrder = 1;
    this.group.add(this.meshes, this.marks);
    this.group.matrixAutoUpdate = false;
  }

  /** Hangs the stock in a (new) machine model: its part frame and its machine frame. */
  mount(part: THREE.Object3D, machine: THREE.Object3D): void {
    this.part = part;
    this.machine = machine;
    part.add(this.group);
    this.group.matrix.identity();
  }

  /**
   * Places the stock with the table's pose of the state (rows of [R | t], machine frame), or
   * in the part frame without one.
   */
  private placeFrame(frame: [number, number, number, number][] | null | undefined): void {
    const parent = frame ? this.machine : this.part;
    if (!parent) return;
    if (this.group.parent !== parent) parent.add(this.group);
    if (frame) {
      const [a, b, c] = frame;
      this.pose.set(a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3], c[0], c[1], c[2], c[3], 0, 0, 0, 1);
    } else {
      this.pose.identity();
    }
    if (!this.pose.equals(this.group.matrix)) {
      this.group.matrix.copy(this.pose);
      this.group.matrixWorldNeedsUpdate = true;
      this.redraw();
    }
  }

  /** The meshes shown and the stock version they show (for the browser test). */
  shownMeshes(): { meshes: number; version: number } {
    return { meshes: this.tiles.size, version: this.shown };
  }

  /** The face colours the meshes show, as hex numbers (for the browser test: one per pen). */
  shownColors(): number[] {
    const seen = new Set<number>();
    const c = new THREE.Color();
    for (const mesh of this.tiles.values()) {
      const attr = mesh.geometry.getAttribute("color");
      if (!attr) continue;
      for (let i = 0; i < attr.count; i += 3) seen.add(c.fromBufferAttribute(attr as THREE.BufferAttribute, i).getHex());
    }
    return [...seen].sort((a, b) => a - b);
  }

  /** The check marks drawn: which check and the program line (for the browser test). */
  markList(): { check: string; line: number }[] {
    return this.marks.children.map((m) => ({ check: String(m.userData.check), line: Number(m.userData.line) }));
  }

  /**
   * The angle (degrees) the stock is turned about the machine axis `about` relative to the
   * machine frame (for the browser test); null before a model is mounted.
   */
  turn(about: [number, number, number]): number | null {
    if (!this.machine) return null;
    this.group.updateWorldMatrix(true, false);
    this.machine.updateWorldMatrix(true, false);
    const q = this.group.getWorldQuaternion(new THREE.Quaternion());
    q.premultiply(this.machine.getWorldQuaternion(new THREE.Quaternion()).invert());
    const axis = new THREE.Vector3(...about).normalize();
    const ref = Math.abs(axis.z) < 0.9 ? new THREE.Vector3(0, 0, 1) : new THREE.Vector3(1, 0, 0);
    ref.sub(axis.clone().multiplyScalar(ref.dot(axis))).normalize();
    const turned = ref.clone().applyQuaternion(q);
    return THREE.MathUtils.radToDeg(Math.atan2(axis.dot(ref.clone().cross(turned)), ref.dot(turned)));
  }

  attach(id: string): void {
    this.session = id;
    this.clearMeshes();
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
    this.placeFrame(stock?.frame);
    if (!stock) {
      if (this.tiles.size || this.marks.children.length) {
        this.clearMeshes();
        this.marks.clear();
        this.redraw();
      }
      return;
    }
    const key = `${stock.model} ${stock.resolution} ${stock.initial_volume}`;
    if (key !== this.blankKey || stock.version < this.shown) {
      // Another blank: everything anew.
      this.clearMeshes();
      this.blankKey = key;
    }
    this.model = stock.model;
    if (this.busy || stock.version === this.shown) {
      this.behindSince = -Infinity;
      return;
    }
    if (this.behindSince === -Infinity) this.behindSince = now;
    if (this.pushed && now - this.behindSince < PUSH_GRACE_MS) {
      // The push follows the state on the stream; REST only if it does not come.
      setTimeout(() => this.session && this.retry(st), PUSH_GRACE_MS);
      return;
    }
    if (st.status === "running" && now - this.lastFetch < REFRESH_MS) return;
    this.lastFetch = now;
    void this.fetch(stock.model, stock.version);
  }

  /** A state seen while waiting for a push: shown again once the grace is over. */
  private retry(st: State): void {
    if (st.stock && st.stock.version !== this.shown) this.show(st);
  }

  /** A `stock` message of the stream: applied when it continues the version shown. */
  apply(push: StockPush): void {
    this.pushed = true;
    if (!this.session || this.busy || !this.blankKey) return;
    if (push.reload) {
      // The stream cannot bring this view up to date: everything anew over REST.
      this.clearMeshes();
      this.behindSince = -Infinity;
      return;
    }
    if (push.since !== this.shown) return;
    const turning = this.model === "turning";
    const inline = new Set<string>();
    try {
      for (const m of push.meshes) {
        const key = turning ? "all" : `${m.i},${m.j}`;
        this.place(key, parseStl(fromBase64(m.stl)));
        inline.add(`${m.i},${m.j}`);
      }
    } catch {
      return; // a bad mesh: the REST fallback fetches the tiles
    }
    const rest = push.tiles.filter(([i, j]) => !inline.has(`${i},${j}`));
    if (rest.length === 0) {
      this.shown = push.version;
      this.behindSince = -Infinity;
      this.redraw();
      return;
    }
    void this.fetchTiles(rest, push.version);
  }

  /** Fetches the tiles a push only named; then shows `version`. */
  private async fetchTiles(tiles: [number, number][], version: number): Promise<void> {
    const id = this.session;
    this.busy = true;
    try {
      for (const [i, j] of tiles) {
        const tile = await this.get(id, `stock/tiles/${i}/${j}`);
        if (!tile.ok || id !== this.session) return;
        this.place(this.model === "turning" ? "all" : `${i},${j}`, parseStl(await tile.arrayBuffer()));
      }
      this.shown = version;
      this.behindSince = -Infinity;
      this.redraw();
    } catch {
      // Retried over REST with the next state that shows a change.
    } finally {
      this.busy = false;
    }
  }

  private clearMeshes(): void {
    for (const m of this.tiles.values()) m.geometry.dispose();
    this.tiles.clear();
    this.meshes.clear();
    this.blankKey = "";
    this.shown = 0;
  }

  /** Puts `geometry` in place of the mesh `key`. */
  private place(key: string, geometry: THREE.BufferGeometry): void {
    const old = this.tiles.get(key);
    if (old) {
      old.geometry.dispose();
      old.geometry = geometry;
      return;
    }
    const m = new THREE.Mesh(geometry, this.material);
    m.renderOrder = 1;
    this.tiles.set(key, m);
    this.meshes.add(m);
  }

  private async get(id: string, path: string): Promise<Response> {
    const token = tokenFor(id);
    return fetch(`/api/v1/sessions/${encodeURIComponent(id)}/${path}`, {
      headers: token ? { Authorization: `Bearer ${token}` } : {},
    });
  }

  private async fetch(model: string, version: number): Promise<void> {
    const id = this.session;
    if (!id) return;
    this.busy = true;
    try {
      if (model === "turning") {
        const res = await this.get(id, "stock.stl");
        if (!res.ok || id !== this.session) return;
        this.place("all", parseStl(await res.arrayBuffer()));
        this.shown = version;
      } else {
        const res = await this.get(id, `stock/changes?since=${this.shown}`);
        if (!res.ok || id !== this.session) return;
        const changes = (await res.json()) as { version: number; tiles: [number, number][] };
        for (const [i, j] of changes.tiles) {
          const tile = await this.get(id, `stock/tiles/${i}/${j}`);
          if (!tile.ok || id !== this.session) return;
          this.place(`${i},${j}`, parseStl(await tile.arrayBuffer()));
        }
        this.shown = changes.version;
      }
      this.redraw();
    } catch {
      // A failed fetch is retried with the next state that shows a change.
    } finally {
      this.busy = false;
    }
  }
}

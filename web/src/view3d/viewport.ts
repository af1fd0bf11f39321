// A three.js viewport: renderer, camera, orbit/zoom controls, resizing, and rendering on demand
// (only when something changed: SwiftShader renders on the CPU).

import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

export type ViewName = "iso" | "top" | "front";

/** Camera distance as a share of what shows the whole bounding sphere (boxes fill less). */
const FIT = 0.8;

const VIEW_DIRS: Record<ViewName, THREE.Vector3> = {
  iso: new THREE.Vector3(1, -1.3, 0.9).normalize(),
  top: new THREE.Vector3(0, -0.001, 1).normalize(),
  front: new THREE.Vector3(0, -1, 0.12).normalize(),
};

export class Viewport {
  readonly scene = new THREE.Scene();
  readonly camera = new THREE.PerspectiveCamera(35, 1, 1, 50_000);
  readonly renderer: THREE.WebGLRenderer;
  readonly controls: OrbitControls;
  private frame = 0;

  constructor(private readonly host: HTMLElement) {
    // preserveDrawingBuffer: the canvas can be read back (screenshots, the browser test).
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    this.renderer.setClearColor(0x1a1f25);
    this.renderer.domElement.classList.add("view3d-canvas");
    host.prepend(this.renderer.domElement);

    this.camera.up.set(0, 0, 1); // machine frames are Z-up
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener("change", () => this.invalidate());

    this.scene.add(new THREE.HemisphereLight(0xdde6f0, 0x30363d, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.8);
    sun.position.set(1, -2, 3);
    this.scene.add(sun);

    new ResizeObserver(() => this.resize()).observe(host);
    this.resize();
  }

  /** Renders at the next animation frame (once, however often it is asked). */
  invalidate(): void {
    if (this.frame) return;
    this.frame = requestAnimationFrame(() => {
      this.frame = 0;
      this.renderer.render(this.scene, this.camera);
    });
  }

  /** Looks at a box from one of the standard directions, the whole box in view. */
  frameBox(box: THREE.Box3, view: ViewName | THREE.Vector3 = "iso"): void {
    const dir = typeof view === "string" ? VIEW_DIRS[view] : view;
    const sphere = box.getBoundingSphere(new THREE.Sphere());
    const fov = THREE.MathUtils.degToRad(this.camera.fov);
    const fit = Math.min(fov, 2 * Math.atan(Math.tan(fov / 2) * this.camera.aspect));
    const distance = Math.max(1, (sphere.radius / Math.sin(fit / 2)) * FIT);
    this.camera.position.copy(sphere.center).addScaledVector(dir, distance);
    this.camera.near = distance / 100;
    this.camera.far = distance * 10;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(sphere.center);
    this.controls.update();
    this.invalidate();
  }

  private resize(): void {
    const w = Math.max(1, this.host.clientWidth);
    const h = Math.max(1, this.host.clientHeight);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.invalidate();
  }
}

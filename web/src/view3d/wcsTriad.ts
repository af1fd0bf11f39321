// The WCS in the 3D view: three arrows at the workpiece zero along the WCS axes. The frame
// chain may turn the WCS (a swivelled plane of CYCLE800, a ROT): the arrows then point along
// the WCS directions GET .../active-swivel gives (`wcs_axes`, in the BCS), and the zero is
// where the WCS origin lies in the BCS, BCS − R·WCS of the current position.

import * as THREE from "three";

export const AXIS_COLORS = { X: 0xe5534b, Y: 0x57ab5a, Z: 0x539bf5 } as const;

export class WcsTriad {
  readonly group = new THREE.Group();
  /** WCS → BCS rotation of the geometry axes (identity until an answer says otherwise). */
  private readonly rotation = new THREE.Matrix4();
  private readonly scratch = new THREE.Vector3();

  constructor(size: number, letters: string[]) {
    const dirs = { X: new THREE.Vector3(1, 0, 0), Y: new THREE.Vector3(0, 1, 0), Z: new THREE.Vector3(0, 0, 1) };
    for (const letter of ["X", "Y", "Z"] as const) {
      if (!letters.includes(letter)) continue;
      const arrow = new THREE.ArrowHelper(dirs[letter], new THREE.Vector3(), size, AXIS_COLORS[letter], size * 0.2, size * 0.1);
      arrow.name = letter;
      this.group.add(arrow);
    }
  }

  /**
   * Turns the arrows to the WCS directions (unit vectors of WCS X, Y, Z in the BCS); null
   * or a degenerate basis: along the BCS. A mirrored frame keeps the rotation part only.
   */
  setAxes(axes: [number, number, number][] | null): void {
    const [x, y, z] = (axes ?? []).map((a) => new THREE.Vector3(...a));
    if (!x || !y || !z || Math.abs(x.clone().cross(y).dot(z)) < 0.5) {
      this.rotation.identity();
    } else {
      // Orthonormal and right-handed: Y from Z × X keeps a mirror from flipping the arrows.
      x.normalize();
      const yy = z.clone().cross(x).normalize();
      const zz = x.clone().cross(yy);
      this.rotation.makeBasis(x, yy, zz);
    }
    this.group.quaternion.setFromRotationMatrix(this.rotation);
  }

  /** Places the zero from the geometry axes' BCS and WCS position of the same point. */
  place(bcs: THREE.Vector3, wcs: THREE.Vector3): void {
    this.scratch.copy(wcs).applyMatrix4(this.rotation);
    this.group.position.subVectors(bcs, this.scratch);
  }

  /** A direction of the part frame (BCS) in WCS coordinates: Rᵀ·v. */
  toWcs(v: THREE.Vector3): THREE.Vector3 {
    return v.applyMatrix4(this.scratchInverse.copy(this.rotation).transpose());
  }
  private readonly scratchInverse = new THREE.Matrix4();

  /** The direction WCS axis `letter` points in (part frame), for the browser test. */
  direction(letter: "X" | "Y" | "Z"): [number, number, number] {
    const v = new THREE.Vector3(letter === "X" ? 1 : 0, letter === "Y" ? 1 : 0, letter === "Z" ? 1 : 0).applyQuaternion(this.group.quaternion);
    return [v.x, v.y, v.z];
  }
}

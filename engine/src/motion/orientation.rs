//! How the tool orientation changes along one block when it is interpolated as a vector
//! (ORIVECT/ORIPLANE great circle, ORICONxx cone) rather than through the rotary axes.
//!
//! Both kinds are a rotation of the start orientation about a fixed axis by an angle that grows
//! uniformly with the path parameter: the great circle turns about `start × end`, the cone about
//! its programmed axis. So one representation serves both, slices exactly, and costs one
//! `sin_cos` per IPO point. ORICURVE instead follows a second curve ([`TwoCurves`]). ORIPATH
//! on an arc adds a second rotation ([`OriPath::turn`]): the path frame turning with the
//! tangent, so lead and tilt hold at every point of the arc. ORISON adds to a great circle the
//! smoothing of the orientation's steps near it ([`OriKink`], `motion/orison.rs`).

use super::ori_curve::TwoCurves;

/// A 3-vector in the BCS (X, Y, Z of the geometry axes).
pub type Vec3 = [f64; 3];

/// The orientation along a block: `o(u) = R(axis, angle·u) · start`.
#[derive(Debug, Clone, PartialEq)]
pub struct OriPath {
    /// Unit orientation at the block start.
    pub start: Vec3,
    /// Unit rotation axis.
    pub axis: Vec3,
    /// Total rotation in radians (signed, right-handed about `axis`). For ORICURVE the angle
    /// between start and end orientation (the feed base of a block without tip motion).
    pub angle: f64,
    /// ORICURVE: the orientation follows the direction from the tip line to the upper line
    /// instead of the rotation.
    pub curve: Option<TwoCurves>,
    /// ORIPATH on an arc: the rotation (unit axis, radians over the block) of the path's
    /// tangent frame, applied after the own rotation: `o(u) = R(turn, φ·u)·R(axis, angle·u)·start`.
    pub turn: Option<(Vec3, f64)>,
    /// ORISON: the smoothing of the orientation's steps whose sections reach into this block
    /// (empty without ORISON); the other fields still describe the programmed great circle.
    pub kinks: Vec<OriKink>,
}

/// ORISON's smoothing of one step of the orientation's rate (a kink at a block end): the
/// vector `jump · bump(u − at, half)` added to the programmed orientation within `half` of
/// `at`, then normalised (see `motion/orison.rs`). In units of the parameter it is kept in: a
/// block's `u` on an [`OriPath`], mm of path where the main run decides it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OriKink {
    /// Where the step is.
    pub at: f64,
    /// Half the section it is smoothed over.
    pub half: f64,
    /// The rate after the step less the rate before (per unit of the parameter).
    pub jump: Vec3,
}

impl OriKink {
    /// The step in another parameter: `u = (s − origin) / scale`.
    pub fn rescaled(&self, origin: f64, scale: f64) -> OriKink {
        OriKink { at: (self.at - origin) / scale, half: self.half / scale, jump: self.jump.map(|j| j * scale) }
    }

    /// True if its section reaches into the parameter interval `u0..u1`.
    pub fn reaches(&self, u0: f64, u1: f64) -> bool {
        self.at - self.half < u1 && self.at + self.half > u0
    }

    /// The correction at parameter `u` and its derivative (zero outside the section).
    pub fn offset(&self, u: f64) -> (Vec3, Vec3) {
        let (b, db) = bump(u - self.at, self.half);
        (self.jump.map(|j| j * b), self.jump.map(|j| j * db))
    }
}

/// Half the difference between |x| convolved with the triangle kernel of half width `r` and
/// |x| itself, with its derivative (left-continuous at 0): `(r/3 + x²/r − |x|³/(3r²) − |x|)/2`
/// inside `|x| < r`, zero outside. Added with a step's rate jump it cancels the step (its
/// slope goes from +½ to −½ at 0) and is C2 at ±r (value, slope and curvature 0 there).
pub fn bump(x: f64, r: f64) -> (f64, f64) {
    let a = x.abs();
    if a >= r {
        return (0.0, 0.0);
    }
    let value = 0.5 * (r / 3.0 + x * x / r - a * a * a / (3.0 * r * r) - a);
    let sign = if x > 0.0 { 1.0 } else { -1.0 };
    let slope = 0.5 * (2.0 * x / r - x * a / (r * r) - sign);
    (value, slope)
}

/// Start and end orientation point in opposite directions: the plane of the great circle is
/// undefined (alarm 14120).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("start and end orientation are antiparallel")]
pub struct Antiparallel;

impl OriPath {
    /// The great circle from `start` to `end` (unit vectors). `None` when they coincide.
    pub fn great_circle(start: Vec3, end: Vec3) -> Result<Option<OriPath>, Antiparallel> {
        let c = cross(start, end);
        let sin = norm(c);
        let cos = dot(start, end);
        if sin < 1e-9 {
            return if cos > 0.0 { Ok(None) } else { Err(Antiparallel) };
        }
        Ok(Some(OriPath {
            start,
            axis: scale(c, 1.0 / sin),
            angle: sin.atan2(cos),
            curve: None,
            turn: None,
            kinks: Vec::new(),
        }))
    }

    /// A rotation of `start` about `axis` (any length) by `angle` radians: the cone.
    pub fn cone(start: Vec3, axis: Vec3, angle: f64) -> Option<OriPath> {
        let n = norm(axis);
        (n > 1e-12).then(|| OriPath {
            start,
            axis: scale(axis, 1.0 / n),
            angle,
            curve: None,
            turn: None,
            kinks: Vec::new(),
        })
    }

    /// An orientation carried by a frame turning about unit axis `k` by `sweep` radians (an
    /// arc's tangent frame under ORIPATH): from `start` to `end`, the part not explained by
    /// the turn interpolated as a great circle in the turning frame. When `end` is `start`
    /// turned with the frame (lead and tilt already held at the start) it is the pure cone.
    pub fn turning_with(start: Vec3, end: Vec3, k: Vec3, sweep: f64) -> Result<OriPath, Antiparallel> {
        let own_end = rotate(end, k, -sweep);
        let own = OriPath::great_circle(start, own_end)?.unwrap_or(OriPath {
            start,
            axis: k,
            angle: 0.0,
            curve: None,
            turn: None,
            kinks: Vec::new(),
        });
        Ok(OriPath { turn: Some((k, sweep)), ..own })
    }

    /// ORICURVE: the orientation from the tip line to the upper line of `curves`.
    pub fn two_curves(curves: TwoCurves) -> OriPath {
        let (start, end) = (curves.at(0.0), curves.at(1.0));
        let c = cross(start, end);
        let n = norm(c);
        let axis = if n > 1e-12 { scale(c, 1.0 / n) } else { [0.0, 0.0, 1.0] };
        OriPath { start, axis, angle: n.atan2(dot(start, end)), curve: Some(curves), turn: None, kinks: Vec::new() }
    }

    /// Orientation at path parameter `u` in 0..=1.
    pub fn at(&self, u: f64) -> Vec3 {
        let u = u.clamp(0.0, 1.0);
        let programmed = self.programmed_at(u);
        if self.kinks.is_empty() {
            return programmed;
        }
        let mut v = programmed;
        for k in &self.kinks {
            let (d, _) = k.offset(u);
            v = std::array::from_fn(|i| v[i] + d[i]);
        }
        scale(v, 1.0 / norm(v))
    }

    /// The programmed orientation at `u` in 0..=1 (without ORISON's smoothed ends).
    pub fn programmed_at(&self, u: f64) -> Vec3 {
        let u = u.clamp(0.0, 1.0);
        match (&self.curve, self.turn) {
            (Some(c), _) => c.at(u),
            (None, None) => rotate(self.start, self.axis, self.angle * u),
            (None, Some((k, sweep))) => rotate(rotate(self.start, self.axis, self.angle * u), k, sweep * u),
        }
    }

    /// Unit direction in which the orientation moves at the block end (for ORICONTO's
    /// tangential transition); `None` for a path that does not turn.
    pub fn end_direction(&self) -> Option<Vec3> {
        if !self.kinks.is_empty() {
            // ORISON (great circles only): d/du of v/|v| with v = o + Σ corrections.
            let o = self.programmed_at(1.0);
            let mut v = o;
            let mut dv = scale(cross(self.axis, o), self.angle);
            for k in &self.kinks {
                let (d, dd) = k.offset(1.0);
                v = std::array::from_fn(|i| v[i] + d[i]);
                dv = std::array::from_fn(|i| dv[i] + dd[i]);
            }
            let n = scale(v, 1.0 / norm(v));
            let along = dot(n, dv);
            let t: Vec3 = std::array::from_fn(|i| dv[i] - along * n[i]);
            let len = norm(t);
            return (len > 1e-12).then(|| scale(t, 1.0 / len));
        }
        if let Some(c) = &self.curve {
            return c.end_direction();
        }
        if let Some((k, sweep)) = self.turn {
            // do/du = R(k, φ)·(θ·a × own(1)) + φ·k × o(1).
            let own = rotate(self.start, self.axis, self.angle);
            let spin = rotate(scale(cross(self.axis, own), self.angle), k, sweep);
            let carried = scale(cross(k, self.at(1.0)), sweep);
            let d: Vec3 = std::array::from_fn(|i| spin[i] + carried[i]);
            let n = norm(d);
            return (n > 1e-12).then(|| scale(d, 1.0 / n));
        }
        let d = scale(cross(self.axis, self.at(1.0)), self.angle.signum());
        let n = norm(d);
        (n > 1e-12 && self.angle != 0.0).then(|| scale(d, 1.0 / n))
    }

    /// The part between parameters `u0` and `u1`.
    pub fn slice(&self, u0: f64, u1: f64) -> OriPath {
        let mut out = match &self.curve {
            Some(c) => OriPath::two_curves(c.slice(u0, u1)),
            None => match self.turn {
                None => OriPath {
                    start: self.programmed_at(u0),
                    axis: self.axis,
                    angle: self.angle * (u1 - u0),
                    curve: None,
                    turn: None,
                    kinks: Vec::new(),
                },
                // The slice's own rotation is this one seen in the frame turned to u0.
                Some((k, sweep)) => OriPath {
                    start: self.programmed_at(u0),
                    axis: rotate(self.axis, k, sweep * u0),
                    angle: self.angle * (u1 - u0),
                    curve: None,
                    turn: Some((k, sweep * (u1 - u0))),
                    kinks: Vec::new(),
                },
            },
        };
        if u1 > u0 {
            out.kinks = self.kinks.iter().filter(|k| k.reaches(u0, u1)).map(|k| k.rescaled(u0, u1 - u0)).collect();
        }
        out
    }
}

/// `v` rotated about unit axis `k` by `angle` radians (Rodrigues).
pub fn rotate(v: Vec3, k: Vec3, angle: f64) -> Vec3 {
    let (s, c) = angle.sin_cos();
    rotate_by(v, k, s, c)
}

/// [`rotate`] with the angle given by its sine and cosine.
pub(super) fn rotate_by(v: Vec3, k: Vec3, s: f64, c: f64) -> Vec3 {
    let kxv = cross(k, v);
    let kv = dot(k, v) * (1.0 - c);
    std::array::from_fn(|i| v[i] * c + kxv[i] * s + k[i] * kv)
}

pub(super) fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(super) fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

pub(super) fn norm(a: Vec3) -> f64 {
    dot(a, a).sqrt()
}

/// The angle (radians) between unit vectors `a` and `b`.
pub(super) fn angle(a: Vec3, b: Vec3) -> f64 {
    norm(cross(a, b)).atan2(dot(a, b))
}

fn scale(a: Vec3, f: f64) -> Vec3 {
    a.map(|x| x * f)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-12)
    }

    #[test]
    fn great_circle_from_z_to_x_passes_the_bisector() {
        let p = OriPath::great_circle([0.0, 0.0, 1.0], [1.0, 0.0, 0.0]).unwrap().unwrap();
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!(close(p.at(0.5), [h, 0.0, h]));
        assert!(close(p.at(1.0), [1.0, 0.0, 0.0]));
        // Every point stays a unit vector in the XZ plane.
        for i in 0..=10 {
            let o = p.at(i as f64 / 10.0);
            assert!((norm(o) - 1.0).abs() < 1e-12 && o[1].abs() < 1e-12);
        }
    }

    #[test]
    fn slices_continue_the_same_circle() {
        let p = OriPath::great_circle([0.0, 0.0, 1.0], [0.0, 1.0, 0.0]).unwrap().unwrap();
        let s = p.slice(0.25, 0.75);
        assert!(close(s.at(0.0), p.at(0.25)));
        assert!(close(s.at(0.5), p.at(0.5)));
        assert!(close(s.at(1.0), p.at(0.75)));
    }

    #[test]
    fn equal_orientations_need_no_path_and_opposite_ones_are_refused() {
        assert_eq!(OriPath::great_circle([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]), Ok(None));
        assert_eq!(OriPath::great_circle([0.0, 0.0, 1.0], [0.0, 0.0, -1.0]), Err(Antiparallel));
    }

    #[test]
    fn cone_keeps_the_opening_angle() {
        // 45° cone about Z, a quarter turn: from (s,0,c) to (0,s,c).
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let p = OriPath::cone([h, 0.0, h], [0.0, 0.0, 2.0], std::f64::consts::FRAC_PI_2).unwrap();
        assert!(close(p.at(1.0), [0.0, h, h]));
        for i in 0..=8 {
            assert!((p.at(i as f64 / 8.0)[2] - h).abs() < 1e-12);
        }
    }

    #[test]
    fn a_turning_frame_holds_the_lead_on_a_quarter_circle() {
        // Lead 20° on a CCW quarter circle about Z from (40, 0) to (0, 40): tangent +Y at the
        // start, −X at the end; the tool (sin 20° along the tangent, cos 20° along Z) turns
        // with it, so at angle a the tangent is (−sin a, cos a, 0) and the orientation
        // (−sin a·sin 20°, cos a·sin 20°, cos 20°).
        let (s20, c20) = 20f64.to_radians().sin_cos();
        let at = |a: f64| [-a.sin() * s20, a.cos() * s20, c20];
        let quarter = std::f64::consts::FRAC_PI_2;
        let p = OriPath::turning_with(at(0.0), at(quarter), [0.0, 0.0, 1.0], quarter).unwrap();
        for i in 0..=8 {
            let u = i as f64 / 8.0;
            assert!(close(p.at(u), at(quarter * u)), "{u}: {:?}", p.at(u));
        }
        // A slice continues the same orientation.
        let s = p.slice(0.25, 0.75);
        assert!(close(s.at(0.0), p.at(0.25)) && close(s.at(0.5), p.at(0.5)) && close(s.at(1.0), p.at(0.75)));
        // Leaving along the cone: d/da of at(a) = (−cos a·s20, −sin a·s20, 0), at 90° −Y.
        let d = p.end_direction().unwrap();
        assert!(close(d, [0.0, -1.0, 0.0]), "{d:?}");
    }

    #[test]
    fn a_turning_frame_from_another_start_still_meets_both_ends() {
        // Start vertical (a corner before the arc), end with lead 20° at the quarter circle's
        // end: the own great circle takes up the difference in the turning frame.
        let (s20, c20) = 20f64.to_radians().sin_cos();
        let quarter = std::f64::consts::FRAC_PI_2;
        let end = [-s20, 0.0, c20];
        let p = OriPath::turning_with([0.0, 0.0, 1.0], end, [0.0, 0.0, 1.0], quarter).unwrap();
        assert!(close(p.at(0.0), [0.0, 0.0, 1.0]) && close(p.at(1.0), end));
        let s = p.slice(0.3, 1.0);
        assert!(close(s.at(1.0), end) && close(s.at(0.5), p.at(0.65)));
    }
}

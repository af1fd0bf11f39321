//! Geometry of one motion block in axis space: a straight line, or a circular arc (helix) in
//! any plane of the geometry axes with every other axis moving linearly along.

use super::curve::Curve;
use super::orientation::{OriPath, Vec3};
use crate::machine_data::registry::MAX_CHANNEL_AXES;

/// Positions of all channel axes (only the first `n` of a channel are used).
pub type AxisVec = [f64; MAX_CHANNEL_AXES];

/// A circular arc spanned by the axis-space vectors `u` and `v`: the circle is
/// `centre + radius·(cos a·u + sin a·v)` for `a` from `start_angle` to `start_angle + sweep`.
/// `u` and `v` are orthonormal for an undistorted circle; they carry a frame's rotation (any
/// plane) and mirroring (reversed sense) without special cases.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arc {
    pub u: AxisVec,
    pub v: AxisVec,
    pub radius: f64,
    /// Angle of the start point, radians.
    pub start_angle: f64,
    /// Signed sweep in radians: positive turns from `u` towards `v`.
    pub sweep: f64,
}

impl Arc {
    /// An arc in the plane of axes `a` (abscissa) and `o` (ordinate).
    pub fn in_plane(a: usize, o: usize, radius: f64, start_angle: f64, sweep: f64) -> Arc {
        let mut u = [0.0; MAX_CHANNEL_AXES];
        let mut v = [0.0; MAX_CHANNEL_AXES];
        u[a] = 1.0;
        v[o] = 1.0;
        Arc { u, v, radius, start_angle, sweep }
    }

    /// True if axis `k` takes part in the circular motion.
    pub fn moves_axis(&self, k: usize) -> bool {
        self.u[k] != 0.0 || self.v[k] != 0.0
    }
}

/// The geometric path of one block. The start and end points are met exactly; an arc adds
/// its circular deviation from the straight line between them.
#[derive(Debug, Clone, PartialEq)]
pub struct Path {
    pub start: AxisVec,
    pub end: AxisVec,
    /// `None`: linear interpolation of every axis.
    pub arc: Option<Box<Arc>>,
    /// The tool orientation when it is interpolated as a vector (an orientation
    /// transformation's rotary axes then follow it); `None`: the axes interpolate.
    pub ori: Option<Box<OriPath>>,
    /// A free-form element (a corner rounding of continuous-path mode): when set, it is the
    /// path from `start` to `end` and `arc` is `None`.
    /// Shared (`Arc`): the front move's cycles hold it too, and it is a kilobyte.
    pub curve: Option<std::sync::Arc<Curve>>,
}

impl Path {
    /// Position at parameter `s` in 0..=1 (uniform in path length).
    pub fn at(&self, s: f64, out: &mut AxisVec) {
        if s >= 1.0 {
            *out = self.end;
            return;
        }
        if let Some(c) = &self.curve {
            *out = self.start;
            c.at(s, out);
            return;
        }
        for (o, (a, b)) in out.iter_mut().zip(self.start.iter().zip(&self.end)) {
            *o = a + (b - a) * s;
        }
        if let Some(arc) = &self.arc {
            // Circle minus its chord: zero at both ends.
            let (a0, a1) = (arc.start_angle, arc.start_angle + arc.sweep);
            let (sin, cos) = (a0 + arc.sweep * s).sin_cos();
            let (sin0, cos0) = a0.sin_cos();
            let (sin1, cos1) = a1.sin_cos();
            let cu = arc.radius * (cos - cos0 - s * (cos1 - cos0));
            let cv = arc.radius * (sin - sin0 - s * (sin1 - sin0));
            for (k, o) in out.iter_mut().enumerate() {
                *o += cu * arc.u[k] + cv * arc.v[k];
            }
        }
    }

    /// The part of the path between parameters `u0` and `u1` (0 ≤ u0 < u1 ≤ 1), as a path of
    /// its own: the same line, or the same arc with a shorter sweep.
    pub fn slice(&self, u0: f64, u1: f64) -> Path {
        let mut start = [0.0; MAX_CHANNEL_AXES];
        let mut end = [0.0; MAX_CHANNEL_AXES];
        self.at(u0, &mut start);
        self.at(u1, &mut end);
        let arc = self
            .arc
            .as_ref()
            .map(|a| Box::new(Arc { start_angle: a.start_angle + a.sweep * u0, sweep: a.sweep * (u1 - u0), ..**a }));
        let ori = self.ori.as_ref().map(|o| Box::new(o.slice(u0, u1)));
        let curve = self.curve.as_ref().map(|c| std::sync::Arc::new(c.slice(u0, u1)));
        Path { start, end, arc, ori, curve }
    }

    /// A straight line from `start` to `end`.
    pub fn line(start: AxisVec, end: AxisVec) -> Path {
        Path { start, end, arc: None, ori: None, curve: None }
    }

    /// Tool orientation at parameter `s` when the path carries one.
    pub fn orientation_at(&self, s: f64) -> Option<Vec3> {
        self.ori.as_ref().map(|o| o.at(s))
    }

    /// Tangent `dp/ds` at `s` (not normalised).
    pub fn tangent(&self, s: f64) -> AxisVec {
        if let Some(c) = &self.curve {
            return c.tangent(s);
        }
        let mut t = [0.0; MAX_CHANNEL_AXES];
        for (k, tk) in t.iter_mut().enumerate() {
            *tk = self.end[k] - self.start[k];
        }
        if let Some(arc) = &self.arc {
            let (a0, a1) = (arc.start_angle, arc.start_angle + arc.sweep);
            let a = a0 + arc.sweep * s;
            let du = arc.radius * (-arc.sweep * a.sin() - (a1.cos() - a0.cos()));
            let dv = arc.radius * (arc.sweep * a.cos() - (a1.sin() - a0.sin()));
            for (k, tk) in t.iter_mut().enumerate() {
                *tk += du * arc.u[k] + dv * arc.v[k];
            }
        }
        t
    }

    /// Upper bound of `|dp_k/ds|` over the whole block, per axis.
    pub fn max_rate(&self) -> AxisVec {
        self.max_rate_of_first(MAX_CHANNEL_AXES)
    }

    /// [`Path::max_rate`] of the first `n` axes (a channel's), the rest left 0: a block's
    /// limits need no more, and they are worked out for every block.
    pub fn max_rate_of_first(&self, n: usize) -> AxisVec {
        let mut r = [0.0; MAX_CHANNEL_AXES];
        let n = n.min(MAX_CHANNEL_AXES);
        if let Some(c) = &self.curve {
            let (rate, _) = c.rates();
            let length = c.length();
            for (rk, q) in r[..n].iter_mut().zip(rate) {
                *rk = q * length;
            }
            return r;
        }
        match &self.arc {
            None => {
                for (k, rk) in r[..n].iter_mut().enumerate() {
                    *rk = (self.end[k] - self.start[k]).abs();
                }
            }
            Some(arc) => {
                // `arc_parts`' linear part, for the first `n` axes only.
                let turn = arc_turn(arc);
                for (k, rk) in r[..n].iter_mut().enumerate() {
                    let linear_k = self.end[k] - self.start[k] - chord(arc, turn, k);
                    // Most axes are outside the circle's plane or along one of its directions:
                    // skip libm's hypot for them (hypot(x, 0) is |x| exactly).
                    let (u, v) = (arc.u[k], arc.v[k]);
                    let span = if v == 0.0 {
                        u.abs()
                    } else if u == 0.0 {
                        v.abs()
                    } else {
                        u.hypot(v)
                    };
                    let circle = arc.radius * arc.sweep.abs() * span;
                    *rk = linear_k.abs() + circle;
                }
            }
        }
        r
    }

    /// The smallest and largest value each axis takes along the path.
    pub fn extent(&self) -> (AxisVec, AxisVec) {
        let mut lo = [0.0; MAX_CHANNEL_AXES];
        let mut hi = [0.0; MAX_CHANNEL_AXES];
        for k in 0..MAX_CHANNEL_AXES {
            lo[k] = self.start[k].min(self.end[k]);
            hi[k] = self.start[k].max(self.end[k]);
        }
        if self.curve.is_some() {
            // A short rounding element: its extent sampled finely enough for limit checks.
            // A curve that overflowed (POLY coefficients near f64::MAX) has NaN points: its
            // extent is NaN then, which no limit check passes.
            let mut p = [0.0; MAX_CHANNEL_AXES];
            for i in 1..64 {
                self.at(f64::from(i) / 64.0, &mut p);
                for k in 0..MAX_CHANNEL_AXES {
                    let nan = p[k].is_nan() || lo[k].is_nan();
                    lo[k] = if nan { f64::NAN } else { lo[k].min(p[k]) };
                    hi[k] = if nan { f64::NAN } else { hi[k].max(p[k]) };
                }
            }
            return (lo, hi);
        }
        let Some(arc) = &self.arc else { return (lo, hi) };
        // Axis k follows f(s) = c + b·s + ρ·cos(a0 + sweep·s − φ): its extremes lie where
        // f'(s) = b − ρ·sweep·sin(…) = 0.
        let (linear, _) = self.arc_parts(arc);
        let mut p = [0.0; MAX_CHANNEL_AXES];
        for k in 0..MAX_CHANNEL_AXES {
            if !arc.moves_axis(k) {
                continue;
            }
            let rho = arc.radius * arc.u[k].hypot(arc.v[k]);
            let phi = arc.v[k].atan2(arc.u[k]);
            let ratio = linear[k] / (rho * arc.sweep);
            if !ratio.is_finite() || ratio.abs() > 1.0 {
                continue;
            }
            let base = ratio.asin();
            for root in [base, std::f64::consts::PI - base] {
                // θ = a0 + sweep·s − φ ≡ root (mod 2π): every s in 0..1.
                let theta0 = arc.start_angle - phi;
                let turns = ((theta0.min(theta0 + arc.sweep) - root) / std::f64::consts::TAU).floor() as i64;
                for n in turns..=turns + 2 + (arc.sweep.abs() / std::f64::consts::TAU) as i64 {
                    let s = (root + n as f64 * std::f64::consts::TAU - theta0) / arc.sweep;
                    if (0.0..=1.0).contains(&s) {
                        self.at(s, &mut p);
                        lo[k] = lo[k].min(p[k]);
                        hi[k] = hi[k].max(p[k]);
                    }
                }
            }
        }
        (lo, hi)
    }

    /// The linear part of an arc path per axis (end − start without the chord of the circle),
    /// and the chord.
    fn arc_parts(&self, arc: &Arc) -> (AxisVec, AxisVec) {
        // The same for every axis: computed once, not per axis (libm calls are not hoisted).
        let turn = arc_turn(arc);
        let mut linear = [0.0; MAX_CHANNEL_AXES];
        let mut chord_of = [0.0; MAX_CHANNEL_AXES];
        for k in 0..MAX_CHANNEL_AXES {
            chord_of[k] = chord(arc, turn, k);
            linear[k] = self.end[k] - self.start[k] - chord_of[k];
        }
        (linear, chord_of)
    }
}

/// `(cos a1 − cos a0, sin a1 − sin a0)` of an arc from its start angle a0 to its end a1: the
/// chord of the unit circle, the same for every axis.
fn arc_turn(arc: &Arc) -> (f64, f64) {
    let (a0, a1) = (arc.start_angle, arc.start_angle + arc.sweep);
    let (sin0, cos0) = a0.sin_cos();
    let (sin1, cos1) = a1.sin_cos();
    (cos1 - cos0, sin1 - sin0)
}

/// The share of axis `k` in the chord of `arc` (`turn` from [`arc_turn`]).
fn chord(arc: &Arc, (dcos, dsin): (f64, f64), k: usize) -> f64 {
    arc.radius * (dcos * arc.u[k] + dsin * arc.v[k])
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn half_circle() -> Path {
        let mut start = [0.0; MAX_CHANNEL_AXES];
        let mut end = [0.0; MAX_CHANNEL_AXES];
        start[0] = 10.0;
        end[0] = -10.0;
        end[2] = 4.0;
        Path { start, end, arc: Some(Box::new(Arc::in_plane(0, 1, 10.0, 0.0, PI))), ori: None, curve: None }
    }

    #[test]
    fn a_helix_lifts_linearly_while_turning() {
        let p = half_circle();
        let mut q = [0.0; MAX_CHANNEL_AXES];
        p.at(0.5, &mut q);
        assert!((q[0]).abs() < 1e-12 && (q[1] - 10.0).abs() < 1e-12 && (q[2] - 2.0).abs() < 1e-12, "{q:?}");
    }

    #[test]
    fn a_slice_of_a_helix_lies_on_the_helix() {
        let p = half_circle();
        let s = p.slice(0.25, 0.75);
        let (mut a, mut b) = ([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]);
        for u in [0.0, 0.3, 1.0] {
            s.at(u, &mut a);
            p.at(0.25 + 0.5 * u, &mut b);
            assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-12), "{u}");
        }
    }

    #[test]
    fn the_rates_of_the_first_axes_are_those_of_all_axes() {
        // Half circle of radius 10 in X/Y with Z rising 4: |dX/ds| ≤ linear 0 + circle 10·π,
        // |dZ/ds| = 4; the first two axes only leave Z at 0.
        let p = half_circle();
        let (all, first) = (p.max_rate(), p.max_rate_of_first(2));
        assert!((all[0] - 10.0 * PI).abs() < 1e-12 && (all[2] - 4.0).abs() < 1e-12, "{all:?}");
        assert_eq!(&first[..2], &all[..2]);
        assert_eq!(first[2], 0.0);
    }

    #[test]
    fn the_extent_of_an_arc_includes_the_quadrant_points_it_crosses() {
        let (lo, hi) = half_circle().extent();
        assert!(lo[1].abs() < 1e-12 && (hi[1] - 10.0).abs() < 1e-12, "{} {}", lo[1], hi[1]);
        assert_eq!((lo[0], hi[0]), (-10.0, 10.0));
        assert_eq!((lo[2], hi[2]), (0.0, 4.0));
    }

    #[test]
    fn an_arc_in_a_tilted_plane_stays_on_its_sphere() {
        // u = x, v = (0, cos 30°, sin 30°): a circle of radius 5 about the origin tilted about X.
        let mut u = [0.0; MAX_CHANNEL_AXES];
        let mut v = [0.0; MAX_CHANNEL_AXES];
        u[0] = 1.0;
        v[1] = (PI / 6.0).cos();
        v[2] = (PI / 6.0).sin();
        let arc = Arc { u, v, radius: 5.0, start_angle: 0.0, sweep: PI };
        let mut start = [0.0; MAX_CHANNEL_AXES];
        let mut end = [0.0; MAX_CHANNEL_AXES];
        start[0] = 5.0;
        end[0] = -5.0;
        let p = Path { start, end, arc: Some(Box::new(arc)), ori: None, curve: None };
        let mut q = [0.0; MAX_CHANNEL_AXES];
        for i in 0..=20 {
            p.at(i as f64 / 20.0, &mut q);
            assert!(((q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt() - 5.0).abs() < 1e-12);
        }
        let (_, hi) = p.extent();
        assert!((hi[2] - 2.5).abs() < 1e-9, "top of the tilted half circle: {}", hi[2]);
    }
}

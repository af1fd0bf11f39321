//! The per-cycle interpolation of the move at the front of the planner's queue.
//!
//! What every cycle of one move needs and is the same for all of them is worked out once, when
//! the move comes to the front ([`FrontMove::new`]): the axes that move (a channel has 20 slots,
//! a block moves a few), their start and travel, the arc's plane vectors on them and the sine
//! and cosine of its end angles. Each cycle then touches only the moving axes, and the arc's
//! angle is stepped from the last cycle's with the addition theorem ([`SinCosStep`]) instead
//! of a `sin_cos`; every [`EXACT_EVERY`]th cycle and the block end are exact.

use super::curve::Curve;
use super::orientation::{OriPath, Vec3, rotate_by};
use super::path::{AxisVec, Path};
use crate::machine_data::registry::MAX_CHANNEL_AXES;

/// Cycles after which a stepped sine and cosine are computed afresh with `sin_cos` (the
/// rounding of the stepped ones grows by about one unit in the last place per cycle).
pub(super) const EXACT_EVERY: u32 = 64;

/// Largest angle step (radians) taken with the series; a larger one uses `sin_cos`.
const MAX_STEP: f64 = 0.05;

/// An angle with its sine and cosine, stepped from one cycle to the next.
#[derive(Debug, Clone, Copy)]
pub(super) struct SinCosStep {
    angle: f64,
    sin: f64,
    cos: f64,
    /// Cycles since `sin_cos` was called.
    stepped: u32,
}

impl SinCosStep {
    /// Sine and cosine of `angle`, stepped from `last` when there is one near enough: the
    /// angle moves by a small `d`, so they follow from the last ones by the addition theorem
    /// with `sin d` and `cos d` from their Taylor series (to d⁹ and d⁸: below 1e-21 for
    /// |d| < 0.05 rad). Otherwise, and every [`EXACT_EVERY`]th cycle, `sin_cos`.
    pub(super) fn next(last: Option<SinCosStep>, angle: f64) -> SinCosStep {
        match last {
            Some(last) if last.stepped < EXACT_EVERY && (angle - last.angle).abs() < MAX_STEP => {
                let d = angle - last.angle;
                let d2 = d * d;
                // Reciprocals, not divisions (the terms are < 1e-3 of the result: their rounding
                // stays far below the last place).
                let sin_d = d
                    * (1.0
                        - d2 * (1.0 / 6.0)
                            * (1.0 - d2 * (1.0 / 20.0) * (1.0 - d2 * (1.0 / 42.0) * (1.0 - d2 * (1.0 / 72.0)))));
                let cos_d =
                    1.0 - d2 * 0.5 * (1.0 - d2 * (1.0 / 12.0) * (1.0 - d2 * (1.0 / 30.0) * (1.0 - d2 * (1.0 / 56.0))));
                SinCosStep {
                    angle,
                    sin: last.sin * cos_d + last.cos * sin_d,
                    cos: last.cos * cos_d - last.sin * sin_d,
                    stepped: last.stepped + 1,
                }
            }
            _ => {
                let (sin, cos) = angle.sin_cos();
                SinCosStep { angle, sin, cos, stepped: 0 }
            }
        }
    }
}

/// The moving axes' positions on a free-form element at `u` (out of the line's and the arc's
/// code).
#[inline(never)]
fn curve_position(c: &Curve, m: &Moving, u: f64, out: &mut AxisVec) {
    let mut p = [0.0; MAX_CHANNEL_AXES];
    c.at(u, &mut p);
    for &k in &m.slot[..m.len] {
        out[k] = p[k];
    }
}

/// The moving axes of the front move: slot, start and travel (`end − start`), and for an arc
/// the plane vectors' components. Compact: only the first `len` entries are used.
#[derive(Debug, Clone)]
struct Moving {
    slot: [usize; MAX_CHANNEL_AXES],
    start: [f64; MAX_CHANNEL_AXES],
    travel: [f64; MAX_CHANNEL_AXES],
    arc_u: [f64; MAX_CHANNEL_AXES],
    arc_v: [f64; MAX_CHANNEL_AXES],
    len: usize,
}

/// The arc's constant parts: start angle, sweep, radius, and `(sin, cos)` of both end angles.
#[derive(Debug, Clone, Copy)]
struct ArcConst {
    start_angle: f64,
    sweep: f64,
    radius: f64,
    ends: [(f64, f64); 2],
}

/// The front move's constant data and stepped angles, rebuilt when the front changes.
#[derive(Debug, Clone)]
pub(super) struct FrontMove {
    moving: Moving,
    arc: Option<ArcConst>,
    /// The arc's angle at the last cycle.
    arc_angle: Option<SinCosStep>,
    /// The orientation's rotation angle at the last cycle.
    ori_angle: Option<SinCosStep>,
    /// A corner rounding element, evaluated directly each cycle.
    curve: Option<std::sync::Arc<Curve>>,
    /// The move's tag, so that its cycles need not look the move up.
    pub(super) tag: u32,
    /// The move interpolates an orientation (its cycles need the move's orientation path).
    pub(super) oriented: bool,
}

impl FrontMove {
    /// Sets up the cycles of `path`, and puts every axis it does not move at the value
    /// [`Path::at`] gives it for every `s < 1` (`start + 0.0`: a −0.0 start reads +0.0 there).
    /// `tag` is the move's.
    #[inline(never)]
    pub(super) fn new(path: &Path, position: &mut AxisVec, tag: u32) -> FrontMove {
        let mut moving = Moving {
            slot: [0; MAX_CHANNEL_AXES],
            start: [0.0; MAX_CHANNEL_AXES],
            travel: [0.0; MAX_CHANNEL_AXES],
            arc_u: [0.0; MAX_CHANNEL_AXES],
            arc_v: [0.0; MAX_CHANNEL_AXES],
            len: 0,
        };
        for (k, standing) in position.iter_mut().enumerate() {
            let (a, b) = (path.start[k], path.end[k]);
            let in_arc = path.arc.as_ref().is_some_and(|arc| arc.moves_axis(k))
                || path.curve.as_ref().is_some_and(|c| c.moves_axis(k));
            // `a == b` holds for ±0 too; NaN never reaches a path (a move's length is finite).
            if a == b && !in_arc {
                *standing = a + 0.0;
                continue;
            }
            let n = moving.len;
            moving.slot[n] = k;
            moving.start[n] = a;
            moving.travel[n] = b - a;
            if let Some(arc) = &path.arc {
                moving.arc_u[n] = arc.u[k];
                moving.arc_v[n] = arc.v[k];
            }
            moving.len += 1;
        }
        // A free-form element is its own path (it carries no arc; were one given, the curve wins).
        let arc = path.arc.as_ref().filter(|_| path.curve.is_none()).map(|arc| ArcConst {
            start_angle: arc.start_angle,
            sweep: arc.sweep,
            radius: arc.radius,
            ends: [arc.start_angle.sin_cos(), (arc.start_angle + arc.sweep).sin_cos()],
        });
        FrontMove {
            moving,
            arc,
            arc_angle: None,
            ori_angle: None,
            curve: path.curve.clone(),
            tag,
            oriented: path.ori.is_some(),
        }
    }

    /// The moving axes' positions at parameter `u` (0 ≤ u < 1) into `out`: [`Path::at`]'s
    /// arithmetic (bit for bit on a line), with the arc's angle stepped.
    #[inline]
    pub(super) fn position(&mut self, u: f64, out: &mut AxisVec) {
        let m = &self.moving;
        let n = m.len;
        // A rounding element has no arc: lines and arcs, the usual moves, test nothing else.
        match (&self.arc, &self.curve) {
            (None, None) => {
                // Sliced once: the loop indexes no array but `out`.
                for ((&k, &a), &t) in m.slot[..n].iter().zip(&m.start[..n]).zip(&m.travel[..n]) {
                    out[k] = a + t * u;
                }
            }
            (None, Some(c)) => curve_position(c, m, u, out),
            (Some(arc), _) => {
                // Circle minus its chord: zero at both ends.
                let [(sin0, cos0), (sin1, cos1)] = arc.ends;
                let now = SinCosStep::next(self.arc_angle, arc.start_angle + arc.sweep * u);
                self.arc_angle = Some(now);
                let cu = arc.radius * (now.cos - cos0 - u * (cos1 - cos0));
                let cv = arc.radius * (now.sin - sin0 - u * (sin1 - sin0));
                let (start, travel) = (&m.start[..n], &m.travel[..n]);
                for (i, &k) in m.slot[..n].iter().enumerate() {
                    let o = start[i] + travel[i] * u;
                    out[k] = o + (cu * m.arc_u[i] + cv * m.arc_v[i]);
                }
            }
        }
    }

    /// [`OriPath::at`] at `u` with the rotation angle stepped from the last cycle's.
    #[inline(never)]
    pub(super) fn orientation(&mut self, ori: &OriPath, u: f64) -> Vec3 {
        if ori.curve.is_some() || ori.turn.is_some() || !ori.kinks.is_empty() {
            return ori.at(u);
        }
        let now = SinCosStep::next(self.ori_angle, ori.angle * u.clamp(0.0, 1.0));
        self.ori_angle = Some(now);
        rotate_by(ori.start, ori.axis, now.sin, now.cos)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::path::Arc;

    fn path(arc: Option<Arc>) -> Path {
        let mut start = [0.0; MAX_CHANNEL_AXES];
        let mut end = [0.0; MAX_CHANNEL_AXES];
        (start[0], start[1], start[2], start[4]) = (10.0, -3.5, 1.25, -0.0);
        (end[0], end[1], end[2], end[4]) = (-2.0, 7.0, -4.0, -0.0);
        (start[7], end[7]) = (3.0, 3.0);
        Path { start, end, arc: arc.map(Box::new), ori: None, curve: None }
    }

    #[test]
    fn a_line_is_interpolated_bit_for_bit_as_path_at() {
        let p = path(None);
        let mut got = [f64::NAN; MAX_CHANNEL_AXES];
        let mut front = FrontMove::new(&p, &mut got, 0);
        for i in 0..1000 {
            let u = f64::from(i) / 1000.0;
            let mut expected = [0.0; MAX_CHANNEL_AXES];
            p.at(u, &mut expected);
            front.position(u, &mut got);
            // Every slot, the standing ones (−0.0 reads +0.0 in `Path::at`) included.
            assert_eq!(expected.map(f64::to_bits), got.map(f64::to_bits), "u = {u}");
        }
    }

    #[test]
    fn a_stepped_arc_stays_within_1e12_of_the_direct_one_over_many_cycles() {
        // Radius 6.3 and 1.1, sweeps −2.9 and 5.5 rad, in 1000 and 20000 uneven steps: the
        // stepped sine and cosine drift by at most 64 roundings (~1.4e-14) before the exact
        // resync, times the radius: far below 1e-12 mm. The standing slots are exact.
        for (arc, steps) in [(Arc::in_plane(0, 1, 6.3, 0.7, -2.9), 1000), (Arc::in_plane(2, 0, 1.1, -1.3, 5.5), 20000)]
        {
            let p = path(Some(arc));
            let mut got = [f64::NAN; MAX_CHANNEL_AXES];
            let mut front = FrontMove::new(&p, &mut got, 0);
            let (mut u, mut worst) = (0.0f64, 0.0f64);
            for i in 0..steps {
                // Accelerating steps, then even ones.
                u += (f64::from(i + 1) / 50.0).min(1.0) / f64::from(steps) * 1.3;
                if u >= 1.0 {
                    break;
                }
                let mut expected = [0.0; MAX_CHANNEL_AXES];
                p.at(u, &mut expected);
                front.position(u, &mut got);
                worst = expected.iter().zip(&got).fold(worst, |w, (e, g)| w.max((e - g).abs()));
                assert_eq!(got[7].to_bits(), 3.0f64.to_bits());
                assert_eq!(got[4].to_bits(), 0.0f64.to_bits());
            }
            assert!(worst < 1e-12, "worst deviation {worst}");
        }
    }

    #[test]
    fn stepped_orientations_stay_on_the_exact_rotation() {
        // A great circle of 1.2 rad run in uneven steps (accelerating, then cruising): every
        // stepped orientation agrees with the direct Rodrigues rotation within 1e-13 (64 steps of
        // rounding at most).
        let ori = OriPath {
            start: [0.0, 0.0, 1.0],
            axis: [0.0, -1.0, 0.0],
            angle: 1.2,
            curve: None,
            turn: None,
            kinks: Vec::new(),
        };
        let mut front = FrontMove::new(
            &Path::line([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]),
            &mut [0.0; MAX_CHANNEL_AXES],
            0,
        );
        let (mut u, mut du) = (0.0f64, 0.0f64);
        let mut cycles = 0;
        while u < 1.0 {
            du = (du + 1e-5).min(2e-3);
            u += du;
            let got = front.orientation(&ori, u);
            let want = ori.at(u);
            for k in 0..3 {
                assert!((got[k] - want[k]).abs() < 1e-13, "u = {u}: {got:?} vs {want:?}");
            }
            cycles += 1;
        }
        assert!(cycles > 2 * EXACT_EVERY, "the test covers fresh starts: {cycles} cycles");
    }
}

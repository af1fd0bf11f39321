//! Corner rounding under a kinematic transformation (Function Manual B1 "Continuous-path
//! mode" with G642/G643/G645 and the orientation tolerance SD42466 / `OTOL`).
//!
//! The moves of a transformed block are paths in the BCS (the tool tip, plus the orientation:
//! the rotary axes' positions in their slots under ORIAXES, or an [`OriPath`] under
//! ORIVECT ...), with the machine axes' rates at their ends. The corner is rounded in the BCS
//! as without a transformation (`blend.rs`): the tool tip's element passes the programmed
//! corner within the contour tolerance. The orientation is rounded with it:
//! - ORIAXES: the element is a curve in every channel axis, the rotary axes' slots included,
//!   so they pass from one block's motion to the next with the same quintic;
//! - a vector-interpolated orientation: the element turns the tool from the orientation where
//!   it leaves the first block to the one where it joins the second, along a quintic whose
//!   direction is the orientation, with both blocks' orientation rates (first and second
//!   derivative per unit length) at its ends: the tool vector's angular velocity goes on
//!   without a jump at the element's seams (a great circle between the cut points turned at
//!   its own rate, in its own direction, and the planner had to slow the path for the jump).
//!
//! Either way the element's orientation comes no farther than the orientation tolerance from
//! the programmed orientation at the corner (the angle from that orientation to the nearest
//! one of the element: the orientation's analogue of the tip's distance from the corner);
//! the element is cut back until both hold. The caller plans the pieces for the machine axes
//! again (`kinematics::plan`): their limits come from the machine axes along them.

use super::blend::{self, Rounded};
use super::curve::Curve;
use super::ori_curve::TwoCurves;
use super::orientation::{OriPath, Vec3};
use super::path::{AxisVec, Path};
use super::planner::{AxisLimit, Move};
use crate::machine_data::registry::MAX_CHANNEL_AXES;

/// The tool orientation of a BCS position whose orientation slots hold the rotary axes
/// (ORIAXES); `None` without an orientation transformation.
pub type OrientationOf<'a> = &'a dyn Fn(&AxisVec) -> Option<Vec3>;

/// Rounds the corner between the transformed moves `a` and `b` (see the module doc);
/// `a_full_length` as for [`blend::round_corner`]. `None` leaves the corner as it is.
pub fn round_transformed_corner(
    a: &Move,
    b: &Move,
    a_full_length: f64,
    metric: &AxisVec,
    limits: &[AxisLimit],
    orientation_of: OrientationOf,
) -> Option<Rounded> {
    let vector = a.path.ori.is_some() || b.path.ori.is_some();
    // The orientation at parameter `u` of a move: its vector path, or its rotary axes.
    let ori_at = |m: &Move, u: f64| -> Option<Vec3> {
        m.path.orientation_at(u).or_else(|| {
            let mut p = [0.0; MAX_CHANNEL_AXES];
            m.path.at(u, &mut p);
            orientation_of(&p)
        })
    };
    let corner_ori = ori_at(a, 1.0);
    let deviation = |curve: &Curve, ua: f64, ub: f64| -> f64 {
        let Some(c) = corner_ori else { return 0.0 };
        if vector {
            let (Some(o0), Some(o1)) = (ori_at(a, ua), ori_at(b, ub)) else { return 0.0 };
            let arc = element_orientation(a, ua, b, ub, o0, o1, chord_length(curve, metric));
            return least_angle(c, |w| arc.at(w));
        }
        // The element writes the axes it moves only: the others stand where it starts.
        let mut p = [0.0; MAX_CHANNEL_AXES];
        a.path.at(ua, &mut p);
        least_angle(c, |w| {
            curve.eval(w, &mut p);
            orientation_of(&p).unwrap_or(c)
        })
    };
    let (bare_a, bare_b) = (bare(a), bare(b));
    let mut r = blend::round_corner_oriented(&bare_a, &bare_b, a_full_length, metric, limits, &deviation)?;
    let (ua, ub) = r.cut;
    r.first.path.ori = a.path.ori.as_ref().map(|o| Box::new(o.slice(0.0, ua)));
    r.second.path.ori = b.path.ori.as_ref().map(|o| Box::new(o.slice(ub, 1.0)));
    if vector {
        let (o0, o1) = (ori_at(a, ua)?, ori_at(b, ub)?);
        // The element's length as the search measured it, so the orientation is the one checked.
        let len = r.corner.path.curve.as_deref().map_or(r.corner.length, |c| chord_length(c, metric));
        r.corner.path.ori = Some(Box::new(element_orientation(a, ua, b, ub, o0, o1, len)));
    }
    Some(r)
}

/// `m` without its orientation path and machine rates: the plain BCS move `blend.rs` rounds.
fn bare(m: &Move) -> Move {
    let mut path = Path::line(m.path.start, m.path.end);
    path.arc = m.path.arc.clone();
    path.curve = m.path.curve.clone();
    let mut out = blend::with_path(m, path);
    out.axis_tangents = None;
    out
}

/// The element's orientation from `o0` (where it leaves `a`, at `ua`) to `o1` (where it
/// joins `b`, at `ub`), `len` its length: where both blocks turn the tool as a vector, a
/// quintic whose direction is the orientation (an ORICURVE-like [`TwoCurves`] with a bent
/// upper curve) with the orientation's first and second derivative per unit length of both
/// blocks at its ends, so that the tool vector's angular velocity and acceleration go on
/// without a jump where the element starts and ends; else the great circle from `o0` to `o1`
/// (a standing orientation where they coincide; antiparallel ends cannot occur within a
/// tolerance of degrees).
fn element_orientation(a: &Move, ua: f64, b: &Move, ub: f64, o0: Vec3, o1: Vec3, len: f64) -> OriPath {
    if let (Some(oa), Some(ob)) = (a.path.ori.as_deref(), b.path.ori.as_deref())
        && len > 0.0
    {
        let ([d0, dd0], [d1, dd1]) = (rates(oa, ua, a.length / len), rates(ob, ub, b.length / len));
        let bend = hermite_bend([(o0, d0, dd0), (o1, d1, dd1)]);
        return OriPath::two_curves(TwoCurves { tip: [[0.0; 3]; 2], upper: [o0, o1], bend });
    }
    match OriPath::great_circle(o0, o1) {
        Ok(Some(arc)) => arc,
        _ => OriPath { start: o0, axis: [0.0, 0.0, 1.0], angle: 0.0, curve: None, turn: None, kinks: Vec::new() },
    }
}

/// The first and second derivative of `o` at `u` (central differences, one-sided at the
/// ends), per unit of a parameter `stretch` times longer (the element's, against the block's).
fn rates(o: &OriPath, u: f64, stretch: f64) -> [Vec3; 2] {
    const H: f64 = 1e-4;
    let c = u.clamp(H, 1.0 - H);
    let (m, z, p) = (o.at(c - H), o.at(c), o.at(c + H));
    let d: Vec3 = std::array::from_fn(|i| (p[i] - m[i]) / (2.0 * H) / stretch);
    let dd: Vec3 = std::array::from_fn(|i| (p[i] - 2.0 * z[i] + m[i]) / (H * H) / (stretch * stretch));
    // From `c` to `u` along the first derivative (the ends lie H beyond the central point).
    let d = std::array::from_fn(|i| d[i] + dd[i] * (u - c) * stretch);
    [d, dd]
}

/// The bend ([`TwoCurves::bend`]: power coefficients of u² .. u⁵) of the quintic with value,
/// first and second derivative `ends` at 0 and 1.
pub(super) fn hermite_bend(ends: [(Vec3, Vec3, Vec3); 2]) -> [Vec3; 4] {
    let [(p0, v0, a0), (p1, v1, a1)] = ends;
    let c = |i: usize| -> [f64; 4] {
        [
            0.5 * a0[i],
            -10.0 * p0[i] - 6.0 * v0[i] - 1.5 * a0[i] + 0.5 * a1[i] - 4.0 * v1[i] + 10.0 * p1[i],
            15.0 * p0[i] + 8.0 * v0[i] + 1.5 * a0[i] - a1[i] + 7.0 * v1[i] - 15.0 * p1[i],
            -6.0 * p0[i] - 3.0 * v0[i] - 0.5 * a0[i] + 0.5 * a1[i] - 3.0 * v1[i] + 6.0 * p1[i],
        ]
    };
    let (cx, cy, cz) = (c(0), c(1), c(2));
    std::array::from_fn(|n| [cx[n], cy[n], cz[n]])
}

/// The length of `curve` in the metric's axes, by 16 chords (the element's length before its
/// table is built; within a fraction of a per cent for a rounding element).
fn chord_length(curve: &Curve, metric: &AxisVec) -> f64 {
    let (mut p, mut q) = ([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]);
    curve.eval(0.0, &mut p);
    let mut len = 0.0;
    for i in 1..=16 {
        curve.eval(f64::from(i) / 16.0, &mut q);
        len += (0..MAX_CHANNEL_AXES).map(|k| metric[k] * (q[k] - p[k]).powi(2)).sum::<f64>().sqrt();
        p = q;
    }
    len
}

/// The smallest angle (radians) between `c` and the orientations `at(w)`, `w` in 0..=1.
fn least_angle(c: Vec3, mut at: impl FnMut(f64) -> Vec3) -> f64 {
    // The chord between unit vectors is 2·sin(angle/2): its least value gives the least angle.
    let chord = super::nearest::least_distance(
        |w| {
            let o = at(w);
            (o[0] - c[0]).powi(2) + (o[1] - c[1]).powi(2) + (o[2] - c[2]).powi(2)
        },
        (0.0, 1.0),
        16,
        16,
    );
    2.0 * (0.5 * chord).min(1.0).asin()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::blend::Blend;
    use crate::motion::planner::Feed;

    fn limits() -> Vec<AxisLimit> {
        vec![AxisLimit { max_velocity: 200.0, max_accel: 2000.0, accel_overload: 1.2 }; 6]
    }

    fn metric() -> AxisVec {
        let mut m = [0.0; super::MAX_CHANNEL_AXES];
        m[..3].fill(1.0);
        m
    }

    /// A line in X/Y whose orientation turns on the great circle from `o0` to `o1`.
    fn oriented(from: [f64; 2], to: [f64; 2], o0: Vec3, o1: Vec3, blend: Option<Blend>) -> Move {
        let (mut s, mut e) = ([0.0; super::MAX_CHANNEL_AXES], [0.0; super::MAX_CHANNEL_AXES]);
        (s[0], s[1], e[0], e[1]) = (from[0], from[1], to[0], to[1]);
        let len = ((to[0] - from[0]).powi(2) + (to[1] - from[1]).powi(2)).sqrt();
        let mut path = Path::line(s, e);
        path.ori = OriPath::great_circle(o0, o1).unwrap().map(Box::new);
        let mut mv = Move::new(path, len, Feed::Path(50.0), &limits(), false, 1);
        mv.blend = blend;
        mv
    }

    fn unit(v: Vec3) -> Vec3 {
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        [v[0] / n, v[1] / n, v[2] / n]
    }

    #[test]
    fn the_orientation_tolerance_cuts_the_element_back_where_the_orientation_turns_a_corner() {
        // X0→10 tilting the tool from Z towards +X by 10°, then Y0→10 tilting it on towards +Y
        // by another 10°: a corner of the orientation at the corner of the tip. With a contour
        // tolerance of 0.05 mm alone the element cuts back about 0.05/(1 − cos 45°)·... mm of
        // each block, and its orientation (taking over both blocks' rates: 1°/mm) passes the
        // corner orientation at some angle (0.045°); with OTOL 0.02° the angle is within 0.02°
        // (and > 0: the orientation is rounded), and the element is shorter than without it.
        let z = [0.0, 0.0, 1.0];
        let tilt = unit([10f64.to_radians().tan(), 0.0, 1.0]);
        let on = unit([tilt[0], 10f64.to_radians().tan(), tilt[2]]);
        let run = |ori_deg: f64| {
            let spec = Blend::Tolerance { contour: 0.05, ori: ori_deg.to_radians() };
            let a = oriented([0.0, 0.0], [10.0, 0.0], z, tilt, Some(spec));
            let b = oriented([10.0, 0.0], [10.0, 10.0], tilt, on, None);
            let r = round_transformed_corner(&a, &b, 10.0, &metric(), &limits(), &|_| None).expect("rounded");
            let ori = r.corner.path.ori.as_ref().expect("the element turns the tool");
            let angle = least_angle(tilt, |w| ori.at(w));
            (r, angle)
        };
        let (wide, wide_angle) = run(90.0);
        let (tight, tight_angle) = run(0.02);
        assert!(
            tight_angle <= 0.02f64.to_radians() * (1.0 + 1e-9) && tight_angle > 0.0,
            "{}",
            tight_angle.to_degrees()
        );
        assert!(wide_angle > tight_angle, "{} vs {}", wide_angle.to_degrees(), tight_angle.to_degrees());
        assert!(tight.corner.length < wide.corner.length);
        // The pieces keep their orientation paths, continuous with the element's.
        let first_end = tight.first.path.orientation_at(1.0).unwrap();
        let element_start = tight.corner.path.orientation_at(0.0).unwrap();
        assert!((0..3).all(|k| (first_end[k] - element_start[k]).abs() < 1e-12));
        let element_end = tight.corner.path.orientation_at(1.0).unwrap();
        let second_start = tight.second.path.orientation_at(0.0).unwrap();
        assert!((0..3).all(|k| (element_end[k] - second_start[k]).abs() < 1e-12));
    }

    #[test]
    fn the_element_takes_over_the_orientation_rate_of_both_blocks() {
        // Both blocks turn the tool by 10° over 10 mm: 1°/mm, along the great circle of
        // each. Where the element starts, its orientation moves at 1°/mm along block a's
        // circle, where it ends at 1°/mm along block b's: the angular velocity has no jump at
        // either seam (a great circle between the cut points would turn at its own rate, the
        // angle between them over the element's length, in another direction).
        let z = [0.0, 0.0, 1.0];
        let tilt = unit([10f64.to_radians().tan(), 0.0, 1.0]);
        let on = unit([tilt[0], 10f64.to_radians().tan(), tilt[2]]);
        let spec = Blend::Tolerance { contour: 0.05, ori: 90f64.to_radians() };
        let a = oriented([0.0, 0.0], [10.0, 0.0], z, tilt, Some(spec));
        let b = oriented([10.0, 0.0], [10.0, 10.0], tilt, on, None);
        let r = round_transformed_corner(&a, &b, 10.0, &metric(), &limits(), &|_| None).expect("rounded");
        let e = r.corner.path.ori.as_ref().unwrap();
        let h = 1e-6;
        let per_mm = |o: &OriPath, u: f64, len: f64| -> Vec3 {
            let (p, q) = (o.at(u), o.at(u + h));
            std::array::from_fn(|i| (q[i] - p[i]) / (h * len))
        };
        let (first, second) = (r.first.path.ori.as_ref().unwrap(), r.second.path.ori.as_ref().unwrap());
        let leaving = per_mm(first, 1.0 - h, r.first.length);
        let entering = per_mm(e, 0.0, r.corner.length);
        let arriving = per_mm(e, 1.0 - h, r.corner.length);
        let joining = per_mm(second, 0.0, r.second.length);
        let deg = |v: Vec3| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().to_degrees();
        // 1°/mm on the great circle through Z and the 10° tilt: (1 − 1e-3) for the
        // difference quotients.
        assert!((deg(leaving) - 1.0).abs() < 1e-3, "{}", deg(leaving));
        for (x, y) in [(leaving, entering), (arriving, joining)] {
            let d: Vec3 = std::array::from_fn(|i| x[i] - y[i]);
            assert!(deg(d) < 2e-3, "{x:?} against {y:?}: {}°/mm apart", deg(d));
        }
    }
}

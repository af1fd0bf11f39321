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
//! - a vector-interpolated orientation: the element turns the tool on the great circle from
//!   the orientation where it leaves the first block to the one where it joins the second
//!   (ORIVECT's interpolation of the element).
//!
//! Either way the element's orientation comes no farther than the orientation tolerance from
//! the programmed orientation at the corner (the angle from that orientation to the nearest
//! one of the element: the orientation's analogue of the tip's distance from the corner);
//! the element is cut back until both hold. The caller plans the pieces for the machine axes
//! again (`kinematics::plan`): their limits come from the machine axes along them.

use super::blend::{self, Rounded};
use super::curve::Curve;
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
            let arc = element_orientation(o0, o1);
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
        r.corner.path.ori = Some(Box::new(element_orientation(o0, o1)));
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

/// The element's orientation: the great circle from `o0` to `o1` (a standing orientation
/// where they coincide; antiparallel ends cannot occur within a tolerance of degrees).
fn element_orientation(o0: Vec3, o1: Vec3) -> OriPath {
    match OriPath::great_circle(o0, o1) {
        Ok(Some(arc)) => arc,
        _ => OriPath { start: o0, axis: [0.0, 0.0, 1.0], angle: 0.0, curve: None, turn: None },
    }
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
        // each block, and its great circle passes the corner orientation at some angle; with
        // OTOL 0.05° the angle is within 0.05° (and > 0: the orientation is rounded), and the
        // element is shorter than without it.
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
        let (tight, tight_angle) = run(0.05);
        assert!(
            tight_angle <= 0.05f64.to_radians() * (1.0 + 1e-9) && tight_angle > 0.0,
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
}

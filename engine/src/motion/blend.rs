//! Corner rounding of continuous-path mode (G641..G645, Function Manual B1): between two
//! consecutive moves the end of the first and the start of the second are cut back by a
//! distance `d` and a rounding element joins them.
//!
//! The element is a quintic (see [`Curve`]) with the neighbours' point, tangent and curvature
//! at both ends: the path stays tangent- and curvature-continuous, so the axes' acceleration
//! has no jump where it enters or leaves the element (what the manual asks of G642/G645; G641
//! gets the same element). `d` comes from the mode:
//! - G641: the programmed rounding distance ADIS (ADISPOS for G0), measured along the blocks.
//! - G642..G645: as large as the tolerance allows: the element passes the programmed corner
//!   at no more than the tolerance.
//!
//! Either way `d` is at most [`MAX_SHARE`] of each block (of its full programmed length), so
//! two roundings never meet inside a short block and something of every block is left.
//! Worked in channel-axis space as the planner sees the moves; lengths in the feed's axes.

use super::blend_tangent;
use super::curve::Curve;
use super::path::{AxisVec, Path};
use super::planner::{AxisLimit, Feed, Move};
use crate::machine_data::registry::MAX_CHANNEL_AXES;

/// How the corner at the end of a move is rounded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Blend {
    /// G641: the element starts and ends this far (ADIS, ADISPOS) from the corner.
    Distance(f64),
    /// G642..G644: the element passes the programmed corner within `contour` (a length), and
    /// under an orientation transformation the tool orientation within `ori` (radians) of the
    /// programmed one at the corner (OTOL, SD42466; infinite where it does not act: G644).
    Tolerance { contour: f64, ori: f64 },
    /// G645: corners as [`Blend::Tolerance`] with `corner` and `ori`; tangential transitions
    /// with a jump in curvature are smoothed too, the element staying within `tangent`
    /// (MD33120) of the programmed contour (`blend_tangent.rs`).
    Smooth { corner: f64, ori: f64, tangent: f64 },
    /// G643: every axis within its own tolerance (`blend_axial.rs`): `geo` for the geometry
    /// axes and `other` for the rest where programmed or set (CTOL, SD42465, ATOL), negative
    /// for each axis' MD33100; `ori` as for [`Blend::Tolerance`]. The channel resolves it per
    /// axis ([`Blend::Tolerance`] where G643 rounds as G642).
    Axial { geo: f64, other: f64, ori: f64 },
}

/// The largest share of a block a rounding takes at one end. The manual reduces the rounding
/// of short blocks "by up to 36 %"; here it is read as: at most 36 % of the block at either
/// end, which leaves at least 28 % of every block as programmed.
pub const MAX_SHARE: f64 = 0.36;

/// Roundings shorter than this (in mm or the feed's unit) are left out: the corner is as good
/// as sharp, and a very short element only costs time.
const MIN_DISTANCE: f64 = 1e-4;

/// The two moves shortened at the corner and the element between them.
#[derive(Debug, Clone)]
pub struct Rounded {
    pub first: Move,
    pub corner: Move,
    pub second: Move,
    /// Where the element leaves the first move and joins the second (their path parameters).
    pub cut: (f64, f64),
    /// Further elements after `corner`, in order (G643's chain; empty otherwise).
    pub more: Vec<Move>,
}

/// The orientation deviation of a rounding element from the programmed corner orientation
/// (radians), given the element and the two cut parameters: for rounding under an orientation
/// transformation (`motion/blend_ori.rs`). [`no_orientation`] where nothing is oriented.
pub type OriDeviation<'a> = &'a dyn Fn(&Curve, f64, f64) -> f64;

/// The [`OriDeviation`] of moves without an orientation.
pub fn no_orientation(_: &Curve, _: f64, _: f64) -> f64 {
    0.0
}

/// Rounds the corner between `a` and `b` as `a.blend` asks. `a_full_length` is `a`'s length
/// before its start was cut back by the rounding before it. `metric` is 1.0 for the axes whose
/// distance is the path length (the geometry axes). `None` leaves the corner as it is: no
/// rounding requested, exact stop, a move in machine axes or with an orientation path, a
/// tangential transition (but G645's with a curvature jump), a reversal, or a rounding too
/// short to matter.
pub fn round_corner(a: &Move, b: &Move, a_full_length: f64, metric: &AxisVec, limits: &[AxisLimit]) -> Option<Rounded> {
    round_corner_oriented(a, b, a_full_length, metric, limits, &no_orientation)
}

/// [`round_corner`] with the orientation's deviation `ori_dev` bounded by the tolerance's
/// `ori` as well (the caller has taken the moves' orientation paths and machine rates off; it
/// puts them back on the pieces).
pub fn round_corner_oriented(
    a: &Move,
    b: &Move,
    a_full_length: f64,
    metric: &AxisVec,
    limits: &[AxisLimit],
    ori_dev: OriDeviation,
) -> Option<Rounded> {
    let spec = a.blend?;
    if a.exact_stop
        || a.machine_space
        || b.machine_space
        || a.axis_tangents.is_some()
        || b.axis_tangents.is_some()
        || a.path.ori.is_some()
        || b.path.ori.is_some()
        || b.path.curve.is_some()
        || !(a.length > 0.0 && b.length > 0.0)
    {
        return None;
    }
    let ta = unit(&a.path.tangent(1.0), metric)?;
    let tb = unit(&b.path.tangent(0.0), metric)?;
    let cos = dot(&ta, &tb, metric);
    if cos < -0.9995 {
        return None;
    }
    // A tangential transition: only G645 smooths it, and only where the curvature jumps.
    let tangential = cos > 1.0 - 1e-9;
    let spec = match spec {
        Blend::Smooth { tangent, .. } if tangential => {
            if !(tangent > 0.0 && blend_tangent::curvature_jumps(a, b, metric)) {
                return None;
            }
            spec
        }
        _ if tangential => return None,
        Blend::Smooth { corner, ori, .. } => Blend::Tolerance { contour: corner, ori },
        // Unresolved by the channel: the geometry axes' common tolerance where it is one.
        Blend::Axial { geo, ori, .. } => Blend::Tolerance { contour: geo, ori },
        _ => spec,
    };
    let d_max = (MAX_SHARE * a_full_length.max(a.length).min(b.length)).min(0.9 * a.length);
    let corner = a.path.end;
    let d = match spec {
        Blend::Distance(adis) => adis.min(d_max),
        // The cut grows in proportion to d between two lines, nearly so next to arcs.
        Blend::Tolerance { contour: tol, ori } if tol > 0.0 => search(d_max, tol, 1.0, |d| {
            let curve = element(a, b, d, metric)?;
            let cut = curve.distance_to(&corner);
            if ori.is_finite() {
                // The orientation's deviation in the contour's scale: within `ori` where this is
                // within `tol`.
                let (ua, ub) = (1.0 - d / a.length, d / b.length);
                return Some(cut.max(ori_dev(&curve, ua, ub) * tol / ori.max(1e-12)));
            }
            Some(cut)
        })?,
        // Along a tangential transition the deviation grows with d² (as a clothoid's shift).
        Blend::Smooth { tangent, .. } => search(d_max, tangent, 0.5, |d| {
            let (ua, ub) = (1.0 - d / a.length, d / b.length);
            Some(blend_tangent::contour_deviation(&element(a, b, d, metric)?, a, ua, b, ub, metric))
        })?,
        Blend::Tolerance { .. } | Blend::Axial { .. } => 0.0,
    };
    if d.is_nan() || d < MIN_DISTANCE {
        return None;
    }
    let (ua, ub) = (1.0 - d / a.length, d / b.length);
    let curve = element(a, b, d, metric)?;
    let mut first = with_path(a, a.path.slice(0.0, ua));
    first.set_limits(a.length * ua, feed_of(a.feed), limits);
    first.blend = None;
    let mut second = with_path(b, b.path.slice(ub, 1.0));
    second.set_limits(b.length * (1.0 - ub), feed_of(b.feed), limits);
    let mut curve = curve;
    curve.finish();
    let length = curve.length();
    let path = Path {
        start: first.path.end,
        end: second.path.start,
        arc: None,
        ori: None,
        curve: Some(std::sync::Arc::new(curve)),
    };
    let mut corner = Move::unlimited(path, false, a.tag);
    corner.set_limits(length, feed_of(a.feed.min(b.feed)), limits);
    corner.limit_element_jerk(a, b);
    Some(Rounded { first, corner, second, cut: (ua, ub), more: Vec::new() })
}

/// The largest cut-back `d` up to `d_max` whose `cut(d)` is within `tol` (within 2 % below
/// it where `d_max` does not bound it): steps scaled by `(tol/cut)^power`, then shrinking.
fn search(d_max: f64, tol: f64, power: f64, cut_at: impl Fn(f64) -> Option<f64>) -> Option<f64> {
    let mut d = d_max;
    let mut cut = cut_at(d)?;
    for _ in 0..8 {
        if cut <= tol && (cut >= 0.98 * tol || d >= d_max) {
            break;
        }
        // (Written as before for the corners, so their roundings stay bit for bit the same.)
        let scaled = if power == 1.0 { d * tol / cut.max(1e-300) } else { d * (tol / cut.max(1e-300)).powf(power) };
        d = (scaled * 0.999).min(d_max);
        cut = cut_at(d)?;
    }
    while cut > tol && d >= MIN_DISTANCE {
        d *= 0.8;
        cut = cut_at(d)?;
    }
    Some(d)
}

/// `m` on another `path`: its data copied, its own path not (a clone would copy and drop it,
/// an arc's box included, at every corner).
pub(super) fn with_path(m: &Move, path: Path) -> Move {
    Move {
        // A piece of a line keeps its DRIVE curve (the same axis shares); a rounding element
        // plans with `a_max`, the curve's lowest value.
        drive: if path.arc.is_none() && path.curve.is_none() { m.drive.clone() } else { None },
        path,
        length: m.length,
        v_max: m.v_max,
        v_axes: m.v_axes,
        feed: m.feed,
        a_max: m.a_max,
        exact_stop: m.exact_stop,
        tag: m.tag,
        machine_space: m.machine_space,
        axis_tangents: m.axis_tangents.clone(),
        per_rev: m.per_rev,
        jerk: m.jerk,
        seam_jerk: m.seam_jerk,
        blend: m.blend,
        compress: m.compress,
        orison: m.orison.clone(),
    }
}

/// Share of each axis' acceleration a rounding element leaves to the centripetal part; the
/// rest is the path acceleration's, so the sum never exceeds the axis' limit (as for arcs).
const CENTRIPETAL: f64 = 0.5;

/// The velocity and acceleration a rounding element allows: [`CENTRIPETAL`] of each axis'
/// acceleration for the centripetal part (`v²·|d²p_k/ds²|`), the rest for the path's.
pub fn curve_limits(curve: &Curve, limits: &[AxisLimit], v_max: f64, a_max: f64) -> (f64, f64) {
    let (_, second) = curve.rates();
    let mut v = v_max;
    for (k, lim) in limits.iter().enumerate() {
        if second[k] > 1e-12 {
            v = v.min((CENTRIPETAL * lim.max_accel / second[k]).sqrt());
        }
    }
    (v, (1.0 - CENTRIPETAL) * a_max)
}

/// The rounding element for cut-back distance `d` (without its length table).
fn element(a: &Move, b: &Move, d: f64, metric: &AxisVec) -> Option<Curve> {
    let (ua, ub) = (1.0 - d / a.length, d / b.length);
    let mut q0 = [0.0; MAX_CHANNEL_AXES];
    let mut q1 = [0.0; MAX_CHANNEL_AXES];
    a.path.at(ua, &mut q0);
    b.path.at(ub, &mut q1);
    let chord: AxisVec = std::array::from_fn(|k| q1[k] - q0[k]);
    let l = dot(&chord, &chord, metric).sqrt();
    if l.is_nan() || l <= 1e-12 {
        return None;
    }
    let t0 = a.path.tangent(ua).map(|x| x / a.length * l);
    let t1 = b.path.tangent(ub).map(|x| x / b.length * l);
    let k0 = second_derivative(&a.path, ua).map(|x| x / (a.length * a.length) * l * l);
    let k1 = second_derivative(&b.path, ub).map(|x| x / (b.length * b.length) * l * l);
    Some(Curve::hermite_untabled([(q0, t0, k0), (q1, t1, k1)], *metric))
}

/// `d²p/du²` of a line (zero), an arc (the circle's part; the helix's lift is linear) or a
/// compressed curve.
pub(super) fn second_derivative(path: &Path, u: f64) -> AxisVec {
    if let Some(c) = &path.curve {
        return c.second(u);
    }
    let mut out = [0.0; MAX_CHANNEL_AXES];
    if let Some(arc) = &path.arc {
        let (sin, cos) = (arc.start_angle + arc.sweep * u).sin_cos();
        let f = -arc.radius * arc.sweep * arc.sweep;
        for (k, o) in out.iter_mut().enumerate() {
            *o = f * (cos * arc.u[k] + sin * arc.v[k]);
        }
    }
    out
}

pub(super) fn feed_of(feed: f64) -> Feed {
    if feed.is_infinite() { Feed::Rapid } else { Feed::Path(feed) }
}

/// Scalar product in axis space, each axis weighted by `metric` (0 for axes outside the path).
pub(super) fn dot(a: &AxisVec, b: &AxisVec, metric: &AxisVec) -> f64 {
    a.iter().zip(b).zip(metric).map(|((x, y), m)| x * y * m).sum()
}

/// `v` scaled to length 1 in the `metric`, `None` for a vector of no length.
pub(super) fn unit(v: &AxisVec, metric: &AxisVec) -> Option<AxisVec> {
    let n = dot(v, v, metric).sqrt();
    (n > 1e-12).then(|| v.map(|x| x / n))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits() -> Vec<AxisLimit> {
        vec![AxisLimit { max_velocity: 200.0, max_accel: 2000.0, accel_overload: 1.2 }; 3]
    }

    fn metric() -> AxisVec {
        let mut m = [0.0; MAX_CHANNEL_AXES];
        m[..3].fill(1.0);
        m
    }

    fn line(from: [f64; 2], to: [f64; 2], blend: Option<Blend>) -> Move {
        let (mut s, mut e) = ([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]);
        (s[0], s[1], e[0], e[1]) = (from[0], from[1], to[0], to[1]);
        let len = ((to[0] - from[0]).powi(2) + (to[1] - from[1]).powi(2)).sqrt();
        let mut mv = Move::new(Path::line(s, e), len, Feed::Path(50.0), &limits(), false, 1);
        mv.blend = blend;
        mv
    }

    #[test]
    fn a_right_angle_under_a_tolerance_is_passed_at_the_tolerance() {
        // X0→10 then Y0→10 with 0.05: the element passes (10, 0) at 0.05 (within 2 %).
        let a = line([0.0, 0.0], [10.0, 0.0], Some(Blend::Tolerance { contour: 0.05, ori: f64::INFINITY }));
        let b = line([10.0, 0.0], [10.0, 10.0], None);
        let r = round_corner(&a, &b, 10.0, &metric(), &limits()).expect("rounded");
        let c = r.corner.path.curve.as_ref().unwrap();
        let cut = c.distance_to(&a.path.end);
        assert!(cut <= 0.05 && cut > 0.049, "cut {cut}");
        // Symmetric cut-back, the shortened blocks meet the element exactly.
        let d = 10.0 - r.first.path.end[0];
        assert!((r.second.path.start[1] - d).abs() < 1e-12 && d > 0.0 && d < 3.6);
        assert_eq!(r.first.path.end, r.corner.path.start);
        assert_eq!(r.second.path.start, r.corner.path.end);
    }

    #[test]
    fn adis_is_the_cut_back_distance_reduced_to_36_percent_of_short_blocks() {
        let a = line([0.0, 0.0], [10.0, 0.0], Some(Blend::Distance(0.5)));
        let b = line([10.0, 0.0], [10.0, 10.0], None);
        let r = round_corner(&a, &b, 10.0, &metric(), &limits()).unwrap();
        assert!((r.first.path.end[0] - 9.5).abs() < 1e-12);
        // The second block is 1 mm long: at most 0.36 mm of it.
        let b = line([10.0, 0.0], [10.0, 1.0], None);
        let r = round_corner(&a, &b, 10.0, &metric(), &limits()).unwrap();
        assert!((r.first.path.end[0] - 9.64).abs() < 1e-12, "{}", r.first.path.end[0]);
    }

    #[test]
    fn collinear_blocks_and_exact_stop_get_no_rounding() {
        let a = line([0.0, 0.0], [10.0, 0.0], Some(Blend::Tolerance { contour: 0.05, ori: f64::INFINITY }));
        assert!(round_corner(&a, &line([10.0, 0.0], [20.0, 0.0], None), 10.0, &metric(), &limits()).is_none());
        let mut stop = a.clone();
        stop.exact_stop = true;
        assert!(round_corner(&stop, &line([10.0, 0.0], [10.0, 5.0], None), 10.0, &metric(), &limits()).is_none());
    }

    #[test]
    fn a_corner_from_a_line_into_an_arc_is_rounded_within_the_tolerance_on_the_arc() {
        // X0→10, then clockwise half circle about (5, 0) from (10, 0) to (0, 0): it leaves
        // (10, 0) heading −Y, a 90° corner. With 0.03 the element passes the corner within
        // 2 % below the tolerance (the search iterates: an arc's cut is not proportional to
        // d), and its end lies on the circle.
        let a = line([0.0, 0.0], [10.0, 0.0], Some(Blend::Tolerance { contour: 0.03, ori: f64::INFINITY }));
        let (mut s, mut e) = ([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]);
        (s[0], e[0]) = (10.0, 0.0);
        let arc = crate::motion::Arc::in_plane(0, 1, 5.0, 0.0, -std::f64::consts::PI);
        let path = Path { start: s, end: e, arc: Some(Box::new(arc)), ori: None, curve: None };
        let b = Move::new(path, 5.0 * std::f64::consts::PI, Feed::Path(50.0), &limits(), false, 2);
        let r = round_corner(&a, &b, 10.0, &metric(), &limits()).expect("rounded");
        let cut = r.corner.path.curve.as_ref().unwrap().distance_to(&a.path.end);
        assert!((0.98 * 0.03 * 0.999..=0.03).contains(&cut), "cut {cut}");
        let q = r.second.path.start;
        assert!((((q[0] - 5.0).powi(2) + q[1] * q[1]).sqrt() - 5.0).abs() < 1e-9, "{:?}", &q[..2]);
        assert!(q[1] < 0.0);
    }

    #[test]
    fn the_element_limits_its_speed_by_its_curvature() {
        // Tolerance 0.01 at 90°: a tight element; v²·|p''| stays within its share of 2000 mm/s².
        let a = line([0.0, 0.0], [10.0, 0.0], Some(Blend::Tolerance { contour: 0.01, ori: f64::INFINITY }));
        let b = line([10.0, 0.0], [10.0, 10.0], None);
        let r = round_corner(&a, &b, 10.0, &metric(), &limits()).unwrap();
        let (_, second) = r.corner.path.curve.as_ref().unwrap().rates();
        let v = r.corner.v_max;
        assert!(v < 50.0 && v * v * second[0] <= 2000.0 * CENTRIPETAL * 1.0001, "v {v}");
    }
}

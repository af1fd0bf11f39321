//! ORISON, smoothing of the orientation characteristic (Function Manual F2 3.9.4,
//! Programming Manual "Smoothing the orientation characteristic (ORISON, ORISOF)"): a 5-axis
//! CAM program whose tool tip runs smoothly but whose orientation changes in steps from block
//! to block (a kink of the orientation at every block end) gets an orientation that turns
//! smoothly across the block ends, never farther than SD42678 `$SC_ORISON_TOL` (degrees)
//! from the programmed one and over at most SD42680 `$SC_ORISON_DIST` of path. The tool tip
//! keeps its programmed path: only the orientation along it changes.
//!
//! How it is modelled (the manuals name the limits, not the method):
//! - Every block end between two smoothable blocks (both under ORISON, vector-interpolated as
//!   a great circle, no longer than MD20178 `$MC_ORISON_BLOCK_PATH_LIMIT`, no exact stop in
//!   between) gets a zone of `r` mm of path on each side, `2r` at most SD42680 and `r` at most
//!   half of either block (so zones never overlap). Across the zone the orientation is the
//!   direction of a quintic with the programmed orientation and its first and second
//!   derivative per mm at both zone ends (the same form as the corner rounding's orientation,
//!   `blend_ori.rs`): position, angular rate and angular acceleration go on without a jump
//!   where it starts and ends, and it is one polynomial across the block end.
//! - The deviation is the angle between the tool vectors at the same point of the tip path
//!   (the same path parameter), sampled at 65 points of the zone; where it passes the
//!   tolerance the zone is made shorter (the deviation shrinks with it) until it keeps it.
//! - A block end without a kink, a rapid, spline, compressed (COMPON ...) or orientation-
//!   only block, an orientation interpolated through the rotary axes (ORIAXES) or on a cone,
//!   and a block longer than MD20178 leave the orientation as programmed there.
//! - The blocks a zone reaches are the two at the block end: MD28590 `$MC_MM_ORISON_BLOCKS`
//!   only enables the function (memory for at least 4 blocks, as the manual asks).

use super::blend_ori::hermite_bend;
use super::ori_curve::TwoCurves;
use super::orientation::{OriPath, SmoothEnds, Vec3, angle, cross, dot, norm};
use super::planner::Move;

/// The limits ORISON smooths within, read at block preparation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OriSmoothing {
    /// SD42678 ORISON_TOL in radians: the largest angle from the programmed orientation.
    pub tol: f64,
    /// SD42680 ORISON_DIST (mm): the longest path one zone spans.
    pub dist: f64,
    /// MD20178 ORISON_BLOCK_PATH_LIMIT (mm): longer blocks are not smoothed.
    pub block_limit: f64,
}

/// The smoothing zone at the end between two blocks.
#[derive(Debug, Clone, PartialEq)]
pub struct Zone {
    /// The orientation across the zone, parameter 0..=1 over its `2·half` mm of path.
    pub curve: TwoCurves,
    /// The path (mm) the zone reaches into each block.
    pub half: f64,
    /// The largest sampled angle (radians) from the programmed orientation.
    pub deviation: f64,
}

/// Samples of a zone checked against the tolerance (an even count: the block end is one).
const SAMPLES: u32 = 64;

/// True if `mv` is a block ORISON smooths at its ends (see the module doc).
pub fn smoothable(mv: &Move) -> bool {
    let Some(spec) = mv.orison.as_deref() else { return false };
    mv.axis_tangents.is_some()
        && mv.compress.is_none()
        && !mv.machine_space
        && !mv.is_rapid()
        && mv.path.curve.is_none()
        && mv.length > 0.0
        && mv.length <= spec.block_limit
        && mv.path.ori.as_deref().is_some_and(|o| {
            o.curve.is_none()
                && o.turn.is_none()
                && o.ends.as_ref().is_none_or(|e| e.tail.is_none())
                && dot(o.axis, o.start).abs() < 1e-9
        })
}

/// The zone at the end between `a` and the next move `b` (see the module doc), or `None`
/// where the orientation stays as programmed.
pub fn zone(a: &Move, b: &Move) -> Option<Zone> {
    let spec = a.orison.as_deref().copied()?;
    let limits_allow = spec.tol > 0.0 && spec.dist > 0.0;
    if a.exact_stop || !limits_allow || !smoothable(a) || !smoothable(b) {
        return None;
    }
    let (oa, ob) = (a.path.ori.as_deref()?, b.path.ori.as_deref()?);
    let (la, lb) = (a.length, b.length);
    if angle(oa.programmed_at(1.0), ob.programmed_at(0.0)) > 1e-9 {
        return None;
    }
    // The kink: the jump of the orientation's rate per mm at the block end.
    let (ra, rb) = (rate(oa, 1.0, la), rate(ob, 0.0, lb));
    if norm(std::array::from_fn(|i| ra[i] - rb[i])) < 1e-9 {
        return None;
    }
    let head = oa.ends.as_ref().and_then(|e| e.head.as_ref()).map_or(0.0, |(h, _)| *h);
    let mut half = (0.5 * la).min(0.5 * lb).min(0.5 * spec.dist).min((1.0 - head) * la);
    let limit = spec.tol * (1.0 - 1e-3);
    while half > 1e-6 {
        let curve = across(oa, ob, la, lb, half);
        let deviation = deviation(&curve, oa, ob, la, lb, half);
        if deviation <= limit {
            return Some(Zone { curve, half, deviation });
        }
        // The deviation grows about linearly with the zone's length.
        half *= (0.95 * limit / deviation).clamp(0.05, 0.95);
    }
    None
}

/// Puts `zone` on the ends it smooths: the tail of `a`'s orientation, the head of `b`'s.
pub fn apply(zone: &Zone, a: &mut Move, b: &mut Move) {
    let (la, lb) = (a.length, b.length);
    if let Some(o) = a.path.ori.as_deref_mut() {
        let ends = o.ends.get_or_insert_with(Box::default);
        ends.tail = Some((1.0 - zone.half / la, zone.curve.slice(0.0, 0.5)));
    }
    if let Some(o) = b.path.ori.as_deref_mut() {
        let ends: &mut SmoothEnds = o.ends.get_or_insert_with(Box::default);
        ends.head = Some((zone.half / lb, zone.curve.slice(0.5, 1.0)));
    }
}

/// The zone's orientation: the quintic from `oa` at `half` mm before its end to `ob` at
/// `half` mm after its start, with both great circles' derivatives per unit of the zone.
fn across(oa: &OriPath, ob: &OriPath, la: f64, lb: f64, half: f64) -> TwoCurves {
    let side = |o: &OriPath, u: f64, l: f64| -> (Vec3, Vec3, Vec3) {
        // The great circle: o' = θ·k × o, o'' = −θ²·o (k ⟂ o), per unit of the block's
        // parameter; the zone's parameter runs 2·half/l times faster.
        let p = o.programmed_at(u);
        let s = 2.0 * half / l;
        let d = cross(o.axis, p).map(|x| x * o.angle * s);
        let dd = p.map(|x| -x * (o.angle * s).powi(2));
        (p, d, dd)
    };
    let (start, end) = (side(oa, 1.0 - half / la, la), side(ob, half / lb, lb));
    let bend = hermite_bend([start, end]);
    TwoCurves { tip: [[0.0; 3]; 2], upper: [start.0, end.0], bend }
}

/// The largest angle between `curve` and the programmed orientation at the same path point.
fn deviation(curve: &TwoCurves, oa: &OriPath, ob: &OriPath, la: f64, lb: f64, half: f64) -> f64 {
    (1..SAMPLES)
        .map(|i| {
            let w = f64::from(i) / f64::from(SAMPLES);
            let s = 2.0 * half * w;
            let programmed =
                if s <= half { oa.programmed_at(1.0 - (half - s) / la) } else { ob.programmed_at((s - half) / lb) };
            angle(curve.at(w), programmed)
        })
        .fold(0.0, f64::max)
}

/// The orientation's rate per mm of a great circle `o` at `u` (`l` the block's length).
fn rate(o: &OriPath, u: f64, l: f64) -> Vec3 {
    cross(o.axis, o.programmed_at(u)).map(|x| x * o.angle / l)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine_data::registry::MAX_CHANNEL_AXES;
    use crate::motion::path::Path;
    use crate::motion::planner::{AxisLimit, Feed};

    /// The tool tilted 20° towards +X, turned by `theta` degrees towards −Y on the great
    /// circle through it perpendicular to k = (cos 20°, 0, −sin 20°):
    /// o(θ) = (cos θ·sin 20°, −sin θ, cos θ·cos 20°).
    fn o(theta: f64) -> Vec3 {
        let (s, c) = theta.to_radians().sin_cos();
        let (s20, c20) = 20f64.to_radians().sin_cos();
        [c * s20, -s, c * c20]
    }

    /// A 1 mm line along X from `x` whose orientation turns from θ0 to θ1 (degrees).
    fn block(x: f64, theta0: f64, theta1: f64, tol_deg: f64, dist: f64) -> Move {
        let (mut s, mut e) = ([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]);
        (s[0], e[0]) = (x, x + 1.0);
        let mut path = Path::line(s, e);
        path.ori = OriPath::great_circle(o(theta0), o(theta1)).unwrap().map(Box::new);
        let lim = vec![AxisLimit { max_velocity: 200.0, max_accel: 2000.0, accel_overload: 1.2 }; 6];
        let mut mv = Move::new(path, 1.0, Feed::Path(10.0), &lim, false, 1);
        mv.axis_tangents = Some(Box::new(([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES])));
        mv.orison = Some(Box::new(OriSmoothing { tol: tol_deg.to_radians(), dist, block_limit: 50.0 }));
        mv
    }

    /// The signed angle θ of a unit vector on that great circle.
    fn theta(v: Vec3) -> f64 {
        let (s20, c20) = 20f64.to_radians().sin_cos();
        (-v[1]).atan2(v[0] * s20 + v[2] * c20).to_degrees()
    }

    #[test]
    fn a_zigzag_kink_is_rounded_to_the_hermite_value_by_hand() {
        // −2° → +2° → −2° over 1 mm blocks: 4°/mm up, then down. The zone spans 0.5 mm each
        // side (half the blocks), from θ = 0 at rate +4° per zone unit (1 mm) to θ = 0 at −4°,
        // no angular acceleration on a great circle: θ(w) = 4·(w − 2w³ + w⁴) (the quintic
        // Hermite basis of the two rates). At the block end θ(½) = 4·(½ − ¼ + 1/16) = 1.25°
        // against the programmed 2°: 0.75° apart, the largest deviation (4·(2w³ − w⁴) grows
        // on 0..½). Vector quintic and angle differ by O(θ³): 1e-3° at most here.
        let (mut a, mut b) = (block(0.0, -2.0, 2.0, 1.0, 5.0), block(1.0, 2.0, -2.0, 1.0, 5.0));
        let z = zone(&a, &b).expect("a kink to smooth");
        assert!((z.half - 0.5).abs() < 1e-12, "{}", z.half);
        assert!((z.deviation.to_degrees() - 0.75).abs() < 1e-3, "{}", z.deviation.to_degrees());
        apply(&z, &mut a, &mut b);
        let (oa, ob) = (a.path.ori.as_ref().unwrap(), b.path.ori.as_ref().unwrap());
        assert!((theta(oa.at(1.0)) - 1.25).abs() < 1e-3 && angle(oa.at(1.0), ob.at(0.0)) < 1e-12);
        // Before the zone (u < ½) the orientation is the programmed one.
        assert!(angle(oa.at(0.25), o(-1.0)) < 1e-12);
        // The rate per mm is the same on both sides of the block end (zero: the top).
        let h = 1e-6;
        let (left, right) =
            ((theta(oa.at(1.0)) - theta(oa.at(1.0 - h))) / h, (theta(ob.at(h)) - theta(ob.at(0.0))) / h);
        assert!(left.abs() < 1e-3 && right.abs() < 1e-3, "{left} {right}");
        // Where the zone meets the programmed circle the rate is 4°/mm from both sides.
        let at_seam = (theta(oa.at(0.5 + h)) - theta(oa.at(0.5))) / h;
        assert!((at_seam - 4.0).abs() < 1e-3, "{at_seam}");
    }

    #[test]
    fn a_tighter_tolerance_shortens_the_zone() {
        // The deviation grows linearly with the zone: 0.75° for a half of 0.5 mm, 1.5°/mm.
        // With 0.5° the half is at most 0.5/1.5 = 1/3 mm, and the deviation within 0.5°.
        let (a, b) = (block(0.0, -2.0, 2.0, 0.5, 5.0), block(1.0, 2.0, -2.0, 0.5, 5.0));
        let z = zone(&a, &b).unwrap();
        assert!(z.half <= 1.0 / 3.0 + 1e-9 && z.half > 0.25, "{}", z.half);
        assert!(z.deviation.to_degrees() <= 0.5 && z.deviation.to_degrees() > 0.4, "{}", z.deviation.to_degrees());
        // SD42680 0.4 mm: a zone of 0.2 mm each side, deviation 1.5·0.2 = 0.3°.
        let (a, b) = (block(0.0, -2.0, 2.0, 1.0, 0.4), block(1.0, 2.0, -2.0, 1.0, 0.4));
        let z = zone(&a, &b).unwrap();
        assert!((z.half - 0.2).abs() < 1e-12 && (z.deviation.to_degrees() - 0.3).abs() < 1e-3);
    }

    #[test]
    fn no_kink_no_tolerance_or_a_long_block_leave_the_orientation() {
        let (a, b) = (block(0.0, -2.0, 2.0, 1.0, 5.0), block(1.0, 2.0, 6.0, 1.0, 5.0));
        assert_eq!(zone(&a, &b), None);
        let (a, b) = (block(0.0, -2.0, 2.0, 0.0, 5.0), block(1.0, 2.0, -2.0, 0.0, 5.0));
        assert_eq!(zone(&a, &b), None);
        let (mut a, b) = (block(0.0, -2.0, 2.0, 1.0, 5.0), block(1.0, 2.0, -2.0, 1.0, 5.0));
        a.orison.as_mut().unwrap().block_limit = 0.5;
        assert_eq!(zone(&a, &b), None);
    }
}

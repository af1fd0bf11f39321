//! The compressor under a kinematic transformation (Function Manual F2 "Orientation
//! compression", B1 "Compressor functions"): a 5-axis CAM program's short G1 blocks, the tool
//! tip and the orientation programmed in every block, become one smooth curve in the BCS.
//!
//! The tool tip is compressed as without a transformation (`compress.rs`: a quintic per block,
//! through the programmed points, tangent and curvature from the circle through three of them,
//! within the contour tolerance). What the manual adds for the orientation:
//! - rotary axis positions (`A= C=`, ORIAXES: no great circle) become "axial polynomials for
//!   the rotary axes": their slots are part of the same quintic, with the slope and change of
//!   the parabola through the three programmed positions over the tip's path length, each
//!   axis within the orientation tolerance of its programmed (linear) motion;
//! - direction vectors (A3/B3/C3, A2/B2/C2 under ORIVECT/ORIWKS: the great circle) become a
//!   quintic through the programmed vectors (the same parabola per component), whose direction
//!   is the orientation (an [`OriPath`] of [`TwoCurves`] with a bent upper curve), within the
//!   orientation tolerance of the programmed great circle at the same point of the tip chord.
//!
//! Not compressed, as the manual says: cones (ORICONxx), ORICURVE, ORIPATH's turning frame,
//! rapid traverse and arcs. A curve that would leave a tolerance stays the programmed block.
//! The tolerances: the contour `CTOL`/`ATOL`/MD33100 of the geometry axes, the orientation
//! `OTOL` else the rotary axes' MD33100 (in degrees; [`Compress::ori`]). The caller plans the
//! curve for the machine axes (`channel/smoothing/compress_trafo.rs`), so every machine axis keeps its
//! velocity and acceleration limits on it.

use super::compress::{self, Junction};
use super::ori_curve::TwoCurves;
use super::orientation::{OriPath, Vec3, angle, cross, dot};
use super::path::AxisVec;
use super::planner::{AxisLimit, Move};
use crate::machine_data::registry::MAX_CHANNEL_AXES;

/// True if the transformed move `mv` can be part of a compressed section; `metric` marks the
/// geometry axes (the tool tip), whose chord must be the move's length (the feed's).
pub fn compressible(mv: &Move, metric: &AxisVec) -> bool {
    mv.compress.is_some_and(|c| mv.length <= c.block_limit)
        && mv.axis_tangents.is_some()
        && mv.path.arc.is_none()
        && mv.path.curve.is_none()
        && mv.path.ori.as_ref().is_none_or(|o| great_circle(o))
        && !mv.machine_space
        && !mv.is_rapid()
        && mv.length > 0.0
        && (tip_chord(mv, metric) - mv.length).abs() <= 1e-9 * mv.length
}

/// A plain great circle (ORIVECT, ORIPLANE): no curve, no turning frame, the rotation axis
/// perpendicular to the start (a cone's is not).
fn great_circle(o: &OriPath) -> bool {
    o.curve.is_none() && o.turn.is_none() && o.kinks.is_empty() && dot(o.axis, o.start).abs() < 1e-9
}

/// The tool tip's chord length of `mv`.
fn tip_chord(mv: &Move, metric: &AxisVec) -> f64 {
    (0..MAX_CHANNEL_AXES).map(|k| metric[k] * (mv.path.end[k] - mv.path.start[k]).powi(2)).sum::<f64>().sqrt()
}

/// The smooth passage through the point between the transformed moves `a` and `b` (see the
/// module doc), if both are compressible, `a` is no exact stop, their feeds agree within
/// MD20172, both orient the same way (vectors or axes) and the tip's directions differ by at
/// most [`compress::MAX_ANGLE_DEG`].
pub fn junction(a: &Move, b: &Move, metric: &AxisVec) -> Option<Junction> {
    let spec = a.compress?;
    if a.exact_stop
        || !compressible(a, metric)
        || !compressible(b, metric)
        || (a.feed - b.feed).abs() > spec.velo_tol
        || a.path.ori.is_some() != b.path.ori.is_some()
    {
        return None;
    }
    let mut j = compress::passage(a, b, metric)?;
    let (la, lb) = (a.length, b.length);
    // The axes outside the tip: the parabola through the three positions over path length.
    for k in (0..MAX_CHANNEL_AXES).filter(|&k| metric[k] == 0.0) {
        let (d, dd) = parabola(a.path.start[k], a.path.end[k], b.path.end[k], la, lb);
        (j.tangent[k], j.curvature[k]) = (d, dd);
    }
    if let (Some(oa), Some(ob)) = (&a.path.ori, &b.path.ori) {
        let (o0, o1, o2) = (oa.at(0.0), oa.at(1.0), ob.at(1.0));
        if (0..3).any(|i| (ob.at(0.0)[i] - o1[i]).abs() > 1e-9) {
            return None;
        }
        let fit: [(f64, f64); 3] = std::array::from_fn(|i| parabola(o0[i], o1[i], o2[i], la, lb));
        j.ori = Some([o1, fit.map(|f| f.0), fit.map(|f| f.1)]);
    }
    Some(j)
}

/// Slope and second derivative at the middle point of the parabola through `(−la, qa)`,
/// `(0, qb)`, `(lb, qc)`.
fn parabola(qa: f64, qb: f64, qc: f64, la: f64, lb: f64) -> (f64, f64) {
    let (sa, sb) = ((qb - qa) / la, (qc - qb) / lb);
    ((sa * lb + sb * la) / (la + lb), 2.0 * (sb - sa) / (la + lb))
}

/// The transformed move `mv` as a curve with the passages `start` and `end` (`None`: the
/// chord's own direction, no curvature), or `None` if neither is given or the tip, a rotary
/// axis or the orientation would leave its tolerance. The result is planned in the BCS only:
/// the caller plans it for the machine axes.
pub fn smooth(
    mv: &Move,
    start: Option<&Junction>,
    end: Option<&Junction>,
    metric: &AxisVec,
    limits: &[AxisLimit],
) -> Option<Move> {
    let spec = mv.compress?;
    let mut curve = compress::quintic(mv, start, end, metric)?;
    let (p0, p1) = (mv.path.start, mv.path.end);
    let chord2 = tip_chord(mv, metric).powi(2);
    let ori = mv.path.ori.as_deref().map(|o| orientation_quintic(o, start, end, mv.length));
    let tol = spec.ori.to_radians();
    let mut p = p0;
    for i in 1..16 {
        let w = f64::from(i) / 16.0;
        curve.eval(w, &mut p);
        // The point of the tip chord the sample lies at: the programmed orientation there.
        let along = (0..MAX_CHANNEL_AXES).map(|k| metric[k] * (p[k] - p0[k]) * (p1[k] - p0[k])).sum::<f64>();
        let t = (along / chord2).clamp(0.0, 1.0);
        match (&ori, mv.path.ori.as_deref()) {
            (Some(q), Some(o)) => {
                if angle(q.at(w), o.at(t)) > tol {
                    return None;
                }
            }
            _ => {
                let off = (0..MAX_CHANNEL_AXES)
                    .filter(|&k| metric[k] == 0.0)
                    .map(|k| (p[k] - (p0[k] + t * (p1[k] - p0[k]))).abs())
                    .fold(0.0, f64::max);
                if off > spec.ori {
                    return None;
                }
            }
        }
    }
    curve.finish();
    let mut out = compress::smoothed_move(mv, curve, limits);
    out.path.ori = ori.map(Box::new);
    out.axis_tangents = mv.axis_tangents.clone();
    Some(out)
}

/// The orientation of a compressed block: the quintic through the programmed end vectors
/// with the passages' derivatives (per unit of path length, `l` the block's), or the great
/// circle's own where a side has none; its direction is the orientation.
fn orientation_quintic(o: &OriPath, start: Option<&Junction>, end: Option<&Junction>, l: f64) -> OriPath {
    let side = |j: Option<&Junction>, u: f64| -> [Vec3; 3] {
        match j.and_then(|j| j.ori) {
            Some([p, d, dd]) => [p, d.map(|x| x * l), dd.map(|x| x * l * l)],
            None => {
                // The great circle: o' = θ·k × o, o'' = −θ²·o (k ⟂ o).
                let p = o.at(u);
                let c = cross(o.axis, p);
                [p, c.map(|x| x * o.angle), p.map(|x| -x * o.angle * o.angle)]
            }
        }
    };
    let ([p0, v0, a0], [p1, v1, a1]) = (side(start, 0.0), side(end, 1.0));
    let bend = super::blend_ori::hermite_bend([(p0, v0, a0), (p1, v1, a1)]);
    OriPath::two_curves(TwoCurves { tip: [[0.0; 3]; 2], upper: [p0, p1], bend })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::compress::Compress;
    use crate::motion::compress::tests::{lim as limits, metric};
    use crate::motion::path::Path;
    use crate::motion::planner::Feed;

    /// The chord between the 2° points `i` and `i + 1` of a circle of radius 50 in X/Y, the
    /// tool tilted 20° outwards (vector) or the C slot (4) turning with the point (axes).
    fn chord(i: i32, vector: bool) -> Move {
        let at = |i: i32| f64::from(2 * i).to_radians();
        let (mut s, mut e) = ([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]);
        (s[0], s[1], e[0], e[1]) =
            (50.0 * at(i).cos(), 50.0 * at(i).sin(), 50.0 * at(i + 1).cos(), 50.0 * at(i + 1).sin());
        let mut path = Path::line(s, e);
        if vector {
            let o = |a: f64| {
                [20f64.to_radians().sin() * a.cos(), 20f64.to_radians().sin() * a.sin(), 20f64.to_radians().cos()]
            };
            path.ori = OriPath::great_circle(o(at(i)), o(at(i + 1))).unwrap().map(Box::new);
        } else {
            (path.start[4], path.end[4]) = (at(i).to_degrees(), at(i + 1).to_degrees());
        }
        let len = 100.0 * 1f64.to_radians().sin();
        let mut mv = Move::new(path, len, Feed::Path(50.0), &limits(), false, 1);
        mv.axis_tangents = Some(Box::new(([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES])));
        mv.compress = Some(Compress { tol: 0.01, block_limit: 20.0, velo_tol: 1000.0, ori: 0.1 });
        mv
    }

    #[test]
    fn a_rotary_axis_turning_evenly_with_the_tip_stays_on_its_line() {
        // C turns 2° per 2° chord: the parabola through three positions is the line, slope
        // 2°/(100·sin 1°) per mm, no curvature; the curve's C follows the tip's angle.
        let (a, b, c) = (chord(0, false), chord(1, false), chord(2, false));
        let (j0, j1) = (junction(&a, &b, &metric()).unwrap(), junction(&b, &c, &metric()).unwrap());
        assert!((j0.tangent[4] - 2.0 / (100.0 * 1f64.to_radians().sin())).abs() < 1e-12);
        assert!(j0.curvature[4].abs() < 1e-9);
        let mv = smooth(&b, Some(&j0), Some(&j1), &metric(), &limits()).expect("compressed");
        let mut p = [0.0; MAX_CHANNEL_AXES];
        for i in 0..=8 {
            mv.path.at(f64::from(i) / 8.0, &mut p);
            let angle = p[1].atan2(p[0]).to_degrees();
            assert!((p[4] - angle).abs() < 2e-3, "C {} at the tip's angle {angle}", p[4]);
        }
    }

    #[test]
    fn the_orientation_quintic_stays_within_otol_of_the_great_circles() {
        // The tool tilted 20° outwards turns 2° about Z per chord; the great circle between two
        // such orientations sags towards Z by at most about (sin 20°·1°)²/2 rad: the quintic
        // through the programmed vectors passes them and stays within 0.1° of the programmed
        // orientation, and meets its neighbour's with the same direction.
        let (a, b, c) = (chord(0, true), chord(1, true), chord(2, true));
        let (j0, j1) = (junction(&a, &b, &metric()).unwrap(), junction(&b, &c, &metric()).unwrap());
        let mv = smooth(&b, Some(&j0), Some(&j1), &metric(), &limits()).expect("compressed");
        let o = mv.path.ori.as_ref().unwrap();
        let prog = b.path.ori.as_ref().unwrap();
        assert!(angle(o.at(0.0), prog.at(0.0)) < 1e-12 && angle(o.at(1.0), prog.at(1.0)) < 1e-12);
        for i in 0..=8 {
            let u = f64::from(i) / 8.0;
            assert!(angle(o.at(u), prog.at(u)).to_degrees() < 0.1);
        }
        let next = smooth(&c, Some(&j1), None, &metric(), &limits()).expect("compressed");
        let (e, s) = (o.end_direction().unwrap(), next.path.ori.as_ref().unwrap().at(0.0));
        assert!(angle(o.at(1.0), s) < 1e-12);
        // The next block leaves in the direction this one arrives (d/du of its start).
        let n = next.path.ori.as_ref().unwrap();
        let h = 1e-6;
        let d: Vec3 = std::array::from_fn(|k| (n.at(h)[k] - n.at(0.0)[k]) / h);
        let dn = dot(d, d).sqrt();
        assert!(angle(e, d.map(|x| x / dn)) < 1e-3, "{e:?} vs {d:?}");
    }
}

//! The compressor (COMPON, COMPCURV, COMPCAD, COMPSURF; Function Manual B1 "Compressor"):
//! consecutive short linear blocks of a CAM polyline become one smooth curve, so the path
//! speed need not drop at every chord's corner.
//!
//! Model: every compressible block (a line no longer than MD20170, with a feed within
//! MD20172 of its predecessor's) becomes a quintic from its start to its end point. At a
//! point shared by two compressible blocks whose directions differ by at most
//! [`MAX_ANGLE_DEG`], the tangent and curvature are those of the circle through the point and
//! its two neighbours: both quintics meeting there have the same tangent and curvature, so
//! the path is curvature-continuous through the polyline and passes through every programmed
//! point. A quintic that would leave its chord by more than the tolerance stays the
//! programmed line. The four compressor words select the same curve here.

use super::blend::{dot, unit};
use super::curve::Curve;
use super::path::{AxisVec, Path};
use super::planner::{AxisLimit, Feed, Move};
use crate::machine_data::registry::MAX_CHANNEL_AXES;

/// The compressor's limits for the moves of one block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Compress {
    /// How far the curve may leave a programmed chord (MD33100 or CTOL).
    pub tol: f64,
    /// MD20170 COMPRESS_BLOCK_PATH_LIMIT: longer blocks are not compressed.
    pub block_limit: f64,
    /// MD20172 COMPRESS_VELO_TOL in units per second: a larger feed change ends a section.
    pub velo_tol: f64,
    /// Under an orientation transformation: how far the orientation may leave the programmed
    /// one, in degrees (`OTOL`, else the rotary axes' MD33100): the tool vector's angle, or
    /// each rotary axis' position where the rotary axes interpolate (`compress_ori.rs`).
    pub ori: f64,
}

/// Blocks meeting at a larger angle keep their corner (the section ends there). The value
/// of SD42470 CRIT_SPLINE_ANGLE's default; the manual leaves the compressor's own limit open.
pub const MAX_ANGLE_DEG: f64 = 36.0;

/// The tangent and curvature the path takes through a programmed point (per unit of the
/// feed's length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Junction {
    pub point: AxisVec,
    pub tangent: AxisVec,
    pub curvature: AxisVec,
    /// A vector-interpolated orientation: its value and its first and second derivative
    /// per unit of path length there (`compress_ori.rs`).
    pub ori: Option<[super::orientation::Vec3; 3]>,
}

/// True if `mv` can be part of a compressed section.
pub fn compressible(mv: &Move) -> bool {
    mv.compress.is_some_and(|c| mv.length <= c.block_limit)
        && mv.path.arc.is_none()
        && mv.path.curve.is_none()
        && mv.path.ori.is_none()
        && !mv.machine_space
        && mv.axis_tangents.is_none()
        && !mv.is_rapid()
        && mv.length > 0.0
}

/// The smooth passage through the point between `a` and `b`, if both are compressible, not
/// an exact stop, their feeds agree and their directions differ by at most
/// [`MAX_ANGLE_DEG`]: tangent and curvature of the circle through `a`'s start, the point and
/// `b`'s end.
pub fn junction(a: &Move, b: &Move, metric: &AxisVec) -> Option<Junction> {
    let spec = a.compress?;
    if a.exact_stop || !compressible(a) || !compressible(b) || (a.feed - b.feed).abs() > spec.velo_tol {
        return None;
    }
    passage(a, b, metric)
}

/// The geometry of [`junction`], without its checks: the passage through the point between
/// `a` and `b` on the circle through `a`'s start, that point and `b`'s end, if the directions
/// differ by at most [`MAX_ANGLE_DEG`].
pub fn passage(a: &Move, b: &Move, metric: &AxisVec) -> Option<Junction> {
    let (pa, pb, pc) = (&a.path.start, &a.path.end, &b.path.end);
    let u: AxisVec = std::array::from_fn(|k| pa[k] - pb[k]);
    let w: AxisVec = std::array::from_fn(|k| pc[k] - pb[k]);
    let (uu, ww, uw) = (dot(&u, &u, metric), dot(&w, &w, metric), dot(&u, &w, metric));
    if uu <= 0.0 || ww <= 0.0 {
        return None;
    }
    // The directions a → b and b → c: cos of the angle between −u and w.
    let cos = -uw / (uu * ww).sqrt();
    if cos < MAX_ANGLE_DEG.to_radians().cos() {
        return None;
    }
    // The centre O = b + α·u + β·w: (O − b)·u = |u|²/2, (O − b)·w = |w|²/2.
    let det = uu * ww - uw * uw;
    let chord: AxisVec = std::array::from_fn(|k| (pc[k] - pa[k]) / (a.length + b.length));
    let (tangent, curvature) = if det <= 1e-12 * uu * ww {
        (unit(&chord, metric)?, [0.0; MAX_CHANNEL_AXES])
    } else {
        let alpha = 0.5 * (uu * ww - ww * uw) / det;
        let beta = 0.5 * (ww * uu - uu * uw) / det;
        let r: AxisVec = std::array::from_fn(|k| alpha * u[k] + beta * w[k]);
        let rr = dot(&r, &r, metric);
        // The tangent: the chord a → c without its part along the radius.
        let along = dot(&chord, &r, metric) / rr;
        let t: AxisVec = std::array::from_fn(|k| chord[k] - along * r[k]);
        (unit(&t, metric)?, r.map(|x| x / rr))
    };
    Some(Junction { point: *pb, tangent, curvature, ori: None })
}

/// `mv` as a quintic with the passages `start` and `end` (`None`: the chord's own direction,
/// no curvature), or `None` if neither is given or the curve would leave the chord by more
/// than the tolerance.
pub fn smooth(
    mv: &Move,
    start: Option<&Junction>,
    end: Option<&Junction>,
    metric: &AxisVec,
    limits: &[AxisLimit],
) -> Option<Move> {
    // Finished in its shared place: a curve is ≈ 1.3 KB, and each pass by value copies it.
    let mut curve = std::sync::Arc::new(quintic(mv, start, end, metric)?);
    std::sync::Arc::get_mut(&mut curve).expect("a curve just made is not shared").finish();
    Some(shared_smoothed_move(mv, curve, limits))
}

/// The quintic of [`smooth`], without its length table; `None` as there.
pub fn quintic(mv: &Move, start: Option<&Junction>, end: Option<&Junction>, metric: &AxisVec) -> Option<Curve> {
    let spec = mv.compress?;
    if start.is_none() && end.is_none() {
        return None;
    }
    let (p0, p1) = (&mv.path.start, &mv.path.end);
    let dir: AxisVec = std::array::from_fn(|k| (p1[k] - p0[k]) / mv.length);
    let l = mv.length;
    let zero = [0.0; MAX_CHANNEL_AXES];
    let side = |j: Option<&Junction>| match j {
        Some(j) => (j.tangent.map(|x| x * l), j.curvature.map(|x| x * l * l)),
        None => (dir.map(|x| x * l), zero),
    };
    let ((v0, a0), (v1, a1)) = (side(start), side(end));
    let curve = Curve::hermite_untabled([(*p0, v0, a0), (*p1, v1, a1)], *metric);
    // The largest distance from the chord, at 15 inner points: one axis at a time over all
    // the points. Only the feed's moving axes add to the sums (the others add zeros).
    let chord_len2 = dot(&dir, &dir, metric) * l * l;
    let ts: [f64; 15] = std::array::from_fn(|i| (i + 1) as f64 / 16.0);
    let feed_axes = || curve.axes().iter().copied().filter(|&k| metric[k] != 0.0);
    let mut along = [-0.0; 15];
    for k in feed_axes() {
        for (a, p) in along.iter_mut().zip(curve.eval_row(k, &ts)) {
            *a += (p - p0[k]) * dir[k] * metric[k];
        }
    }
    let t = along.map(|a| (a * l / chord_len2).clamp(0.0, 1.0));
    let mut off2 = [-0.0; 15];
    for k in feed_axes() {
        let p = curve.eval_row(k, &ts);
        for i in 0..15 {
            let off = p[i] - p0[k] - t[i] * (p1[k] - p0[k]);
            off2[i] += off * off * metric[k];
        }
    }
    if off2.iter().any(|&o| o.sqrt() > spec.tol) {
        return None;
    }
    Some(curve)
}

/// `mv` running `curve` (finished) instead of its chord, at its feed.
pub fn smoothed_move(mv: &Move, curve: Curve, limits: &[AxisLimit]) -> Move {
    shared_smoothed_move(mv, std::sync::Arc::new(curve), limits)
}

/// [`smoothed_move`] with the curve already in its shared place.
fn shared_smoothed_move(mv: &Move, curve: std::sync::Arc<Curve>, limits: &[AxisLimit]) -> Move {
    let length = curve.length();
    let mut out = Move::unlimited(
        Path { start: mv.path.start, end: mv.path.end, arc: None, ori: None, curve: Some(curve) },
        mv.exact_stop,
        mv.tag,
    );
    out.set_limits(length, Feed::Path(mv.feed), limits);
    out.blend = mv.blend;
    out.compress = mv.compress;
    out
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    pub(in crate::motion) fn lim() -> Vec<AxisLimit> {
        vec![AxisLimit { max_velocity: 500.0, max_accel: 3000.0, accel_overload: 1.2 }; 3]
    }

    pub(in crate::motion) fn metric() -> AxisVec {
        let mut m = [0.0; MAX_CHANNEL_AXES];
        m[..3].fill(1.0);
        m
    }

    fn chord(a: [f64; 2], b: [f64; 2]) -> Move {
        let (mut s, mut e) = ([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]);
        (s[0], s[1], e[0], e[1]) = (a[0], a[1], b[0], b[1]);
        let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
        let mut mv = Move::new(Path::line(s, e), len, Feed::Path(50.0), &lim(), false, 1);
        mv.compress = Some(Compress { tol: 0.01, block_limit: 20.0, velo_tol: 1000.0, ori: 1.0 });
        mv
    }

    /// Points on a circle of radius 50 about the origin, every 2°.
    fn on_circle(i: i32) -> [f64; 2] {
        let a = f64::from(i * 2).to_radians();
        [50.0 * a.cos(), 50.0 * a.sin()]
    }

    #[test]
    fn chords_of_a_circle_meet_with_the_circles_tangent_and_curvature() {
        // Three points of the circle: the passage through the middle one has the circle's
        // tangent (perpendicular to the radius) and curvature 1/50 towards the centre.
        let (a, b) = (chord(on_circle(0), on_circle(1)), chord(on_circle(1), on_circle(2)));
        let j = junction(&a, &b, &metric()).unwrap();
        let n = on_circle(1);
        let t_dot_r = j.tangent[0] * n[0] + j.tangent[1] * n[1];
        assert!(t_dot_r.abs() < 1e-9, "tangent {:?}", &j.tangent[..2]);
        let k = (j.curvature[0].powi(2) + j.curvature[1].powi(2)).sqrt();
        assert!((k - 0.02).abs() < 1e-9 && j.curvature[0] * n[0] < 0.0, "curvature {:?}", &j.curvature[..2]);
        // The quintic through the chord stays within its sag of 50·(1 − cos 1°) ≈ 7.6 µm.
        let start = junction(&chord(on_circle(-1), on_circle(0)), &a, &metric()).unwrap();
        let curve = smooth(&a, Some(&start), Some(&j), &metric(), &lim()).unwrap();
        let mut p = [0.0; MAX_CHANNEL_AXES];
        for i in 0..=20 {
            curve.path.at(f64::from(i) / 20.0, &mut p);
            let r = (p[0] * p[0] + p[1] * p[1]).sqrt();
            assert!((r - 50.0).abs() < 1e-6, "radius {r} at {i}");
        }
    }

    #[test]
    fn a_sharp_corner_or_a_long_block_ends_the_section() {
        let a = chord([0.0, 0.0], [1.0, 0.0]);
        assert!(junction(&a, &chord([1.0, 0.0], [1.5, 0.5]), &metric()).is_none(), "45° is a corner");
        assert!(junction(&a, &chord([1.0, 0.0], [30.0, 1.0]), &metric()).is_none(), "29 mm is too long");
        assert!(junction(&a, &chord([1.0, 0.0], [2.0, 0.2]), &metric()).is_some());
    }
}

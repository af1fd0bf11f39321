//! RND and RNDM where a circle meets the corner, without tool radius compensation (issue 25,
//! RND at arcs): line-arc, arc-line and arc-arc corners are rounded by a circle of the given
//! radius tangent to both elements on the side the path turns to (Programming Manual,
//! "Chamfer, rounding": RND inserts a tangential circle between line/circle contours in any
//! combination; RNDM does so modally until RNDM=0). Expected points are worked out here from
//! the circle and line equations, not read from the engine.

use crate::trc_support;

use nctwin_engine::Status;
use trc_support::{alarm_of, passes_near, run_all};

type P = (f64, f64);

/// A piece of the expected path: a segment, or the short arc about a centre between two
/// points on its circle.
enum Piece {
    Seg(P, P),
    Arc(P, P, P),
}

fn cross(a: P, b: P) -> f64 {
    a.0 * b.1 - a.1 * b.0
}

/// Distance of `q` from the piece (infinite off an arc's angular range).
fn dist(q: P, piece: &Piece) -> f64 {
    match *piece {
        Piece::Seg(a, b) => trc_support::seg_dist(q, a, b),
        Piece::Arc(c, a, b) => {
            let (u, v, w) = ((a.0 - c.0, a.1 - c.1), (b.0 - c.0, b.1 - c.1), (q.0 - c.0, q.1 - c.1));
            let s = cross(u, v).signum();
            if cross(u, w) * s < -1e-9 || cross(w, v) * s < -1e-9 {
                return f64::INFINITY;
            }
            (w.0.hypot(w.1) - u.0.hypot(u.1)).abs()
        }
    }
}

/// Every sample of the tool centre lies on one of the pieces (to 1e-6 mm), and each arc piece
/// is travelled (a sample within 1e-6 of it away from its ends).
fn follows(samples: &[Vec<f64>], pieces: &[Piece]) {
    for p in samples {
        let q = (p[0], p[1]);
        let d = pieces.iter().map(|piece| dist(q, piece)).fold(f64::INFINITY, f64::min);
        assert!(d < 1e-6, "sample {q:?} is {d} off the expected path");
    }
    for piece in pieces {
        if let Piece::Arc(c, a, b) = *piece {
            let mid = ((a.0 + b.0) / 2.0 - c.0, (a.1 + b.1) / 2.0 - c.1);
            let r = (a.0 - c.0).hypot(a.1 - c.1);
            let m = (c.0 + r * mid.0 / mid.0.hypot(mid.1), c.1 + r * mid.1 / mid.0.hypot(mid.1));
            assert!(samples.iter().any(|p| (p[0] - m.0).hypot(p[1] - m.1) < 0.2), "arc about {c:?} travelled");
        }
    }
}

/// Line (0,0)→(30,0), then G2 to (50,0) about (40,0), radius 10, over the top: the arc starts
/// heading +Y, a left turn. The rounding circle (ρ = 3) lies left of both: 3 above the line and
/// outside the clockwise arc, 10 + 3 from (40,0): centre (40 − √(13² − 3²), 3) = (27.350889, 3).
/// It touches the line at (27.350889, 0) and the arc on the ray from (40,0) to its centre,
/// (40,0) + 10/13·(−√160, 3) = (30.269915, 2.307692).
#[test]
fn line_into_an_arc_is_rounded_tangent_to_both() {
    let (ch, samples) = run_all("G17 G90 G0 X0 Y0 Z0\nG1 X30 Y0 F1000 RND=3\nG2 X50 Y0 CR=10\nM30");
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let cx = 40.0 - 160f64.sqrt();
    let t2: (f64, f64) = (40.0 - 10.0 * 160f64.sqrt() / 13.0, 30.0 / 13.0);
    assert!((cx - 27.350889).abs() < 1e-6 && (t2.0 - 30.269915).abs() < 1e-6 && (t2.1 - 2.307692).abs() < 1e-6);
    // Line to the tangent point, the rounding, the programmed arc over the top (two short arcs).
    follows(
        &samples,
        &[
            Piece::Seg((0.0, 0.0), (cx, 0.0)),
            Piece::Arc((cx, 3.0), (cx, 0.0), t2),
            Piece::Arc((40.0, 0.0), t2, (40.0, 10.0)),
            Piece::Arc((40.0, 0.0), (40.0, 10.0), (50.0, 0.0)),
        ],
    );
    // The programmed corner is cut off: the tool never comes within 0.5 mm of it.
    assert!(!passes_near(&samples, 30.0, 0.0, 0.5));
    assert_eq!(&ch.axis_positions()[..2], &[50.0, 0.0]);
}

/// G3 from (0,0) to (20,0) about (10,0) through the bottom ends heading +Y; the line to (40,0)
/// heads +X: a right turn. The rounding circle (ρ = 2) lies right of both: 2 below the line and
/// outside the counter-clockwise arc, 12 from (10,0): centre (10 + √(12² − 2²), −2) =
/// (21.832160, −2); tangent points (21.832160, 0) on the line and (10,0) + 10/12·(√140, −2) =
/// (19.860133, −1.666667) on the arc.
#[test]
fn arc_into_a_line_is_rounded_tangent_to_both() {
    let (ch, samples) = run_all("G17 G90 G0 X0 Y0 Z0\nG3 X20 Y0 CR=10 F1000 RND=2\nG1 X40 Y0\nM30");
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let cx = 10.0 + 140f64.sqrt();
    let t1: (f64, f64) = (10.0 + 10.0 * 140f64.sqrt() / 12.0, -10.0 * 2.0 / 12.0);
    assert!((cx - 21.832160).abs() < 1e-6 && (t1.0 - 19.860133).abs() < 1e-6);
    follows(
        &samples,
        &[
            Piece::Arc((10.0, 0.0), (0.0, 0.0), (10.0, -10.0)),
            Piece::Arc((10.0, 0.0), (10.0, -10.0), t1),
            Piece::Arc((cx, -2.0), t1, (cx, 0.0)),
            Piece::Seg((cx, 0.0), (40.0, 0.0)),
        ],
    );
    // The rounding centre is 2.16 from the corner: the tool passes it 0.16 away, never closer.
    assert!(!passes_near(&samples, 20.0, 0.0, 0.15));
    assert_eq!(&ch.axis_positions()[..2], &[40.0, 0.0]);
}

/// G3 (0,0)→(20,0) about (10,0) as above, then G2 to (40,0) with I10 J−10: centre (30,−10),
/// radius √200, starting at 135° heading (1,1)/√2, a right turn of 45° from +Y. ρ = 2 on the
/// right: outside the first circle (radius 12 about (10,0)) and inside the second (radius
/// √200 − 2 about (30,−10)); the rounding centre is their intersection nearest (20,0), found
/// from the two circle equations: (21.966553, −0.895320). Tangent points on the rays from the
/// arcs' centres: (19.972128, −0.746100) and (20.643319, 0.604363).
#[test]
fn arc_into_an_arc_is_rounded_tangent_to_both() {
    let (ch, samples) = run_all("G17 G90 G0 X0 Y0 Z0\nG3 X20 Y0 CR=10 F1000 RND=2\nG2 X40 Y0 I10 J-10\nM30");
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let (c1, r1, c2, r2): ((f64, f64), f64, (f64, f64), f64) = ((10.0, 0.0), 12.0, (30.0, -10.0), 200f64.sqrt() - 2.0);
    let d = 500f64.sqrt();
    let a = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
    let h = (r1 * r1 - a * a).sqrt();
    let ex = ((c2.0 - c1.0) / d, (c2.1 - c1.1) / d);
    let p = (c1.0 + a * ex.0 - h * ex.1, c1.1 + a * ex.1 + h * ex.0);
    assert!((p.0 - 21.966553).abs() < 1e-6 && (p.1 + 0.895320).abs() < 1e-6, "{p:?}");
    let t1 = (c1.0 + 10.0 * (p.0 - c1.0) / r1, c1.1 + 10.0 * (p.1 - c1.1) / r1);
    let big = 200f64.sqrt();
    let t2 = (c2.0 + big * (p.0 - c2.0) / r2, c2.1 + big * (p.1 - c2.1) / r2);
    assert!((t1.0 - 19.972128).abs() < 1e-6 && (t2.1 - 0.604363).abs() < 1e-6, "{t1:?} {t2:?}");
    follows(
        &samples,
        &[
            Piece::Arc(c1, (0.0, 0.0), (10.0, -10.0)),
            Piece::Arc(c1, (10.0, -10.0), t1),
            Piece::Arc(p, t1, t2),
            Piece::Arc(c2, t2, (30.0, big - 10.0)),
            Piece::Arc(c2, (30.0, big - 10.0), (40.0, 0.0)),
        ],
    );
    // The rounding centre is 2.16 from the corner: the tool passes it 0.16 away, never closer.
    assert!(!passes_near(&samples, 20.0, 0.0, 0.15));
    assert_eq!(&ch.axis_positions()[..2], &[40.0, 0.0]);
}

/// The rounding must fit on both elements: after G3 (0,0)→(20,0) about (10,0) a line of 10 mm
/// to (30,0) cannot take RND=30, whose circle (centre 30 below the line, 40 from (10,0)) would
/// touch the line at x = 10 + √(40² − 30²) = 36.46, beyond its end. Alarm 12560 on the RND
/// block, before any motion of it.
#[test]
fn a_rounding_that_does_not_fit_an_arc_corner_is_an_alarm() {
    let (ch, samples) = run_all("G17 G90 G0 X0 Y0 Z0\nG3 X20 Y0 CR=10 F1000 RND=30\nG1 X30 Y0\nM30");
    assert_eq!(alarm_of(&ch), Some(12560), "{:?}", ch.alarms());
    assert_eq!(ch.alarms()[0].line, Some(2));
    assert!(samples.iter().all(|p| p[0].abs() < 1e-9 && p[1].abs() < 1e-9), "no motion of the arc");
}

/// RNDM=2 rounds every following corner (line-line here, leg 2 on each side of a right
/// angle) until RNDM=0: the corner at the end of the RNDM=0 block stays sharp.
#[test]
fn rndm_rounds_every_corner_until_switched_off() {
    let prog = "G17 G90 G0 X0 Y0 Z0\nG1 X30 Y0 F1000 RNDM=2\nG1 X30 Y20\nG1 X0 Y20 RNDM=0\nG1 X0 Y0\nM30";
    let (ch, samples) = run_all(prog);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    follows(
        &samples,
        &[
            Piece::Seg((0.0, 0.0), (28.0, 0.0)),
            Piece::Arc((28.0, 2.0), (28.0, 0.0), (30.0, 2.0)),
            Piece::Seg((30.0, 2.0), (30.0, 18.0)),
            Piece::Arc((28.0, 18.0), (30.0, 18.0), (28.0, 20.0)),
            Piece::Seg((28.0, 20.0), (0.0, 20.0)),
            Piece::Seg((0.0, 20.0), (0.0, 0.0)),
        ],
    );
    // The corner of the RNDM=0 block is sharp: the tool reaches (0, 20).
    assert!(passes_near(&samples, 0.0, 20.0, 1e-6));
    assert!(!passes_near(&samples, 30.0, 0.0, 0.5) && !passes_near(&samples, 30.0, 20.0, 0.5));
}

/// RNDM rounds arc corners too: the line-arc corner of the first test with RNDM=3.
#[test]
fn rndm_rounds_an_arc_corner() {
    let (ch, samples) = run_all("G17 G90 G0 X0 Y0 Z0\nG1 X30 Y0 F1000 RNDM=3\nG2 X50 Y0 CR=10\nM30");
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let cx = 40.0 - 160f64.sqrt();
    let t2 = (40.0 - 10.0 * 160f64.sqrt() / 13.0, 30.0 / 13.0);
    follows(
        &samples,
        &[
            Piece::Seg((0.0, 0.0), (cx, 0.0)),
            Piece::Arc((cx, 3.0), (cx, 0.0), t2),
            Piece::Arc((40.0, 0.0), t2, (40.0, 10.0)),
            Piece::Arc((40.0, 0.0), (40.0, 10.0), (50.0, 0.0)),
        ],
    );
}

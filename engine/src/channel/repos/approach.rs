//! REPOS approach shapes: how NC start travels back into the interrupted block.
//!
//! REPOSL/REPOSA (the default): a straight line from where the axes stand to the REPOS target.
//! REPOSQ: a quarter circle of radius DISR that ends tangentially in the path at the target;
//! REPOSH: a semicircle of diameter DISR, likewise (Programming Manual, "Repositioning at the
//! contour"). The axes first travel on a straight line to the start of the circle (every other
//! axis reaches its target value there), then along the circle.
//!
//! Convention (the manual draws the circle in the working plane; the main run does not know the
//! program's plane): the circle lies in the plane of the path tangent at the target and the
//! direction from the target towards where the axes stand, on that side. Where that plane is
//! undefined (the axes stand on the tangent line, no geometry axis moves at the target, the
//! interrupted move runs in machine axes, or the program was interrupted between blocks) the
//! approach is the straight line.

use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::{Arc, AxisVec, Path};

/// The approach shape of REPOS (G group 27 style: REPOSL, REPOSQ, REPOSH).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum ReposApproach {
    /// REPOSL (REPOSA): a straight line.
    #[default]
    Line,
    /// REPOSQ: a quarter circle with radius DISR (mm).
    QuarterCircle { radius: f64 },
    /// REPOSH: a semicircle with diameter DISR (mm).
    SemiCircle { diameter: f64 },
}

/// The circle of the approach into `target`, where the path runs on along `tangent` (axis
/// space); `None` for the straight line. Only the axes `geo` take part in the circle.
pub(in crate::channel) fn approach_arc(
    approach: ReposApproach,
    here: &AxisVec,
    target: &AxisVec,
    tangent: &AxisVec,
    geo: &[usize],
) -> Option<Path> {
    let (radius, sweep) = match approach {
        ReposApproach::Line => return None,
        ReposApproach::QuarterCircle { radius } => (radius, std::f64::consts::FRAC_PI_2),
        ReposApproach::SemiCircle { diameter } => (diameter / 2.0, std::f64::consts::PI),
    };
    let dot = |a: &AxisVec, b: &AxisVec| geo.iter().map(|&k| a[k] * b[k]).sum::<f64>();
    let mut t = [0.0; MAX_CHANNEL_AXES];
    geo.iter().for_each(|&k| t[k] = tangent[k]);
    let tn = dot(&t, &t).sqrt();
    if tn < 1e-9 || radius.is_nan() || radius <= 0.0 {
        return None;
    }
    t.iter_mut().for_each(|x| *x /= tn);
    // n: from the target towards the axes, without its component along the tangent.
    let mut n = [0.0; MAX_CHANNEL_AXES];
    geo.iter().for_each(|&k| n[k] = here[k] - target[k]);
    let along = dot(&n, &t);
    geo.iter().for_each(|&k| n[k] -= along * t[k]);
    let nn = dot(&n, &n).sqrt();
    if nn < 1e-9 {
        return None;
    }
    n.iter_mut().for_each(|x| *x /= nn);
    // Circle centre + r·(cos a·u + sin a·v) with u = −n, v = t: angle 0 is the target, where
    // the motion runs along t; the start lies `sweep` before it.
    let u: AxisVec = std::array::from_fn(|k| -n[k]);
    let centre: AxisVec = std::array::from_fn(|k| target[k] + radius * n[k]);
    let a0 = -sweep;
    // Outside the geometry axes u, t and n are 0: the other axes stand at their target.
    let start: AxisVec = std::array::from_fn(|k| centre[k] + radius * (a0.cos() * u[k] + a0.sin() * t[k]));
    Some(Path {
        start,
        end: *target,
        arc: Some(Box::new(Arc { u, v: t, radius, start_angle: a0, sweep })),
        ori: None,
        curve: None,
    })
}

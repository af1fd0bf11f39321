//! Where an orientation path comes closest to the pole of an orientation transformation.
//!
//! Beside the pole one rotary axis turns at a rate that grows like the inverse of the
//! distance, so the velocity planning (`plan::plan_piece`) must sample the path where that
//! distance is least, not only on its regular grid: a great circle passing 1° from the pole
//! between two grid points would otherwise hide most of the pole axis' rate.

/// Coarse grid of the search.
const GRID: usize = 32;

/// Closer than this (degrees) the path goes through the pole.
const THROUGH: f64 = 1e-4;

/// Beyond this angle (degrees) from the pole the rates stay moderate: no extra sample.
const NEAR: f64 = 15.0;

/// The path parameter in (0, 1) at which `angle(u)` (degrees from the pole) is least, refined
/// by golden-section search around the best grid point; `None` when the least angle lies at
/// an end of the path (the planning samples towards the ends anyway) or is not near the pole.
pub fn closest_to_pole(angle: impl Fn(f64) -> f64) -> Option<f64> {
    let at = |i: usize| i as f64 / GRID as f64;
    let best = (0..=GRID).min_by(|&a, &b| angle(at(a)).total_cmp(&angle(at(b))))?;
    let (mut lo, mut hi) = (at(best.saturating_sub(1)), at((best + 1).min(GRID)));
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut x1, mut x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
    let (mut f1, mut f2) = (angle(x1), angle(x2));
    for _ in 0..40 {
        if f1 < f2 {
            hi = x2;
            (x2, f2) = (x1, f1);
            x1 = hi - g * (hi - lo);
            f1 = angle(x1);
        } else {
            lo = x1;
            (x1, f1) = (x2, f2);
            x2 = lo + g * (hi - lo);
            f2 = angle(x2);
        }
    }
    let u = 0.5 * (lo + hi);
    // A path through the pole itself (a meridian, where the interpolation keeps the pole axis
    // still) has no peak rate of the pole axis there.
    let least = angle(u);
    (u > 1e-6 && u < 1.0 - 1e-6 && least < NEAR && least > THROUGH).then_some(u)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_closest_point_of_a_great_circle_past_the_pole() {
        // A tool vector tilted 1° off the X-Z plane sweeping from X−20° to X+20° about its own
        // circle: the angle to +Z is least (1°) in the middle, at u = 0.5.
        let angle = |u: f64| {
            let t = (-20.0 + 40.0 * u).to_radians();
            let o = [t.sin() * 1f64.to_radians().cos(), 1f64.to_radians().sin(), t.cos() * 1f64.to_radians().cos()];
            o[2].clamp(-1.0, 1.0).acos().to_degrees()
        };
        let u = closest_to_pole(angle).unwrap();
        assert!((u - 0.5).abs() < 1e-6, "{u}");
        // Least at an end, far from the pole, or through it: nothing to add.
        assert_eq!(closest_to_pole(|u| (u - 0.5).abs() * 40.0), None);
        assert_eq!(closest_to_pole(|u| 5.0 + u), None);
        assert_eq!(closest_to_pole(|u| 40.0 + (u - 0.5).abs()), None);
    }
}

//! The least of a distance along a parameter interval: the search the rounding and the
//! compressor use to measure how far an element strays from the programmed path.

/// The smallest `sq_dist(u)` for `u` in `[u0, u1]`, square-rooted: `samples + 1` evenly spaced
/// samples, then a golden-section search of `refinements` steps in the bracket around the
/// nearest one. Enough for short, gently curved elements whose squared distance has one
/// minimum near the sample found.
pub(super) fn least_distance(
    mut sq_dist: impl FnMut(f64) -> f64,
    (u0, u1): (f64, f64),
    samples: usize,
    refinements: usize,
) -> f64 {
    let h = (u1 - u0) / samples as f64;
    let (mut best, mut best_u) = (f64::INFINITY, u0);
    for i in 0..=samples {
        let u = u0 + h * i as f64;
        let d = sq_dist(u);
        if d < best {
            (best, best_u) = (d, u);
        }
    }
    let (mut lo, mut hi) = ((best_u - h).max(u0), (best_u + h).min(u1));
    const G: f64 = 0.618_033_988_749_894_8;
    let (mut m1, mut m2) = (hi - G * (hi - lo), lo + G * (hi - lo));
    let (mut f1, mut f2) = (sq_dist(m1), sq_dist(m2));
    for _ in 0..refinements {
        if f1 < f2 {
            (hi, m2, f2) = (m2, m1, f1);
            m1 = hi - G * (hi - lo);
            f1 = sq_dist(m1);
        } else {
            (lo, m1, f1) = (m1, m2, f2);
            m2 = lo + G * (hi - lo);
            f2 = sq_dist(m2);
        }
    }
    best.min(f1).min(f2).sqrt()
}

#[cfg(test)]
mod tests {
    use super::least_distance;

    #[test]
    fn the_distance_of_a_point_from_a_parabola_is_found_between_the_samples() {
        // The point (0.3, 1) from the line y = 0 for x in [0, 1]: 1 exactly, at x = 0.3, which
        // no sample of eight hits.
        let d = least_distance(|x| (x - 0.3).powi(2) + 1.0, (0.0, 1.0), 8, 24);
        assert!((d - 1.0).abs() < 1e-9, "{d}");
    }
}

//! DRIVE (G group 21): the knee-shaped acceleration characteristic of Function Manual B2.
//!
//! Above the switching speed `v_red` = MD35220 `ACCEL_REDUCTION_SPEED_POINT` · MD32000 an axis
//! accelerates with less than MD32300 `a_max`, down to `a_red` = (1 − MD35230
//! `ACCEL_REDUCTION_FACTOR`) · `a_max` at MD32000 `v_max`; MD35242 `ACCEL_REDUCTION_TYPE`
//! picks the shape between: 0 constant (`a_red` at once above `v_red`), 1 hyperbolic, 2 linear.
//! A path's characteristic is the lowest over the axes of their curves, each read at the
//! axis' share of the path speed ([`DriveCurve`]); the planner accelerates with it and brakes
//! within it (`motion/planner.rs`).
//!
//! Decision where B2 shows only a figure: the hyperbolic type is the hyperbola
//! `a = c₀ + c₁/v` through (`v_red`, `a_max`) and (`v_max`, `a_red`), the two key points B2
//! names for every type.

/// MD35242: the shape of the reduction above the switching speed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReductionKind {
    Constant,
    Hyperbolic,
    Linear,
}

impl ReductionKind {
    /// MD35242's value (0, 1, 2); `None` for others.
    pub fn from_md(v: i64) -> Option<ReductionKind> {
        match v {
            0 => Some(ReductionKind::Constant),
            1 => Some(ReductionKind::Hyperbolic),
            2 => Some(ReductionKind::Linear),
            _ => None,
        }
    }
}

/// One axis' characteristic in some speed unit (the axis' own, or the path's when scaled by
/// [`Knee::along`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Knee {
    pub kind: ReductionKind,
    /// The switching speed: full acceleration at and below it.
    pub v_red: f64,
    /// The maximum velocity, where the acceleration is down to `a_red`.
    pub v_max: f64,
    pub a_max: f64,
    pub a_red: f64,
}

impl Knee {
    /// True when the data reduce anything (B2: MD35220 = 1 or MD35230 = 0 reduce nothing).
    pub fn reduces(&self) -> bool {
        self.v_red < self.v_max && self.a_red < self.a_max
    }

    /// The characteristic as the path sees it when the axis moves `rate` per unit path length.
    pub fn along(&self, rate: f64) -> Knee {
        Knee {
            kind: self.kind,
            v_red: self.v_red / rate,
            v_max: self.v_max / rate,
            a_max: self.a_max / rate,
            a_red: self.a_red / rate,
        }
    }

    /// The acceleration allowed at speed `v`.
    pub fn accel_at(&self, v: f64) -> f64 {
        if v <= self.v_red {
            return self.a_max;
        }
        if v >= self.v_max {
            return self.a_red;
        }
        match self.kind {
            ReductionKind::Constant => self.a_red,
            ReductionKind::Linear => self.a_max - self.slope() * (v - self.v_red),
            ReductionKind::Hyperbolic => {
                let (c0, c1) = self.hyperbola();
                c0 + c1 / v
            }
        }
    }

    /// The speed after one cycle of acceleration from `v`: the `w` with `w = v + a(w)·dt`
    /// (the cycle's acceleration is the one allowed at the speed it ends at, the higher one).
    pub fn accelerate(&self, v: f64, dt: f64) -> f64 {
        let w = v + self.a_max * dt;
        if w <= self.v_red {
            return w;
        }
        let w = match self.kind {
            // Where `a` steps down at `v_red`, the cycle ends there if `a_red` does not reach it.
            ReductionKind::Constant => (v + self.a_red * dt).max(self.v_red),
            ReductionKind::Linear => {
                let k = self.slope();
                (v + (self.a_max + k * self.v_red) * dt) / (1.0 + k * dt)
            }
            ReductionKind::Hyperbolic => {
                let (c0, c1) = self.hyperbola();
                let p = v + c0 * dt;
                (p + (p * p + 4.0 * c1 * dt).sqrt()) / 2.0
            }
        };
        if w > self.v_max { v + self.a_red * dt } else { w }
    }

    fn slope(&self) -> f64 {
        (self.a_max - self.a_red) / (self.v_max - self.v_red)
    }

    /// `(c₀, c₁)` of `a = c₀ + c₁/v` through (`v_red`, `a_max`) and (`v_max`, `a_red`).
    fn hyperbola(&self) -> (f64, f64) {
        if self.v_red <= 0.0 {
            // Switching at standstill: `a_red` at every speed.
            return (self.a_red, 0.0);
        }
        let c1 = (self.a_max - self.a_red) / (1.0 / self.v_red - 1.0 / self.v_max);
        (self.a_max - c1 / self.v_red, c1)
    }
}

/// A move's characteristic under DRIVE: the lowest of its axes' [`Knee`]s, in path units.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DriveCurve {
    /// The path acceleration the axes allow without a reduction (the move's `a_max` before
    /// DRIVE lowered it).
    cap: f64,
    knees: Vec<Knee>,
}

impl DriveCurve {
    /// The curve of a line with path acceleration `cap` and the axes given as
    /// (characteristic, rate per unit path length); `None` when no moving axis reduces its
    /// acceleration.
    pub fn of(cap: f64, axes: impl IntoIterator<Item = (Knee, f64)>) -> Option<DriveCurve> {
        let knees: Vec<Knee> =
            axes.into_iter().filter(|(k, rate)| *rate > 1e-12 && k.reduces()).map(|(k, rate)| k.along(rate)).collect();
        (!knees.is_empty()).then_some(DriveCurve { cap, knees })
    }

    /// The path acceleration allowed at path speed `v`.
    pub fn accel_at(&self, v: f64) -> f64 {
        self.knees.iter().map(|k| k.accel_at(v)).fold(self.cap, f64::min)
    }

    /// The speed after one cycle of acceleration from `v` ([`Knee::accelerate`] of the
    /// lowest curve: `w − v − a(w)·dt` is the largest of the axes' and grows with `w`, so its
    /// root is the smallest of theirs).
    pub fn accelerate(&self, v: f64, dt: f64) -> f64 {
        self.knees.iter().map(|k| k.accelerate(v, dt)).fold(v + self.cap * dt, f64::min)
    }
}

impl DriveCurve {
    /// The speed below which the acceleration is constant (the lowest switching speed).
    fn knee_speed(&self) -> f64 {
        self.knees.iter().map(|k| k.v_red).fold(f64::INFINITY, f64::min)
    }

    /// The distance the path covers from speed `v` (this cycle's travel `v·dt` included) when
    /// it brakes to a stop as fast as the curve allows: each cycle loses `a(w)·dt` from its
    /// speed `w` (the acceleration of the higher speed, as [`DriveCurve::accelerate`] uses the
    /// reverse), and below the switching speed the exact discrete stop of BRISK
    /// (`planner::stop_speed`) with the constant acceleration there.
    pub fn stop_distance(&self, v: f64, dt: f64) -> f64 {
        let (v0, a0) = (self.knee_speed(), self.accel_at(0.0));
        let (mut d, mut w) = (0.0, v);
        while w > v0 {
            d += w * dt;
            w = (w - self.accel_at(w) * dt).max(0.0);
        }
        d + brisk_stop_distance(w, a0 * dt, dt)
    }

    /// The highest speed not above `v` from which the path stops within `distance`
    /// ([`DriveCurve::stop_distance`] is increasing in the speed, so bisection finds it;
    /// below the switching speed the closed form of BRISK).
    pub fn stop_speed(&self, v: f64, distance: f64, dt: f64) -> f64 {
        if self.stop_distance(v, dt) <= distance {
            return v;
        }
        let v0 = self.knee_speed();
        let low = super::planner::stop_speed(distance, self.accel_at(0.0), dt);
        if low <= v0 {
            return low.min(v);
        }
        let (mut lo, mut hi) = (v0, v);
        for _ in 0..64 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.stop_distance(mid, dt) <= distance {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        lo
    }
}

/// BRISK's stop from `v` losing `b` per cycle: `v, v − b, …, f·b, 0` covers
/// `dt·(n + 1)·(v − n·b/2)` with `n = ⌊v/b⌋`.
fn brisk_stop_distance(v: f64, b: f64, dt: f64) -> f64 {
    if v <= 0.0 {
        return 0.0;
    }
    let n = (v / b).floor();
    dt * (n + 1.0) * (v - n * b / 2.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn knee(kind: ReductionKind) -> Knee {
        Knee { kind, v_red: 200.0, v_max: 500.0, a_max: 3000.0, a_red: 1200.0 }
    }

    #[test]
    fn the_three_shapes_meet_the_key_points() {
        // Every shape: a_max up to v_red, a_red at v_max. Halfway (350 mm/s): constant 1200,
        // linear 3000 − 1800·150/300 = 2100, hyperbolic: c1 = 1800/(1/200 − 1/500) = 600 000,
        // c0 = 3000 − 3000 = 0, so 600 000/350 = 1714.29.
        for (kind, mid) in
            [(ReductionKind::Constant, 1200.0), (ReductionKind::Linear, 2100.0), (ReductionKind::Hyperbolic, 1714.2857)]
        {
            let k = knee(kind);
            assert_eq!(k.accel_at(150.0), 3000.0);
            assert_eq!(k.accel_at(200.0), 3000.0);
            assert!((k.accel_at(500.0) - 1200.0).abs() < 1e-9, "{kind:?}");
            assert!((k.accel_at(350.0) - mid).abs() < 1e-3, "{kind:?}: {}", k.accel_at(350.0));
        }
    }

    #[test]
    fn a_cycle_of_acceleration_ends_where_its_acceleration_is_allowed() {
        for kind in [ReductionKind::Constant, ReductionKind::Linear, ReductionKind::Hyperbolic] {
            let k = knee(kind);
            for i in 0..600 {
                let v = f64::from(i);
                let w = k.accelerate(v, 0.004);
                let a = (w - v) / 0.004;
                // The cycle's acceleration is the one allowed at its end speed (constant: at
                // most a_max while it only reaches v_red).
                let allowed = if kind == ReductionKind::Constant && w == 200.0 { 3000.0 } else { k.accel_at(w) };
                assert!(a <= allowed * (1.0 + 1e-9) && a >= k.a_red * (1.0 - 1e-9), "{kind:?} {v}: {a} vs {allowed}");
                if kind != ReductionKind::Constant || w != 200.0 {
                    assert!((a - allowed).abs() < 1e-6, "{kind:?} {v}: {a} vs {allowed}");
                }
            }
        }
    }

    #[test]
    fn along_a_diagonal_the_axis_curve_is_read_at_its_share() {
        // X moves 0.6 per mm of path: at path speed 500 X runs 300 (above its v_red 200):
        // linear 3000 − 6·100 = 2400 mm/s² on X, 4000 along the path.
        // Y moves 0.8 per mm with 3000 mm/s² and no reduction: 3750 along the path caps it.
        let c = DriveCurve::of(f64::INFINITY, [(knee(ReductionKind::Linear), 0.6)]).unwrap();
        assert!((c.accel_at(500.0) - 4000.0).abs() < 1e-9);
        assert_eq!(c.accel_at(300.0), 5000.0);
        let c = DriveCurve::of(3750.0, [(knee(ReductionKind::Linear), 0.6)]).unwrap();
        assert_eq!(c.accel_at(300.0), 3750.0);
        assert!((c.accel_at(500.0) - 3750.0).abs() < 1e-9);
        // At 600 X runs 360: 3000 − 6·160 = 2040 on X, 3400 along the path, below the cap.
        assert!((c.accel_at(600.0) - 3400.0).abs() < 1e-9);
        let none = Knee { a_red: 3000.0, ..knee(ReductionKind::Linear) };
        assert!(DriveCurve::of(3750.0, [(none, 1.0)]).is_none());
    }
}

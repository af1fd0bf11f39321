//! Geometry of one motion block in axis space: a straight line or a circular arc (helix) in a
//! plane of two axes, every other axis moving linearly along with it.

use crate::machine_data::registry::MAX_CHANNEL_AXES;

/// Positions of all channel axes (only the first `n` of a channel are used).
pub type AxisVec = [f64; MAX_CHANNEL_AXES];

/// An arc in the plane of axes `plane.0` (abscissa) and `plane.1` (ordinate).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arc {
    pub plane: (usize, usize),
    pub center: (f64, f64),
    pub radius: f64,
    /// Angle of the start point, radians, measured from the abscissa towards the ordinate.
    pub start_angle: f64,
    /// Signed sweep in radians: positive turns from the abscissa towards the ordinate.
    pub sweep: f64,
}

/// The geometric path of one block.
#[derive(Debug, Clone, PartialEq)]
pub struct Path {
    pub start: AxisVec,
    pub end: AxisVec,
    /// `None`: linear interpolation of every axis.
    pub arc: Option<Arc>,
}

impl Path {
    /// Position at parameter `u` in 0..=1 (uniform in path length).
    pub fn at(&self, u: f64, out: &mut AxisVec) {
        for (o, (s, e)) in out.iter_mut().zip(self.start.iter().zip(&self.end)) {
            *o = s + (e - s) * u;
        }
        if u >= 1.0 {
            *out = self.end;
            return;
        }
        if let Some(arc) = &self.arc {
            let a = arc.start_angle + arc.sweep * u;
            out[arc.plane.0] = arc.center.0 + arc.radius * a.cos();
            out[arc.plane.1] = arc.center.1 + arc.radius * a.sin();
        }
    }

    /// Tangent `dp/du` at `u` (not normalised).
    pub fn tangent(&self, u: f64) -> AxisVec {
        let mut t = [0.0; MAX_CHANNEL_AXES];
        for (i, ti) in t.iter_mut().enumerate() {
            *ti = self.end[i] - self.start[i];
        }
        if let Some(arc) = &self.arc {
            let a = arc.start_angle + arc.sweep * u;
            t[arc.plane.0] = -arc.radius * arc.sweep * a.sin();
            t[arc.plane.1] = arc.radius * arc.sweep * a.cos();
        }
        t
    }

    /// Upper bound of `|dp_i/du|` over the whole block, per axis.
    pub fn max_rate(&self) -> AxisVec {
        let mut r = [0.0; MAX_CHANNEL_AXES];
        for (i, ri) in r.iter_mut().enumerate() {
            *ri = (self.end[i] - self.start[i]).abs();
        }
        if let Some(arc) = &self.arc {
            let k = arc.radius * arc.sweep.abs();
            r[arc.plane.0] = k;
            r[arc.plane.1] = k;
        }
        r
    }

    /// The smallest and largest value each axis takes along the path.
    pub fn extent(&self) -> (AxisVec, AxisVec) {
        let mut lo = [0.0; MAX_CHANNEL_AXES];
        let mut hi = [0.0; MAX_CHANNEL_AXES];
        for i in 0..MAX_CHANNEL_AXES {
            lo[i] = self.start[i].min(self.end[i]);
            hi[i] = self.start[i].max(self.end[i]);
        }
        if let Some(arc) = &self.arc {
            // Quadrant points the arc passes through.
            let (a0, a1) = if arc.sweep >= 0.0 {
                (arc.start_angle, arc.start_angle + arc.sweep)
            } else {
                (arc.start_angle + arc.sweep, arc.start_angle)
            };
            let first = (a0 / std::f64::consts::FRAC_PI_2).ceil() as i64;
            let last = (a1 / std::f64::consts::FRAC_PI_2).floor() as i64;
            for q in first..=last.min(first + 4) {
                let a = q as f64 * std::f64::consts::FRAC_PI_2;
                let (x, y) = (arc.center.0 + arc.radius * a.cos(), arc.center.1 + arc.radius * a.sin());
                lo[arc.plane.0] = lo[arc.plane.0].min(x);
                hi[arc.plane.0] = hi[arc.plane.0].max(x);
                lo[arc.plane.1] = lo[arc.plane.1].min(y);
                hi[arc.plane.1] = hi[arc.plane.1].max(y);
            }
        }
        (lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn half_circle() -> Path {
        let mut start = [0.0; MAX_CHANNEL_AXES];
        let mut end = [0.0; MAX_CHANNEL_AXES];
        start[0] = 10.0;
        end[0] = -10.0;
        end[2] = 4.0;
        Path {
            start,
            end,
            arc: Some(Arc { plane: (0, 1), center: (0.0, 0.0), radius: 10.0, start_angle: 0.0, sweep: PI }),
        }
    }

    #[test]
    fn a_helix_lifts_linearly_while_turning() {
        let p = half_circle();
        let mut q = [0.0; MAX_CHANNEL_AXES];
        p.at(0.5, &mut q);
        assert!((q[0]).abs() < 1e-12 && (q[1] - 10.0).abs() < 1e-12 && (q[2] - 2.0).abs() < 1e-12);
    }

    #[test]
    fn the_extent_of_an_arc_includes_the_quadrant_points_it_crosses() {
        let (lo, hi) = half_circle().extent();
        assert_eq!((lo[1], hi[1]), (0.0, 10.0));
        assert_eq!((lo[0], hi[0]), (-10.0, 10.0));
    }
}

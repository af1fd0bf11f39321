//! The cutting part of a tool, from its cutting edge's data `$TC_DP1..25` (geometry plus wear).
//!
//! - Milling tools (types 100..199, and tools of other types on a mill): radius R = DP6 + DP15,
//!   corner radius r = DP7 + DP16 (the rounding radius of a bull nose), r = R for the ball end
//!   mills 110/111; r = 0 is a flat end mill. The lower surface over the tip at distance d from
//!   the axis is 0 for d <= R − r and r − sqrt(r² − (d − R + r)²) beyond.
//! - Drills (200..299 except 210 boring bar and 240..=249 taps, which cut flat): a cone of
//!   point angle σ, the lower surface d / tan(σ/2). σ is DP24 when it lies in 1..179°, else
//!   90° for the countersink 230 and 118° for the others (the twist drill's usual angle; the
//!   manuals at hand keep no tip angle in the edge data, so this is a decision).
//! - Turning tools (500..599): the nose circle of radius DP6 + DP15, its centre S placed from
//!   the theoretical tip P by the cutting edge position DP2 (`P − S = r·(sx, sx)` in the plane's
//!   abscissa Z and ordinate X, the table of `interp/compensation/cutting_edge.rs`). Positions
//!   1, 2 and 6 have the tip on the far side of the nose from the axis: internal tools (boring).
//!
//! The shank and the holder are taken as lying above the lower surface (milling), outside the
//! nose away from the spindle axis (external turning) or between the nose and the axis
//! (internal turning): everything the tool sweeps over on that side is removed.

use crate::machine_data::EdgeParams;

/// What kind of cutting part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    /// End mill, bull nose or ball nose: `corner` is the corner radius (0 ..= radius).
    Mill { corner: f64 },
    /// Drill with a conical point: `cot` = 1 / tan(σ/2) of the point angle σ.
    Drill { cot: f64 },
    /// Turning insert: the nose centre S = P + `centre` (in Z, X) from the theoretical tip P;
    /// `internal`: the tip points away from the spindle axis (positions 1, 2, 6: a boring bar,
    /// its holder towards the axis).
    Turning { centre: [f64; 2], internal: bool },
}

/// The cutting part of the active tool.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cutter {
    /// Tool radius (milling, drilling) or nose radius (turning), mm.
    pub radius: f64,
    pub kind: Kind,
}

impl Cutter {
    /// The cutter of the cutting edge with data `p` (see the module doc).
    pub fn from_edge(p: &EdgeParams) -> Cutter {
        let dp = |n: usize| p[n - 1];
        let tool_type = dp(1).round() as i64;
        let radius = (dp(6) + dp(15)).max(0.0);
        let kind = match tool_type {
            500..=599 => {
                // G18: the plane's abscissa is Z, its ordinate X.
                let (sz, sx) = crate::interp::edge_direction(dp(2));
                Kind::Turning { centre: [-radius * sz, -radius * sx], internal: sx > 0.0 }
            }
            200..=299 if tool_type != 210 && !(240..=249).contains(&tool_type) => {
                let given = dp(24);
                let angle = if (1.0..=179.0).contains(&given) {
                    given
                } else if tool_type == 230 {
                    90.0
                } else {
                    118.0
                };
                Kind::Drill { cot: 1.0 / (angle.to_radians() / 2.0).tan() }
            }
            110 | 111 => Kind::Mill { corner: radius },
            _ => Kind::Mill { corner: (dp(7) + dp(16)).clamp(0.0, radius) },
        };
        Cutter { radius, kind }
    }

    /// A flat end mill of radius `radius` (for tests and API calls).
    pub fn end_mill(radius: f64) -> Cutter {
        Cutter { radius, kind: Kind::Mill { corner: 0.0 } }
    }

    /// Height of the lower surface above the tip at distance `d` (<= radius) from the tool axis.
    #[inline]
    pub fn lower(&self, d: f64) -> f64 {
        match self.kind {
            Kind::Mill { corner } if corner > 0.0 => {
                let u = d - (self.radius - corner);
                if u <= 0.0 { 0.0 } else { corner - (corner * corner - u * u).max(0.0).sqrt() }
            }
            Kind::Drill { cot } => d * cot,
            _ => 0.0,
        }
    }

    /// The radius the lower surface reaches at height `h` above the tip (the inverse of
    /// [`Cutter::lower`]): the bore an axial tool leaves at that height.
    pub fn reach(&self, h: f64) -> f64 {
        if h < 0.0 {
            return 0.0;
        }
        match self.kind {
            Kind::Mill { corner } if corner > 0.0 && h < corner => {
                let u = corner - h;
                (self.radius - corner) + (corner * corner - u * u).max(0.0).sqrt()
            }
            Kind::Drill { cot } if cot > 0.0 => (h / cot).min(self.radius),
            _ => self.radius,
        }
    }

    /// True for a flat bottom (end mill without corner radius, turning: never).
    pub fn is_flat(&self) -> bool {
        matches!(self.kind, Kind::Mill { corner } if corner == 0.0)
    }
}

/// Edge data with `$TC_DPn` = v for each `(n, v)`, the rest 0 (for tests).
#[cfg(test)]
pub(crate) fn edge(values: &[(usize, f64)]) -> EdgeParams {
    let mut p = [0.0; crate::machine_data::tool_orient::EDGE_SLOTS];
    for &(n, v) in values {
        p[n - 1] = v;
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ball_end_mill_rises_by_its_radius_at_its_rim() {
        let c = Cutter::from_edge(&edge(&[(1, 110.0), (6, 5.0)]));
        assert_eq!(c.kind, Kind::Mill { corner: 5.0 });
        assert!((c.lower(5.0) - 5.0).abs() < 1e-12);
        // At d = 3: 5 − sqrt(25 − 9) = 1.
        assert!((c.lower(3.0) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_bull_nose_is_flat_inside_its_corner_and_wear_adds_to_the_radius() {
        let c = Cutter::from_edge(&edge(&[(1, 121.0), (6, 5.0), (15, 0.5), (7, 2.0)]));
        assert_eq!((c.radius, c.kind), (5.5, Kind::Mill { corner: 2.0 }));
        assert_eq!(c.lower(3.5), 0.0);
        assert!((c.lower(5.5) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn a_twist_drill_has_a_118_degree_point() {
        let c = Cutter::from_edge(&edge(&[(1, 200.0), (6, 4.0)]));
        // Cone height at the rim: 4 / tan 59° = 2.4034.
        assert!((c.lower(4.0) - 2.403_41).abs() < 1e-4);
    }

    #[test]
    fn the_external_turning_tool_has_its_nose_centre_above_and_right_of_the_tip() {
        // Position 3: P − S = r·(−1, −1) in (Z, X), so S = P + (r, r).
        let c = Cutter::from_edge(&edge(&[(1, 500.0), (2, 3.0), (6, 0.8)]));
        assert_eq!(c.kind, Kind::Turning { centre: [0.8, 0.8], internal: false });
        // Position 2: the tip above the centre, pointing away from the axis: a boring bar.
        let c = Cutter::from_edge(&edge(&[(1, 500.0), (2, 2.0), (6, 0.4)]));
        assert_eq!(c.kind, Kind::Turning { centre: [0.4, -0.4], internal: true });
    }
}

//! TRAANG (type 1024): an infeed axis that is not perpendicular to the longitudinal axis
//! (grinding machines); the program uses Cartesian X (infeed) and Z (longitudinal).
//!
//! Roles of `TRAFO_AXES_IN_n`: [0] inclined axis MU, [1] axis parallel to the longitudinal
//! direction MZ, [2] remaining axis (passes through). The Cartesian X lives in MU's channel
//! slot, Z in MZ's.
//!
//! Math (REFERENCE §5.3; α measured from +X towards +Z, the manual's "clockwise from X"):
//! `X = MU·cos α + Bx − Lx`, `Z = MZ + MU·sin α + Bz − Lz`; inverse
//! `MU = (X − Bx + Lx)/cos α`, `MZ = (Z − Bz + Lz) − MU·sin α`.

use super::{BuildError, SelectArgs, Transformation, Unreachable, Vec3, role_geo};
use crate::machine_data::{TrafoDataSet, TrafoParams};
use crate::motion::AxisVec;

#[derive(Debug, Clone, PartialEq)]
pub struct Traang {
    inclined: (usize, usize),
    parallel: (usize, usize),
    geo: [Option<usize>; 3],
    /// Angle α in degrees.
    pub angle: f64,
    sin: f64,
    cos: f64,
    base_tool: Vec3,
    /// Share of the parallel axis' dynamics left for the contour (1 − reserve).
    parallel_share: f64,
}

impl Traang {
    pub fn new(set: &TrafoDataSet, args: &SelectArgs) -> Result<Traang, BuildError> {
        let TrafoParams::Traang { angle, base_tool, velo_reserve, accel_reserve } = set.params else {
            unreachable!("a TRAANG data set has TRAANG parameters")
        };
        let angle = args.angle.unwrap_or(angle);
        // −90° < α < 90°, α ≠ 0 (Transformations FM, TRAANG_ANGLE).
        if !(angle.abs() < 90.0 && angle != 0.0) {
            return Err(BuildError::Value(format!("TRAANG angle {angle} (−90 < α < 90, α ≠ 0)")));
        }
        let (sin, cos) = angle.to_radians().sin_cos();
        let inclined = role_geo(set, 0).expect("checked at activation");
        let parallel = role_geo(set, 1).expect("checked at activation");
        Ok(Traang {
            inclined,
            parallel,
            geo: set.geo_axes,
            angle,
            sin,
            cos,
            base_tool,
            // A reserve of 0 means "computed by the NC"; this product then keeps none.
            parallel_share: 1.0 - velo_reserve.max(accel_reserve),
        })
    }

    /// For oblique plunging (G05/G07): the channel slots of Cartesian X (infeed) and Z
    /// (longitudinal) and tan α, the change of Z per unit of X along the inclined axis.
    pub fn plunge_axes(&self) -> (usize, usize, f64) {
        (self.inclined.0, self.parallel.0, self.sin / self.cos)
    }

    fn off(&self, tool: &Vec3, g: usize) -> f64 {
        self.base_tool[g] - tool[g]
    }
}

impl Transformation for Traang {
    fn name(&self) -> &'static str {
        "TRAANG"
    }

    fn trafo_type(&self) -> u32 {
        1024
    }

    fn geo_slots(&self) -> [Option<usize>; 3] {
        self.geo
    }

    fn machine_slots(&self) -> Vec<usize> {
        vec![self.inclined.0, self.parallel.0]
    }

    fn forward(&self, machine: &AxisVec, tool: &Vec3, bcs: &mut AxisVec) {
        let (mu, mz) = (machine[self.inclined.0], machine[self.parallel.0]);
        bcs[self.inclined.0] = mu * self.cos + self.off(tool, self.inclined.1);
        bcs[self.parallel.0] = mz + mu * self.sin + self.off(tool, self.parallel.1);
    }

    fn inverse(&self, bcs: &AxisVec, _prev: &AxisVec, tool: &Vec3, machine: &mut AxisVec) -> Result<(), Unreachable> {
        let mu = (bcs[self.inclined.0] - self.off(tool, self.inclined.1)) / self.cos;
        machine[self.inclined.0] = mu;
        machine[self.parallel.0] = bcs[self.parallel.0] - self.off(tool, self.parallel.1) - mu * self.sin;
        Ok(())
    }

    fn limit_share(&self, slot: usize) -> f64 {
        if slot == self.parallel.0 { self.parallel_share } else { 1.0 }
    }
}

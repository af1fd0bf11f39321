//! TRACYL (types 512, 513, 514): grooves on a cylinder surface, programmed on the unrolled
//! surface. BCS: X radial (infeed), Y the arc length on the working diameter d (it lives in the
//! rotary axis' channel slot), Z axial.
//!
//! Roles of `TRAFO_AXES_IN_n`: [0] linear axis radial to the rotary axis, [1] rotary axis,
//! [2] linear axis parallel to the rotary axis, [3] (513, 514) real Y axis perpendicular to both.
//!
//! Math (REFERENCE §4.4): `Y = (d/2)·φ + e`, `φ = s·(C − c0)` in radians, `X = Xm + Bx − Lx`,
//! `Z = Zm + Bz − Lz`, where `e = By − Ly (+ Ym for 513/514)` is the tangential offset of the tool.
//! The unrolled coordinate is linear in C, so C is continuous over any number of turns.
//! The groove-wall offset of 513/514 (radius compensation with `OFFN` = half the groove width)
//! is built by the radius compensation: the tool centre runs at `OFFN − tool radius` from the
//! programmed centre line, and the share of that offset along the periphery lives in the real Y
//! axis' slot, so the rotary axis follows the centre line and the walls stay parallel.

use super::{BuildError, RotaryRoles, SelectArgs, Transformation, Unreachable, Vec3};
use crate::machine_data::{TrafoDataSet, TrafoParams};
use crate::motion::AxisVec;

#[derive(Debug, Clone, PartialEq)]
pub struct Tracyl {
    trafo_type: u32,
    axes: RotaryRoles,
    /// Working radius d/2.
    radius: f64,
    rot_offset: f64,
    sign: f64,
    /// Groove-wall offset selected (513 always; 514 by TRACYL's 3rd parameter or the default mode).
    pub groove_wall: bool,
}

impl Tracyl {
    pub fn new(set: &TrafoDataSet, args: &SelectArgs) -> Result<Tracyl, BuildError> {
        let TrafoParams::Tracyl { rot_offset, sign_plus, base_tool, default_mode, .. } = set.params else {
            unreachable!("a TRACYL data set has TRACYL parameters")
        };
        let d = args.diameter.ok_or_else(|| BuildError::Value("TRACYL needs the working diameter".into()))?;
        // The manual: the working diameter must always be given and be larger than 1.
        if d <= 1.0 {
            return Err(BuildError::Value(format!("TRACYL working diameter {d} (must be > 1)")));
        }
        let groove_wall = match set.trafo_type {
            512 => false,
            513 => true,
            _ => args.groove_wall.unwrap_or(default_mode == 1),
        };
        Ok(Tracyl {
            trafo_type: set.trafo_type,
            axes: RotaryRoles::new(set, set.trafo_type != 512, base_tool),
            radius: d / 2.0,
            rot_offset,
            sign: if sign_plus { 1.0 } else { -1.0 },
            groove_wall,
        })
    }
}

impl Tracyl {
    /// The working diameter d of the selection: the unrolled Y is the arc length on it.
    pub fn diameter(&self) -> f64 {
        2.0 * self.radius
    }

    /// With the groove-wall offset selected: the channel slots of the unrolled peripheral
    /// coordinate and of the real Y axis that travels the offset along the periphery.
    pub fn groove_wall_axes(&self) -> Option<(usize, usize)> {
        self.axes.extra.filter(|_| self.groove_wall).map(|y| (self.axes.rotary.0, y))
    }
}

impl Transformation for Tracyl {
    fn name(&self) -> &'static str {
        "TRACYL"
    }

    fn trafo_type(&self) -> u32 {
        self.trafo_type
    }

    fn geo_slots(&self) -> [Option<usize>; 3] {
        self.axes.geo
    }

    fn machine_slots(&self) -> Vec<usize> {
        self.axes.machine_slots()
    }

    fn rotary_slot(&self) -> Option<usize> {
        Some(self.axes.rotary.0)
    }

    fn forward(&self, machine: &AxisVec, tool: &Vec3, bcs: &mut AxisVec) {
        let phi = (self.sign * (machine[self.axes.rotary.0] - self.rot_offset)).to_radians();
        bcs[self.axes.radial.0] = machine[self.axes.radial.0] + self.axes.off(tool, self.axes.radial.1);
        bcs[self.axes.rotary.0] = self.radius * phi + self.axes.side_offset(machine, tool);
        if let Some((k, g)) = self.axes.axial {
            bcs[k] = machine[k] + self.axes.off(tool, g);
        }
    }

    fn inverse(&self, bcs: &AxisVec, _prev: &AxisVec, tool: &Vec3, machine: &mut AxisVec) -> Result<(), Unreachable> {
        let y = bcs[self.axes.rotary.0] - self.axes.side_offset(bcs, tool);
        machine[self.axes.rotary.0] = self.rot_offset + self.sign * (y / self.radius).to_degrees();
        machine[self.axes.radial.0] = bcs[self.axes.radial.0] - self.axes.off(tool, self.axes.radial.1);
        if let Some((k, g)) = self.axes.axial {
            machine[k] = bcs[k] - self.axes.off(tool, g);
        }
        Ok(())
    }
}

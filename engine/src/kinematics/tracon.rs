//! TRACON (type 8192): two transformations one after the other. The BCS is the input of the
//! first member (TRANSMIT, TRACYL, TRAANG or TRAORI), whose machine-side output is the input of
//! the second, a TRAANG for an inclined machine axis (Transformations FM, chained
//! transformations). The tool belongs to the first member; the second works as if the tool had
//! no length. The geometry axes, the rotary axis, poles and orientation are the first member's;
//! the velocity reserve of the inclined axis is the second's.

use super::{AnyTrafo, Transformation, Unreachable, Vec3};
use crate::motion::{AxisVec, Path};

#[derive(Debug, Clone, PartialEq)]
pub struct Tracon {
    pub first: AnyTrafo,
    pub second: AnyTrafo,
}

const NO_TOOL: Vec3 = [0.0; 3];

impl Tracon {
    /// The position between the members (`$AA_ITR[.., 1]`) for machine position `machine`.
    pub fn intermediate(&self, machine: &AxisVec) -> AxisVec {
        let mut mid = *machine;
        self.second.forward(machine, &NO_TOOL, &mut mid);
        mid
    }
}

impl Transformation for Tracon {
    fn name(&self) -> &'static str {
        "TRACON"
    }

    fn trafo_type(&self) -> u32 {
        8192
    }

    fn geo_slots(&self) -> [Option<usize>; 3] {
        self.first.geo_slots()
    }

    fn machine_slots(&self) -> Vec<usize> {
        let mut slots = self.first.machine_slots();
        for k in self.second.machine_slots() {
            if !slots.contains(&k) {
                slots.push(k);
            }
        }
        slots
    }

    fn rotary_slot(&self) -> Option<usize> {
        self.first.rotary_slot()
    }

    // Each member writes only the slots it maps; the others pass through from its input, so
    // the output buffers start as the member's input.
    fn forward(&self, machine: &AxisVec, tool: &Vec3, bcs: &mut AxisVec) {
        let mid = self.intermediate(machine);
        *bcs = mid;
        self.first.forward(&mid, tool, bcs);
    }

    fn inverse(&self, bcs: &AxisVec, prev: &AxisVec, tool: &Vec3, machine: &mut AxisVec) -> Result<(), Unreachable> {
        let mut mid = *bcs;
        self.first.inverse(bcs, &self.intermediate(prev), tool, &mut mid)?;
        *machine = mid;
        self.second.inverse(&mid, prev, &NO_TOOL, machine)
    }

    fn check_path(&self, path: &Path, tool: &Vec3) -> Result<(), Unreachable> {
        self.first.check_path(path, tool)
    }

    fn poles(&self, path: &Path, tool: &Vec3) -> Vec<f64> {
        self.first.poles(path, tool)
    }

    fn on_excluded_pole_side(&self, machine: &AxisVec, tool: &Vec3) -> bool {
        self.first.on_excluded_pole_side(&self.intermediate(machine), tool)
    }

    fn critical_params(&self, path: &Path, tool: &Vec3) -> Vec<f64> {
        self.first.critical_params(path, tool)
    }

    fn limit_share(&self, slot: usize) -> f64 {
        self.first.limit_share(slot).min(self.second.limit_share(slot))
    }

    fn orientation_slots(&self) -> [Option<usize>; 3] {
        self.first.orientation_slots()
    }

    fn orientation(&self, machine: &AxisVec) -> Option<Vec3> {
        self.first.orientation(&self.intermediate(machine))
    }

    fn orientation_axes(&self, o: &Vec3, prev: &AxisVec, axes: &mut AxisVec) -> Result<(), Unreachable> {
        self.first.orientation_axes(o, &self.intermediate(prev), axes)
    }
}

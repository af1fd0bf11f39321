//! The 7th axis of the generic 7-axis transformation (F2 §3.7.6): a rotary axis that turns
//! the workpiece while the generic 5-/6-axis tool kinematics (type 24) moves the tool.
//!
//! The programmed tool tip and orientation are relative to the workpiece: the BCS is fixed to
//! the workpiece and coincides with the frame of the tool chain when the 7th axis stands at
//! `TRAFO7_EXT_ROT_AX_OFFSET`. Conventions of this product where the manual is silent: the
//! axis runs through the BCS zero point along `TRAFO7_EXT_AXIS1` and a positive motion turns
//! the workpiece right-handedly about that vector (as the table axes of the generic types 40
//! and 56 with the vector as entered; reverse it for a DIN table), so a workpiece point `p`
//! lies at `R(e7, pos − offset)·p` in the chain's frame.

use super::Vec3;
use super::orient::vec3::Rot;
use crate::motion::AxisVec;

/// The 7th axis as the transformation needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seventh {
    /// Channel axis (`TRAFO_AXES_IN_n[6]`).
    pub slot: usize,
    /// `TRAFO7_EXT_ROT_AX_OFFSET` (degrees).
    pub offset: f64,
    /// `TRAFO7_EXT_AXIS1` (unit).
    pub axis: Vec3,
}

impl Seventh {
    /// The rotation that carries workpiece coordinates into the chain's frame for the 7th
    /// axis position in `axes`.
    #[inline]
    pub fn rotation(&self, axes: &AxisVec) -> Rot {
        Rot::about(&self.axis, (axes[self.slot] - self.offset).to_radians())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quarter_turn_about_z_carries_x_onto_y() {
        let s = Seventh { slot: 0, offset: 10.0, axis: [0.0, 0.0, 1.0] };
        let mut axes: AxisVec = [0.0; crate::machine_data::registry::MAX_CHANNEL_AXES];
        axes[0] = 100.0;
        let v = s.rotation(&axes).apply(&[1.0, 0.0, 0.0]);
        assert!(v[0].abs() < 1e-15 && (v[1] - 1.0).abs() < 1e-15 && v[2].abs() < 1e-15, "{v:?}");
    }
}

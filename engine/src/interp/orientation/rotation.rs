//! The tool's rotation about its own axis on a generic 6-axis transformation: `THETA=` (the
//! angle of rotation, `THETA=IC(..)` incremental) and the G group of the rotation reference,
//! ORIROTA / ORIROTR / ORIROTT / ORIROTC (Transformations Function Manual F2 §3.11.2, G group
//! 54 of the Programming Manual).
//!
//! Conventions of this product where the manual is silent (named in the module so a reader
//! finds them):
//! * THETA is the right-handed angle about the tool orientation (tip → holder) from the
//!   reference direction to the rotation vector; the reference is projected perpendicular to
//!   the orientation.
//! * ORIROTA: reference = the basic rotation vector (`TRAFO6_BASE_ORIENT_NORMAL`, the tool
//!   normal in the zero position), under ORIWKS turned with the frame. ORIROTR: the normal of
//!   the plane of the start and end orientation (`o_start × o_end`). ORIROTT: the direction in
//!   which the orientation changes at the block end (tangent of the great circle). ORIROTC: the
//!   path tangent at the block end. Without an orientation change (ORIROTR/T) or without a path
//!   motion (ORIROTC) the ORIROTA reference is used.
//! * The rotation vector is reached at the block end; during the block the 3rd rotary axis
//!   moves linearly (the orientation itself is interpolated as G group 51 says).
//! * THETA is modal: under ORIROTC every motion block keeps the last THETA relative to its
//!   path tangent. Under ORIROTA/R/T a block without THETA leaves the 3rd rotary axis where it
//!   is (the tool keeps its rotation relative to the head).
//! * A direct position of the 3rd rotary axis while ORIROTC is active is alarm 14128 (the
//!   absolute programming of the tool rotation the manual refuses with ORIROTC).

use crate::alarm::{Alarm, Clear};
use crate::interp::Interpreter;
use crate::interp::frames::frame::Frame;
use crate::interp::orientation::words::OriReference;
use crate::kinematics::orient::rotation::{perpendicular, rotation_vector, theta_of};
use crate::kinematics::orient::vec3::{cross, normalize};
use crate::kinematics::{AnyTrafo, Transformation, Vec3};
use crate::motion::AxisVec;

/// G group 54: what THETA is measured from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RotReference {
    /// ORIROTA: an absolute direction (the basic rotation vector).
    Absolute,
    /// ORIROTR: the plane of the start and end orientation.
    Plane,
    /// ORIROTT: the change of the orientation vector.
    OriChange,
    /// ORIROTC: the path tangent.
    PathTangent,
}

impl RotReference {
    /// The G function of G group 54, if `name` is one.
    pub fn keyword(name: &str) -> Option<RotReference> {
        Some(match name {
            "ORIROTA" => RotReference::Absolute,
            "ORIROTR" => RotReference::Plane,
            "ORIROTT" => RotReference::OriChange,
            "ORIROTC" => RotReference::PathTangent,
            _ => return None,
        })
    }
}

/// 14128: absolute programming of the tool rotation while ORIROTC is active (number from
/// the Programming Manual's G group table, wording after the alarm list from memory).
fn absolute_with_orirotc(line: u32) -> Alarm {
    Alarm {
        number: 14128,
        message: format!("Channel 1 block {line} absolute programming of tool rotation with active ORIROTC"),
        line: Some(line),
        clear: Clear::Reset,
    }
}

/// The reference direction of `kind` at orientation `o` (BCS) of a block from `o_start` to
/// `o_end` with path tangent `tangent` (BCS), and `absolute` the ORIROTA reference.
fn reference(
    kind: RotReference,
    o: &Vec3,
    o_start: &Vec3,
    o_end: &Vec3,
    tangent: Option<Vec3>,
    absolute: &Vec3,
) -> Vec3 {
    let plane = normalize(&cross(o_start, o_end)).filter(|_| perpendicular(o_end, o_start).is_some());
    let own = match kind {
        RotReference::Absolute => None,
        RotReference::Plane => plane,
        RotReference::OriChange => plane.map(|n| cross(&n, o)),
        RotReference::PathTangent => tangent,
    };
    own.filter(|v| perpendicular(v, o).is_some()).unwrap_or(*absolute)
}

impl Interpreter {
    /// The tool rotation of a block under a 6-axis transformation: with `THETA=` (or under
    /// ORIROTC with a path motion) the three rotary axes of `end` are solved for the block's
    /// end orientation and the rotation vector THETA gives. Returns the THETA now in force.
    #[allow(clippy::too_many_arguments)]
    pub(in crate::interp) fn tool_rotation(
        &self,
        words: &crate::interp::modal::Words,
        frame: &Frame,
        start: &AxisVec,
        end: &mut AxisVec,
        tangent: Option<Vec3>,
        line: u32,
    ) -> Result<Option<f64>, Alarm> {
        let modal = self.modal.ori;
        let theta_word = words.ori.theta;
        let follows_path = modal.rotation == RotReference::PathTangent && tangent.is_some();
        let active = self.orientation_transformation();
        let third = active.and_then(|(a, _)| match &a.trafo {
            AnyTrafo::Traori(t) => t.third_slot(),
            _ => None,
        });
        let third_word = third.is_some_and(|k| words.axes.iter().any(|(j, ..)| *j == k));
        if modal.rotation == RotReference::PathTangent && third_word {
            return Err(absolute_with_orirotc(line));
        }
        if theta_word.is_none() && !follows_path {
            return Ok(None);
        }
        let Some((active, machine)) = active else {
            return Err(Alarm::value_out_of_range(line, "THETA needs an active orientation transformation"));
        };
        let (AnyTrafo::Traori(t), Some(_)) = (&active.trafo, third) else {
            if theta_word.is_none() {
                return Ok(None);
            }
            return Err(Alarm::value_out_of_range(
                line,
                "THETA needs a generic 6-axis transformation (a 3rd rotary axis TRAFO_AXES_IN[5])",
            ));
        };
        if third_word {
            return Err(Alarm::conflicting_functions(line, "THETA and a position of the 3rd rotary axis together"));
        }
        let at = |src: &AxisVec| {
            let mut m = *machine;
            for s in t.orientation_slots().iter().flatten().chain(&t.seventh_slot()) {
                m[*s] = src[*s];
            }
            m
        };
        let (m_start, m_end) = (at(start), at(end));
        let o_start = t.orientation(&m_start).unwrap_or([0.0, 0.0, 1.0]);
        let o_end = t.orientation(&m_end).unwrap_or([0.0, 0.0, 1.0]);
        let absolute = match modal.reference {
            OriReference::Workpiece => frame.rotate_direction(t.base_normal()),
            OriReference::Machine => t.base_normal(),
        };
        let tangent = tangent.map(|v| frame.rotate_direction(v));
        let ref_start = reference(modal.rotation, &o_start, &o_start, &o_end, tangent, &absolute);
        let ref_end = reference(modal.rotation, &o_end, &o_start, &o_end, tangent, &absolute);
        let theta_start = theta_of(&o_start, &ref_start, &t.rotation_vector(&m_start)).unwrap_or(0.0).to_degrees();
        let theta = match theta_word {
            Some((v, true)) => theta_start + v,
            Some((v, false)) => v,
            None => modal.theta,
        };
        let fail = || Alarm::value_out_of_range(line, "tool rotation THETA not reachable by the rotary axes");
        let r = rotation_vector(&o_end, &ref_end, theta.to_radians()).ok_or_else(fail)?;
        let mut out = *end;
        t.rotated_axes(&o_end, &r, &m_start, &mut out).map_err(|_| fail())?;
        // Only the rotary axes change; the tool tip (geometry slots) stays as programmed.
        for s in t.orientation_slots().iter().flatten() {
            end[*s] = out[*s];
        }
        Ok(Some(theta))
    }
}

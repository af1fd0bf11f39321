//! The tool orientation system variables (Transformations Function Manual F2 §3.9.5, "System
//! variable for tool orientation"), components 1..3 in the BCS:
//! * `$P_TOOLO[i]`, `$P_TOOLROT[i]`: orientation and (6-axis) rotation vector at the end of
//!   the last prepared block, read during preparation;
//! * `$AC_TOOLO_ACT[i]`, `$AC_TOOLO_END[i]`, `$AC_TOOLR_ACT[i]`, `$AC_TOOLR_END[i]`,
//!   `$VC_TOOLO[i]`, `$VC_TOOLR[i]`: main-run values. A block that reads them waits until the
//!   main run has caught up (the implicit preprocessing stop of
//!   [`crate::interp::eval::scope::is_main_run_variable`]), so the actual value, the end of the block in the
//!   main run and the value of the last prepared block are the same orientation there. With no
//!   following error in this model the servo value `$VC_` equals the setpoint. (`..._DIFF`,
//!   the angle between them, is not offered: at the stop it could only ever read 0.)
//!
//! Without an orientation transformation the tool points along the applicate of the working
//! plane (G17 +Z, G18 +Y, G19 +X); a rotation vector exists only on a 6-axis kinematics
//! (alarm otherwise, as for an unknown variable).

use crate::alarm::Alarm;
use crate::interp::eval::scope::SysView;
use crate::interp::eval::value::Value;
use crate::interp::modal::Plane;
use crate::kinematics::Vec3;

/// The value of orientation variable `name`, or `None` if `name` is not one of them.
pub(in crate::interp) fn read(sys: &SysView, name: &str, indices: &[Value], line: u32) -> Option<Result<Value, Alarm>> {
    let rotation = match name {
        "$P_TOOLO" | "$AC_TOOLO_ACT" | "$AC_TOOLO_END" | "$VC_TOOLO" => false,
        "$P_TOOLROT" | "$AC_TOOLR_ACT" | "$AC_TOOLR_END" | "$VC_TOOLR" => true,
        _ => return None,
    };
    Some(value(sys, name, rotation, indices, line))
}

fn value(sys: &SysView, name: &str, rotation: bool, indices: &[Value], line: u32) -> Result<Value, Alarm> {
    let (o, r) = sys.trafo.tool_vectors().unwrap_or_else(|| {
        let o = match sys.modal.plane {
            Plane::G17 => [0.0, 0.0, 1.0],
            Plane::G18 => [0.0, 1.0, 0.0],
            Plane::G19 => [1.0, 0.0, 0.0],
        };
        (o, None)
    });
    let v: Vec3 = if rotation {
        r.ok_or_else(|| Alarm::unknown_name(line, &format!("{name} (needs a 6-axis orientation transformation)")))?
    } else {
        o
    };
    let i = match indices {
        [i] => i.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?,
        _ => return Err(Alarm::index_error(line, name, "needs one index 1..3")),
    };
    match i {
        1..=3 => Ok(Value::Real(v[i as usize - 1])),
        _ => Err(Alarm::index_error(line, name, &format!("index {i} (1..3)"))),
    }
}

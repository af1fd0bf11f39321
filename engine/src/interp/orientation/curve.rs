//! ORICURVE with `XH=`, `YH=`, `ZH=` (F2 §3.11, REFERENCE §6.3.4): the block's orientation
//! runs from the tool tip line to a second, upper line; the programmed point is where the upper
//! line ends. Conventions of this product where the manual text is silent:
//! * the upper line starts at the previous ORICURVE block's upper end point if the block before
//!   was one, otherwise on the start orientation at the distance the block ends with
//!   (`tip₀ + o₀·|U₁ − tip₁|`), so the orientation does not jump at the block start;
//! * an omitted XH/YH/ZH keeps the previous upper point's coordinate (WCS); in the first block
//!   of a curve all three are needed;
//! * the tool tip must move on a straight line (the manual excludes circles and involutes).

use crate::alarm::Alarm;
use crate::interp::Interpreter;
use crate::interp::frames::frame::Frame;
use crate::interp::orientation::words::OriWords;
use crate::kinematics::orient::vec3::{add, norm, normalize, scale, sub};
use crate::kinematics::{ActiveTrafo, Transformation, Vec3};
use crate::machine_data::MachineConfig;
use crate::motion::{AxisVec, OriPath, TwoCurves};

impl Interpreter {
    /// The ORICURVE orientation path of a block with XH/YH/ZH, with the orientation axes of
    /// `end` set to the end orientation.
    #[allow(clippy::too_many_arguments)]
    pub(in crate::interp) fn curve_orientation(
        &self,
        ori: &OriWords,
        cfg: &MachineConfig,
        frame: &Frame,
        start: &AxisVec,
        end: &mut AxisVec,
        active: &ActiveTrafo,
        machine: &AxisVec,
        circle: bool,
        line: u32,
    ) -> Result<Option<OriPath>, Alarm> {
        if circle {
            return Err(Alarm::value_out_of_range(line, "ORICURVE needs a straight tool tip path (no circle)"));
        }
        let geo = &cfg.geo_axes;
        let point = |p: &AxisVec| -> Vec3 { std::array::from_fn(|g| geo[g].map_or(0.0, |k| p[k])) };
        let (tip0, tip1) = (point(start), point(end));
        // The previous upper end point in the WCS, for omitted coordinates.
        let previous = self.modal.ori.upper.and_then(|u| {
            let mut v = [0.0; crate::machine_data::registry::MAX_CHANNEL_AXES];
            for (g, k) in geo.iter().enumerate() {
                if let Some(k) = k {
                    v[*k] = u[g];
                }
            }
            frame.unapply(geo, &v).map(|w| point(&w))
        });
        let mut wcs = [0.0; 3];
        for (g, c) in wcs.iter_mut().enumerate() {
            *c = match (ori.upper[g], previous) {
                (Some(v), _) => v,
                (None, Some(p)) => p[g],
                (None, None) => {
                    return Err(Alarm::value_out_of_range(
                        line,
                        "ORICURVE: XH, YH and ZH are all needed where the upper curve begins",
                    ));
                }
            };
        }
        let mut v = [0.0; crate::machine_data::registry::MAX_CHANNEL_AXES];
        for (g, k) in geo.iter().enumerate() {
            if let Some(k) = k {
                v[*k] = wcs[g];
            }
        }
        let upper1 = point(&frame.apply(geo, &v));
        let reach = norm(&sub(&upper1, &tip1));
        if reach < 1e-9 {
            return Err(Alarm::value_out_of_range(line, "ORICURVE: XH/YH/ZH coincide with the tool tip"));
        }
        let upper0 = match self.modal.ori.upper {
            Some(u) => u,
            None => {
                let o0 = active.trafo.orientation(machine).and_then(|o| normalize(&o)).unwrap_or([0.0, 0.0, 1.0]);
                add(&tip0, &scale(&o0, reach))
            }
        };
        let path = OriPath::two_curves(TwoCurves::lines([tip0, tip1], [upper0, upper1]));
        active.trafo.orientation_axes(&path.at(1.0), machine, end).map_err(|_| {
            Alarm::value_out_of_range(line, "orientation not reachable by the rotary axes of the transformation")
        })?;
        Ok(Some(path))
    }
}

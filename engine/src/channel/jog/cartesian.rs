//! Cartesian manual travel with an orientation transformation (Transformations FM, Cartesian
//! manual travel): translation along the axes of the tool coordinate system (TCS), and
//! orientation JOG, which turns the tool about an axis of the BCS, the WCS or the TCS while the
//! tool tip stands still. The virtual orientation axes are addressed as A2, B2 and C2 (the names
//! of MD10620 EULER_ANGLE_NAME_TAB): rotations about X, Y and Z of the chosen system.

use super::settings::{OrientationJogKind, angle_rotation_axis};
use super::{ActiveJog, JogSystem};
use crate::alarm::Alarm;
use crate::channel::{Channel, CommandError, MoveMeta, Status};
use crate::kinematics::orient::vec3::cross;
use crate::kinematics::{Transformation, Vec3};
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::{AxisLimit, AxisVec, Feed, Move, OriPath, Path, rotate};

/// Longest continuous orientation JOG, degrees (it ends earlier where the axes cannot follow).
const MAX_ORIENTATION_JOG: f64 = 360.0;
/// Step of the reachability walk along an orientation JOG, degrees.
const ORI_STEP: f64 = 0.5;

/// The virtual orientation axis an axis name addresses (0 = about X, 1 = Y, 2 = Z).
pub(in crate::channel) fn orientation_axis(name: &str) -> Option<usize> {
    match name.to_ascii_uppercase().as_str() {
        "A2" => Some(0),
        "B2" => Some(1),
        "C2" => Some(2),
        _ => None,
    }
}

fn unit(v: Vec3) -> Option<Vec3> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (n > 1e-9).then(|| v.map(|x| x / n))
}

impl Channel {
    /// The axes of the tool coordinate system in the BCS: Z along the tool (tip → holder), X in
    /// the plane of the old X and Z (MD21110 X_AXIS_IN_OLD_X_Z_PLANE), Y completing a right-hand
    /// system. Without an orientation transformation the tool stands along Z.
    pub(in crate::channel) fn tool_axes(&self) -> [Vec3; 3] {
        let z = self.trafo.as_ref().and_then(|t| t.trafo.orientation(&self.machine)).unwrap_or([0.0, 0.0, 1.0]);
        let x = unit(cross(&[0.0, 1.0, 0.0], &z))
            .unwrap_or_else(|| unit(cross(&z, &[0.0, 0.0, 1.0])).unwrap_or([1.0, 0.0, 0.0]));
        [x, cross(&z, &x), z]
    }

    /// The direction in the BCS slots of geometry axis `g` of the TCS.
    pub(in crate::channel) fn tool_direction(&self, g: usize, geo_slots: &[Option<usize>; 3]) -> AxisVec {
        let axis = self.tool_axes()[g];
        let mut d = [0.0; MAX_CHANNEL_AXES];
        for (i, slot) in geo_slots.iter().enumerate() {
            if let Some(k) = slot {
                d[*k] = axis[i];
            }
        }
        d
    }

    /// The BCS axis orientation JOG of `about` (0..2 = A2, B2, C2) turns `o` about: an axis of the
    /// reference system (kind `Axes`, and always in the TCS, whose axes move with the tool), or
    /// the axis about which that angle of `kind` turns, reckoned in the BCS or the WCS.
    fn orientation_jog_axis(
        &self,
        about: usize,
        o: Vec3,
        system: JogSystem,
        kind: OrientationJogKind,
    ) -> Result<Vec3, CommandError> {
        let e: Vec3 = std::array::from_fn(|i| if i == about { 1.0 } else { 0.0 });
        let wcs = system == JogSystem::Workpiece;
        Ok(match (system, kind) {
            (JogSystem::Tool, _) => self.tool_axes()[about],
            (_, OrientationJogKind::Axes) if wcs => self.offsets.frame.rotate_direction(e),
            (_, OrientationJogKind::Axes) => e,
            _ => {
                let tab = self.turn_tab(kind);
                let o_ref = if wcs { self.offsets.frame.unrotate_direction(o) } else { o };
                let axis = angle_rotation_axis(kind, tab, &o_ref, about)?;
                if wcs { self.offsets.frame.rotate_direction(axis) } else { axis }
            }
        })
    }

    /// Orientation JOG: turns the tool about axis `about` (0..2) of `system` by `distance`
    /// degrees (continuous: until released or until the axes cannot follow), the tool tip held.
    pub(in crate::channel) fn start_orientation_jog(
        &mut self,
        about: usize,
        dir: f64,
        distance: Option<f64>,
        system: JogSystem,
        kind: OrientationJogKind,
    ) -> Result<(), CommandError> {
        let Some(t) = self.trafo_in_force().filter(|t| t.trafo.orientation_slots().iter().any(Option::is_some)) else {
            return Err(CommandError::Invalid("orientation JOG needs an active orientation transformation".into()));
        };
        let o = t.trafo.orientation(&self.machine).expect("orientation transformation");
        let axis = self.orientation_jog_axis(about, o, system, kind)?;
        // As for any JOG: in an interrupted program the program's motion is put aside (REPOS).
        let resume = if self.status == Status::Stopped { Status::Stopped } else { Status::Idle };
        if resume == Status::Stopped {
            self.interrupt_for_jog();
        }
        // Walk the rotation to where the rotary axes can still follow (limits, reachability).
        let wanted = distance.unwrap_or(MAX_ORIENTATION_JOG).min(MAX_ORIENTATION_JOG);
        let start = t.forward(&self.machine);
        let mut prev = self.machine;
        let mut turned = 0.0;
        let mut end = start;
        while turned < wanted - 1e-12 {
            let next = (turned + ORI_STEP).min(wanted);
            let o_next = rotate(o, axis, (dir * next).to_radians());
            let mut bcs = start;
            if t.trafo.orientation_axes(&o_next, &prev, &mut bcs).is_err() {
                break;
            }
            let Ok(m) = t.inverse(&bcs, &prev) else { break };
            let inside = (0..self.cfg.channel_axes.len()).all(|i| {
                let ax = self.cfg.axis(i);
                ax.modulo.is_some() || ax.spindle.is_some() || (ax.limit_minus..=ax.limit_plus).contains(&m[i])
            });
            if !inside {
                break;
            }
            (turned, prev, end) = (next, m, bcs);
        }
        if turned < 1e-9 {
            let k = t.trafo.orientation_slots()[0].expect("an orientation axis");
            let name = self.cfg.axis(k).name.clone();
            self.notify_alarm(Alarm::rests_on_software_limit(&name, dir > 0.0));
            return Ok(());
        }
        let mut path = Path::line(start, end);
        path.ori = OriPath::cone(o, axis, (dir * turned).to_radians()).map(Box::new);
        let velocity = t
            .trafo
            .orientation_slots()
            .iter()
            .flatten()
            .map(|&k| self.cfg.axis(k).jog_velocity.min(self.cfg.axis(k).max_velocity))
            .fold(f64::INFINITY, f64::min);
        let mv = Move::new(path, turned, Feed::Path(velocity), &AxisLimit::for_channel(&self.cfg), true, self.next_tag);
        self.push_bcs_move(
            mv,
            MoveMeta {
                line: 0,
                seq: crate::channel::pending::NO_SEQ,
                offsets: self.offsets.clone(),
                machine_space: false,
                feed: 0.0,
            },
        );
        self.jog_serial = self.jog_serial.wrapping_add(1);
        let k = t.trafo.orientation_slots()[0].expect("an orientation axis");
        self.jog = Some(ActiveJog::orientation(k, end, resume));
        self.wake_motion_readers();
        self.status = Status::Running;
        Ok(())
    }
}

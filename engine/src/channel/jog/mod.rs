//! JOG: one axis at a time, continuous (until released), incremental (INC1 … INC1000 weighted by
//! MD31090 JOG_INCR_WEIGHT, or a variable distance) or by handwheel pulses; in the machine
//! coordinate system or along the axes of the workpiece coordinate system (WCS); stopping at
//! the software limits (and, with a transformation active, where the machine axes cannot follow).
//!
//! With a program interrupted (NC stop, M0) JOG runs on a planner of its own and the program's
//! main run waits (see `repos/mod.rs`).

pub(super) mod cartesian;
pub(super) mod settings;

use super::{Channel, CommandError, JogRequest, Mode, MoveMeta, Status};
use crate::alarm::{Alarm, Clear};
use crate::kinematics::Transformation;
use crate::machine_data::registry::{self, MAX_CHANNEL_AXES};
use crate::motion::{AxisLimit, AxisVec, Feed, Move, Path};
use settings::OrientationJogKind;

/// The fixed increments of the machine control panel (INC1, INC10, INC100, INC1000); each step
/// moves by MD31090 JOG_INCR_WEIGHT (0.001 mm or 0.001° by default).
pub const JOG_INCREMENTS: [u32; 4] = [1, 10, 100, 1000];

/// Most handwheel moves queued at once; further pulses are refused until the axis catches up.
const MAX_HANDWHEEL_QUEUE: usize = 8;

/// Longest Cartesian JOG with a transformation active, in mm (a continuous JOG ends there).
const MAX_CARTESIAN_JOG: f64 = 10_000.0;

/// The coordinate system a JOG motion moves in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum JogSystem {
    /// MCS: the machine axis behind the named axis moves alone (with a transformation active,
    /// the machine axis itself, not a Cartesian coordinate).
    #[default]
    Machine,
    /// BCS: a geometry axis moves along that axis of the basic coordinate system (frames do not
    /// act); with a transformation active, the tool tip moves Cartesian and the machine axes
    /// follow. Other channel axes move as in the MCS.
    Basic,
    /// WCS: a geometry axis moves along the direction of that axis of the active frame (all
    /// geometry axes move when the frame is rotated); with a transformation active, the tool tip
    /// moves Cartesian and the machine axes follow through the inverse transformation. Other
    /// channel axes move as in the MCS.
    Workpiece,
    /// TCS: a geometry axis moves along that axis of the tool coordinate system (Z along the
    /// tool), the orientation held; see `cartesian.rs`.
    Tool,
}

/// A JOG motion in progress.
#[derive(Debug, Clone)]
pub(super) struct ActiveJog {
    /// The channel axis the operator moves.
    axis: usize,
    /// Unit direction of the motion in the space of its moves.
    direction: AxisVec,
    /// The direction for the plus key (handwheel pulses of either sign append along it).
    plus: AxisVec,
    /// End of the last queued move (handwheel pulses append from here).
    end: AxisVec,
    /// The moves are in machine axes although a transformation is active.
    machine_space: bool,
    /// Started by handwheel pulses (more pulses append).
    handwheel: bool,
    /// Status to return to when the motion is over (stopped when a program is interrupted).
    resume: Status,
}

impl ActiveJog {
    /// An orientation JOG ending at BCS point `end` (`axis`: an orientation axis, for reports).
    pub(super) fn orientation(axis: usize, end: AxisVec, resume: Status) -> ActiveJog {
        ActiveJog {
            axis,
            direction: [0.0; MAX_CHANNEL_AXES],
            plus: [0.0; MAX_CHANNEL_AXES],
            end,
            machine_space: false,
            handwheel: false,
            resume,
        }
    }
}

impl Channel {
    /// Starts a JOG motion of one axis in the MCS (JOG mode only).
    pub fn jog(&mut self, req: &JogRequest) -> Result<(), CommandError> {
        self.jog_in(req, JogSystem::Machine)
    }

    /// Starts a JOG motion of one axis in `system` (JOG mode only). `req.axis` is a machine axis
    /// name, a geometry axis name or a channel axis name.
    pub fn jog_in(&mut self, req: &JogRequest, system: JogSystem) -> Result<(), CommandError> {
        self.jog_with(req, Some(system), None)
    }

    /// Starts a JOG motion; what the request leaves open comes from the setting data: the
    /// coordinate system from SD42650 `$SC_CART_JOG_MODE`, the orientation JOG kind (A2/B2/C2)
    /// from SD42660 `$SC_ORI_JOG_MODE` (see `settings.rs`).
    pub fn jog_with(
        &mut self,
        req: &JogRequest,
        system: Option<JogSystem>,
        rotation: Option<OrientationJogKind>,
    ) -> Result<(), CommandError> {
        self.check_jog_allowed()?;
        if req.direction != 1 && req.direction != -1 {
            return Err(CommandError::Invalid(format!("direction must be 1 or -1, not {}", req.direction)));
        }
        let distance = match req.increment {
            Some(inc) if inc.is_finite() && inc > 0.0 => Some(inc),
            Some(inc) => return Err(CommandError::Invalid(format!("increment must be positive, not {inc}"))),
            None => None,
        };
        if let Some(about) = self::cartesian::orientation_axis(&req.axis) {
            let system = system.unwrap_or_else(|| self.default_orientation_system());
            let kind = rotation.unwrap_or_else(|| self.default_orientation_kind());
            return self.start_orientation_jog(about, f64::from(req.direction), distance, system, kind);
        }
        let system = system.unwrap_or_else(|| self.default_translation_system());
        let k = self.jog_axis_index(&req.axis)?;
        self.start_jog(k, f64::from(req.direction), distance, req.rapid, system, false)
    }

    /// The distance of `steps` increments of the named axis: `steps` × MD31090 JOG_INCR_WEIGHT.
    pub fn increment_distance(&self, axis: &str, steps: u32) -> Result<f64, CommandError> {
        let k = self.jog_axis_index(axis)?;
        Ok(f64::from(steps) * self.increment_weight(k))
    }

    /// Handwheel pulses: each detent moves the axis by `steps` increments (INC1 … INC1000) of
    /// MD31090 JOG_INCR_WEIGHT, `pulses` signed by the direction of turning. Pulses that come while
    /// the axis still moves from earlier ones are appended to its path.
    pub fn handwheel(&mut self, axis: &str, pulses: i32, steps: u32, system: JogSystem) -> Result<(), CommandError> {
        if pulses == 0 {
            return Err(CommandError::Invalid("pulses must not be 0".into()));
        }
        if steps == 0 {
            return Err(CommandError::Invalid("the increment must be at least 1 step".into()));
        }
        let k = self.jog_axis_index(axis)?;
        let distance = f64::from(pulses.unsigned_abs()) * f64::from(steps) * self.increment_weight(k);
        let dir = f64::from(pulses.signum());
        if let Some(jog) = &self.jog
            && jog.handwheel
            && jog.axis == k
            && self.status == Status::Running
        {
            return self.append_handwheel(distance * dir);
        }
        self.check_jog_allowed()?;
        self.start_jog(k, dir, Some(distance), false, system, true)
    }

    fn check_jog_allowed(&self) -> Result<(), CommandError> {
        if self.mode != Mode::Jog {
            return Err(CommandError::WrongMode(self.mode.as_str(), "JOG needs JOG mode"));
        }
        if self.status == Status::Alarm {
            return Err(CommandError::AlarmActive);
        }
        if self.is_busy() || self.repos_returning {
            return Err(CommandError::Busy("an axis is moving"));
        }
        Ok(())
    }

    /// The channel axis behind a machine axis name, geometry axis name or channel axis name.
    fn jog_axis_index(&self, name: &str) -> Result<usize, CommandError> {
        let cfg = &self.cfg;
        let by_machine_name = (0..cfg.channel_axes.len()).find(|&k| cfg.axis(k).name.eq_ignore_ascii_case(name));
        let k = by_machine_name
            .or_else(|| self.trafo_geo_slot(name))
            .or_else(|| cfg.program_axis(name))
            .ok_or_else(|| CommandError::UnknownAxis(name.to_string()))?;
        let positioned = self.spindles.iter().any(|s| s.axis == k && s.axis_mode)
            || self.trafo.as_ref().and_then(|t| t.trafo.rotary_slot()) == Some(k);
        if cfg.axis(k).spindle.is_some() && !positioned {
            return Err(CommandError::Invalid(format!("{name} is a spindle")));
        }
        Ok(k)
    }

    /// With a transformation active, the slot of a geometry axis it names.
    fn trafo_geo_slot(&self, name: &str) -> Option<usize> {
        let t = self.trafo.as_ref()?;
        let g = self.cfg.geo_names.iter().position(|n| n.eq_ignore_ascii_case(name))?;
        t.trafo.geo_slots()[g]
    }

    /// MD31090 JOG_INCR_WEIGHT of channel axis `k` (mm or degrees per increment).
    fn increment_weight(&self, k: usize) -> f64 {
        let def = registry::lookup("$MA_JOG_INCR_WEIGHT").expect("JOG_INCR_WEIGHT is in the registry");
        let machine_axis = self.cfg.channel_axes[k].machine_axis;
        self.data.get(def, machine_axis, 0).as_f64().unwrap_or(0.001)
    }

    /// Plans and starts the motion; `distance` None is continuous JOG.
    fn start_jog(
        &mut self,
        k: usize,
        dir: f64,
        distance: Option<f64>,
        rapid: bool,
        system: JogSystem,
        handwheel: bool,
    ) -> Result<(), CommandError> {
        let resume = if self.status == Status::Stopped { Status::Stopped } else { Status::Idle };
        if resume == Status::Stopped {
            self.interrupt_for_jog();
        }
        // The direction in the space of the moves: one machine axis, or a WCS axis through the frame.
        let geo_slots = match &self.trafo {
            Some(t) => t.trafo.geo_slots(),
            None => self.cfg.geo_axes,
        };
        let geo = geo_slots.iter().position(|s| *s == Some(k));
        let cartesian = system != JogSystem::Machine && geo.is_some();
        let machine_space = self.trafo.is_some() && !cartesian;
        let mut direction = [0.0; MAX_CHANNEL_AXES];
        direction[k] = dir;
        if cartesian && system == JogSystem::Tool {
            direction = self.tool_direction(geo.expect("cartesian"), &geo_slots).map(|d| d * dir);
        } else if cartesian && system == JogSystem::Workpiece {
            direction = self.offsets.frame.apply_vector(&geo_slots, &direction);
            let norm = direction.iter().map(|d| d * d).sum::<f64>().sqrt();
            if norm < 1e-12 {
                return Err(CommandError::Invalid(format!("the frame maps {} to no direction", self.axis_label(k))));
            }
            direction.iter_mut().for_each(|d| *d /= norm);
        }
        let start = if machine_space { self.machine } else { *self.planner.position() };
        if machine_space {
            self.planner.set_position(start);
        }
        let reach = self.reachable_length(&start, &direction, machine_space);
        let length = distance.unwrap_or(reach).min(reach);
        let ax = self.cfg.axis(k);
        if length < 1e-9 {
            let plus = dir > 0.0;
            let name = ax.name.clone();
            self.restore_planner_space(machine_space);
            self.notify_alarm(Alarm::rests_on_software_limit(&name, plus));
            return Ok(());
        }
        let end: AxisVec = std::array::from_fn(|i| start[i] + direction[i] * length);
        let velocity = self.jog_velocity(&direction, rapid);
        let mv = Move::new(
            Path::line(start, end),
            length,
            Feed::Path(velocity),
            &AxisLimit::for_channel(&self.cfg),
            !handwheel,
            self.next_tag,
        );
        let mut mv = mv;
        if rapid {
            rapid_overlay(&mut mv, velocity);
        }
        mv.machine_space = machine_space;
        self.push_bcs_move(
            mv,
            MoveMeta { line: 0, seq: super::pending::NO_SEQ, offsets: self.offsets.clone(), machine_space, feed: 0.0 },
        );
        self.jog_serial = self.jog_serial.wrapping_add(1);
        let plus = direction.map(|d| d * dir);
        self.jog = Some(ActiveJog { axis: k, direction, plus, end, machine_space, handwheel, resume });
        self.wake_motion_readers();
        self.status = Status::Running;
        Ok(())
    }

    /// Appends handwheel pulses (signed distance along the axis) to the motion in progress.
    fn append_handwheel(&mut self, signed: f64) -> Result<(), CommandError> {
        if self.planner.len() >= MAX_HANDWHEEL_QUEUE {
            return Err(CommandError::Busy("the axis has not caught up with the handwheel yet"));
        }
        let Some(jog) = self.jog.clone() else { return Ok(()) };
        // Handwheel motion along the jog's own direction (its sign gives the sense).
        let direction: AxisVec = jog.plus.map(|d| d * signed.signum());
        let start = jog.end;
        let reach = self.reachable_length(&start, &direction, jog.machine_space);
        let length = signed.abs().min(reach);
        if length < 1e-9 {
            return Ok(());
        }
        let end: AxisVec = std::array::from_fn(|i| start[i] + direction[i] * length);
        let velocity = self.jog_velocity(&direction, false);
        let mut mv = Move::new(
            Path::line(start, end),
            length,
            Feed::Path(velocity),
            &AxisLimit::for_channel(&self.cfg),
            false,
            self.next_tag,
        );
        mv.machine_space = jog.machine_space;
        self.push_move(
            mv,
            MoveMeta {
                line: 0,
                seq: super::pending::NO_SEQ,
                offsets: self.offsets.clone(),
                machine_space: jog.machine_space,
                feed: 0.0,
            },
        );
        if let Some(j) = &mut self.jog {
            j.end = end;
        }
        Ok(())
    }

    /// The JOG velocity along `direction`: the slowest JOG velocity (MD32020 JOG_VELO or with
    /// rapid traverse overlay MD32010 JOG_VELO_RAPID) of the axes that move, within their maximum.
    fn jog_velocity(&self, direction: &AxisVec, rapid: bool) -> f64 {
        (0..self.cfg.channel_axes.len())
            .filter(|&i| direction[i].abs() > 1e-12)
            .map(|i| {
                let ax = self.cfg.axis(i);
                let v = if rapid { ax.jog_rapid_velocity } else { ax.jog_velocity };
                v.min(ax.max_velocity)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// How far a motion from `start` along the unit `direction` may go before a machine axis
    /// reaches its software limit (or, Cartesian with a transformation, before the machine axes
    /// cannot follow).
    fn reachable_length(&self, start: &AxisVec, direction: &AxisVec, machine_space: bool) -> f64 {
        let n = self.cfg.channel_axes.len();
        match self.trafo_in_force().filter(|_| !machine_space) {
            None => {
                let mut reach = f64::INFINITY;
                for i in 0..n {
                    let d = direction[i];
                    let ax = self.cfg.axis(i);
                    if d.abs() < 1e-12 || ax.modulo.is_some() {
                        continue;
                    }
                    let room = if d > 0.0 { ax.limit_plus - start[i] } else { ax.limit_minus - start[i] };
                    reach = reach.min((room / d).max(0.0));
                }
                if reach.is_infinite() { 1e9 } else { reach }
            }
            Some(t) => {
                // Walk the line in steps of 0.5 mm, then halve the last step ten times.
                let ok = |s: f64, prev: &AxisVec| -> Option<AxisVec> {
                    let p: AxisVec = std::array::from_fn(|i| start[i] + direction[i] * s);
                    let m = t.inverse(&p, prev).ok()?;
                    let inside = (0..n).all(|i| {
                        let ax = self.cfg.axis(i);
                        ax.modulo.is_some() || (ax.limit_minus..=ax.limit_plus).contains(&m[i])
                    });
                    inside.then_some(m)
                };
                let (mut good, mut prev) = (0.0, self.machine);
                let step = 0.5;
                while good < MAX_CARTESIAN_JOG {
                    match ok(good + step, &prev) {
                        Some(m) => {
                            good += step;
                            prev = m;
                        }
                        None => {
                            let mut h = step;
                            for _ in 0..10 {
                                h /= 2.0;
                                if let Some(m) = ok(good + h, &prev) {
                                    good += h;
                                    prev = m;
                                }
                            }
                            break;
                        }
                    }
                }
                good
            }
        }
    }

    /// Releases the JOG key: the axis brakes to standstill.
    pub fn jog_stop(&mut self) {
        if self.jog.is_some() {
            self.planner.stop_and_flush();
        }
    }

    /// Releases the JOG key only if the motion in progress is the one numbered `serial` (see
    /// [`Channel::jog_serial`]); a newer motion started by someone else goes on.
    pub fn jog_stop_if(&mut self, serial: u64) {
        if self.jog_serial == serial {
            self.jog_stop();
        }
    }

    /// The number of the last JOG motion started.
    pub fn jog_serial(&self) -> u64 {
        self.jog_serial
    }

    /// True while a JOG motion is in progress.
    pub fn is_jogging(&self) -> bool {
        self.jog.is_some()
    }

    pub(super) fn finish_jog_if_done(&mut self) {
        let Some(jog) = &self.jog else { return };
        if !self.planner.is_idle() {
            return;
        }
        let jog = jog.clone();
        self.jog = None;
        if self.status == Status::Running {
            self.status = jog.resume;
        }
        // An axis standing on its software limit after the motion (the motion was clipped there).
        for i in 0..self.cfg.channel_axes.len() {
            let ax = self.cfg.axis(i);
            let moved = if jog.machine_space || self.trafo.is_none() { jog.direction[i].abs() > 1e-12 } else { true };
            let p = self.machine[i];
            if moved && ax.modulo.is_none() && ax.spindle.is_none() && (p >= ax.limit_plus || p <= ax.limit_minus) {
                let name = ax.name.clone();
                self.notify_alarm(Alarm::rests_on_software_limit(&name, p >= ax.limit_plus));
                break;
            }
        }
        self.restore_planner_space(jog.machine_space);
        // Preparation continues from here, unless an interrupted program returns by REPOS.
        if jog.resume != Status::Stopped {
            match &self.trafo {
                Some(_) => self.interp.sync_transformation(&self.machine),
                None => self.interp.sync_position(self.planner.position()),
            }
        }
    }

    /// After motion in machine axes with a transformation active, the planner goes back to the
    /// BCS position of the machine.
    fn restore_planner_space(&mut self, machine_space: bool) {
        if machine_space && let Some(t) = self.trafo_in_force() {
            let bcs = t.forward(&self.machine);
            self.planner.set_position(bcs);
        }
    }

    /// Shows an alarm that does not stop anything (a JOG motion is already over).
    pub(super) fn notify_alarm(&mut self, alarm: Alarm) {
        debug_assert_eq!(alarm.clear, Clear::Cancel);
        if self.alarms.iter().any(|a| a.number == alarm.number && a.message == alarm.message) {
            return;
        }
        self.events.push(super::Event::AlarmRaised(alarm.clone()));
        self.alarms.push(alarm);
    }

    fn axis_label(&self, k: usize) -> String {
        self.cfg.program_axis_name(k).to_string()
    }
}

/// The rapid traverse overlay: the move runs at MD32010 JOG_VELO_RAPID (`velocity`) scaled by
/// the rapid override, like G0, not by the feed override.
fn rapid_overlay(mv: &mut Move, velocity: f64) {
    mv.feed = f64::INFINITY;
    mv.v_axes = mv.v_axes.min(velocity);
    mv.v_max = mv.v_axes;
}

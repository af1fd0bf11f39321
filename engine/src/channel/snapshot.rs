//! The channel's state as the outside world sees it (the contract's state object, in engine
//! types; the server turns it into JSON).

use super::{Channel, Mode, Status};
use crate::alarm::Alarm;
use crate::kinematics::{AnyTrafo, Transformation};
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::AxisVec;

/// The block shown as current.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockRef {
    /// 1-based line in the program text.
    pub line: u32,
    pub text: String,
}

/// The active kinematic transformation.
#[derive(Debug, Clone, PartialEq)]
pub struct TransformationInfo {
    pub name: String,
    pub trafo_type: u32,
    pub index: u32,
    /// TRACYL: the working diameter of the selection (programmed Y is the arc length on it), so
    /// a view can wrap the unrolled path onto the cylinder.
    pub diameter: Option<f64>,
}

/// A consistent view of one channel at one IPO cycle.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    pub status: Status,
    pub mode: Mode,
    /// Simulated seconds since the channel was created.
    pub time: f64,
    pub tick: u64,
    /// MCS: every machine axis of the channel, by machine axis name.
    pub machine: Vec<(String, f64)>,
    /// BCS: channel axes by program name (geometry axes first by their geometry names).
    pub basic: Vec<(String, f64)>,
    /// WCS: as `basic`, after work offsets.
    pub workpiece: Vec<(String, f64)>,
    /// Unit tool direction in the WCS, when known.
    pub orientation: Option<[f64; 3]>,
    pub transformation: Option<TransformationInfo>,
    pub block: Option<BlockRef>,
    pub alarms: Vec<Alarm>,
    /// Active tool and cutting edge (T, D); D0 = no offset.
    pub tool: (u32, u32),
    /// Path velocity in mm/min.
    pub path_velocity: f64,
    /// Spindles: (channel axis name, speed in rev/min, signed: + = M3).
    pub spindles: Vec<(String, f64)>,
    /// The program's last MSG text.
    pub message: Option<String>,
    /// Feed, rapid and spindle override.
    pub overrides: super::Overrides,
    /// Single block (SBL1) and optional stop (M1) selected.
    pub single_block: bool,
    pub optional_stop: bool,
    /// The active G functions of the block in execution, one per displayed G group.
    pub gcodes: Vec<String>,
    /// Reference point state by machine axis name, in machine axis order.
    pub referenced: Vec<(String, bool)>,
    /// The axis whose reference point approach is in progress, and its phase.
    pub referencing: Option<(String, super::ReferencePhase)>,
    /// Number of the last JOG motion started (see `Channel::jog_stop_if`).
    pub jog_serial: u64,
    /// The program was interrupted and axes moved by JOG: NC start repositions first (REPOS).
    pub repos_pending: bool,
}

pub(super) fn build(ch: &Channel) -> Snapshot {
    let cfg = &ch.cfg;
    let pos = &ch.machine;
    let n = cfg.channel_axes.len();
    let value = |k: usize| -> f64 {
        match ch.spindles.iter().find(|s| s.axis == k && !s.axis_mode) {
            Some(s) => s.position,
            None => pos[k],
        }
    };
    let display = |k: usize, v: f64| -> f64 {
        match cfg.axis(k).modulo {
            Some((start, range)) => start + (v - start).rem_euclid(range),
            None => v,
        }
    };
    let mut machine: Vec<(usize, (String, f64))> =
        (0..n).map(|k| (cfg.channel_axes[k].machine_axis, (cfg.axis(k).name.clone(), display(k, value(k))))).collect();
    machine.sort_by_key(|(m, _)| *m);
    // BCS: with a transformation the forward map of the machine position (the tool tip), the
    // geometry axes named by the transformation's assignment; the axes it drives have no BCS
    // value of their own.
    let (geo_axes, driven, bcs) = match &ch.trafo {
        // An orientation transformation's rotary axes keep their own value in the BCS.
        Some(t) => {
            let ori = t.trafo.orientation_slots();
            // So does the 7th axis of a 7-axis TRAORI (it turns the workpiece).
            let seventh = match &t.trafo {
                crate::kinematics::AnyTrafo::Traori(t) => t.seventh_slot(),
                _ => None,
            };
            let driven = t
                .trafo
                .machine_slots()
                .into_iter()
                .filter(|k| !ori.contains(&Some(*k)) && Some(*k) != seventh)
                .collect();
            // With the tool lengthened by the online offset: the display keeps the tool tip.
            (t.trafo.geo_slots(), driven, ch.space_of_machine())
        }
        None => {
            let mut b: AxisVec = std::array::from_fn(value);
            for (g, k) in cfg.geo_axes.iter().enumerate() {
                if let Some(k) = k {
                    b[*k] -= ch.toff.current[g];
                }
            }
            (cfg.geo_axes, Vec::new(), b)
        }
    };
    let geo: Vec<usize> = geo_axes.iter().flatten().copied().collect();
    let order: Vec<usize> =
        geo.iter().copied().chain((0..n).filter(|k| !geo.contains(k) && !driven.contains(k))).collect();
    let name = |k: usize| -> String {
        match geo_axes.iter().position(|g| *g == Some(k)) {
            Some(g) => cfg.geo_names[g].clone(),
            None => cfg.channel_axes[k].name.clone(),
        }
    };
    // A Cartesian coordinate in a rotary axis' slot is not shown modulo.
    let show = |k: usize, v: f64| if ch.trafo.is_some() && geo.contains(&k) { v } else { display(k, v) };
    let offsets = &ch.offsets;
    let basic: Vec<(String, f64)> = order.iter().map(|&k| (name(k), show(k, bcs[k] - offsets.tool[k]))).collect();
    let mut basic_vec = [0.0; MAX_CHANNEL_AXES];
    for (k, b) in basic_vec.iter_mut().enumerate().take(n) {
        *b = bcs[k] - offsets.tool[k];
    }
    let wcs = offsets.frame.unapply(&geo_axes, &basic_vec).unwrap_or(basic_vec);
    let workpiece: Vec<(String, f64)> = order.iter().map(|&k| (name(k), show(k, wcs[k]))).collect();
    // The tool direction in the WCS: through the orientation transformation when one is
    // active, else the fixed +Z of a milling head (when the channel has three geometry axes).
    let orientation = match ch.trafo.as_ref().and_then(|t| t.trafo.orientation(pos)) {
        Some(o) => Some(offsets.frame.unrotate_direction(o)),
        None => geo_axes[2].map(|_| [0.0, 0.0, 1.0]).filter(|_| geo_axes.iter().all(Option::is_some)),
    };
    let transformation = ch.trafo.as_ref().map(|t| TransformationInfo {
        name: t.trafo.name().to_string(),
        trafo_type: t.trafo.trafo_type(),
        index: t.number as u32,
        diameter: match &t.trafo {
            AnyTrafo::Tracyl(c) => Some(c.diameter()),
            _ => None,
        },
    });
    Snapshot {
        status: ch.status,
        mode: ch.mode,
        time: ch.time(),
        tick: ch.tick,
        machine: machine.into_iter().map(|(_, p)| p).collect(),
        basic,
        workpiece,
        orientation,
        transformation,
        block: ch.current_line.and_then(|l| ch.block_ref(l)),
        alarms: ch.alarms.clone(),
        tool: ch.interp.tool_in_main_run(&ch.offsets),
        path_velocity: ch.planner.velocity() * 60.0,
        spindles: ch.spindles.iter().map(|s| (cfg.program_axis_name(s.axis).to_string(), s.speed)).collect(),
        message: ch.message.clone(),
        overrides: ch.overrides,
        single_block: ch.single_block,
        optional_stop: ch.optional_stop,
        gcodes: ch.offsets.gcodes.names(),
        referenced: ch.reference_state(),
        referencing: ch.referencing(),
        jog_serial: ch.jog_serial,
        repos_pending: ch.repos_pending(),
    }
}

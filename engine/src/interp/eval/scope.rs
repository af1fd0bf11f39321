//! What expressions in a block can read: variables and the system variables of preparation.

use crate::alarm::Alarm;
use crate::interp::Offsets;
use crate::interp::eval::Scope;
use crate::interp::eval::value::Value;
use crate::interp::eval::vars::Variables;
use crate::interp::frames::frame::{Frame, GeoAxes};
use crate::interp::modal::{CircleForm, Modal, MotionMode, Plane};
use crate::machine_data::MachineConfig;
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::AxisVec;

/// A read-only view of the preparation state for system variables.
pub(crate) struct SysView<'a> {
    pub cfg: &'a MachineConfig,
    pub modal: &'a Modal,
    /// Programmed end position in machine coordinates per channel axis.
    pub pos: &'a AxisVec,
    /// The main run's following error per channel axis (what `$AA_IM` lacks of the setpoint).
    pub lag: &'a AxisVec,
    pub offsets: &'a Offsets,
    /// The programmable frame.
    pub pframe: &'a Frame,
    /// The system frames.
    pub system: &'a crate::interp::frames::frame::SystemFrames,
    /// `$P_IFRAME` as a program wrote it.
    pub iframe: &'a Option<Frame>,
    /// Spindles switched to position control (SPOS): programmable as rotary axes.
    pub positioned: &'a [bool; MAX_CHANNEL_AXES],
    /// The active transformation's view (machine positions, chain layers).
    pub trafo: &'a crate::interp::transform::selection::TrafoState,
    /// The orientable toolholder state.
    pub holder: &'a crate::interp::tools::toolholder::Holder,
    /// The session's machine and setting data as stored (`$MN_`... reads).
    pub stored: &'a crate::machine_data::MachineData,
    /// The digital inputs and outputs (`$A_IN`, `$A_OUT`).
    pub io: &'a crate::interp::io::DigitalIo,
    /// Markers, parameters, timers, analog signals, `$AC_DELT` of synchronized actions.
    pub sync: &'a crate::interp::synchronized::MainRunData,
    /// The spindles as preparation sees them (`$P_S`, `$P_SDIR`).
    pub spindles: &'a crate::interp::spindles::Spindles,
    /// The probe's last results (`$AC_MEA`, `$AA_MM`, `$AA_MW`).
    pub measured: &'a crate::interp::measuring::Results,
    /// How the program runs (`$P_SIM`, see `run_vars.rs`).
    pub env: &'a crate::interp::eval::run_vars::RunEnv,
    /// Workpiece counters, runtimes, the clock (`process_vars.rs`).
    pub process: &'a crate::interp::eval::process_vars::ProcessData,
    /// The arguments of the running subprogram's call (`None`: left out), for `$P_SUBPAR`.
    pub call_args: &'a [Option<Value>],
    /// The PLC data area (`$A_DBB`..).
    pub plc: &'a crate::interp::io::plc_data::PlcData,
}

/// A [`SysView`] of an interpreter's fields. A macro rather than a method so that the
/// interpreter's variables can be borrowed mutably beside it.
macro_rules! sys_view {
    ($interp:expr, $cfg:expr) => {
        $crate::interp::eval::scope::SysView {
            cfg: $cfg,
            modal: &$interp.modal,
            pos: &$interp.pos,
            lag: &$interp.lag,
            offsets: &$interp.offsets,
            pframe: &$interp.pframe,
            system: &$interp.system,
            iframe: &$interp.iframe,
            positioned: &$interp.positioned,
            trafo: &$interp.trafo,
            holder: &$interp.holder,
            stored: &$interp.stored,
            io: &$interp.io,
            sync: &$interp.sync_data,
            spindles: &$interp.spindles,
            measured: &$interp.measured,
            env: &$interp.env,
            process: &$interp.process,
            plc: &$interp.plc,
            call_args: $crate::interp::calls::call_args(&$interp.calls),
        }
    };
}
pub(crate) use sys_view;

/// Variables plus system variables, for [`crate::interp::eval::eval`].
pub(crate) struct Ctx<'a> {
    pub vars: &'a Variables,
    pub sys: &'a SysView<'a>,
}

/// Main-run variables: reading them makes preparation wait until the main run has caught up
/// (the control's implicit preprocessing stop), because their value is only known there.
pub fn is_main_run_variable(name: &str) -> bool {
    ["$AA_", "$AC_", "$VA_", "$VC_"].iter().any(|p| name.starts_with(p))
        || crate::interp::io::is_io_name(name)
        || super::process_vars::is_clock_name(name)
}

impl Scope for Ctx<'_> {
    fn vars(&self) -> &Variables {
        self.vars
    }

    fn axis_index(&self, name: &str) -> Option<usize> {
        self.sys.cfg.program_axis(name)
    }

    fn geo_axes(&self) -> GeoAxes {
        self.sys.cfg.geo_axes
    }

    fn applicate(&self) -> usize {
        self.sys.modal.plane.axes().2
    }

    fn frame_angles(&self) -> crate::machine_data::FrameAngles {
        self.sys.cfg.frame_angles
    }

    fn system(&self, name: &str, indices: &[Value], line: u32) -> Result<Value, Alarm> {
        let sys = self.sys;
        let axis = || -> Result<usize, Alarm> {
            match indices {
                [Value::Axis(a)] | [Value::Str(a)] => {
                    sys.cfg.program_axis(a).ok_or_else(|| Alarm::unknown_name(line, &format!("{name}[{a}]")))
                }
                _ => Err(Alarm::index_error(line, name, "needs one axis name")),
            }
        };
        // The machine-side values also take the names of the axes an active transformation
        // hides behind its geometry axes (`$AA_IM[MU]` under TRAANG) and machine axis names.
        let machine_axis = || -> Result<usize, Alarm> {
            axis().or_else(|alarm| match indices {
                [Value::Axis(a) | Value::Str(a)] => {
                    sys.trafo.base_config().unwrap_or(sys.cfg).axis_by_any_name(a).ok_or(alarm)
                }
                _ => Err(alarm),
            })
        };
        // `$AA_IW` stands where the main run stands: where it differs from the programmed
        // position (command axes, STOPREOF) and no transformation lies between, the BCS is
        // the machine position less the online tool offset (`$P_EP` stays the programmed one).
        let main_run_basic = || match (&sys.sync.machine, sys.trafo.machine()) {
            (Some(machine), None) => {
                let mut basic = *machine;
                for (g, k) in sys.cfg.geo_axes.iter().enumerate() {
                    if let Some(k) = k {
                        basic[*k] -= sys.offsets.toff[g];
                    }
                }
                basic
            }
            _ => *sys.pos,
        };
        let wcs = |k: usize| {
            let mut basic = *sys.pos;
            for (b, t) in basic.iter_mut().zip(&sys.offsets.tool) {
                *b -= t;
            }
            sys.offsets.frame.unapply(&sys.cfg.geo_axes, &basic).map_or(f64::NAN, |w| w[k])
        };
        let actual_wcs = |k: usize| {
            let mut basic = main_run_basic();
            for (b, t) in basic.iter_mut().zip(&sys.offsets.tool) {
                *b -= t;
            }
            sys.offsets.frame.unapply(&sys.cfg.geo_axes, &basic).map_or(f64::NAN, |w| w[k])
        };
        if let Some(v) = crate::interp::orientation::vars::read(sys, name, indices, line) {
            return v;
        }
        if let Some(v) = crate::interp::spindles::vars::read(sys, name, indices, line) {
            return v;
        }
        if let Some(v) = super::run_vars::read(sys, name, indices, line) {
            return v;
        }
        if let Some(v) = super::process_vars::read(sys, name, indices, line) {
            return v;
        }
        if let Some(v) = super::cycle_vars::read(sys, name, indices, line) {
            return v;
        }
        if let Some(v) = crate::interp::eval::machine_data::read(sys.stored, sys.cfg, name, indices, line) {
            return v;
        }
        if let Some(v) = sys.plc.read(name, indices, line) {
            return v;
        }
        if let Some(v) = sys.io.read(name, indices, line) {
            return v;
        }
        if let Some(v) = sys.sync.read(name, indices, line) {
            return v;
        }
        if let Some(v) = sys.measured.read(sys.cfg, name, indices, line) {
            return v;
        }
        Ok(match name {
            "$P_TOOLNO" => Value::Int(sys.offsets.t.into()),
            "$P_TOOL" => Value::Int(sys.offsets.d.into()),
            "$P_TOOLP" => Value::Int(sys.offsets.prepared.into()),
            "GETT" => crate::interp::tools::management::gett(sys.cfg, indices, line)?,
            "$P_TOOLL" => super::cycle_vars::tool_length(sys, indices, line)?,
            "$P_AD" => super::cycle_vars::active_edge_param(sys, indices, line)?,
            "$P_TOOLEXIST" => crate::interp::tools::management::tool_exists(sys.cfg, indices, line)?,
            "CHKDNO" => crate::interp::tools::dnumbers::chkdno(sys.cfg, indices, line)?,
            _ if crate::machine_data::tools_mgmt::ToolMgmtData::handles(name) => {
                crate::interp::tools::management::read(sys.cfg, name, indices, line)?
            }
            "$P_EP" => Value::Real(wcs(axis()?)),
            // Machine axes: through the active transformation, not the BCS. `$AA_IM` (and the
            // encoder's `$VA_IM`) is the actual value, the setpoint less the following error of
            // the servo model (channel/servo.rs); `$AA_IPO` the interpolator's setpoint.
            "$AA_IM" | "$VA_IM" | "$AA_IPO" => {
                let k = machine_axis()?;
                let setpoint = match &sys.sync.machine {
                    // The main run stands elsewhere than programmed (STOPREOF, command axes).
                    Some(machine) => machine[k],
                    None => crate::interp::compensation::toff::machine_in_force(
                        sys.offsets.trafo.as_ref(),
                        sys.trafo.machine(),
                        sys.pos,
                        &sys.offsets.toff,
                        &sys.cfg.geo_axes,
                    )[k],
                };
                let v = if name == "$AA_IPO" { setpoint } else { setpoint - sys.lag[k] };
                // A modulo rotary axis reads within its modulo range, as the display shows it
                // (the machine axis' range: TRANSMIT's C under its virtual Y).
                Value::Real(match sys.trafo.base_config().unwrap_or(sys.cfg).axis(k).modulo {
                    Some((start, range)) => start + (v - start).rem_euclid(range),
                    None => v,
                })
            }
            // Chained transformation: layer 1 is the output of the first member, the last layer
            // the machine axes; without a chain there is only the machine layer.
            "$AA_ITR" => {
                let (k, layer) = match indices {
                    [Value::Axis(a) | Value::Str(a), l] => (
                        sys.cfg.program_axis(a).ok_or_else(|| Alarm::unknown_name(line, &format!("{name}[{a}]")))?,
                        l.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?,
                    ),
                    _ => return Err(Alarm::index_error(line, name, "needs an axis and a layer")),
                };
                let machine = sys.trafo.machine().unwrap_or(sys.pos);
                Value::Real(match (layer, sys.trafo.intermediate()) {
                    (1, Some(mid)) => mid[k],
                    (1, None) | (2, Some(_)) => machine[k],
                    _ => return Err(Alarm::index_error(line, name, &format!("no transformation layer {layer}"))),
                })
            }
            "$AA_IBC" => {
                let k = machine_axis()?;
                let machine = sys.trafo.machine().unwrap_or(sys.pos);
                Value::Real(sys.trafo.intermediate().map_or(machine[k], |mid| mid[k]))
            }
            "$AA_IB" => {
                let k = axis()?;
                Value::Real(main_run_basic()[k] - sys.offsets.tool[k])
            }
            // A modulo rotary axis reads within its modulo range in the WCS too, as the
            // display shows it (the way to 0 from 300 the short way ends at 360 ≡ 0).
            "$AA_IW" => {
                let k = axis()?;
                let v = actual_wcs(k);
                Value::Real(match sys.cfg.axis(k).modulo {
                    Some((start, range)) => start + (v - start).rem_euclid(range),
                    None => v,
                })
            }
            // The axis' velocity in the main run: 0 at rest, which the wait for the main run
            // gives but for command and positioning axes and STOPREOF.
            "$AA_VACTM" => Value::Real(sys.sync.velocity[machine_axis()?]),
            "$AA_TOFF" => {
                let k = axis()?;
                let dir = sys.cfg.geo_axes.iter().position(|g| *g == Some(k)).ok_or_else(|| {
                    Alarm::index_error(line, name, "needs a tool direction X, Y or Z (a geometry axis)")
                })?;
                Value::Real(sys.offsets.toff[dir])
            }
            // Seconds since the start of the block: preparation after a preprocessing stop
            // reads it at the block's start.
            "$AC_TIME" => Value::Real(0.0),
            "$P_GG" => {
                let group = match indices {
                    [g] => g.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?,
                    _ => return Err(Alarm::index_error(line, name, "needs one G group number")),
                };
                if group == 29 {
                    return Ok(Value::Int(sys.spindles.diameter.mode.position().into()));
                }
                Value::Int(
                    g_group_index(sys.modal, sys.holder, group)
                        .ok_or_else(|| Alarm::index_error(line, name, &format!("G group {group} is not modelled")))?,
                )
            }
            _ if name.starts_with("$TC_DP") => tool_param(sys.cfg, name, indices, line)?,
            _ if crate::machine_data::chains::is_chain_name(name) => {
                // The axes of the chain elements are the real ones, not the transformation's.
                let axes = sys.trafo.base_config().unwrap_or(sys.cfg);
                chain_datum(sys.cfg, axes, name, indices, line)?
            }
            _ if name.starts_with("$TC_CARR") => carrier_param(sys.cfg, name, indices, line)?,
            "$P_TCANG" => {
                let n = match indices {
                    [n] => n.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?,
                    _ => return Err(Alarm::index_error(line, name, "needs one index 1..4")),
                };
                let h = sys.holder;
                let second = h.second.unwrap_or([0.0; 2]);
                Value::Real(match n {
                    1 | 2 if h.number != 0 => h.angles[n as usize - 1],
                    3 | 4 if h.number != 0 => second[n as usize - 3],
                    1..=4 => 0.0,
                    _ => return Err(Alarm::index_error(line, name, &format!("index {n} (1..4)"))),
                })
            }
            "$P_TCSOL" => Value::Int(if sys.holder.number != 0 { sys.holder.solutions.into() } else { 0 }),
            "$P_TCNUM" => Value::Int(sys.holder.number.into()),
            _ if name == "$P_ACTFRAME"
                || crate::interp::frames::vars::ChainFrame::of(name).is_some()
                || stored_frames(name) =>
            {
                let stored = |list: &[crate::machine_data::FrameData]| {
                    let (n, rest) = indices
                        .split_first()
                        .ok_or_else(|| Alarm::index_error(line, name, "needs the frame number"))?;
                    let n = n.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
                    let data = usize::try_from(n)
                        .ok()
                        .and_then(|n| list.get(n))
                        .ok_or_else(|| Alarm::index_error(line, name, &format!("frame {n} does not exist")))?;
                    Ok::<_, Alarm>((Frame::from_data(data, &sys.cfg.geo_axes, sys.cfg.frame_angles), rest))
                };
                let (frame, rest) = match name {
                    "$P_ACTFRAME" => (sys.offsets.frame.clone(), indices),
                    "$P_UIFR" => stored(&sys.cfg.work_offsets)?,
                    "$P_CHBFR" => stored(&sys.cfg.base_frames)?,
                    "$P_NCBFR" => stored(&sys.cfg.ncu_base_frames)?,
                    "$P_UBFR" => (
                        sys.cfg.base_frames.first().map_or_else(Frame::identity, |f| {
                            Frame::from_data(f, &sys.cfg.geo_axes, sys.cfg.frame_angles)
                        }),
                        indices,
                    ),
                    _ => {
                        let which = crate::interp::frames::vars::ChainFrame::of(name).expect("checked above");
                        (sys.chain_frame(which), indices)
                    }
                };
                match rest {
                    [] => Value::Frame(Box::new(frame)),
                    [axis, component] => frame_component(sys, &frame, name, axis, component, line)?,
                    _ => return Err(Alarm::index_error(line, name, "a frame takes [axis, TR|FI|RT|SC|MI]")),
                }
            }
            _ => return Err(Alarm::unknown_name(line, name)),
        })
    }
}

/// The stored frames of the data management a program reads by number.
fn stored_frames(name: &str) -> bool {
    matches!(name, "$P_UIFR" | "$P_CHBFR" | "$P_NCBFR" | "$P_UBFR")
}

/// `$NK_…[i]` / `$NT_…[n, k]`: a kinematic chain datum as stored (written values are visible
/// at once, like tool data; the transformations built from them change with NEWCONF).
fn chain_datum(
    cfg: &MachineConfig,
    axes: &MachineConfig,
    name: &str,
    indices: &[Value],
    line: u32,
) -> Result<Value, Alarm> {
    let indices =
        indices.iter().map(|v| v.as_i64().map_err(|e| Alarm::type_error(line, &e.0))).collect::<Result<Vec<_>, _>>()?;
    if name == "$NT_ROT_AX_CNT" {
        // Read only: the rotary axes of the workpiece (k = 0) or the tool (k = 1) subchain.
        let [n, k] = indices[..] else { return Err(Alarm::index_error(line, name, "needs [n, k]")) };
        if !(0..cfg.kin_counts.1 as i64).contains(&n) || !(0..=1).contains(&k) {
            return Err(Alarm::index_error(
                line,
                name,
                &format!("[{n},{k}]: n 0..{}, k 0..1", cfg.kin_counts.1 as i64 - 1),
            ));
        }
        let count = crate::machine_data::chains::rot_ax_cnt(
            &cfg.kin,
            &cfg.kin_build,
            &axes.channel_axes,
            &axes.machine_axes,
            n as usize,
            k as usize,
        );
        return Ok(Value::Int(count as i64));
    }
    let value = cfg.kin.read(name, &indices, cfg.kin_counts).map_err(|e| match e {
        _ if e.contains("no kinematic chain datum") => Alarm::unknown_name(line, name),
        _ => Alarm::index_error(line, name, &e),
    })?;
    Ok(match value {
        crate::machine_data::Value::Str(s) => Value::Str(s),
        crate::machine_data::Value::Real(r) => Value::Real(r),
        crate::machine_data::Value::Int(n) => Value::Int(n),
        crate::machine_data::Value::Bool(b) => Value::Bool(b),
    })
}

/// `$TC_CARRn[m]`: one toolholder parameter as stored (0 / "" for a holder without data).
fn carrier_param(cfg: &MachineConfig, name: &str, indices: &[Value], line: u32) -> Result<Value, Alarm> {
    use crate::machine_data::carrier::{ParamKind, param_kind};
    let n: u32 = name[8..].parse().map_err(|_| Alarm::unknown_name(line, name))?;
    let kind = param_kind(n).ok_or_else(|| Alarm::unknown_name(line, name))?;
    let [m] = indices else { return Err(Alarm::index_error(line, name, "needs [toolholder]")) };
    let m = m.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
    let c = u32::try_from(m).ok().and_then(|m| cfg.carriers.get(&m));
    let Some(c) = c else {
        return Ok(match kind {
            ParamKind::Kind => Value::Str("T".into()),
            ParamKind::Str | ParamKind::Axis => Value::Str(String::new()),
            ParamKind::Int => Value::Int(0),
            ParamKind::Real => Value::Real(0.0),
        });
    };
    let v3 = |v: &[f64; 3], first: u32| v[(n - first) as usize];
    Ok(match n {
        1..=3 => Value::Real(v3(&c.l_basic[0], 1)),
        4..=6 => Value::Real(v3(&c.l_basic[1], 4)),
        7..=9 => Value::Real(v3(&c.v[0], 7)),
        10..=12 => Value::Real(v3(&c.v[1], 10)),
        13 | 14 => Value::Real(c.angles[(n - 13) as usize]),
        15..=17 => Value::Real(v3(&c.l_basic[2], 15)),
        18..=20 => Value::Real(v3(&c.l_basic[3], 18)),
        21 | 22 => c.axes[(n - 21) as usize].clone().map_or(Value::Int(0), Value::Axis),
        23 => Value::Str(
            match c.kind {
                crate::machine_data::CarrierKind::Tool => "T",
                crate::machine_data::CarrierKind::Part => "P",
                crate::machine_data::CarrierKind::Mixed => "M",
            }
            .into(),
        ),
        24 | 25 => Value::Real(c.offsets_basic[(n - 24) as usize]),
        26 | 27 => Value::Real(c.hirth[(n - 26) as usize].map_or(0.0, |h| h.offset)),
        28 | 29 => Value::Real(c.hirth[(n - 28) as usize].map_or(0.0, |h| h.increment)),
        30 | 31 => Value::Real(c.limits[(n - 30) as usize].map_or(0.0, |l| l.0)),
        32 | 33 => Value::Real(c.limits[(n - 32) as usize].map_or(0.0, |l| l.1)),
        34 => Value::Str(c.name.clone()),
        35 | 36 => Value::Str(c.axis_names[(n - 35) as usize].clone()),
        37 => Value::Int(c.control),
        38..=40 => Value::Real(c.retract[(n - 38) as usize]),
        41..=43 => Value::Real(v3(&c.l_fine[0], 41)),
        44..=46 => Value::Real(v3(&c.l_fine[1], 44)),
        55..=57 => Value::Real(v3(&c.l_fine[2], 55)),
        58..=60 => Value::Real(v3(&c.l_fine[3], 58)),
        _ => Value::Real(c.offsets_fine[(n - 64) as usize]),
    })
}

fn tool_param(cfg: &MachineConfig, name: &str, indices: &[Value], line: u32) -> Result<Value, Alarm> {
    let p = crate::machine_data::tool_orient::slot(&name[6..]).ok_or_else(|| Alarm::unknown_name(line, name))?;
    let (t, d) = match indices {
        [t, d] => (t.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?, d),
        // A flat D number (MD18102 = 1): `$TC_DPx[d]`.
        [d] => (0, d),
        _ => return Err(Alarm::index_error(line, name, "needs [tool, edge]")),
    };
    let d = d.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
    let edge = u32::try_from(t).ok().zip(u32::try_from(d).ok()).and_then(|k| cfg.tools.get(&k));
    Ok(Value::Real(edge.map_or(0.0, |e| e[p])))
}

/// Position of the active G function within its group, numbered as `$P_GG` reports it.
fn g_group_index(m: &Modal, h: &crate::interp::tools::toolholder::Holder, group: i64) -> Option<i64> {
    use crate::interp::tools::toolholder::{CutMode, TcoMode};
    match group {
        // Group 22: CUT2D 1 (the reset value); CUT3DFS 4, CUT3DFF 5, CUT2DF 6 are this product's
        // numbering (the consulted sources do not list the group). Group 42: TCOABS 1, TCOFR 2,
        // TCOFRY 4, TCOFRX 5 (TCOFRZ reads as TCOFR). Group 52: PAROT 1, PAROTOF 2. Group 53: P7.
        22 => {
            return Some(match h.cut {
                CutMode::Cut2d => 1,
                CutMode::Cut3dFs => 4,
                CutMode::Cut3dFf => 5,
                CutMode::Cut2dF => 6,
            });
        }
        42 => {
            return Some(match h.tco {
                TcoMode::Abs => 1,
                TcoMode::Frame(2) => 2,
                TcoMode::Frame(1) => 4,
                TcoMode::Frame(_) => 5,
            });
        }
        52 => return Some(if h.parot { 1 } else { 2 }),
        // Group 21: BRISK 1, SOFT 2, DRIVE 3. Group 24: FFWOF 1, FFWON 2. Group 59: DYNNORM 1,
        // DYNPOS 2, DYNROUGH 3, DYNSEMIFIN 4, DYNFINISH 5.
        21 => return Some(m.dynamics.profile as i64 + 1),
        24 => return Some(i64::from(m.dynamics.ffw) + 1),
        59 => return Some(m.dynamics.mode as i64 + 1),
        // Group 30: COMPOF 1, COMPON 2, COMPCURV 3, COMPCAD 4, COMPSURF 5.
        30 => return Some(m.path.compressor as i64 + 1),
        // Group 61: ORISOF 1 (the reset value), ORISON 2.
        61 => return Some(i64::from(m.path.orison) + 1),
        53 => return Some(h.g53),
        // Group 1's spline types: ASPLINE 6, BSPLINE 7, CSPLINE 8, POLY 9. Groups 19/20: BNAT/
        // ENAT 1, BTAN/ETAN 2, BAUTO/EAUTO 3. Group 43: G140..G143 1..4. Group 44: G340 1, G341 2.
        1 if m.spline.kind.is_some() => {
            use crate::interp::path_control::spline::Kind;
            return m.spline.kind.map(|k| match k {
                Kind::Akima => 6,
                Kind::BSpline => 7,
                Kind::Cubic => 8,
                Kind::Poly => 9,
            });
        }
        19 | 20 => {
            use crate::interp::path_control::spline::Transition;
            let t = if group == 19 { m.spline.begin } else { m.spline.end };
            return Some(match t {
                Transition::Natural => 1,
                Transition::Tangent => 2,
                Transition::Auto => 3,
            });
        }
        43 => return Some(m.sar.side as i64 + 1),
        44 => return Some(i64::from(m.sar.in_plane) + 1),
        _ => {}
    }
    Some(match group {
        // CIP 5, CT 15: the control's numbers of G group 1.
        1 => match (m.motion, m.circle_form) {
            (MotionMode::Rapid, _) => 1,
            (MotionMode::Linear, _) => 2,
            (MotionMode::Cw | MotionMode::Ccw, CircleForm::ThroughPoint) => 5,
            (MotionMode::Cw | MotionMode::Ccw, CircleForm::Tangent) => 15,
            (MotionMode::Cw, CircleForm::Standard) => 3,
            (MotionMode::Ccw, CircleForm::Standard) => 4,
        },
        6 => match m.plane {
            Plane::G17 => 1,
            Plane::G18 => 2,
            Plane::G19 => 3,
        },
        8 => match m.work_offset {
            0 => 1,
            n => n as i64 + 1,
        },
        10 => {
            if m.exact_stop {
                1
            } else {
                m.path.group10()
            }
        }
        12 => m.path.group12(),
        13 => match (m.inch, m.inch_feed) {
            (true, false) => 1,
            (false, false) => 2,
            (true, true) => 3,
            (false, true) => 4,
        },
        14 => {
            if m.absolute {
                1
            } else {
                2
            }
        }
        15 => {
            if m.feed_per_rev {
                3
            } else {
                2
            }
        }
        // Group 54, the reference of the tool rotation: ORIROTA 1, ORIROTR 2, ORIROTT 3, ORIROTC 4.
        54 => {
            use crate::interp::orientation::rotation::RotReference as R;
            match m.ori.rotation {
                R::Absolute => 1,
                R::Plane => 2,
                R::OriChange => 3,
                R::PathTangent => 4,
            }
        }
        _ => return None,
    })
}

/// One component of a frame: `TR` translation (FI fine is part of it), `RT` RPY angle about a
/// geometry axis, `SC` scale factor, `MI` mirror (1 when mirrored).
fn frame_component(
    sys: &SysView,
    frame: &Frame,
    name: &str,
    axis: &Value,
    component: &Value,
    line: u32,
) -> Result<Value, Alarm> {
    let (Value::Axis(a) | Value::Str(a)) = axis else {
        return Err(Alarm::index_error(line, name, "first index is an axis"));
    };
    let k = sys.cfg.program_axis(a).ok_or_else(|| Alarm::unknown_name(line, a))?;
    let g = sys.cfg.geo_axes.iter().position(|x| *x == Some(k));
    let column = |g: usize| (0..3).map(|r| frame.lin[r][g]).collect::<Vec<_>>();
    let scale = |g: usize| column(g).iter().map(|x| x * x).sum::<f64>().sqrt();
    Ok(Value::Real(match (component.as_text().as_str(), g) {
        ("TR", _) => frame.trans[k],
        ("FI", _) => 0.0,
        ("RT", Some(g)) => {
            // The unscaled rotation, read back in the convention of MD10600.
            let s = [scale(0), scale(1), scale(2)];
            let m: [[f64; 3]; 3] = std::array::from_fn(|r| std::array::from_fn(|c| frame.lin[r][c] / s[c]));
            crate::interp::frames::frame::angles_of(sys.cfg.frame_angles, &m)[g]
        }
        ("RT", None) => 0.0,
        ("SC", Some(g)) => scale(g),
        ("SC", None) => frame.factor[k].abs(),
        ("MI", Some(g)) => f64::from(u8::from(frame.lin[g][g] < 0.0)),
        ("MI", None) => f64::from(u8::from(frame.factor[k] < 0.0)),
        (other, _) => return Err(Alarm::index_error(line, name, &format!("unknown frame component {other}"))),
    }))
}

//! The interpreter's side of the kinematic transformations: the selection words TRANSMIT,
//! TRACYL, TRAANG and TRAFOOF, the geometry-axis reassignment while one is active, the tool
//! length taken into it, and the planning of each block in the BCS.
//!
//! While a transformation is active the interpreter works on a derived configuration in which
//! every channel axis that carries a Cartesian coordinate (`$MC_TRAFO_GEOAX_ASSIGN_TAB_n`) is a
//! virtual linear axis named like its geometry axis: `Y` then addresses TRANSMIT's rotary axis
//! slot, and the rotary axis' own name is no longer defined (alarm 12550), as the rotary axis is
//! "occupied by a geometry axis" (Programming Manual). Moves are prepared in the BCS (tool tip)
//! and planned per block by [`crate::kinematics::plan`] against the real machine axes.

use std::sync::Arc;

use crate::alarm::{Alarm, Clear};
use crate::interp::modal::PtpMode;
use crate::interp::{Interpreter, Item};
use crate::kinematics::plan::{self, PlanError, plan_block};
use crate::kinematics::{self, ActiveTrafo, AnyTrafo, SelectArgs, Transformation, Vec3};
use crate::lang::{Block, Expr, Word};
use crate::machine_data::{ChannelAxis, MachineAxis, MachineConfig, TrafoKind, TrafoParams};
use crate::motion::{AxisLimit, AxisVec, Feed, Move, Path};

/// The words this module handles; `modal::collect` lets them through.
pub fn is_keyword(name: &str) -> bool {
    matches!(name, "TRANSMIT" | "TRACYL" | "TRAANG" | "TRAORI" | "TRACON" | "TRAFOOF" | "TRAFOON")
}

/// A selection or deselection programmed in a block.
#[derive(Debug, Clone, PartialEq)]
pub enum Selection {
    Off,
    On {
        kind: TrafoKind,
        n: usize,
        args: SelectArgs,
    },
    /// `TRAFOON("name", ...)`: a transformation defined by kinematic chains, by `$NT_NAME`.
    Named {
        name: String,
        args: SelectArgs,
    },
}

/// The selection word of `block`, with its arguments evaluated by `eval`.
pub fn selection(block: &Block, eval: impl Fn(&Expr) -> Result<f64, Alarm>) -> Result<Option<Selection>, Alarm> {
    let line = block.line;
    let mut found = None;
    for word in &block.words {
        let Word::Keyword { name, args } = word else { continue };
        if !is_keyword(name) {
            continue;
        }
        if found.is_some() {
            return Err(Alarm::syntax(line, "only one transformation selection per block"));
        }
        // An omitted argument (`TRAANG(,2)`) arrives as the parser's `_OMITTED` marker.
        let arg = |i: usize| -> Result<Option<f64>, Alarm> {
            match args.get(i) {
                None => Ok(None),
                Some(Expr::Call(n, a)) if n == "_OMITTED" && a.is_empty() => Ok(None),
                Some(e) => eval(e).map(Some),
            }
        };
        let data_set = |v: Option<f64>| -> Result<usize, Alarm> {
            match v {
                None => Ok(1),
                Some(n) if n == 1.0 || n == 2.0 => Ok(n as usize),
                Some(n) => Err(Alarm::value_out_of_range(line, &format!("{name} data set {n} (1 or 2)"))),
            }
        };
        let max_args = match name.as_str() {
            "TRAFOOF" => 0,
            "TRANSMIT" => 1,
            "TRAANG" => 2,
            // TRAORI(n, x, y, z): the offsets of the orientation axes (5th and 6th parameter)
            // are not modelled.
            "TRAORI" | "TRACON" => 4,
            // TRAFOON(name, d, k): the diameter and groove-wall mode are TRACYL_K's.
            _ => 3,
        };
        if args.len() > max_args {
            return Err(Alarm::syntax(line, &format!("{name} takes at most {max_args} parameter(s)")));
        }
        found = Some(match name.as_str() {
            "TRAFOOF" => Selection::Off,
            "TRAFOON" => {
                let Some(Expr::Str(trafo)) = args.first() else {
                    return Err(Alarm::syntax(
                        line,
                        "TRAFOON needs the transformation name as a string, TRAFOON(\"name\")",
                    ));
                };
                let groove_wall = arg(2)?.map(|k| k == 1.0);
                Selection::Named {
                    name: trafo.clone(),
                    args: SelectArgs { diameter: arg(1)?, groove_wall, ..SelectArgs::default() },
                }
            }
            "TRANSMIT" => {
                Selection::On { kind: TrafoKind::Transmit, n: data_set(arg(0)?)?, args: SelectArgs::default() }
            }
            "TRACYL" => {
                let diameter = arg(0)?.ok_or_else(|| Alarm::syntax(line, "TRACYL needs the working diameter"))?;
                let groove_wall = match arg(2)? {
                    None => None,
                    Some(k) if k == 0.0 || k == 1.0 => Some(k == 1.0),
                    Some(k) => return Err(Alarm::value_out_of_range(line, &format!("TRACYL groove-wall mode {k}"))),
                };
                Selection::On {
                    kind: TrafoKind::Tracyl,
                    n: data_set(arg(1)?)?,
                    args: SelectArgs { diameter: Some(diameter), groove_wall, ..SelectArgs::default() },
                }
            }
            "TRACON" => {
                let n = arg(0)?.ok_or_else(|| Alarm::syntax(line, "TRACON needs the number of the chain"))?;
                Selection::On {
                    kind: TrafoKind::Tracon,
                    n: data_set(Some(n))?,
                    args: SelectArgs { chain: [arg(1)?, arg(2)?, arg(3)?], ..SelectArgs::default() },
                }
            }
            "TRAORI" => {
                let base_orient = match (arg(1)?, arg(2)?, arg(3)?) {
                    (None, None, None) => None,
                    (x, y, z) => Some([x.unwrap_or(0.0), y.unwrap_or(0.0), z.unwrap_or(0.0)]),
                };
                Selection::On {
                    kind: TrafoKind::Traori,
                    n: data_set(arg(0)?)?,
                    args: SelectArgs { base_orient, ..SelectArgs::default() },
                }
            }
            _ => Selection::On {
                kind: TrafoKind::Traang,
                n: data_set(arg(1)?)?,
                args: SelectArgs { angle: arg(0)?, ..SelectArgs::default() },
            },
        });
    }
    Ok(found)
}

/// 14401: the programmed transformation is not configured.
fn not_available(line: u32, what: &str) -> Alarm {
    Alarm {
        number: 14401,
        message: format!("Channel 1 block {line} transformation not available ({what})"),
        line: Some(line),
        clear: Clear::Reset,
    }
}

/// Why `TRAFOON("name")` finds no data set: no record has the name, or its type is one this
/// product stores but does not build.
fn unbuilt_reason(cfg: &MachineConfig, name: &str) -> String {
    match crate::machine_data::chains::type_of(&cfg.kin, name).as_deref() {
        None => format!("\"{name}\" is no transformation defined by kinematic chains"),
        Some("TRACON_K") => format!(
            "\"{name}\" is TRACON_K, which chains an Open Architecture (OA) transformation with a standard one; \
             OA transformations are not modelled, so the chain cannot be selected"
        ),
        Some("TRAORI_STAT") => {
            format!("\"{name}\" is TRAORI_STAT, whose static orientation transformation is not modelled")
        }
        Some("TRAORI_DYN" | "TRANSMIT_K" | "TRACYL_K" | "TRAANG_K") => {
            format!("\"{name}\" is not active yet: NEWCONF or a reset activates written chain data")
        }
        Some(ty) => format!("\"{name}\" ({ty}) is a type of transformation that is not modelled"),
    }
}

/// 21617: the machine stands on the side of the pole that `TRANSMIT_POLE_SIDE_FIX` excludes,
/// so the block could only start by traversing the pole, which the transformation forbids.
fn pole_side_fixed(line: u32) -> Alarm {
    Alarm {
        number: 21617,
        message: format!("Channel 1 block {line} transformation does not allow to traverse the pole"),
        line: Some(line),
        clear: Clear::Reset,
    }
}

/// 21619: a motion into the working-area limitation of TRANSMIT; the block is not executed.
pub fn working_area(line: u32) -> Alarm {
    Alarm {
        number: 21619,
        message: format!("Channel 1 block {line} transformation active: motion not possible (working-area limitation)"),
        line: Some(line),
        clear: Clear::Reset,
    }
}

/// 14092: an axis used in a way its current role does not allow (the spindle that a
/// transformation uses as rotary axis cannot turn in speed mode). Number chosen by this product
/// after the control's "axis is wrong axis type".
fn wrong_axis_type(line: u32, axis: &str) -> Alarm {
    Alarm {
        number: 14092,
        message: format!("Channel 1 block {line} axis {axis} is wrong axis type"),
        line: Some(line),
        clear: Clear::Reset,
    }
}

/// The interpreter's view of the active transformation.
#[derive(Debug, Clone, Default)]
pub(in crate::interp) struct TrafoState {
    active: Option<Box<Active>>,
    /// Counts selections and deselections, so the channel can see one happen.
    generation: u32,
}

#[derive(Debug, Clone)]
struct Active {
    trafo: ActiveTrafo,
    /// The selection's arguments, kept to rebuild the transformation after CORRTRAFO and to
    /// select it again after a restart (the tool's orientation in them is replaced by the
    /// active cutting edge's at every selection).
    args: SelectArgs,
    includes_tool: bool,
    /// The real configuration (machine axes, limits) and the derived one the words are read with.
    base: Arc<MachineConfig>,
    derived: Arc<MachineConfig>,
    /// Machine position at the end of the last prepared block.
    machine: AxisVec,
    /// BCS point where the last prepared move ended, so a jump in the axes that the radius
    /// compensation splits (TRACYL groove wall) gets a linking move.
    bcs: Option<AxisVec>,
    /// Blocks (move tags) to travel point to point, with their STAT= and TU= values.
    ptp: Vec<PtpBlock>,
}

/// A block to travel point to point (G group 49).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(in crate::interp) struct PtpBlock {
    pub tag: u32,
    pub stat: Option<u32>,
    pub tu: Option<u32>,
}

/// 10753: point-to-point travel with tool radius compensation active.
fn ptp_with_trc(line: u32) -> Alarm {
    Alarm {
        number: 10753,
        message: format!("Channel 1 block {line} PTP travel is not possible with tool radius compensation active"),
        line: Some(line),
        clear: Clear::Reset,
    }
}

impl TrafoState {
    /// The machine position at the end of what was prepared, while a transformation is active
    /// (without one it is the programmed position itself).
    pub fn machine(&self) -> Option<&AxisVec> {
        self.active.as_ref().map(|a| &a.machine)
    }

    /// The setpoints between the members of a chained transformation (`$AA_ITR[.., 1]`,
    /// `$AA_IBC`): the output of the first member.
    pub fn intermediate(&self) -> Option<AxisVec> {
        let a = self.active.as_ref()?;
        match &a.trafo.trafo {
            AnyTrafo::Tracon(t) => Some(t.intermediate(&a.machine)),
            _ => None,
        }
    }

    /// The tool orientation (unit, BCS) and, on a 6-axis kinematics, the rotation vector at the
    /// end of what was prepared; `None` without an orientation transformation.
    pub fn tool_vectors(&self) -> Option<(Vec3, Option<Vec3>)> {
        let a = self.active.as_ref()?;
        let o = a.trafo.trafo.orientation(&a.machine)?;
        let r = match &a.trafo.trafo {
            AnyTrafo::Traori(t) if t.third_slot().is_some() => Some(t.rotation_vector(&a.machine)),
            _ => None,
        };
        Some((o, r))
    }

    /// The rotary axis whose channel slot a Cartesian axis uses while active (TRANSMIT, TRACYL).
    pub fn rotary_slot(&self) -> Option<usize> {
        self.active.as_ref().and_then(|a| a.trafo.trafo.rotary_slot())
    }

    /// The real configuration (machine axes as configured) while a transformation is active.
    pub fn base_config(&self) -> Option<&MachineConfig> {
        self.active.as_ref().map(|a| &*a.base)
    }

    /// The configuration blocks are read with while a transformation is active.
    pub fn config(&self) -> Option<Arc<MachineConfig>> {
        self.active.as_ref().map(|a| a.derived.clone())
    }
}

/// `cfg` with the geometry axes of `trafo` and a virtual linear axis, named like the geometry
/// axis, in each channel slot that carries a Cartesian coordinate.
fn derive(cfg: &MachineConfig, trafo: &AnyTrafo) -> MachineConfig {
    let mut d = cfg.clone();
    let geo = trafo.geo_slots();
    let driven = trafo.machine_slots();
    d.geo_axes = geo;
    for (g, slot) in geo.iter().enumerate() {
        let Some(k) = *slot else { continue };
        if !driven.contains(&k) {
            continue;
        }
        let real = cfg.axis(k);
        d.machine_axes.push(MachineAxis {
            name: cfg.geo_names[g].clone(),
            rotary: false,
            modulo: None,
            spindle: None,
            spindle_only: false,
            spindle_posctrl_velo: 0.0,
            // The transformation planning limits the path by the real axes.
            max_velocity: f64::INFINITY,
            max_accel: f64::INFINITY,
            accel_overload: real.accel_overload,
            dynamics: crate::machine_data::dynamics::AxisDynamics::UNLIMITED,
            jog_velocity: real.jog_velocity,
            jog_rapid_velocity: real.jog_rapid_velocity,
            pos_velocity: real.pos_velocity,
            limit_minus: f64::NEG_INFINITY,
            limit_plus: f64::INFINITY,
        });
        d.channel_axes[k] = ChannelAxis { name: cfg.geo_names[g].clone(), machine_axis: d.machine_axes.len() - 1 };
    }
    d
}

impl Interpreter {
    /// Applies a selection or deselection (and checks the block against the active one).
    /// The frame is reset as by G500 at selection, as the control does.
    pub(in crate::interp) fn apply_transformation(
        &mut self,
        selection: Option<Selection>,
        block: &Block,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<(), Alarm> {
        if let Some(a) = &self.trafo.active {
            let rot = a.trafo.trafo.rotary_slot();
            let turns = block.words.iter().any(|w| matches!(w, Word::M(3 | 4)));
            if let Some(k) = rot.filter(|&k| turns && self.spindles.master() == Some(k)) {
                return Err(wrong_axis_type(line, &cfg.channel_axes[k].name));
            }
        }
        let Some(selection) = selection else { return Ok(()) };
        let derived = self.trafo.config();
        let moving = block.words.iter().any(|w| match w {
            Word::Address { name, .. } => {
                derived.as_deref().unwrap_or(cfg).program_axis(name).is_some()
                    || matches!(&**name, "I" | "J" | "K" | "CR")
            }
            _ => false,
        });
        if moving {
            return Err(Alarm::syntax(line, "a transformation is selected or deselected in a block without motion"));
        }
        let machine = self.transformation_machine_position();
        let persistent = cfg.reset_trafo.data_set.filter(|_| cfg.reset_trafo.persistent);
        match selection {
            // TRAFOOF returns to a persistent transformation.
            Selection::Off => match persistent {
                Some(n) if self.trafo.active.as_ref().is_some_and(|a| a.trafo.number == n) => {}
                Some(n) => self.select_data_set(n, &SelectArgs::default(), cfg, &machine, line, true)?,
                None => {
                    if self.trafo.active.take().is_some() {
                        self.pos = machine;
                        self.deselect_current_frame();
                        self.trafo.generation = self.trafo.generation.wrapping_add(1);
                    }
                }
            },
            Selection::Named { name, args } => {
                let set = cfg
                    .trafos
                    .iter()
                    .find(|s| s.chain.as_ref().is_some_and(|c| c.name == name))
                    .ok_or_else(|| not_available(line, &unbuilt_reason(cfg, &name)))?;
                self.select_data_set(set.number, &args, cfg, &machine, line, false)?;
            }
            Selection::On { kind, n, args } => {
                // A chain-defined transformation linked by $NT_TRAFO_INDEX wins over the
                // machine-data set of the conventional call.
                let chain = cfg
                    .trafos
                    .iter()
                    .find(|s| s.kind == kind && s.chain.as_ref().is_some_and(|c| c.conventional == Some(n)));
                let set = chain
                    .or_else(|| cfg.trafos.iter().filter(|s| s.kind == kind && s.chain.is_none()).nth(n - 1))
                    .ok_or_else(|| not_available(line, &format!("{} data set {n}", kind.name())))?;
                match persistent.filter(|p| *p != set.number && kind != TrafoKind::Tracon) {
                    None => self.select_data_set(set.number, &args, cfg, &machine, line, false)?,
                    // Next to a persistent transformation another one runs as the first member
                    // of the chain configured with it (the program names the first member).
                    Some(p) => {
                        let chain = cfg
                            .trafos
                            .iter()
                            .find(|c| matches!(c.params, TrafoParams::Tracon { members } if members == [set.number, p]))
                            .ok_or_else(|| {
                                not_available(
                                    line,
                                    &format!(
                                        "{} next to the persistent transformation (needs a TRACON chain)",
                                        kind.name()
                                    ),
                                )
                            })?;
                        let chain_args = SelectArgs { chain: [args.diameter.or(args.angle), None, None], ..args };
                        self.select_data_set(chain.number, &chain_args, cfg, &machine, line, false)?;
                    }
                }
            }
        }
        Ok(())
    }

    /// Makes data set `number` the active transformation, the machine standing at `machine`.
    /// A program's selection outside the pole takes the machine on whichever side it stands
    /// (TRANSMIT does not evaluate POLE_SIDE_FIX there); the `persistent` transformation
    /// (reset, TRAFOOF back to it) refuses the excluded side with 21617, as in the manual's
    /// persistent-transformation example ("also 2, causes alarm 21617").
    fn select_data_set(
        &mut self,
        number: usize,
        args: &SelectArgs,
        cfg: &MachineConfig,
        machine: &AxisVec,
        line: u32,
        persistent: bool,
    ) -> Result<(), Alarm> {
        let set = cfg
            .trafos
            .iter()
            .find(|s| s.number == number)
            .ok_or_else(|| not_available(line, &format!("data set {number}")))?;
        // The active cutting edge's own orientation ($TC_DPV3..5, $TC_DPVN3..5).
        let (tool_orient, tool_normal) = cfg
            .tools
            .get(&(self.offsets.t, self.offsets.d))
            .filter(|_| self.offsets.d != 0)
            .map_or((None, None), |e| crate::machine_data::tool_orient::vectors(e, plane_number(self.modal.plane)));
        let args = &SelectArgs { tool_orient, tool_normal, ..*args };
        let trafo = kinematics::build(set, cfg, args).map_err(|e| Alarm::value_out_of_range(line, &e.to_string()))?;
        if let Some(k) = trafo.rotary_slot().filter(|&k| self.spindles.turns(k)) {
            return Err(wrong_axis_type(line, &cfg.channel_axes[k].name));
        }
        let derived = Arc::new(derive(cfg, &trafo));
        let trafo = ActiveTrafo { trafo, tool: [0.0; 3], number: set.number };
        if !plan::takes_over(&trafo, machine, cfg)
            || (persistent && trafo.trafo.on_excluded_pole_side(machine, &trafo.tool))
        {
            return Err(pole_side_fixed(line));
        }
        self.pos = trafo.forward(machine);
        self.deselect_current_frame();
        self.trafo.active = Some(Box::new(Active {
            trafo,
            args: *args,
            includes_tool: set.includes_tool,
            base: Arc::new(cfg.clone()),
            derived,
            machine: *machine,
            bcs: None,
            ptp: Vec::new(),
        }));
        self.trafo.generation = self.trafo.generation.wrapping_add(1);
        Ok(())
    }

    /// Keeps the chain data and CORRTRAFO's limits of the configuration blocks are read with
    /// while a transformation is active (a copy made at selection) equal to the channel's, so
    /// `$NK_`/`$NT_` writes and CORRTRAFO corrections read back at once.
    pub(in crate::interp) fn refresh_derived_chain_data(&mut self, cfg: &MachineConfig) {
        let Some(a) = self.trafo.active.as_mut() else { return };
        if a.derived.kin != cfg.kin || a.derived.corr_limits != cfg.corr_limits {
            let d = Arc::make_mut(&mut a.derived);
            d.kin = cfg.kin.clone();
            d.corr_limits = cfg.corr_limits;
        }
    }

    /// The data-set number of the active transformation.
    pub(in crate::interp) fn active_data_set(&self) -> Option<usize> {
        self.trafo.active.as_ref().map(|a| a.trafo.number)
    }

    /// Puts `set` (the active data set, rebuilt after CORRTRAFO) in place of the active
    /// transformation at once: the machine stays where it is, the tool length taken into the
    /// transformation stays, the BCS position follows through the corrected model. The channel
    /// switches over at standstill, as for a selection.
    pub(in crate::interp) fn replace_active_set(
        &mut self,
        set: &crate::machine_data::TrafoDataSet,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<(), Alarm> {
        let Some(a) = self.trafo.active.as_mut() else { return Ok(()) };
        let trafo =
            kinematics::build(set, cfg, &a.args).map_err(|e| Alarm::value_out_of_range(line, &e.to_string()))?;
        a.trafo = ActiveTrafo { trafo, tool: a.trafo.tool, number: set.number };
        a.bcs = None;
        self.pos = a.trafo.forward(&a.machine);
        self.offsets.trafo = Some(a.trafo.clone());
        self.trafo.generation = self.trafo.generation.wrapping_add(1);
        Ok(())
    }

    /// Selecting and deselecting a transformation deselects the current frame, as a programmed
    /// G500 does, together with the programmable frame (TRANS, ROT ... of the program). A
    /// program selects its frames again afterwards (the manual's TRACYL sequence).
    fn deselect_current_frame(&mut self) {
        self.modal.work_offset = 0;
        *self.pframe = crate::interp::frames::frame::Frame::identity();
    }

    /// The active transformation's data set number and selection parameters, if one is active.
    pub(in crate::interp) fn active_selection(&self) -> Option<(usize, SelectArgs)> {
        self.trafo.active.as_ref().map(|a| (a.trafo.number, a.args))
    }

    /// Selects data set `number` with `args` again, the machine standing at `machine` (restart
    /// of a checkpoint whose transformation stays over reset), with the tool taken into it.
    pub(in crate::interp) fn reselect_transformation(
        &mut self,
        number: usize,
        args: &SelectArgs,
        cfg: &MachineConfig,
        machine: &AxisVec,
    ) -> Result<(), Alarm> {
        self.clear_transformation();
        self.pos = *machine;
        self.select_data_set(number, args, cfg, machine, 0, false)?;
        self.absorb_tool_into_transformation();
        Ok(())
    }

    /// The transformation after reset and program end: the active one stays (RESET_MODE_MASK
    /// bit 7), or the reset data set (TRAFO_RESET_VALUE) is selected, or none. The machine
    /// stands at `machine`. Data checked at activation cannot fail here; should it, the channel
    /// is left without transformation rather than with a half-built one.
    pub(in crate::interp) fn reset_transformation(&mut self, cfg: &MachineConfig, machine: &AxisVec) {
        if cfg.reset_trafo.keep_active && self.trafo.active.is_some() {
            self.sync_transformation(machine);
            self.absorb_tool_into_transformation();
            return;
        }
        self.clear_transformation();
        self.pos = *machine;
        if let Some(n) = cfg.reset_trafo.data_set {
            if self.select_data_set(n, &SelectArgs::default(), cfg, machine, 0, cfg.reset_trafo.persistent).is_err() {
                self.clear_transformation();
                self.pos = *machine;
            }
            self.absorb_tool_into_transformation();
        }
    }

    /// Moves the tool length of the geometry axes into the active transformation (when it
    /// includes the tool). A new tool leaves the machine where it is, so the tip moves.
    pub(in crate::interp) fn absorb_tool_into_transformation(&mut self) {
        // The offsets are written only where they change (see `Interpreter::shared_offsets`).
        let Some(a) = self.trafo.active.as_mut() else {
            if self.offsets.trafo.is_some() {
                self.offsets.trafo = None;
            }
            return;
        };
        let geo = a.trafo.trafo.geo_slots();
        let mut tool = [0.0; 3];
        if a.includes_tool {
            for (g, slot) in geo.iter().enumerate() {
                if let Some(k) = *slot {
                    tool[g] = self.offsets.tool[k];
                    if tool[g] != 0.0 {
                        self.offsets.tool[k] = 0.0;
                    }
                }
            }
        }
        if tool != a.trafo.tool {
            a.trafo.tool = tool;
            a.bcs = None;
            self.pos = a.trafo.forward(&a.machine);
        }
        if self.offsets.trafo.as_ref() != Some(&a.trafo) {
            self.offsets.trafo = Some(a.trafo.clone());
        }
    }

    /// With a transformation, replaces the prepared BCS moves of `out` (after radius
    /// compensation and corner shaping) by moves whose limits come from the machine axes
    /// (alarm 21619 for the working-area limitation, 10720 for a machine axis' software limit).
    pub(in crate::interp) fn transform_moves(&mut self, out: &mut Vec<Item>) -> Result<(), Alarm> {
        let Some(a) = self.trafo.active.as_mut() else { return Ok(()) };
        if !out.iter().any(|i| matches!(i, Item::Move { .. })) {
            return Ok(());
        }
        let mut result = Vec::with_capacity(out.len());
        let limits = AxisLimit::for_channel(&a.derived);
        for item in out.drain(..) {
            let Item::Move { mv, line, offsets } = item else {
                result.push(item);
                continue;
            };
            let plan = |a: &Active, mv: &Move| {
                plan_block(&a.trafo, mv, &a.machine, &a.base).map_err(|e| match e {
                    PlanError::Unreachable => working_area(line),
                    PlanError::SoftLimit { axis, plus } => Alarm::software_limit(line, &axis, plus),
                    PlanError::PoleSide => pole_side_fixed(line),
                })
            };
            if let Some(i) = a.ptp.iter().position(|p| p.tag == mv.tag) {
                let block = a.ptp.remove(i);
                let m = point_to_point(a, &mv, block, line)?;
                for k in a.trafo.trafo.orientation_slots().into_iter().flatten() {
                    self.pos[k] = m.path.end[k];
                }
                result.push(Item::Move { mv: m, line, offsets });
                continue;
            }
            let jump = a.bcs.filter(|b| b.iter().zip(&mv.path.start).any(|(x, y)| (x - y).abs() > 1e-6));
            if let Some(from) = jump {
                let path = Path::line(from, mv.path.start);
                let length = path.start.iter().zip(&path.end).map(|(x, y)| (y - x).powi(2)).sum::<f64>().sqrt();
                let feed = if mv.is_rapid() { Feed::Rapid } else { Feed::Path(mv.feed) };
                let link = Move::new(path, length, feed, &limits, true, mv.tag);
                let planned = plan(a, &link)?;
                a.machine = planned.end;
                result.extend(planned.moves.into_iter().map(|mv| Item::Move { mv, line, offsets: offsets.clone() }));
            }
            let planned = plan(a, &mv)?;
            if planned.irregular_velocity && !self.warnings.iter().any(|w| w.line == Some(line)) {
                self.warnings.push(Alarm::irregular_velocity(line));
            }
            let (moves, end) = (planned.moves, planned.end);
            a.machine = end;
            // The orientation axes end where the machine's continuity put them (a vector
            // interpolation may pass a pole into the other solution).
            let mut bcs_end = mv.path.end;
            for k in a.trafo.trafo.orientation_slots().into_iter().flatten() {
                bcs_end[k] = end[k];
                self.pos[k] = end[k];
            }
            a.bcs = Some(bcs_end);
            result.extend(moves.into_iter().map(|mv| Item::Move { mv, line, offsets: offsets.clone() }));
        }
        *out = result;
        Ok(())
    }

    /// The active transformation when it orients the tool, with the machine position at the
    /// end of what was prepared.
    pub(in crate::interp) fn orientation_transformation(&self) -> Option<(&ActiveTrafo, &AxisVec)> {
        let a = self.trafo.active.as_ref()?;
        a.trafo.trafo.orientation_slots().iter().any(Option::is_some).then_some((&a.trafo, &a.machine))
    }

    /// The orientation axes' rest positions of an active TRAORI (ORIRESET without values).
    pub(in crate::interp) fn orientation_rest(&self) -> Option<[f64; 3]> {
        match &self.trafo.active.as_ref()?.trafo.trafo {
            AnyTrafo::Traori(t) => Some(t.rest_positions()),
            _ => None,
        }
    }

    /// G07/G05 with an active TRAANG: the BCS end of the block turned into the start of an
    /// oblique plunge (G07: only Z moves, to the line through the programmed end along the
    /// inclined axis) or the plunge itself (G05: Z follows X along the inclined axis).
    pub(in crate::interp) fn oblique_plunge(
        &self,
        kind: crate::interp::modal::Oblique,
        start: &AxisVec,
        end: &mut AxisVec,
        line: u32,
    ) -> Result<(), Alarm> {
        let Some(AnyTrafo::Traang(t)) = self.trafo.active.as_ref().map(|a| &a.trafo.trafo) else {
            return Err(not_available(line, "G05/G07 oblique plunge needs an active TRAANG"));
        };
        let (x, z, tan) = t.plunge_axes();
        match kind {
            crate::interp::modal::Oblique::Approach => {
                end[z] += (start[x] - end[x]) * tan;
                end[x] = start[x];
            }
            crate::interp::modal::Oblique::Plunge => end[z] = start[z] + (end[x] - start[x]) * tan,
        }
        Ok(())
    }

    /// The TRACYL groove-wall slots when that offset is selected.
    pub(in crate::interp) fn groove_wall_axes(&self) -> Option<(usize, usize)> {
        match &self.trafo.active.as_ref()?.trafo.trafo {
            AnyTrafo::Tracyl(t) => t.groove_wall_axes(),
            _ => None,
        }
    }

    /// Marks the move of block `tag` for point-to-point travel when G group 49 asks for it and
    /// a transformation is active (alarm 10753 with radius compensation under PTP/PTPWOC; PTPG0
    /// then travels the Cartesian path).
    pub(in crate::interp) fn request_point_to_point(
        &mut self,
        tag: u32,
        rapid: bool,
        stat: Option<u32>,
        tu: Option<u32>,
    ) -> Result<(), Alarm> {
        let mode = self.modal.ptp;
        let Some(a) = self.trafo.active.as_mut() else { return Ok(()) };
        if !mode.applies(rapid) {
            return Ok(());
        }
        if self.modal.trc.is_some() {
            return if mode == PtpMode::PtpG0 { Ok(()) } else { Err(ptp_with_trc(tag)) };
        }
        a.ptp.push(PtpBlock { tag, stat, tu });
        Ok(())
    }

    /// Machine position at the end of what was prepared.
    pub(in crate::interp) fn transformation_machine_position(&self) -> AxisVec {
        self.trafo.active.as_ref().map_or(self.pos, |a| a.machine)
    }

    /// Counts selections and deselections prepared so far.
    pub fn transformation_generation(&self) -> u32 {
        self.trafo.generation
    }

    /// Takes over the machine position from the main run (after a selection executed, or at
    /// reset and program end); the programmed position follows through the active transformation.
    /// With an online tool offset in force the machine stands lengthened by it: the programmed
    /// position is taken back through the lengthened tool (and the prepared machine position
    /// is kept without the offset, as the blocks are prepared).
    pub fn sync_transformation(&mut self, machine: &AxisVec) {
        self.lane_memo.forget();
        let toff = self.offsets.toff;
        match self.trafo.active.as_mut() {
            Some(a) if toff != [0.0; 3] => {
                self.pos = a.trafo.lengthened(&toff).forward(machine);
                a.machine = a.trafo.inverse(&self.pos, machine).unwrap_or(*machine);
                a.bcs = None;
            }
            Some(a) => {
                a.machine = *machine;
                a.bcs = None;
                self.pos = a.trafo.forward(machine);
            }
            None => self.pos = *machine,
        }
    }

    /// Drops the active transformation (reset, program end).
    pub(in crate::interp) fn clear_transformation(&mut self) {
        if self.trafo.active.take().is_some() {
            self.trafo.generation = self.trafo.generation.wrapping_add(1);
        }
        self.offsets.trafo = None;
    }
}

/// The machine-space move of a point-to-point block: the BCS end point (with the orientation
/// solution STAT= picks and the turn ranges TU= asks for) transformed once, the machine axes
/// moving linearly together from where the last block left them.
///
/// STAT bit 0 selects between the two orientation solutions of the generic 5/6-axis TRAORI
/// relative to the start (Programming Manual, Job planning, Cartesian PTP travel): 0 (the
/// default) the rotary-axis positions at the shorter distance from the start positions, 1 those
/// at the greater distance. TU bit k (channel axis k+1) places a rotary orientation axis in
/// 0..360 (bit 0) or −360..0 (bit 1); without TU a modulo axis takes the shortest way.
fn point_to_point(a: &mut Active, mv: &Move, block: PtpBlock, line: u32) -> Result<Move, Alarm> {
    let mut end = mv.path.end;
    let slots = a.trafo.trafo.orientation_slots();
    if let (Some(stat), AnyTrafo::Traori(t)) = (block.stat, &a.trafo.trafo) {
        let o = t.orientation(&end).expect("TRAORI orients the tool");
        let both = t.solutions_at(&o, &end).map_err(|_| working_area(line))?;
        let pick = super::ptp_stat::nearer_first(both, &slots, &a.machine, &a.base)[(stat & 1) as usize];
        for (role, slot) in slots.iter().enumerate() {
            if let Some(k) = slot {
                end[*k] = pick[role];
            }
        }
    }
    match block.tu {
        Some(tu) => {
            for k in slots.iter().flatten() {
                let turned = end[*k].rem_euclid(360.0);
                end[*k] = if tu & (1 << k) != 0 && turned > 0.0 { turned - 360.0 } else { turned };
            }
        }
        None => super::ptp_stat::shortest_way(&mut end, &slots, &a.machine, &a.base),
    }
    let machine = match (block.stat, &a.trafo.trafo) {
        // TRANSMIT: STAT resolves the pole (see `Transmit::ptp_end`); TU has no meaning there.
        (Some(stat), AnyTrafo::Transmit(t)) => t.ptp_end(&end, &a.machine, &a.trafo.tool, stat),
        _ => a.trafo.inverse(&end, &a.machine),
    }
    .map_err(|_| working_area(line))?;
    for k in a.trafo.trafo.machine_slots() {
        let ax = a.base.axis(k);
        if ax.modulo.is_none() && (machine[k] > ax.limit_plus + 1e-9 || machine[k] < ax.limit_minus - 1e-9) {
            return Err(Alarm::software_limit(line, &ax.name, machine[k] > ax.limit_plus));
        }
    }
    let path = Path::line(a.machine, machine);
    let length = path.start.iter().zip(&path.end).map(|(x, y)| (y - x).powi(2)).sum::<f64>().sqrt();
    let feed = if mv.is_rapid() { Feed::Rapid } else { Feed::Path(mv.feed) };
    let mut m = Move::new(path, length, feed, &AxisLimit::for_channel(&a.base), mv.exact_stop, mv.tag);
    m.machine_space = true;
    a.machine = machine;
    a.bcs = Some(a.trafo.forward(&machine));
    Ok(m)
}

/// 17, 18 or 19 for G17, G18, G19.
fn plane_number(p: crate::interp::modal::Plane) -> u32 {
    match p {
        crate::interp::modal::Plane::G17 => 17,
        crate::interp::modal::Plane::G18 => 18,
        crate::interp::modal::Plane::G19 => 19,
    }
}

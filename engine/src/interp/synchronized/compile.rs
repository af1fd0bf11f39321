//! Compiles a parsed synchronized action ([`crate::lang::sync_action::SyncAction`]) into the
//! form the main run evaluates every IPO cycle: names resolved once (variables to
//! [`SyncVar`], axis names to channel axis indices, functions to [`Func`]), so the cycle does
//! no string work.
//!
//! Alarms, as the control raises them when it compiles the action in block preparation:
//! 12550 for a name that is not a variable of synchronized actions, 12584 for a variable a
//! synchronized action may read but not write, 12571 for an action not admissible (or not
//! modelled) in a synchronized action.

use super::flat::{Act, Code};
use crate::alarm::{Alarm, Clear};
use crate::lang::CoordMode;
use crate::lang::sync_action::{BinOp, Index, SAction, SExpr, SyncAction, SyncId, Trigger, VarRef};
use crate::machine_data::MachineConfig;

/// A synchronized action ready for the main run.
#[derive(Debug, Clone, PartialEq)]
pub struct SyncDef {
    pub id: Option<SyncId>,
    pub trigger: Trigger,
    pub condition: Option<CExpr>,
    pub actions: Vec<SyncAct>,
    /// The condition as written, for the state and the HMI.
    pub condition_text: String,
    /// The line that defined it.
    pub line: u32,
    /// The condition and the actions in the flat form the main run evaluates (`flat.rs`).
    pub flat_condition: Option<Code>,
    pub flat_actions: Vec<Act>,
}

impl SyncDef {
    /// True if an action deletes the distance to go (the next block then waits for the main
    /// run, so that it starts where the path was stopped).
    pub fn deletes_distance(&self) -> bool {
        self.actions.iter().any(|a| matches!(a, SyncAct::DelDtg))
    }

    /// True if an action ends the preprocessing stop after its motion block (STOPREOF).
    pub fn ends_preprocessing_stop(&self) -> bool {
        self.actions.iter().any(|a| matches!(a, SyncAct::StopReOf))
    }

    /// True if an action disables the read-in of blocks (RDISABLE).
    pub fn disables_read_in(&self) -> bool {
        self.actions.iter().any(|a| matches!(a, SyncAct::RDisable))
    }
}

/// An expression with its names resolved; booleans are 0/1.
#[derive(Debug, Clone, PartialEq)]
pub enum CExpr {
    Num(f64),
    Var(SyncVar),
    Neg(Box<CExpr>),
    Not(Box<CExpr>),
    Bin(BinOp, Box<CExpr>, Box<CExpr>),
    Func(Func, Vec<CExpr>),
}

/// The variables of synchronized actions. Lengths are in mm (the basic system), speeds in
/// mm/min, times in s, overrides in percent.
#[derive(Debug, Clone, PartialEq)]
pub enum SyncVar {
    /// `$AA_IM[ax]`: actual position, machine coordinates.
    AaIm(usize),
    /// `$AA_IW[ax]`: actual position, workpiece coordinates.
    AaIw(usize),
    /// `$AA_IPO[ax]`: the interpolator's setpoint, machine coordinates.
    AaIpo(usize),
    /// `$AA_VACTM[ax]`: axis speed (mm/min or deg/min) from the setpoints of the last cycle.
    AaVactm(usize),
    /// `$AA_OVR[ax]`: axial override.
    AaOvr(usize),
    /// `$AC_TIME`: seconds since the block started.
    AcTime,
    /// `$AC_PATH`: path distance travelled in the block.
    AcPath,
    /// `$AC_DTEB`: path distance to the end of the block.
    AcDteb,
    /// `$AC_VACTB`: path speed (mm/min).
    AcVactb,
    /// `$AC_OVR`: path override of this cycle.
    AcOvr,
    /// `$AC_DELT`: the path distance the last DELDTG deleted.
    AcDelt,
    AcTimer(Box<CExpr>),
    AcMarker(Box<CExpr>),
    AcParam(Box<CExpr>),
    R(Box<CExpr>),
    AIn(Box<CExpr>),
    AOut(Box<CExpr>),
    AIna(Box<CExpr>),
    AOuta(Box<CExpr>),
    /// `$AA_S[n]`: actual speed of spindle n (rev/min, signed: + = M3).
    AaS(Box<CExpr>),
}

/// The functions synchronized actions may call.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Func {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan2,
    Sqrt,
    Abs,
    Pot,
    Trunc,
    Round,
    Ln,
    Exp,
    MinVal,
    MaxVal,
}

/// One action.
#[derive(Debug, Clone, PartialEq)]
pub enum SyncAct {
    Set(SyncVar, CExpr),
    /// M/H output to the PLC; `S` a spindle speed (extension: spindle number, 0 the master).
    Aux {
        letter: char,
        extension: u32,
        value: CExpr,
    },
    DelDtg,
    /// A command axis or spindle motion: `POS[ax]=`, `MOV[ax]=`, `FA[ax]=`, `SPOS[n]=`
    /// (`axis`: the channel axis; for SPOS the spindle's).
    Command {
        kind: CommandKind,
        axis: usize,
        value: CExpr,
        mode: Option<CoordMode>,
    },
    /// `STOPREOF`: ends the preprocessing stop after the action's motion block.
    StopReOf,
    /// `RDISABLE`: no further block enters the main run in a cycle it runs.
    RDisable,
    /// `PRESETON(ax, value)`: the axis' machine position becomes `value`, without motion.
    Preset {
        axis: usize,
        value: CExpr,
    },
    /// `SETM(n)` (true) / `CLEARM(n)` (false): the channel's wait marker n.
    WaitMarker {
        set: bool,
        marker: CExpr,
    },
    /// `NAME` (a technology cycle): the program `NAME`, a sequence of actions run block by
    /// block from the main run (`interp/synchronized/technology.rs`).
    Cycle(String),
}

/// The motion words of synchronized actions (`channel/positioning_axes.rs` moves them).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CommandKind {
    /// `POS[ax]=v`: to a position (`IC`/`AC`/`DC`/`ACP`/`ACN`).
    Pos,
    /// `MOV[ax]=1/-1/0`: endless motion in the plus or minus direction, or stop.
    Mov,
    /// `FA[ax]=f`: the command axis' feed, mm/min (deg/min).
    Fa,
    /// `SPOS[n]=angle`: the spindle to an angle in position control.
    Spos,
}

/// Compiles `action` (defined at `line`) for the channel described by `cfg`.
pub fn compile(action: &SyncAction, cfg: &MachineConfig, line: u32) -> Result<SyncDef, Alarm> {
    let c = Compiler { cfg, line };
    // G70/G700 in the condition: its lengths are read in inch (the basic system is metric).
    let inch = matches!(action.units, Some(70 | 700));
    let condition = action.condition.as_ref().map(|e| c.expr(e, inch)).transpose()?;
    let actions: Vec<SyncAct> = action.actions.iter().map(|a| c.action(a)).collect::<Result<_, _>>()?;
    let sizes = &cfg.sync_sizes;
    let flat_condition = condition.as_ref().map(|e| super::flat::lower_sized(e, sizes));
    let flat_actions = actions.iter().map(|a| super::flat::lower_act(a, sizes)).collect();
    Ok(SyncDef {
        id: action.id,
        trigger: action.trigger,
        condition,
        actions,
        condition_text: action.condition_text.clone(),
        line,
        flat_condition,
        flat_actions,
    })
}

/// 12571: an action the control does not allow (or NCTwin does not model) in a synchronized action.
pub fn not_admissible(line: u32, what: &str) -> Alarm {
    Alarm {
        number: 12571,
        message: format!("Channel 1 block {line} {what} not admissible in motion synchronized action"),
        line: Some(line),
        clear: Clear::Reset,
    }
}

impl Compiler<'_> {
    /// `POS[ax]=`, `MOV[ax]=`, `FA[ax]=`, `SPOS[n]=`: the axis resolved, the coordinate mode
    /// (`IC(..)` ...) taken off the value. POSA is a program word only (12571).
    fn command(&self, word: &str, axis: &str, value: &SExpr) -> Result<SyncAct, Alarm> {
        let kind = match word {
            "POS" => CommandKind::Pos,
            "MOV" => CommandKind::Mov,
            "FA" => CommandKind::Fa,
            "SPOS" => CommandKind::Spos,
            _ => return Err(not_admissible(self.line, &format!("{word}[{axis}]"))),
        };
        let k = if kind == CommandKind::Spos {
            let spindle = match axis {
                "" => self.cfg.master_spindle,
                n => n.parse::<u32>().ok().and_then(|n| {
                    self.cfg.channel_axes.iter().position(|c| self.cfg.machine_axes[c.machine_axis].spindle == Some(n))
                }),
            };
            spindle.ok_or_else(|| Alarm::unknown_name(self.line, &format!("SPOS[{axis}]")))?
        } else {
            let k = self
                .cfg
                .program_axis(axis)
                .ok_or_else(|| Alarm::unknown_name(self.line, &format!("{word}[{axis}]")))?;
            if self.cfg.axis(k).spindle.is_some() {
                return Err(Alarm::sync_axis_type(Some(self.line), axis));
            }
            k
        };
        let (mode, value) = match value {
            SExpr::Call(f, args) if args.len() == 1 => match f.as_str() {
                "AC" => (Some(CoordMode::Ac), &args[0]),
                "IC" => (Some(CoordMode::Ic), &args[0]),
                "DC" => (Some(CoordMode::Dc), &args[0]),
                "ACP" => (Some(CoordMode::Acp), &args[0]),
                "ACN" => (Some(CoordMode::Acn), &args[0]),
                _ => (None, value),
            },
            _ => (None, value),
        };
        if mode.is_some() && matches!(kind, CommandKind::Mov | CommandKind::Fa)
            || matches!(mode, Some(CoordMode::Dc | CoordMode::Acp | CoordMode::Acn))
                && kind == CommandKind::Pos
                && self.cfg.axis(k).modulo.is_none()
        {
            return Err(Alarm::value_out_of_range(self.line, &format!("{word}[{axis}]")));
        }
        Ok(SyncAct::Command { kind, axis: k, value: self.expr(value, false)?, mode })
    }
}

struct Compiler<'a> {
    cfg: &'a MachineConfig,
    line: u32,
}

impl Compiler<'_> {
    fn expr(&self, e: &SExpr, inch: bool) -> Result<CExpr, Alarm> {
        Ok(match e {
            SExpr::Num(v) => CExpr::Num(*v),
            SExpr::Var(VarRef { name, index: None }) if let Some(c) = crate::interp::eval::nc_constants::real(name) => {
                CExpr::Num(c)
            }
            SExpr::Var(v) => {
                let var = self.var(v)?;
                let length = matches!(
                    var,
                    SyncVar::AaIm(_)
                        | SyncVar::AaIw(_)
                        | SyncVar::AaIpo(_)
                        | SyncVar::AcPath
                        | SyncVar::AcDteb
                        | SyncVar::AcDelt
                );
                if inch && length {
                    CExpr::Bin(BinOp::Div, Box::new(CExpr::Var(var)), Box::new(CExpr::Num(25.4)))
                } else {
                    CExpr::Var(var)
                }
            }
            SExpr::Neg(x) => CExpr::Neg(Box::new(self.expr(x, inch)?)),
            SExpr::Not(x) => CExpr::Not(Box::new(self.expr(x, inch)?)),
            SExpr::Bin(op, a, b) => CExpr::Bin(*op, Box::new(self.expr(a, inch)?), Box::new(self.expr(b, inch)?)),
            SExpr::Call(name, args) if name == "BOUND" => {
                // BOUND(min, max, value) = MINVAL(MAXVAL(value, min), max), as in the part
                // program: the flat code needs no function of three arguments.
                let [min, max, value] = args.as_slice() else {
                    return Err(Alarm::syntax(self.line, "BOUND needs 3 argument(s)"));
                };
                let (min, max, value) = (self.expr(min, inch)?, self.expr(max, inch)?, self.expr(value, inch)?);
                CExpr::Func(Func::MinVal, vec![CExpr::Func(Func::MaxVal, vec![value, min]), max])
            }
            SExpr::Call(name, args) => {
                let (f, n) = match name.as_str() {
                    "SIN" => (Func::Sin, 1),
                    "COS" => (Func::Cos, 1),
                    "TAN" => (Func::Tan, 1),
                    "ASIN" => (Func::Asin, 1),
                    "ACOS" => (Func::Acos, 1),
                    "ATAN2" => (Func::Atan2, 2),
                    "SQRT" => (Func::Sqrt, 1),
                    "ABS" => (Func::Abs, 1),
                    "POT" => (Func::Pot, 1),
                    "TRUNC" => (Func::Trunc, 1),
                    "ROUND" => (Func::Round, 1),
                    "LN" => (Func::Ln, 1),
                    "EXP" => (Func::Exp, 1),
                    "MINVAL" => (Func::MinVal, 2),
                    "MAXVAL" => (Func::MaxVal, 2),
                    _ => return Err(Alarm::unknown_name(self.line, name)),
                };
                if args.len() != n {
                    return Err(Alarm::syntax(self.line, &format!("{name} needs {n} argument(s)")));
                }
                CExpr::Func(f, args.iter().map(|a| self.expr(a, inch)).collect::<Result<_, _>>()?)
            }
        })
    }

    fn axis(&self, v: &VarRef) -> Result<usize, Alarm> {
        match &v.index {
            Some(Index::Axis(a)) => {
                self.cfg.program_axis(a).ok_or_else(|| Alarm::unknown_name(self.line, &format!("{}[{a}]", v.name)))
            }
            _ => Err(Alarm::index_error(self.line, &v.name, "needs one axis name")),
        }
    }

    fn index(&self, v: &VarRef) -> Result<Box<CExpr>, Alarm> {
        match &v.index {
            Some(Index::Expr(e)) => Ok(Box::new(self.expr(e, false)?)),
            _ => Err(Alarm::index_error(self.line, &v.name, "needs one number")),
        }
    }

    fn var(&self, v: &VarRef) -> Result<SyncVar, Alarm> {
        let scalar = |var: SyncVar| match v.index {
            None => Ok(var),
            Some(_) => Err(Alarm::index_error(self.line, &v.name, "takes no index")),
        };
        Ok(match v.name.as_str() {
            "$AA_IM" => SyncVar::AaIm(self.axis(v)?),
            "$AA_IW" => SyncVar::AaIw(self.axis(v)?),
            "$AA_IPO" => SyncVar::AaIpo(self.axis(v)?),
            "$AA_VACTM" => SyncVar::AaVactm(self.axis(v)?),
            "$AA_OVR" => SyncVar::AaOvr(self.axis(v)?),
            "$AC_TIME" => scalar(SyncVar::AcTime)?,
            "$AC_PATH" => scalar(SyncVar::AcPath)?,
            "$AC_DTEB" => scalar(SyncVar::AcDteb)?,
            "$AC_VACTB" => scalar(SyncVar::AcVactb)?,
            "$AC_OVR" => scalar(SyncVar::AcOvr)?,
            "$AC_DELT" => scalar(SyncVar::AcDelt)?,
            "$AC_TIMER" => SyncVar::AcTimer(self.index(v)?),
            "$AC_MARKER" => SyncVar::AcMarker(self.index(v)?),
            "$AC_PARAM" => SyncVar::AcParam(self.index(v)?),
            "$R" => SyncVar::R(self.index(v)?),
            "$A_IN" => SyncVar::AIn(self.index(v)?),
            "$A_OUT" => SyncVar::AOut(self.index(v)?),
            "$A_INA" => SyncVar::AIna(self.index(v)?),
            "$A_OUTA" => SyncVar::AOuta(self.index(v)?),
            "$AA_S" => SyncVar::AaS(self.index(v)?),
            name => return Err(Alarm::unknown_name(self.line, name)),
        })
    }

    fn action(&self, a: &SAction) -> Result<SyncAct, Alarm> {
        Ok(match a {
            SAction::Assign(v, e) => {
                let var = match crate::interp::eval::nc_constants::is_constant(&v.name) {
                    // A constant is read only: the alarm of a variable not writable in an action.
                    true => return Err(not_changeable(self.line, &v.name)),
                    false => self.var(v)?,
                };
                let writable = matches!(
                    var,
                    SyncVar::AcOvr
                        | SyncVar::AaOvr(_)
                        | SyncVar::AcTimer(_)
                        | SyncVar::AcMarker(_)
                        | SyncVar::AcParam(_)
                        | SyncVar::R(_)
                        | SyncVar::AOut(_)
                        | SyncVar::AOuta(_)
                );
                if !writable {
                    return Err(not_changeable(self.line, &v.name));
                }
                SyncAct::Set(var, self.expr(e, false)?)
            }
            SAction::Aux { letter, extension, value } => {
                SyncAct::Aux { letter: *letter, extension: *extension, value: self.expr(value, false)? }
            }
            SAction::DelDtg => SyncAct::DelDtg,
            SAction::AxisCommand { word, axis, value } => self.command(word, axis, value)?,
            SAction::Word(w) if w == "STOPREOF" => SyncAct::StopReOf,
            SAction::Word(w) if w == "RDISABLE" => SyncAct::RDisable,
            SAction::Call(w, args) if w == "PRESETON" => match args.as_slice() {
                [SExpr::Var(VarRef { name, index: None })] | [SExpr::Var(VarRef { name, index: None }), _]
                    if args.len() == 2 =>
                {
                    let axis = self
                        .cfg
                        .program_axis(name)
                        .ok_or_else(|| Alarm::unknown_name(self.line, &format!("PRESETON({name})")))?;
                    SyncAct::Preset { axis, value: self.expr(&args[1], false)? }
                }
                _ => return Err(Alarm::syntax(self.line, "PRESETON(axis, value)")),
            },
            SAction::Call(w, args) if w == "SETM" || w == "CLEARM" => match args.as_slice() {
                [marker] => SyncAct::WaitMarker { set: w == "SETM", marker: self.expr(marker, false)? },
                _ => return Err(Alarm::syntax(self.line, &format!("{w}(marker)"))),
            },
            // Any other word is the name of a technology cycle (found when the block is
            // prepared, 12550 if there is none).
            SAction::Word(w) => SyncAct::Cycle(w.clone()),
            SAction::Call(w, _) => {
                return Err(not_admissible(self.line, &format!("{w} (not modelled in NCTwin)")));
            }
        })
    }
}

/// 12584: a synchronized action writes a variable that cannot change with the motion.
fn not_changeable(line: u32, name: &str) -> Alarm {
    Alarm {
        number: 12584,
        message: format!("Channel 1 block {line} variable {name} cannot be changed synchronously with motion"),
        line: Some(line),
        clear: Clear::Reset,
    }
}

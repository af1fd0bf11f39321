//! The flat form of a compiled synchronized action, the one the main run evaluates in every
//! IPO cycle: each expression a short array of operations in postfix order over variables
//! whose element is resolved once ([`Slot`]), so a cycle walks no tree, follows no box and
//! matches no index expression. The most common condition, `variable <op> constant`, is one
//! operation ([`Op::Compare`]).
//!
//! Each condition also says what it reads ([`Code::deps`], [`Code::volatile`]): a condition
//! that reads only main-run data (markers, parameters, signals, `$AC_DELT`) keeps its value
//! until one of those changes, and the main run does not evaluate it again until then.
//!
//! Evaluation order and results are those of the expression tree ([`CExpr`]): operands left
//! to right, both operands of AND/OR, the same alarms in the same order.

use super::compile::{CExpr, Func, SyncAct, SyncVar};
use crate::alarm::Alarm;
use crate::lang::sync_action::BinOp;

pub use crate::machine_data::sync_sizes::SyncSizes;

/// A variable read whose element is known before the run (indices are channel axes, array
/// elements from 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slot {
    AaIm(usize),
    AaIw(usize),
    AaIpo(usize),
    AaVactm(usize),
    AaOvr(usize),
    AcTime,
    AcPath,
    AcDteb,
    AcVactb,
    AcOvr,
    AcDelt,
    Timer(usize),
    Marker(usize),
    Param(usize),
    /// Digital input/output by signal number (from 1).
    AIn(usize),
    AOut(usize),
    AIna(usize),
    AOuta(usize),
    /// `$R[n]` (its range is the interpreter's, checked when read).
    R(usize),
}

/// An array variable whose element is computed in the cycle (the index is on the stack).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Array {
    Timer,
    Marker,
    Param,
    R,
    AIn,
    AOut,
    AIna,
    AOuta,
    AaS,
}

impl Array {
    /// The name, the element count and the first index (`None` for `$R` and `$AA_S`, whose
    /// sizes are the channel's).
    pub fn shape(self, z: &SyncSizes) -> (&'static str, Option<(usize, usize)>) {
        match self {
            Array::Timer => ("$AC_TIMER", Some((z.timers, 0))),
            Array::Marker => ("$AC_MARKER", Some((z.markers, 0))),
            Array::Param => ("$AC_PARAM", Some((z.params, 0))),
            Array::AIn => ("$A_IN", Some((z.digital_in, 1))),
            Array::AOut => ("$A_OUT", Some((z.digital_out, 1))),
            Array::AIna => ("$A_INA", Some((z.analog_in, 1))),
            Array::AOuta => ("$A_OUTA", Some((z.analog_out, 1))),
            Array::R => ("$R", None),
            Array::AaS => ("$AA_S", None),
        }
    }

    /// The element of a known index, if it is in range of the sizes `z` (else the cycle
    /// raises the alarm).
    pub fn slot(self, v: f64, z: &SyncSizes) -> Option<Slot> {
        let (_, Some((size, first))) = self.shape(z) else {
            // `$R[n]`: a whole number from 0 (its upper bound is checked when read).
            return (self == Array::R && v.is_finite() && v >= 0.0 && v.fract() == 0.0 && v < 1e9)
                .then_some(Slot::R(v as usize));
        };
        let n = v.round();
        (v.is_finite() && n >= first as f64 && n < (size + first) as f64).then(|| {
            let i = n as usize - first;
            match self {
                Array::Timer => Slot::Timer(i),
                Array::Marker => Slot::Marker(i),
                Array::Param => Slot::Param(i),
                Array::AIn => Slot::AIn(i + 1),
                Array::AOut => Slot::AOut(i + 1),
                Array::AIna => Slot::AIna(i),
                Array::AOuta => Slot::AOuta(i),
                Array::R | Array::AaS => unreachable!("no fixed shape"),
            }
        })
    }

    /// The main-run data an element of this array may be (see [`Code::deps`]).
    fn deps(self) -> Option<u64> {
        Some(match self {
            Array::Marker => MARKER_BITS,
            Array::Param => PARAM_BITS,
            Array::AIna => ANALOG_IN_BITS,
            Array::AOuta => ANALOG_OUT_BITS,
            Array::AIn => 1 << DIGITAL_IN_BIT,
            Array::AOut => 1 << DIGITAL_OUT_BIT,
            Array::Timer => 1 << TIMER_BIT,
            Array::R | Array::AaS => return None,
        })
    }
}

/// Bits of [`Code::deps`]: markers 0..7 (marker i on bit i mod 8), parameters 8..39
/// (parameter i on bit 8 + i mod 32), analog inputs 40..43, analog outputs 44..47 (signal i
/// from 0 on i mod 4), then the digital inputs, the digital
/// outputs, `$AC_DELT` and the timers.
pub const MARKER_BITS: u64 = 0xff;
pub const PARAM_BITS: u64 = 0xffff_ffff << 8;
pub const ANALOG_IN_BITS: u64 = 0xf << 40;
pub const ANALOG_OUT_BITS: u64 = 0xf << 44;
pub const DIGITAL_IN_BIT: u32 = 48;
pub const DIGITAL_OUT_BIT: u32 = 49;
pub const DELT_BIT: u32 = 50;
pub const TIMER_BIT: u32 = 51;
/// Events that break the bounds of the horizon (`horizon.rs`) of a condition reading
/// positions, speeds or times: the block changed (`$AC_TIME`), the offsets changed (`$AA_IW`),
/// the axes jumped (a preset, a probe's deletion, a new transformation, reset).
pub const BLOCK_BIT: u32 = 52;
pub const FRAME_BIT: u32 = 53;
pub const MOTION_BIT: u32 = 54;

/// The data bits of marker, parameter and analog signal `i` (from 0): sizes from the machine
/// data may exceed the bits, so elements share them (a change wakes a few more readers).
pub fn marker_bit(i: usize) -> u64 {
    1 << (i % 8)
}
pub fn param_bit(i: usize) -> u64 {
    1 << (8 + i % 32)
}
pub fn analog_in_bit(i: usize) -> u64 {
    1 << (40 + i % 4)
}
pub fn analog_out_bit(i: usize) -> u64 {
    1 << (44 + i % 4)
}

impl Slot {
    /// The main-run data bit this variable is, or `None` for one that may change in any cycle
    /// (positions, speeds, times, overrides, `$R`).
    pub fn dep(self) -> Option<u64> {
        Some(match self {
            Slot::Marker(i) => marker_bit(i),
            Slot::Param(i) => param_bit(i),
            Slot::AIna(i) => analog_in_bit(i),
            Slot::AOuta(i) => analog_out_bit(i),
            Slot::AIn(_) => 1 << DIGITAL_IN_BIT,
            Slot::AOut(_) => 1 << DIGITAL_OUT_BIT,
            Slot::AcDelt => 1 << DELT_BIT,
            Slot::Timer(_) => 1 << TIMER_BIT,
            _ => return None,
        })
    }

    /// The events after which a horizon computed with this variable no longer holds (the
    /// path's speed and distances have ranges only, which no event changes; a jump of the
    /// axes makes `$AA_VACTM` leave its range for a cycle).
    pub fn events(self) -> u64 {
        match self {
            Slot::AaIm(_) | Slot::AaIpo(_) | Slot::AaVactm(_) => 1 << MOTION_BIT,
            Slot::AaIw(_) => (1 << MOTION_BIT) | (1 << FRAME_BIT),
            Slot::AcTime => 1 << BLOCK_BIT,
            _ => 0,
        }
    }
}

/// One operation of an expression in postfix order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Op {
    Num(f64),
    Read(Slot),
    /// Pops the index.
    ReadAt(Array),
    /// `slot <op> constant` in one step (pushes the 1/0 result).
    Compare(Slot, BinOp, f64),
    Neg,
    Not,
    Bin(BinOp),
    /// Pops its one or two arguments.
    Func(Func),
}

/// An expression in postfix order, with the stack depth it needs and the data it reads.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Code {
    pub ops: Box<[Op]>,
    pub depth: usize,
    /// The main-run data it reads (bits as [`MARKER_BITS`]...), and the events that end the
    /// horizon of a volatile one ([`BLOCK_BIT`]...).
    pub deps: u64,
    /// It reads something that may change in any cycle: it has to be evaluated again when
    /// its horizon (`horizon.rs`) ends.
    pub volatile: bool,
}

/// Where an action's assignment goes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    Ovr,
    AxisOvr(usize),
    /// An element of an array: `Code` of [`Act::Set`] computes the index.
    At(Array),
    Timer(usize),
    Marker(usize),
    Param(usize),
    R(usize),
    AOut(usize),
    AOuta(usize),
    /// A variable that may not be written (refused when compiled; kept for the alarm).
    ReadOnly,
}

/// One action in flat form.
#[derive(Debug, Clone, PartialEq)]
pub enum Act {
    /// The value, then (for [`Target::At`]) the index.
    Set {
        target: Target,
        value: Code,
        index: Code,
    },
    Aux {
        letter: char,
        extension: u32,
        value: Code,
    },
    DelDtg,
    /// A command axis or spindle motion (`compile::CommandKind`), its value computed.
    Command {
        kind: super::compile::CommandKind,
        axis: usize,
        value: Code,
        mode: Option<crate::lang::CoordMode>,
    },
    StopReOf,
    RDisable,
    Preset {
        axis: usize,
        value: Code,
    },
    WaitMarker {
        set: bool,
        marker: Code,
    },
    /// A technology cycle, resolved when the block is prepared (`technology.rs`).
    Cycle(std::sync::Arc<super::technology::TechCycle>),
    /// A technology cycle's name before it is resolved (never run).
    CycleName(String),
}

/// Lowers a compiled expression (array sizes: the defaults).
pub fn lower(e: &CExpr) -> Code {
    lower_sized(e, &SyncSizes::default())
}

/// Lowers a compiled expression for the array sizes `z`: a constant index in range is
/// resolved now, any other is checked in the main run.
pub fn lower_sized(e: &CExpr, z: &SyncSizes) -> Code {
    let mut ops = Vec::new();
    let mut c = Code::default();
    let depth = emit(e, &mut ops, &mut c, z);
    c.ops = ops.into_boxed_slice();
    c.depth = depth;
    c
}

/// Lowers a compiled action for the array sizes `z`.
pub fn lower_act(a: &SyncAct, z: &SyncSizes) -> Act {
    let lower = |e: &CExpr| lower_sized(e, z);
    match a {
        SyncAct::Set(var, e) => {
            let (target, index) = match var {
                SyncVar::AcOvr => (Target::Ovr, Code::default()),
                SyncVar::AaOvr(k) => (Target::AxisOvr(*k), Code::default()),
                SyncVar::AcTimer(i) => element(Array::Timer, i, z),
                SyncVar::AcMarker(i) => element(Array::Marker, i, z),
                SyncVar::AcParam(i) => element(Array::Param, i, z),
                SyncVar::R(i) => element(Array::R, i, z),
                SyncVar::AOut(i) => element(Array::AOut, i, z),
                SyncVar::AOuta(i) => element(Array::AOuta, i, z),
                _ => (Target::ReadOnly, Code::default()),
            };
            Act::Set { target, value: lower(e), index }
        }
        SyncAct::Aux { letter, extension, value } => {
            Act::Aux { letter: *letter, extension: *extension, value: lower(value) }
        }
        SyncAct::DelDtg => Act::DelDtg,
        SyncAct::Command { kind, axis, value, mode } => {
            Act::Command { kind: *kind, axis: *axis, value: lower(value), mode: *mode }
        }
        SyncAct::StopReOf => Act::StopReOf,
        SyncAct::RDisable => Act::RDisable,
        SyncAct::Preset { axis, value } => Act::Preset { axis: *axis, value: lower(value) },
        SyncAct::WaitMarker { set, marker } => Act::WaitMarker { set: *set, marker: lower(marker) },
        SyncAct::Cycle(name) => Act::CycleName(name.clone()),
    }
}

/// The target of an assignment to `array[i]`: resolved when `i` is a number in range.
fn element(array: Array, i: &CExpr, z: &SyncSizes) -> (Target, Code) {
    if let CExpr::Num(v) = i
        && let Some(slot) = array.slot(*v, z)
    {
        let t = match slot {
            Slot::Timer(i) => Target::Timer(i),
            Slot::Marker(i) => Target::Marker(i),
            Slot::Param(i) => Target::Param(i),
            Slot::R(i) => Target::R(i),
            Slot::AOut(n) => Target::AOut(n),
            Slot::AOuta(i) => Target::AOuta(i),
            _ => unreachable!("an array's element"),
        };
        return (t, Code::default());
    }
    (Target::At(array), lower_sized(i, z))
}

/// Appends `e`'s operations; returns the stack depth they need.
fn emit(e: &CExpr, ops: &mut Vec<Op>, c: &mut Code, z: &SyncSizes) -> usize {
    match e {
        CExpr::Num(v) => {
            ops.push(Op::Num(*v));
            1
        }
        CExpr::Var(v) => read(v, ops, c, z),
        // A negative number (`$AC_DTEB<-1`) is a number: -v is exact.
        CExpr::Neg(x) if matches!(**x, CExpr::Num(_)) => {
            let CExpr::Num(v) = **x else { unreachable!() };
            ops.push(Op::Num(-v));
            1
        }
        CExpr::Neg(x) => {
            let d = emit(x, ops, c, z);
            ops.push(Op::Neg);
            d
        }
        CExpr::Not(x) => {
            let d = emit(x, ops, c, z);
            ops.push(Op::Not);
            d
        }
        CExpr::Bin(op, a, b) => {
            if is_comparison(*op)
                && let (CExpr::Var(v), Some(k)) = (&**a, number(b))
                && let Some(slot) = fixed(v, z)
            {
                note(slot, c);
                ops.push(Op::Compare(slot, *op, k));
                return 1;
            }
            let da = emit(a, ops, c, z);
            let db = emit(b, ops, c, z);
            ops.push(Op::Bin(*op));
            da.max(db + 1)
        }
        CExpr::Func(f, args) => {
            let mut depth = 0;
            for (i, a) in args.iter().enumerate() {
                depth = depth.max(emit(a, ops, c, z) + i);
            }
            ops.push(Op::Func(*f));
            depth
        }
    }
}

/// The value of a number or a negated number.
fn number(e: &CExpr) -> Option<f64> {
    match e {
        CExpr::Num(v) => Some(*v),
        CExpr::Neg(x) => match **x {
            CExpr::Num(v) => Some(-v),
            _ => None,
        },
        _ => None,
    }
}

fn is_comparison(op: BinOp) -> bool {
    matches!(op, BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Gt | BinOp::Le | BinOp::Ge)
}

/// Records what a read of `slot` depends on.
fn note(slot: Slot, c: &mut Code) {
    match slot.dep() {
        Some(bit) => c.deps |= bit,
        None => {
            c.volatile = true;
            c.deps |= slot.events();
        }
    }
}

/// The slot of a variable whose element is known now.
fn fixed(v: &SyncVar, z: &SyncSizes) -> Option<Slot> {
    let at = |array: Array, i: &CExpr| match i {
        CExpr::Num(n) => array.slot(*n, z),
        _ => None,
    };
    match v {
        SyncVar::AaIm(k) => Some(Slot::AaIm(*k)),
        SyncVar::AaIw(k) => Some(Slot::AaIw(*k)),
        SyncVar::AaIpo(k) => Some(Slot::AaIpo(*k)),
        SyncVar::AaVactm(k) => Some(Slot::AaVactm(*k)),
        SyncVar::AaOvr(k) => Some(Slot::AaOvr(*k)),
        SyncVar::AcTime => Some(Slot::AcTime),
        SyncVar::AcPath => Some(Slot::AcPath),
        SyncVar::AcDteb => Some(Slot::AcDteb),
        SyncVar::AcVactb => Some(Slot::AcVactb),
        SyncVar::AcOvr => Some(Slot::AcOvr),
        SyncVar::AcDelt => Some(Slot::AcDelt),
        SyncVar::AcTimer(i) => at(Array::Timer, i),
        SyncVar::AcMarker(i) => at(Array::Marker, i),
        SyncVar::AcParam(i) => at(Array::Param, i),
        SyncVar::R(i) => at(Array::R, i),
        SyncVar::AIn(i) => at(Array::AIn, i),
        SyncVar::AOut(i) => at(Array::AOut, i),
        SyncVar::AIna(i) => at(Array::AIna, i),
        SyncVar::AOuta(i) => at(Array::AOuta, i),
        SyncVar::AaS(_) => None,
    }
}

fn read(v: &SyncVar, ops: &mut Vec<Op>, c: &mut Code, z: &SyncSizes) -> usize {
    if let Some(slot) = fixed(v, z) {
        note(slot, c);
        ops.push(Op::Read(slot));
        return 1;
    }
    let (array, i) = match v {
        SyncVar::AcTimer(i) => (Array::Timer, i),
        SyncVar::AcMarker(i) => (Array::Marker, i),
        SyncVar::AcParam(i) => (Array::Param, i),
        SyncVar::R(i) => (Array::R, i),
        SyncVar::AIn(i) => (Array::AIn, i),
        SyncVar::AOut(i) => (Array::AOut, i),
        SyncVar::AIna(i) => (Array::AIna, i),
        SyncVar::AOuta(i) => (Array::AOuta, i),
        SyncVar::AaS(i) => (Array::AaS, i),
        _ => unreachable!("scalars and axis variables are fixed"),
    };
    let d = emit(i, ops, c, z);
    match array.deps() {
        Some(bits) => c.deps |= bits,
        None => c.volatile = true,
    }
    ops.push(Op::ReadAt(array));
    d
}

/// An alarm of the main run's evaluation, boxed: results stay two words wide.
pub type Fault = Box<Alarm>;

/// The variables an expression reads, as the main run provides them.
pub trait Reader {
    fn read(&self, slot: Slot, line: u32) -> Result<f64, Fault>;
    fn read_at(&self, array: Array, index: f64, line: u32) -> Result<f64, Fault>;
}

/// The value of `code` in this cycle (booleans 1/0).
#[inline]
pub fn eval<R: Reader>(code: &Code, r: &R, line: u32) -> Result<f64, Fault> {
    match &*code.ops {
        [Op::Compare(s, op, k)] => Ok(f64::from(compare(*op, r.read(*s, line)?, *k))),
        [Op::Read(s)] => r.read(*s, line),
        [Op::Num(v)] => Ok(*v),
        ops if code.depth <= 4 => run(ops, r, line, &mut [0.0; 4]),
        ops if code.depth <= 16 => run(ops, r, line, &mut [0.0; 16]),
        ops => run(ops, r, line, &mut vec![0.0; code.depth]),
    }
}

/// The general case, out of line: [`eval`]'s single-operation cases stay small.
#[inline(never)]
fn run<R: Reader>(ops: &[Op], r: &R, line: u32, stack: &mut [f64]) -> Result<f64, Fault> {
    let mut sp = 0;
    for op in ops {
        match *op {
            Op::Num(v) => {
                stack[sp] = v;
                sp += 1;
            }
            Op::Read(s) => {
                stack[sp] = r.read(s, line)?;
                sp += 1;
            }
            Op::ReadAt(a) => stack[sp - 1] = r.read_at(a, stack[sp - 1], line)?,
            Op::Compare(s, op, k) => {
                stack[sp] = f64::from(compare(op, r.read(s, line)?, k));
                sp += 1;
            }
            Op::Neg => stack[sp - 1] = -stack[sp - 1],
            Op::Not => stack[sp - 1] = f64::from(stack[sp - 1] == 0.0),
            Op::Bin(op) => {
                sp -= 1;
                let (a, b) = (stack[sp - 1], stack[sp]);
                stack[sp - 1] = match op {
                    BinOp::Add => a + b,
                    BinOp::Sub => a - b,
                    BinOp::Mul => a * b,
                    _ => binary(op, a, b, line)?,
                };
            }
            Op::Func(f) => {
                let y = second_argument(f, stack, &mut sp, 0.0);
                stack[sp - 1] = function(f, stack[sp - 1], y, line)?;
            }
        }
    }
    Ok(stack[0])
}

/// Pops the second argument of a function of two (ATAN2, MINVAL, MAXVAL), else `none`.
pub(crate) fn second_argument<T: Copy>(f: Func, stack: &[T], sp: &mut usize, none: T) -> T {
    if matches!(f, Func::Atan2 | Func::MinVal | Func::MaxVal) {
        *sp -= 1;
        stack[*sp]
    } else {
        none
    }
}

/// `a op b` as the control computes it in a synchronized action.
pub fn binary(op: BinOp, a: f64, b: f64, line: u32) -> Result<f64, Fault> {
    Ok(match op {
        BinOp::Add => a + b,
        BinOp::Sub => a - b,
        BinOp::Mul => a * b,
        BinOp::Div | BinOp::IntDiv | BinOp::Mod if b == 0.0 => {
            return Err(Box::new(Alarm::arithmetic(line, "division by zero in a synchronized action")));
        }
        BinOp::Div => a / b,
        BinOp::IntDiv => (a / b).trunc(),
        BinOp::Mod => a % b,
        BinOp::And => f64::from(a != 0.0 && b != 0.0),
        BinOp::Or => f64::from(a != 0.0 || b != 0.0),
        BinOp::Xor => f64::from((a != 0.0) != (b != 0.0)),
        cmp => f64::from(compare(cmp, a, b)),
    })
}

/// A comparison; REAL comparisons on the control are within 1e-12 relative (MD10280).
#[inline]
fn compare(op: BinOp, a: f64, b: f64) -> bool {
    match op {
        BinOp::Eq => same(a, b),
        BinOp::Ne => !same(a, b),
        BinOp::Lt => a < b && !same(a, b),
        BinOp::Gt => a > b && !same(a, b),
        BinOp::Le => a <= b || same(a, b),
        BinOp::Ge => a >= b || same(a, b),
        _ => unreachable!("not a comparison"),
    }
}

pub(crate) fn function(f: Func, x: f64, y: f64, line: u32) -> Result<f64, Fault> {
    let v = match f {
        Func::Sin => x.to_radians().sin(),
        Func::Cos => x.to_radians().cos(),
        Func::Tan => x.to_radians().tan(),
        Func::Asin => x.asin().to_degrees(),
        Func::Acos => x.acos().to_degrees(),
        Func::Atan2 => x.atan2(y).to_degrees(),
        Func::Sqrt => x.sqrt(),
        Func::Abs => x.abs(),
        Func::Pot => x * x,
        Func::Trunc => x.trunc(),
        Func::Round => x.round(),
        Func::Ln => x.ln(),
        Func::Exp => x.exp(),
        Func::MinVal => x.min(y),
        Func::MaxVal => x.max(y),
    };
    if !v.is_finite() {
        return Err(Box::new(Alarm::arithmetic(line, "a function's argument outside its domain")));
    }
    Ok(v)
}

/// Equal within the control's relative tolerance for REAL comparisons.
fn same(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= 1e-12 * a.abs().max(b.abs())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interp::synchronized::compile::CExpr as E;

    /// Variables as a test sets them: `$AA_IM[k]` = 10·(k + 1), marker i = i, `$R[n]` for n < 5.
    struct Vars;

    impl Reader for Vars {
        fn read(&self, slot: Slot, line: u32) -> Result<f64, Fault> {
            match slot {
                Slot::AaIm(k) => Ok(10.0 * (k + 1) as f64),
                Slot::Marker(i) => Ok(i as f64),
                Slot::R(n) if n < 5 => Ok(n as f64 * 0.5),
                _ => Err(Box::new(Alarm::index_error(line, "test", "no such variable"))),
            }
        }
        fn read_at(&self, array: Array, index: f64, line: u32) -> Result<f64, Fault> {
            let slot = array
                .slot(index, &SyncSizes::default())
                .ok_or_else(|| Box::new(Alarm::index_error(line, "test", "range")))?;
            self.read(slot, line)
        }
    }

    fn num(v: f64) -> Box<E> {
        Box::new(E::Num(v))
    }

    fn bin(op: BinOp, a: E, b: E) -> E {
        E::Bin(op, Box::new(a), Box::new(b))
    }

    fn value(e: &E) -> Result<f64, Fault> {
        eval(&lower(e), &Vars, 7)
    }

    #[test]
    fn a_comparison_of_a_variable_with_a_number_is_one_operation() {
        let e = bin(BinOp::Gt, E::Var(SyncVar::AaIm(1)), E::Num(15.0));
        let c = lower(&e);
        assert_eq!(&*c.ops, &[Op::Compare(Slot::AaIm(1), BinOp::Gt, 15.0)]);
        assert!(c.volatile);
        // $AA_IM[Y] = 20 > 15.
        assert_eq!(value(&e).unwrap(), 1.0);
    }

    #[test]
    fn arithmetic_and_functions_give_the_values_worked_by_hand() {
        // SQRT(POT(3) + POT(4)) = 5; ATAN2(1, 1) = 45°; MINVAL(-2, $AA_IM[X]) = -2;
        // 7 DIV 2 = 3; 7 MOD 2 = 1; NOT (1 AND 0) = 1; -(3 - 5) = 2.
        let pot = |v| E::Func(Func::Pot, vec![E::Num(v)]);
        let sqrt = E::Func(Func::Sqrt, vec![bin(BinOp::Add, pot(3.0), pot(4.0))]);
        assert_eq!(value(&sqrt).unwrap(), 5.0);
        let atan = E::Func(Func::Atan2, vec![E::Num(1.0), E::Num(1.0)]);
        assert!((value(&atan).unwrap() - 45.0).abs() < 1e-12);
        let min = E::Func(Func::MinVal, vec![E::Num(-2.0), E::Var(SyncVar::AaIm(0))]);
        assert_eq!(value(&min).unwrap(), -2.0);
        assert_eq!(value(&bin(BinOp::IntDiv, E::Num(7.0), E::Num(2.0))).unwrap(), 3.0);
        assert_eq!(value(&bin(BinOp::Mod, E::Num(7.0), E::Num(2.0))).unwrap(), 1.0);
        assert_eq!(value(&E::Not(Box::new(bin(BinOp::And, E::Num(1.0), E::Num(0.0))))).unwrap(), 1.0);
        assert_eq!(value(&E::Neg(Box::new(bin(BinOp::Sub, E::Num(3.0), E::Num(5.0))))).unwrap(), 2.0);
    }

    #[test]
    fn constant_indices_are_resolved_and_computed_ones_read_in_the_cycle() {
        // $AC_MARKER[3] is marker 3; $AC_MARKER[1+2] the same element found in the cycle.
        let fixed = E::Var(SyncVar::AcMarker(num(3.0)));
        assert_eq!(&*lower(&fixed).ops, &[Op::Read(Slot::Marker(3))]);
        let computed = E::Var(SyncVar::AcMarker(Box::new(bin(BinOp::Add, E::Num(1.0), E::Num(2.0)))));
        let c = lower(&computed);
        assert_eq!(c.ops.last(), Some(&Op::ReadAt(Array::Marker)));
        assert_eq!(value(&computed).unwrap(), 3.0);
        // Markers only: no volatile input, all eight marker bits.
        assert!(!c.volatile);
        assert_eq!(c.deps, MARKER_BITS);
        // An index out of range stays for the cycle to refuse (alarm 17020 there).
        let out = E::Var(SyncVar::AcMarker(num(8.0)));
        assert_eq!(lower(&out).ops.last(), Some(&Op::ReadAt(Array::Marker)));
    }

    #[test]
    fn data_inputs_are_named_by_their_bits() {
        let e = bin(
            BinOp::Or,
            E::Var(SyncVar::AIn(num(3.0))),
            bin(BinOp::Gt, E::Var(SyncVar::AcParam(num(40.0))), E::Var(SyncVar::AIna(num(2.0)))),
        );
        let c = lower(&e);
        assert!(!c.volatile);
        assert_eq!(c.deps, (1 << DIGITAL_IN_BIT) | (1 << (8 + 40 % 32)) | (1 << (40 + 1)));
        assert!(lower(&E::Var(SyncVar::R(num(1.0)))).volatile);
    }

    #[test]
    fn errors_come_in_the_order_of_the_operands() {
        // 1/0 on the left is found before the unknown variable on the right.
        let e = bin(BinOp::Add, bin(BinOp::Div, E::Num(1.0), E::Num(0.0)), E::Var(SyncVar::AcTime));
        let a = value(&e).unwrap_err();
        assert!(a.message.contains("division by zero"), "{}", a.message);
        assert_eq!(a.line, Some(7));
        let sqrt = E::Func(Func::Sqrt, vec![E::Num(-1.0)]);
        assert!(value(&sqrt).unwrap_err().message.contains("outside its domain"));
    }

    #[test]
    fn deep_expressions_get_a_stack_of_their_depth() {
        // 1 + (1 + (1 + ... )) forty deep: forty-one values on the stack at the innermost.
        let mut e = E::Num(1.0);
        for _ in 0..40 {
            e = bin(BinOp::Add, E::Num(1.0), e);
        }
        let c = lower(&e);
        assert_eq!(c.depth, 41);
        assert_eq!(value(&e).unwrap(), 41.0);
    }

    #[test]
    fn assignments_to_known_elements_need_no_index_code() {
        let set = SyncAct::Set(SyncVar::AcParam(num(4.0)), E::Num(1.0));
        assert_eq!(
            lower_act(&set, &SyncSizes::default()),
            Act::Set { target: Target::Param(4), value: lower(&E::Num(1.0)), index: Code::default() }
        );
        let set = SyncAct::Set(SyncVar::R(Box::new(E::Var(SyncVar::AcMarker(num(2.0))))), E::Num(1.0));
        let Act::Set { target, index, .. } = lower_act(&set, &SyncSizes::default()) else { panic!() };
        assert_eq!(target, Target::At(Array::R));
        assert_eq!(&*index.ops, &[Op::Read(Slot::Marker(2))]);
    }
}

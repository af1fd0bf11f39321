//! How many IPO cycles a synchronized action's condition provably keeps the value it has
//! now: "a condition sleeps while it cannot change its truth value". The main run gives, for
//! each variable the condition reads, its value and conservative bounds ([`Bound`]: the most
//! it changes per cycle, the range it can ever take); [`horizon`] evaluates the condition over
//! intervals (each variable within `value ± h·rate`, cut to its range) and finds the largest
//! `h` for which the result is certainly the value the exact evaluation gave. The main run
//! then skips the condition for `h` cycles, unless an event breaks the bounds (it wakes it).
//!
//! Everything here is conservative: rounding is covered by widening each result by far more
//! than the arithmetic's error, comparisons count only when the operands are apart by more
//! than the control's REAL tolerance (MD10280, 1e-12 relative) with a wide margin, and what
//! is not modelled (computed indices, trigonometry, `DIV`/`MOD` of intervals, a divisor
//! interval holding 0, a function outside its domain) gives "no horizon" (evaluate in every
//! cycle). A horizon that is too short only costs an evaluation; one too long would change
//! the program's behaviour, so every doubt shortens it.

use super::compile::Func;
use super::flat::{self, Code, Op, Slot};
use crate::lang::sync_action::BinOp;

mod linear;

/// What the main run guarantees about a variable a condition reads, until an event.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bound {
    /// The value in this cycle (the one the condition's evaluation read).
    pub value: f64,
    /// The most it changes from one IPO cycle to the next (`INFINITY`: any amount).
    pub rate: f64,
    /// The values it can take at all.
    pub lo: f64,
    pub hi: f64,
}

impl Bound {
    /// Data that changes only when written (markers, parameters, signals): the writes wake
    /// the conditions that read it, so between them the value is fixed.
    pub fn fixed(value: f64) -> Bound {
        Bound { value, rate: 0.0, lo: f64::NEG_INFINITY, hi: f64::INFINITY }
    }

    /// The values possible `h` cycles from now.
    fn after(self, h: f64) -> Iv {
        if self.rate == 0.0 {
            return Iv::point(self.value);
        }
        let reach = self.rate * h;
        let lo = if reach.is_finite() { (self.value - reach).max(self.lo) } else { self.lo };
        let hi = if reach.is_finite() { (self.value + reach).min(self.hi) } else { self.hi };
        Iv { lo: lo.min(self.value), hi: hi.max(self.value) }
    }
}

/// The bounds of the variables, as the main run knows them in this cycle.
pub trait Bounds {
    /// `None`: nothing is known (a condition reading it is evaluated in every cycle).
    fn bound(&self, slot: Slot) -> Option<Bound>;
}

/// The longest horizon given (2^24 cycles, over 18 hours at 4 ms): then it is looked at again.
pub const MAX_HORIZON: u64 = 1 << 24;
/// Conditions with more operations, a deeper stack or more variables get no horizon (the
/// interval evaluation stays on small arrays on the stack).
const MAX_OPS: usize = 32;
const MAX_DEPTH: usize = 8;
const MAX_READS: usize = 6;
/// Results are widened by this much relative to their value (one rounding is about 1e-16).
const WIDEN: f64 = 1e-12;
/// Operands of a comparison count as apart when more than this relative distance separates
/// them (1000 times the control's REAL tolerance).
const APART: f64 = 1e-9;

/// The number of cycles after this one in which `code` certainly keeps the value `now` it
/// had in this cycle's evaluation (0: it may change in the next one).
pub fn horizon<B: Bounds>(code: &Code, b: &B, now: bool) -> u64 {
    if code.ops.len() > MAX_OPS || code.depth > MAX_DEPTH {
        return 0;
    }
    // The bounds of the variables read, in the order read, once (reading one may cost a
    // frame transformation).
    let mut reads = [Bound::fixed(0.0); MAX_READS];
    let mut n = 0;
    for op in code.ops.iter() {
        match op {
            Op::Read(s) | Op::Compare(s, _, _) if n < MAX_READS => match b.bound(*s) {
                Some(bound) if bound.value.is_finite() && !bound.rate.is_nan() => {
                    reads[n] = bound;
                    n += 1;
                }
                _ => return 0,
            },
            Op::Read(_) | Op::Compare(..) | Op::ReadAt(_) => return 0,
            _ => {}
        }
    }
    // `variable <op> constant` (most conditions): `truth` of its one operation, without the stack.
    let single = match *code.ops {
        [Op::Compare(_, cmp, k)] => Some((cmp, k)),
        _ => None,
    };
    let holds = |h: u64| match single {
        Some((cmp, k)) => compare(cmp, reads[0].after(h as f64), Iv::point(k)).nonzero() == Some(now),
        None => truth(&code.ops, &reads[..n], h as f64) == Some(now),
    };
    // A range or fixed data decide at once (a speed beyond any the axes reach). For
    // `variable <op> constant` only when the variable's values after the longest horizon
    // are one or leave out the constant (else the comparison is unknown there: the same
    // answer, one interval evaluation less, in most evaluations of positions and times).
    let for_good = match *code.ops {
        [Op::Compare(_, _, k)] => {
            let iv = reads[0].after(MAX_HORIZON as f64);
            iv.is_point() || !(iv.lo..=iv.hi).contains(&k)
        }
        _ => true,
    };
    if for_good && holds(MAX_HORIZON) {
        return MAX_HORIZON;
    }
    // `variable <op> constant`: the cycles until the variable could reach the constant, one
    // less where the margin of the comparison needs it.
    let mut bad = MAX_HORIZON;
    if let [Op::Compare(_, _, k)] = *code.ops {
        let b = reads[0];
        let reach = ((b.value - k).abs() / b.rate).floor();
        if reach.is_finite() && reach < MAX_HORIZON as f64 {
            let reach = reach as u64;
            for h in [reach, reach.saturating_sub(1)] {
                if h > 0 && holds(h) {
                    return h;
                }
            }
            bad = reach.saturating_sub(1).max(1);
        }
    }
    // Any other condition linear in its variables: the cycles until the first comparison
    // that decides it could flip, checked as above (the search below finds the same, by
    // about 15 interval evaluations instead of 2).
    if bad == MAX_HORIZON
        && let Some(reach) = linear::reach(&code.ops, &reads[..n], now)
        && reach < MAX_HORIZON as f64
    {
        let reach = reach as u64;
        for h in [reach, reach.saturating_sub(1)] {
            if h > 0 && holds(h) {
                return h;
            }
        }
    }
    if !holds(1) {
        return 0;
    }
    // Doubling, then bisection between the last horizon that holds and the first that not.
    let mut good = 1;
    while good * 2 < bad {
        if !holds(good * 2) {
            bad = good * 2;
            break;
        }
        good *= 2;
    }
    while bad - good > 1 {
        let mid = good + (bad - good) / 2;
        if holds(mid) {
            good = mid;
        } else {
            bad = mid;
        }
    }
    good
}

/// An interval of values; truth values are [0, 0], [1, 1] or [0, 1] (unknown).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Iv {
    lo: f64,
    hi: f64,
}

const UNKNOWN: Iv = Iv { lo: 0.0, hi: 1.0 };

impl Iv {
    fn point(v: f64) -> Iv {
        Iv { lo: v, hi: v }
    }

    fn truth(b: bool) -> Iv {
        Iv::point(f64::from(u8::from(b)))
    }

    fn is_point(self) -> bool {
        self.lo == self.hi
    }

    /// Certainly nonzero (`Some(true)`), certainly zero (`Some(false)`) or either.
    fn nonzero(self) -> Option<bool> {
        if self.lo > 0.0 || self.hi < 0.0 {
            Some(true)
        } else if self.lo == 0.0 && self.hi == 0.0 {
            Some(false)
        } else {
            None
        }
    }

    fn magnitude(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }

    /// `[lo, hi]` computed from the operands' ends, widened. The cycle computes with the same
    /// operations, rounded to nearest, which are monotone: its values lie between the ends
    /// computed so; the widening (far more than one rounding) is a reserve, and for the
    /// library's EXP/LN, which are not correctly rounded. The sign stays (monotone rounding
    /// cannot cross zero): a sum of squares stays a valid argument of SQRT.
    fn widened(lo: f64, hi: f64) -> Option<Iv> {
        let (el, eh) = (WIDEN * lo.abs() + f64::MIN_POSITIVE, WIDEN * hi.abs() + f64::MIN_POSITIVE);
        let lo = if lo >= 0.0 { (lo - el).max(0.0) } else { lo - el };
        let hi = if hi <= 0.0 { (hi + eh).min(0.0) } else { hi + eh };
        let iv = Iv { lo, hi };
        (!iv.lo.is_nan() && !iv.hi.is_nan() && iv.lo <= iv.hi).then_some(iv)
    }
}

/// The condition's truth over all values `h` cycles from now, if certain (`reads`: the
/// variables' bounds in the order the operations read them).
fn truth(ops: &[Op], reads: &[Bound], h: f64) -> Option<bool> {
    let mut stack = [Iv::point(0.0); MAX_DEPTH];
    let mut sp = 0;
    let mut next = reads.iter();
    for op in ops {
        match *op {
            Op::Num(v) => {
                stack[sp] = Iv::point(v);
                sp += 1;
            }
            Op::Read(_) => {
                stack[sp] = next.next()?.after(h);
                sp += 1;
            }
            Op::Compare(_, cmp, k) => {
                stack[sp] = compare(cmp, next.next()?.after(h), Iv::point(k));
                sp += 1;
            }
            Op::ReadAt(_) => return None,
            Op::Neg => stack[sp - 1] = Iv { lo: -stack[sp - 1].hi, hi: -stack[sp - 1].lo },
            Op::Not => {
                stack[sp - 1] = match stack[sp - 1].nonzero() {
                    Some(b) => Iv::truth(!b),
                    None => UNKNOWN,
                }
            }
            Op::Bin(op) => {
                sp -= 1;
                stack[sp - 1] = binary(op, stack[sp - 1], stack[sp])?;
            }
            Op::Func(f) => {
                let y = flat::second_argument(f, &stack, &mut sp, Iv::point(0.0));
                stack[sp - 1] = function(f, stack[sp - 1], y)?;
            }
        }
    }
    stack[0].nonzero()
}

/// `a op b` over intervals; `None` where no bound is known.
fn binary(op: BinOp, a: Iv, b: Iv) -> Option<Iv> {
    if a.is_point() && b.is_point() {
        // Exactly as the cycle computes it (an alarm there: no horizon, it is evaluated).
        return flat::binary(op, a.lo, b.lo, 0).ok().map(Iv::point);
    }
    match op {
        BinOp::Add => Iv::widened(a.lo + b.lo, a.hi + b.hi),
        BinOp::Sub => Iv::widened(a.lo - b.hi, a.hi - b.lo),
        BinOp::Mul => {
            let p = [a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi];
            let (lo, hi) = p.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(*v), h.max(*v)));
            Iv::widened(lo, hi)
        }
        BinOp::Div if b.lo > 0.0 || b.hi < 0.0 => {
            let q = [a.lo / b.lo, a.lo / b.hi, a.hi / b.lo, a.hi / b.hi];
            let (lo, hi) = q.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(*v), h.max(*v)));
            Iv::widened(lo, hi)
        }
        BinOp::Div | BinOp::IntDiv | BinOp::Mod => None,
        BinOp::And => Some(match (a.nonzero(), b.nonzero()) {
            (Some(false), _) | (_, Some(false)) => Iv::truth(false),
            (Some(true), Some(true)) => Iv::truth(true),
            _ => UNKNOWN,
        }),
        BinOp::Or => Some(match (a.nonzero(), b.nonzero()) {
            (Some(true), _) | (_, Some(true)) => Iv::truth(true),
            (Some(false), Some(false)) => Iv::truth(false),
            _ => UNKNOWN,
        }),
        BinOp::Xor => Some(match (a.nonzero(), b.nonzero()) {
            (Some(x), Some(y)) => Iv::truth(x != y),
            _ => UNKNOWN,
        }),
        cmp => Some(compare(cmp, a, b)),
    }
}

/// A comparison over intervals: certain only when the operands are well apart.
fn compare(op: BinOp, a: Iv, b: Iv) -> Iv {
    if a.is_point() && b.is_point() {
        return flat::binary(op, a.lo, b.lo, 0).map_or(UNKNOWN, Iv::point);
    }
    // The margin is relative to the ends compared (an unbounded range's other end is none).
    let below = a.hi < b.lo - APART * a.hi.abs().max(b.lo.abs());
    let above = a.lo > b.hi + APART * a.lo.abs().max(b.hi.abs());
    if !(below || above) {
        return UNKNOWN;
    }
    Iv::truth(match op {
        BinOp::Lt | BinOp::Le => below,
        BinOp::Gt | BinOp::Ge => above,
        BinOp::Ne => true,
        _ => false,
    })
}

/// A function over an interval; `None` where it is not monotone or leaves its domain.
fn function(f: Func, x: Iv, y: Iv) -> Option<Iv> {
    if x.is_point() && y.is_point() {
        return flat::function(f, x.lo, y.lo, 0).ok().map(Iv::point);
    }
    let size = x.magnitude();
    match f {
        Func::Sqrt if x.lo >= 0.0 => Iv::widened(x.lo.sqrt(), x.hi.sqrt()),
        Func::Abs if x.lo >= 0.0 => Some(x),
        Func::Abs if x.hi <= 0.0 => Some(Iv { lo: -x.hi, hi: -x.lo }),
        Func::Abs => Some(Iv { lo: 0.0, hi: size }),
        Func::Pot => {
            let lo = if x.lo > 0.0 {
                x.lo * x.lo
            } else if x.hi < 0.0 {
                x.hi * x.hi
            } else {
                0.0
            };
            Iv::widened(lo, size * size)
        }
        Func::Trunc => Some(Iv { lo: x.lo.trunc(), hi: x.hi.trunc() }),
        Func::Round => Some(Iv { lo: x.lo.round(), hi: x.hi.round() }),
        Func::Exp if x.hi.exp().is_finite() => Iv::widened(x.lo.exp(), x.hi.exp()),
        Func::Ln if x.lo > 0.0 && x.hi.is_finite() => Iv::widened(x.lo.ln(), x.hi.ln()),
        Func::MinVal => Some(Iv { lo: x.lo.min(y.lo), hi: x.hi.min(y.hi) }),
        Func::MaxVal => Some(Iv { lo: x.lo.max(y.lo), hi: x.hi.max(y.hi) }),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interp::synchronized::compile::{CExpr as E, SyncVar};
    use crate::interp::synchronized::flat::lower;

    /// X (`$AA_IM[X]`) at 10 moving at most 1 per cycle, Y at 0 likewise, `$AC_TIME` at
    /// 0.2 s growing 4 ms per cycle, `$AA_VACTM[X]` anywhere in ±100, marker 1 = 3, `$R` unknown.
    struct Vars;

    impl Bounds for Vars {
        fn bound(&self, slot: Slot) -> Option<Bound> {
            let (inf, ninf) = (f64::INFINITY, f64::NEG_INFINITY);
            Some(match slot {
                Slot::AaIm(0) => Bound { value: 10.0, rate: 1.0, lo: ninf, hi: inf },
                Slot::AaIm(1) => Bound { value: 0.0, rate: 1.0, lo: ninf, hi: inf },
                Slot::AcTime => Bound { value: 0.2, rate: 0.004, lo: 0.0, hi: inf },
                Slot::AaVactm(0) => Bound { value: 7.0, rate: inf, lo: -100.0, hi: 100.0 },
                Slot::Marker(1) => Bound::fixed(3.0),
                _ => return None,
            })
        }
    }

    fn var(v: SyncVar) -> E {
        E::Var(v)
    }

    fn bin(op: BinOp, a: E, b: E) -> E {
        E::Bin(op, Box::new(a), Box::new(b))
    }

    fn h(e: &E, now: bool) -> u64 {
        horizon(&lower(e), &Vars, now)
    }

    fn x() -> E {
        var(SyncVar::AaIm(0))
    }

    #[test]
    fn a_position_threshold_sleeps_until_the_axis_could_reach_it() {
        // X = 10 at most 1 per cycle: X > 20 cannot hold in the next 9 cycles (X ≤ 19); in the
        // 10th X may be 20 (within the margin): it is evaluated then.
        assert_eq!(h(&bin(BinOp::Gt, x(), E::Num(20.0)), false), 9);
        // X < 5 is false for 4 cycles (X ≥ 6), X >= 10 true for none (X may fall at once).
        assert_eq!(h(&bin(BinOp::Lt, x(), E::Num(5.0)), false), 4);
        assert_eq!(h(&bin(BinOp::Ge, x(), E::Num(10.0)), true), 0);
        // A value that does not match the evaluation's (rounding): no horizon.
        assert_eq!(h(&bin(BinOp::Gt, x(), E::Num(20.0)), true), 0);
    }

    #[test]
    fn a_time_threshold_sleeps_until_the_cycle_before_it_flips() {
        // 0.2 s + 4 ms·h stays below 0.5 s for h ≤ 74; in cycle 75 $AC_TIME is 0.5 (not above
        // it within the REAL tolerance), in cycle 76 0.504: the evaluation in 75 comes first.
        assert_eq!(h(&bin(BinOp::Gt, var(SyncVar::AcTime), E::Num(0.5)), false), 74);
    }

    #[test]
    fn ranges_and_interval_arithmetic_give_long_horizons() {
        // |$AA_VACTM[X]| ≤ 100: SQRT(POT(v)) > 1000 never holds.
        let v = || var(SyncVar::AaVactm(0));
        let pot = |e| E::Func(Func::Pot, vec![e]);
        let sqrt = E::Func(Func::Sqrt, vec![pot(v())]);
        assert_eq!(h(&bin(BinOp::Gt, sqrt, E::Num(1000.0)), false), MAX_HORIZON);
        // SQRT(POT(X − 10) + POT(Y)) > 5 from X = 10, Y = 0: √2·h < 5 for h ≤ 3.
        let dx = bin(BinOp::Sub, x(), E::Num(10.0));
        let radius = E::Func(Func::Sqrt, vec![bin(BinOp::Add, pot(dx), pot(var(SyncVar::AaIm(1))))]);
        assert_eq!(h(&bin(BinOp::Gt, radius, E::Num(5.0)), false), 3);
        // AND is false while one side is: X > 100 (false for 89 cycles) AND an unbounded
        // velocity comparison.
        let and = bin(BinOp::And, bin(BinOp::Gt, x(), E::Num(100.0)), bin(BinOp::Gt, v(), E::Num(50.0)));
        assert_eq!(h(&and, false), 89);
    }

    #[test]
    fn linear_conditions_get_the_horizon_of_the_comparison_that_decides_them() {
        let y = || var(SyncVar::AaIm(1));
        let marker = || var(SyncVar::AcMarker(Box::new(E::Num(1.0))));
        // (X > M1 + 2000) AND (Y < -100), X = 10, Y = 0, M1 = 3, 1 per cycle each: both false;
        // the AND holds while the later one does: X stays below 2003 for 1992 cycles, after
        // 1993 it may be 2003 (not above it by the margin); Y could flip after 100.
        let far = bin(BinOp::Gt, x(), bin(BinOp::Add, marker(), E::Num(2000.0)));
        let and = bin(BinOp::And, far.clone(), bin(BinOp::Lt, y(), E::Num(-100.0)));
        assert_eq!(linear::reach(&lower(&and).ops, &reads(&and), false), Some(1993.0));
        assert_eq!(h(&and, false), 1992);
        // OR of two false sides: false while both are; (X−Y)/2 < −6 needs X−Y to fall by 2
        // per cycle from 10 to −12: 11 cycles, at the 11th it may be −12 exactly.
        let half = bin(BinOp::Div, bin(BinOp::Sub, x(), y()), E::Num(2.0));
        let or = bin(BinOp::Or, far, bin(BinOp::Lt, half, E::Num(-6.0)));
        assert_eq!(h(&or, false), 10);
        // NOT and a true AND: true while both sides are: X < 30 for 19 cycles, Y > -5 for 4.
        let both =
            bin(BinOp::And, bin(BinOp::Lt, x(), E::Num(30.0)), E::Not(Box::new(bin(BinOp::Le, y(), E::Num(-5.0)))));
        assert_eq!(h(&both, true), 4);
        // Not linear (a product of two moving values): no guess, the search decides.
        let product = bin(BinOp::Gt, bin(BinOp::Mul, x(), y()), E::Num(50.0));
        assert_eq!(linear::reach(&lower(&product).ops, &reads(&product), false), None);
    }

    /// The bounds a condition reads, in order.
    fn reads(e: &E) -> Vec<Bound> {
        let code = lower(e);
        code.ops
            .iter()
            .filter_map(|op| match op {
                Op::Read(s) | Op::Compare(s, _, _) => Vars.bound(*s),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn data_and_constants_keep_their_value_and_unknowns_give_no_horizon() {
        let marker = bin(BinOp::Eq, var(SyncVar::AcMarker(Box::new(E::Num(1.0)))), E::Num(3.0));
        assert_eq!(h(&marker, true), MAX_HORIZON);
        // $R is not bounded; a divisor that may be 0 neither; nor trigonometry.
        assert_eq!(h(&bin(BinOp::Gt, var(SyncVar::R(Box::new(E::Num(1.0)))), E::Num(1.0)), false), 0);
        let div = bin(BinOp::Div, E::Num(1.0), var(SyncVar::AaIm(1)));
        assert_eq!(h(&bin(BinOp::Gt, div, E::Num(1.0)), false), 0);
        let sin = E::Func(Func::Sin, vec![x()]);
        assert_eq!(h(&bin(BinOp::Gt, sin, E::Num(2.0)), false), 0);
    }
}

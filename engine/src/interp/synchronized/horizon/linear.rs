//! A first guess of a condition's horizon in one pass, for conditions linear in their
//! variables (`($AA_IW[X]>$AC_PARAM[3]+2000) AND ($AA_IW[Z]<-100)`): each value is carried as
//! its value now and the most it changes per cycle, each comparison gives the cycles until
//! its two sides could meet, and AND/OR/NOT combine those as the interval evaluation does (a
//! false AND holds while one false side holds, a true one while both do). The guess is only
//! a candidate: `horizon` checks it with the interval evaluation, and searches when it fails.

use super::{Bound, MAX_DEPTH};
use crate::interp::synchronized::compile::Func;
use crate::interp::synchronized::flat::{self, Op};
use crate::lang::sync_action::BinOp;

/// A value on the stack: a number as `c ± w·h` after `h` cycles, or a truth value with the
/// cycles it certainly keeps.
#[derive(Clone, Copy)]
enum V {
    Num { c: f64, w: f64 },
    Truth { v: bool, h: f64 },
}

impl V {
    /// As a truth value: nonzero, until it could reach zero.
    fn truth(self) -> (bool, f64) {
        match self {
            V::Truth { v, h } => (v, h),
            V::Num { c, w } => (c != 0.0, cycles(c, w)),
        }
    }
}

/// The cycles until `c ± w·h` could reach 0.
fn cycles(c: f64, w: f64) -> f64 {
    if w == 0.0 { f64::INFINITY } else { c.abs() / w }
}

/// The cycles the condition (`ops`, reading `reads` in order) certainly keeps its value `now`,
/// estimated; `None` when it is not linear, or the value found is not `now`.
pub(super) fn reach(ops: &[Op], reads: &[Bound], now: bool) -> Option<f64> {
    let mut stack = [V::Num { c: 0.0, w: 0.0 }; MAX_DEPTH];
    let mut sp = 0;
    let mut next = reads.iter();
    for op in ops {
        let value = match *op {
            Op::Num(c) => V::Num { c, w: 0.0 },
            Op::Read(_) => {
                let b = next.next()?;
                V::Num { c: b.value, w: b.rate }
            }
            Op::Compare(_, cmp, k) => {
                let b = next.next()?;
                compare(cmp, (b.value, b.rate), (k, 0.0))?
            }
            Op::ReadAt(_) => return None,
            Op::Neg => match stack[sp - 1] {
                V::Num { c, w } => {
                    sp -= 1;
                    V::Num { c: -c, w }
                }
                V::Truth { .. } => return None,
            },
            Op::Not => {
                sp -= 1;
                let (v, h) = stack[sp].truth();
                V::Truth { v: !v, h }
            }
            Op::Bin(op) => {
                sp -= 2;
                binary(op, stack[sp], stack[sp + 1])?
            }
            Op::Func(f) => {
                let two = matches!(f, Func::Atan2 | Func::MinVal | Func::MaxVal);
                sp -= 1 + usize::from(two);
                function(f, stack[sp], two.then(|| stack[sp + 1]))?
            }
        };
        stack[sp] = value;
        sp += 1;
    }
    let (v, h) = stack[0].truth();
    (sp == 1 && v == now && !h.is_nan()).then_some(h.floor())
}

fn num(v: V) -> Option<(f64, f64)> {
    match v {
        V::Num { c, w } => Some((c, w)),
        V::Truth { .. } => None,
    }
}

fn binary(op: BinOp, a: V, b: V) -> Option<V> {
    match op {
        BinOp::And | BinOp::Or | BinOp::Xor => {
            let ((x, hx), (y, hy)) = (a.truth(), b.truth());
            let (v, h) = match op {
                // False while a false side is; true while both are.
                BinOp::And if !(x && y) => (
                    false,
                    if x {
                        hy
                    } else if y {
                        hx
                    } else {
                        hx.max(hy)
                    },
                ),
                BinOp::Or if x || y => (
                    true,
                    if !x {
                        hy
                    } else if !y {
                        hx
                    } else {
                        hx.max(hy)
                    },
                ),
                BinOp::And => (true, hx.min(hy)),
                BinOp::Or => (false, hx.min(hy)),
                _ => (x != y, hx.min(hy)),
            };
            Some(V::Truth { v, h })
        }
        BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Gt | BinOp::Le | BinOp::Ge => compare(op, num(a)?, num(b)?),
        _ => {
            let ((ca, wa), (cb, wb)) = (num(a)?, num(b)?);
            let (c, w) = match op {
                BinOp::Add => (ca + cb, wa + wb),
                BinOp::Sub => (ca - cb, wa + wb),
                BinOp::Mul if wb == 0.0 => (ca * cb, wa * cb.abs()),
                BinOp::Mul if wa == 0.0 => (ca * cb, wb * ca.abs()),
                BinOp::Div if wb == 0.0 && cb != 0.0 => (ca / cb, wa / cb.abs()),
                _ => return None,
            };
            Some(V::Num { c, w })
        }
    }
}

/// `a <op> b` now, and the cycles until the two sides could meet.
fn compare(op: BinOp, (ca, wa): (f64, f64), (cb, wb): (f64, f64)) -> Option<V> {
    let v = flat::binary(op, ca, cb, 0).ok()? != 0.0;
    Some(V::Truth { v, h: cycles(ca - cb, wa + wb) })
}

/// ABS, MINVAL and MAXVAL change at most as fast as their arguments.
fn function(f: Func, x: V, y: Option<V>) -> Option<V> {
    let (cx, wx) = num(x)?;
    let (c, w) = match (f, y.map(num)) {
        (Func::Abs, None) => (cx.abs(), wx),
        (Func::MinVal, Some(Some((cy, wy)))) => (cx.min(cy), wx.max(wy)),
        (Func::MaxVal, Some(Some((cy, wy)))) => (cx.max(cy), wx.max(wy)),
        _ => return None,
    };
    Some(V::Num { c, w })
}

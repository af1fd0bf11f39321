//! The vector chain of an orientation kinematics (REFERENCE §6.4.1): offset vectors l1..l4,
//! rotary axis directions v1..v3 and the basic tool orientation b. The same chain describes a
//! 5-axis transformation (TRAORI) and an orientable toolholder (TCARR), so it knows nothing of
//! machine data: the caller fills it in and passes effective angles in radians.
//!
//! With R1 = R(v1, α1), R2 = R(v2, α2), R3 = R(v3, α3), M the linear machine axes, P the tool
//! tip in the BCS and t_c the tool vector from the holder reference to the tip:
//! * tool (T): `P = M + l1 + R1·(l2 + R2·(l23 + R3·(l3 + t_c)))`, `o = R1·R2·R3·b`;
//! * part (P): `P = R2ᵀ·(R1ᵀ·(M + t_c − l2) − l3) − l4`, `o = R2ᵀ·R1ᵀ·b`;
//! * mixed (M, axis 1 on the tool, axis 2 on the table):
//!   `P = R2ᵀ·(M + l1 + R1·(l2 + t_c) − l3) − l4`, `o = R2ᵀ·R1·b`.
//!
//! Missing axes (3-/4-axis variants) are the identity rotation; a third axis (6-axis, T only)
//! sits between axis 2 and the tool with the offset `l23` before it.

use super::solve::{AxisPair, Turn, angle_about};
use super::stepped::AngleMemo;
use super::vec3::{Rot, add, sub};
use crate::kinematics::Vec3;

/// Which part of the machine the rotary axes move.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ChainKind {
    /// Both (all) rotary axes turn the tool: swivel head, machine type 1, `$TC_CARR23 = "T"`.
    Tool,
    /// Both rotary axes turn the workpiece: tilting rotary table, type 2, `"P"`.
    Part,
    /// Axis 1 turns the tool, axis 2 the workpiece: type 3, `"M"`.
    Mixed,
}

/// One orientation kinematics. Directions and `base` are unit vectors.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    pub kind: ChainKind,
    /// Number of rotary axes (1..=3); axes beyond it are ignored.
    pub axes: usize,
    pub v: [Vec3; 3],
    pub l1: Vec3,
    pub l2: Vec3,
    pub l3: Vec3,
    pub l4: Vec3,
    /// Offset between rotary axes 2 and 3 (6-axis tool kinematics).
    pub l23: Vec3,
    /// Basic tool orientation (tip → holder) at zero angles.
    pub base: Vec3,
}

/// The rotations of one pose, built once and applied to several vectors.
#[derive(Debug, Clone, Copy)]
pub struct Pose {
    pub r: [Rot; 3],
}

impl Chain {
    /// The rotations for effective angles `alpha` (radians).
    pub fn pose(&self, alpha: &[f64; 3]) -> Pose {
        let r = std::array::from_fn(|i| if i < self.axes { Rot::about(&self.v[i], alpha[i]) } else { Rot::IDENTITY });
        Pose { r }
    }

    /// [`Chain::pose`] from angles given with their cosine and sine (no `sin_cos`).
    #[inline]
    pub fn pose_turns(&self, turns: &[Turn; 3]) -> Pose {
        let r = std::array::from_fn(|i| {
            if i < self.axes { Rot::about_cs(&self.v[i], turns[i].cos, turns[i].sin) } else { Rot::IDENTITY }
        });
        Pose { r }
    }

    /// Tool orientation in the BCS at `pose`.
    pub fn orientation(&self, pose: &Pose) -> Vec3 {
        let [r1, r2, r3] = &pose.r;
        match self.kind {
            ChainKind::Tool => r1.apply(&r2.apply(&r3.apply(&self.base))),
            ChainKind::Part => r2.apply_t(&r1.apply_t(&self.base)),
            ChainKind::Mixed => r2.apply_t(&r1.apply(&self.base)),
        }
    }

    /// Forward: tool tip in the BCS for linear axes `m`, tool vector `t_c` (holder → tip).
    pub fn tip(&self, m: &Vec3, pose: &Pose, t_c: &Vec3) -> Vec3 {
        let [r1, r2, r3] = &pose.r;
        match self.kind {
            ChainKind::Tool => {
                let inner = add(&self.l23, &r3.apply(&add(&self.l3, t_c)));
                add(&add(m, &self.l1), &r1.apply(&add(&self.l2, &r2.apply(&inner))))
            }
            ChainKind::Part => {
                let x = sub(&add(m, t_c), &self.l2);
                sub(&r2.apply_t(&sub(&r1.apply_t(&x), &self.l3)), &self.l4)
            }
            ChainKind::Mixed => {
                let tool_tip = add(&add(m, &self.l1), &r1.apply(&add(&self.l2, t_c)));
                sub(&r2.apply_t(&sub(&tool_tip, &self.l3)), &self.l4)
            }
        }
    }

    /// Inverse position: the linear axes that put the tool tip on BCS point `p` at `pose`.
    pub fn linear(&self, p: &Vec3, pose: &Pose, t_c: &Vec3) -> Vec3 {
        let [r1, r2, r3] = &pose.r;
        match self.kind {
            ChainKind::Tool => {
                let inner = add(&self.l23, &r3.apply(&add(&self.l3, t_c)));
                sub(&sub(p, &self.l1), &r1.apply(&add(&self.l2, &r2.apply(&inner))))
            }
            ChainKind::Part => {
                let x = add(&self.l2, &r1.apply(&add(&self.l3, &r2.apply(&add(&self.l4, p)))));
                sub(&x, t_c)
            }
            ChainKind::Mixed => {
                let table = add(&self.l3, &r2.apply(&add(&self.l4, p)));
                sub(&sub(&table, &self.l1), &r1.apply(&add(&self.l2, t_c)))
            }
        }
    }

    /// Both angle sets (radians) that give BCS orientation `o`; the 3rd angle (6-axis) is
    /// given, not solved. `hint` supplies the free angle in a pole (the previous angles).
    /// `None` if `o` cannot be reached. With one rotary axis there is one solution (returned
    /// twice) and the component of `o` along the axis is ignored: the orientation is projected
    /// onto the cone the axis can sweep (3-/4-axis transformations orient in one plane).
    pub fn solve(&self, o: &Vec3, hint: &[f64; 3]) -> Option<[[f64; 3]; 2]> {
        Some(self.solve_turns(o, hint)?.map(|[a1, a2, _]| [a1.angle, a2.angle, hint[2]]))
    }

    /// [`Chain::solve`] with the cosine and sine of each angle, for [`Chain::pose_turns`]. The
    /// 3rd turn is `hint[2]` with a 3rd axis and no rotation without.
    #[inline]
    pub fn solve_turns(&self, o: &Vec3, hint: &[f64; 3]) -> Option<[[Turn; 3]; 2]> {
        self.solve_turns_stepped(o, hint, &mut AngleMemo::default())
    }

    /// [`Chain::solve_turns`] once per IPO cycle, the angles stepped from the last cycle's in
    /// `memo` (see [`super::stepped`]).
    #[inline]
    pub fn solve_turns_stepped(&self, o: &Vec3, hint: &[f64; 3], memo: &mut AngleMemo) -> Option<[[Turn; 3]; 2]> {
        self.solve_turns_paired(&self.axis_pair(), o, hint, memo)
    }

    /// The first two axes in the order the solve of this kind of chain passes them to
    /// subproblem 2, with their constant terms: built once per transformation.
    pub fn axis_pair(&self) -> AxisPair {
        let [v1, v2, _] = &self.v;
        match self.kind {
            ChainKind::Tool | ChainKind::Part => AxisPair::new(v1, v2),
            ChainKind::Mixed => AxisPair::new(v2, v1),
        }
    }

    /// [`Chain::solve_turns_stepped`] with `pair`, this chain's [`Chain::axis_pair`].
    #[inline(always)]
    pub fn solve_turns_paired(
        &self,
        pair: &AxisPair,
        o: &Vec3,
        hint: &[f64; 3],
        memo: &mut AngleMemo,
    ) -> Option<[[Turn; 3]; 2]> {
        let [v1, _, v3] = &self.v;
        let third = if self.axes == 3 { Turn::new(hint[2]) } else { Turn::ZERO };
        if self.axes == 1 {
            let a = match self.kind {
                ChainKind::Tool => angle_about(v1, &self.base, o),
                // Part (and a lone axis of a mixed chain, refused at build time): R1ᵀ·b = o.
                _ => angle_about(v1, o, &self.base),
            }
            .unwrap_or(hint[0]);
            return Some([[Turn::new(a), Turn::new(hint[1]), third]; 2]);
        }
        let s = match self.kind {
            ChainKind::Tool => {
                let p =
                    if self.axes == 3 { Rot::about_cs(v3, third.cos, third.sin).apply(&self.base) } else { self.base };
                pair.turns_stepped(&p, o, [hint[0], hint[1]], memo)?
            }
            ChainKind::Part => pair.turns_stepped(o, &self.base, [hint[0], hint[1]], memo)?,
            ChainKind::Mixed => {
                // R(v2, −α2)·R(v1, α1)·b = o: subproblem 2 with the axes swapped.
                let s = pair.turns_stepped(&self.base, o, [-hint[1], hint[0]], memo)?;
                s.map(|[t1, t2]| [t2, t1.reversed()])
            }
        };
        Some(s.map(|[a1, a2]| [a1, a2, third]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const X: Vec3 = [1.0, 0.0, 0.0];
    const Z: Vec3 = [0.0, 0.0, 1.0];

    fn head_ca() -> Chain {
        Chain {
            kind: ChainKind::Tool,
            axes: 2,
            v: [Z, X, Z],
            l1: [0.0, 0.0, 100.0],
            l2: [0.0; 3],
            l3: [0.0, 0.0, -100.0],
            l4: [0.0; 3],
            l23: [0.0; 3],
            base: Z,
        }
    }

    #[test]
    fn the_closed_chain_is_the_identity_at_zero_angles() {
        let c = head_ca();
        let pose = c.pose(&[0.0; 3]);
        assert_eq!(c.tip(&[1.0, 2.0, 3.0], &pose, &[0.0, 0.0, -50.0]), [1.0, 2.0, -47.0]);
        assert_eq!(c.orientation(&pose), Z);
    }

    #[test]
    fn linear_inverts_tip_for_each_kind() {
        for kind in [ChainKind::Tool, ChainKind::Part, ChainKind::Mixed] {
            let c = Chain {
                kind,
                axes: 2,
                v: [[0.0, 1.0, 0.0], [0.6, 0.0, 0.8], Z],
                l1: [1.0, 2.0, 3.0],
                l2: [-4.0, 5.0, 6.0],
                l3: [7.0, -8.0, 9.0],
                l4: [1.5, 2.5, -3.5],
                l23: [0.0; 3],
                base: Z,
            };
            let pose = c.pose(&[0.3, -1.1, 0.0]);
            let t_c = [0.0, 0.0, -42.0];
            let m = [10.0, -20.0, 30.0];
            let back = c.linear(&c.tip(&m, &pose, &t_c), &pose, &t_c);
            assert!((0..3).all(|i| (back[i] - m[i]).abs() < 1e-12), "{kind:?}: {back:?}");
        }
    }
}

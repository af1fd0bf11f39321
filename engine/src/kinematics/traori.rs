//! TRAORI (types 16..255): the orientation transformation of 3- to 6-axis machines with a
//! swivel head, a tilting rotary table or both (REFERENCE §6). The contour is programmed as the
//! tool tip (TCP) in the BCS; the orientation either as rotary axis positions (A=, C=, which
//! pass through) or as a vector/angles that [`Traori::orientation_axes`] turns into rotary
//! positions.
//!
//! Roles of `TRAFO_AXES_IN_n`: [0..2] the linear axes along X, Y, Z of the chain, [3] the 1st,
//! [4] the 2nd, [5] the 3rd rotary axis (6-axis), [6] the 7th axis (7-axis, see
//! [`super::seventh`]). A 0 entry leaves the role out (3-/4-axis).
//! On the BCS side the geometry slots hold the TCP, the rotary slots their own positions.
//!
//! Math: the vector chain of [`super::orient::chain`], with effective angles
//! `α = s·(position − TRAFO5_ROT_AX_OFFSET)`, s = +1 if `TRAFO5_ROT_SIGN_IS_PLUS` else −1.
//! The tool vector from the holder reference to the tip is `t_c = −L` (L = tool length vector
//! by geometry axis, tip → holder).

use super::orient::rotation::zero_normal;
use super::orient::solve::{AxisPair, Turn};
use super::orient::stepped::AngleMemo;
use super::orient::vec3::{dot, normalize, scale};
use super::orient::{Chain, ChainKind};
use super::seventh::Seventh;
use super::{BuildError, SelectArgs, Transformation, Unreachable, Vec3, unwrap_near};
use crate::machine_data::{MachineConfig, OriMachine, TrafoDataSet, TrafoParams};
use crate::motion::{AxisVec, Path};

/// One rotary axis of the transformation as the inverse needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Rotary {
    slot: usize,
    /// `TRAFO5_ROT_AX_OFFSET`: position of the kinematic zero (degrees).
    offset: f64,
    /// +1 or −1 (`TRAFO5_ROT_SIGN_IS_PLUS`).
    sign: f64,
    /// Software limits; `None` for a modulo axis (any turn is allowed).
    limits: Option<(f64, f64)>,
    /// Seconds per degree at the axis' maximum velocity: the weight of the nearest-solution choice.
    weight: f64,
}

impl Rotary {
    fn angle(&self, pos: f64) -> f64 {
        (self.sign * (pos - self.offset)).to_radians()
    }

    fn position(&self, angle: f64) -> f64 {
        self.offset + self.sign * angle.to_degrees()
    }

    /// `pos` shifted by whole turns to the value nearest `near` that lies within the limits.
    fn place(&self, pos: f64, near: f64) -> Option<f64> {
        let p = unwrap_near(pos, near);
        let Some((lo, hi)) = self.limits else { return Some(p) };
        // p itself is the nearest turn (|p − near| ≤ 180°, and ties keep p): the usual case
        // needs no search.
        if p >= lo - 1e-9 && p <= hi + 1e-9 {
            return Some(p);
        }
        [0.0, -360.0, 360.0, -720.0, 720.0]
            .into_iter()
            .map(|k| p + k)
            .filter(|q| *q >= lo - 1e-9 && *q <= hi + 1e-9)
            .min_by(|a, b| (a - near).abs().total_cmp(&(b - near).abs()))
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct Traori {
    trafo_type: u32,
    chain: Chain,
    /// The chain's [`Chain::axis_pair`], built once: the per-cycle solve reuses its terms.
    pair: AxisPair,
    /// Channel axes of the linear roles [0..2].
    lin: [Option<usize>; 3],
    geo: [Option<usize>; 3],
    /// The rotary axes in chain order (roles [3], [4], [5] without the empty ones).
    rot: [Option<Rotary>; 3],
    /// Channel axes of roles [3], [4], [5]: the orientation slots.
    ori_slots: [Option<usize>; 3],
    /// Index into `rot` of each role [3], [4], [5].
    role_to_chain: [Option<usize>; 3],
    /// `TRAFO5_NON_POLE_LIMIT`, `TRAFO5_POLE_LIMIT` (degrees).
    non_pole_limit: f64,
    pole_limit: f64,
    /// Tool normal at the zero position (perpendicular to the basic orientation): the
    /// rotation vector of THETA = 0 in the basic orientation (6-axis).
    normal: Vec3,
    /// The 7th axis turning the workpiece (generic 7-axis transformation).
    seventh: Option<Seventh>,
}

impl Traori {
    /// The transformation of `set`; rotary-axis limits and velocities come from `cfg`.
    /// `args.base_orient` (TRAORI(n, x, y, z)) replaces the basic orientation of generic types.
    pub fn new(set: &TrafoDataSet, cfg: &MachineConfig, args: &SelectArgs) -> Result<Traori, BuildError> {
        let TrafoParams::Traori(p) = &set.params else { unreachable!("a TRAORI data set has TRAORI parameters") };
        // Priority of the basic orientation of generic types (F2 §3.9.1): the vector of the
        // call, then the active tool's orientation, then TRAFO5_BASE_ORIENT.
        let base = match (args.base_orient, args.tool_orient) {
            (Some(b), _) if p.generic => {
                normalize(&b).ok_or_else(|| BuildError::Value("TRAORI basic orientation is the zero vector".into()))?
            }
            (None, Some(t)) if p.generic => normalize(&t).unwrap_or(p.base_orient),
            _ => p.base_orient,
        };
        let normal_in = match args.tool_normal {
            Some(n) if p.generic && args.base_orient.is_none() => n,
            _ => p.base_orient_normal,
        };
        let mut rot = [None; 3];
        let mut v = [[0.0; 3]; 3];
        let mut role_to_chain = [None; 3];
        let mut n = 0;
        for (role, entry) in set.axes_in[3..6].iter().enumerate() {
            let Some(slot) = *entry else { continue };
            let axis = cfg.axis(slot);
            rot[n] = Some(Rotary {
                slot,
                offset: p.rot_offset[role],
                sign: if p.sign_plus[role] { 1.0 } else { -1.0 },
                limits: axis.modulo.is_none().then_some((axis.limit_minus, axis.limit_plus)),
                weight: 1.0 / axis.max_velocity,
            });
            v[n] = p.axis[role];
            role_to_chain[role] = Some(n);
            n += 1;
        }
        let zero = [0.0; 3];
        let (kind, l1, l2, l3, l4) = match p.machine {
            OriMachine::Tool => (ChainKind::Tool, p.part_offset, p.joint_offset, p.base_tool, zero),
            OriMachine::Part => (ChainKind::Part, zero, p.base_tool, p.joint_offset, p.part_offset),
            OriMachine::Mixed => (ChainKind::Mixed, p.joint_offset, p.base_tool, p.joint_offset_part, p.part_offset),
        };
        let normal = zero_normal(&base, &normal_in);
        let chain = Chain { kind, axes: n, v, l1, l2, l3, l4, l23: p.joint_offset_2_3, base };
        Ok(Traori {
            trafo_type: set.trafo_type,
            pair: chain.axis_pair(),
            chain,
            lin: [set.axes_in[0], set.axes_in[1], set.axes_in[2]],
            geo: set.geo_axes,
            rot,
            ori_slots: [set.axes_in[3], set.axes_in[4], set.axes_in[5]],
            role_to_chain,
            non_pole_limit: p.non_pole_limit,
            pole_limit: p.pole_limit,
            normal,
            seventh: set.axes_in[6].map(|slot| Seventh { slot, offset: p.ext_offset, axis: p.ext_axis }),
        })
    }

    /// A BCS (workpiece) direction `v` in the frame of the tool chain for the 7th axis at
    /// `axes` (unchanged without a 7th axis): where the pole tests of the orientation
    /// interpolation look, since the pole is a direction of the tool kinematics.
    pub fn in_chain_frame(&self, v: &Vec3, axes: &AxisVec) -> Vec3 {
        self.workpiece_to_chain(v, axes)
    }

    /// [`Traori::in_chain_frame`] backwards.
    pub fn in_workpiece_frame(&self, v: &Vec3, axes: &AxisVec) -> Vec3 {
        self.chain_to_workpiece(v, axes)
    }

    /// The channel axis of the 7th axis (`TRAFO_AXES_IN_n[6]`), which turns the workpiece; its
    /// BCS value is its own position.
    pub fn seventh_slot(&self) -> Option<usize> {
        self.seventh.map(|s| s.slot)
    }

    /// `v` (a BCS vector: workpiece-fixed) in the frame of the tool chain for the 7th axis
    /// at `axes`; unchanged without a 7th axis.
    #[inline]
    fn workpiece_to_chain(&self, v: &Vec3, axes: &AxisVec) -> Vec3 {
        self.seventh.map_or(*v, |s| s.rotation(axes).apply(v))
    }

    /// [`Traori::workpiece_to_chain`] backwards: a chain-frame vector in workpiece (BCS) coordinates.
    #[inline]
    fn chain_to_workpiece(&self, v: &Vec3, axes: &AxisVec) -> Vec3 {
        self.seventh.map_or(*v, |s| s.rotation(axes).apply_t(v))
    }

    /// The tool tip and the tool orientation (unit, tip → holder) in the workpiece frame (the
    /// BCS of this transformation) at machine positions `machine`, for the tool length vector
    /// `tool` (tip → holder, by geometry axis). Whether or not the transformation is active:
    /// the stock turns with a table's rotary axes in any case (`channel/stock/pose.rs`).
    pub fn tip_and_orientation(&self, machine: &AxisVec, tool: &Vec3) -> (Vec3, Vec3) {
        let pose = self.chain.pose(&self.angles(machine));
        let p = self.chain.tip(&self.linear(machine), &pose, &scale(tool, -1.0));
        let o = self.chain.orientation(&pose);
        (self.chain_to_workpiece(&p, machine), self.chain_to_workpiece(&o, machine))
    }

    /// The vector chain (for the toolholder and for tests).
    pub fn chain(&self) -> &Chain {
        &self.chain
    }

    /// `TRAFO5_NON_POLE_LIMIT` and `TRAFO5_POLE_LIMIT` in degrees: the interpolator passes a
    /// great circle exactly through the pole when it comes closer than the first
    /// ([`Traori::pole_angle`]) and the end orientation deviates by less than the second.
    pub fn pole_limits(&self) -> (f64, f64) {
        (self.non_pole_limit, self.pole_limit)
    }

    /// Angle (degrees, 0..90) between orientation `o` and the pole line of this kinematics: the
    /// direction at which one rotary axis becomes free (head and mixed: the outer axis of the
    /// orientation equation, table: the inner one). 90 for one-axis variants.
    pub fn pole_angle(&self, o: &Vec3) -> f64 {
        if self.chain.axes < 2 {
            return 90.0;
        }
        let Some(o) = normalize(o) else { return 90.0 };
        let axis = match self.chain.kind {
            ChainKind::Tool => &self.chain.v[0],
            ChainKind::Part | ChainKind::Mixed => &self.chain.v[1],
        };
        dot(&o, axis).abs().clamp(0.0, 1.0).acos().to_degrees()
    }

    /// The channel axis that becomes free in the pole ([`Traori::pole_angle`] = 0): the outer
    /// axis of a head, the inner (table) axis of a table or mixed kinematics. The
    /// interpolator keeps it still when it passes through the pole. `None` for one axis.
    pub fn pole_slot(&self) -> Option<usize> {
        if self.chain.axes < 2 {
            return None;
        }
        let i = match self.chain.kind {
            ChainKind::Tool => 0,
            ChainKind::Part | ChainKind::Mixed => 1,
        };
        self.rot[i].map(|r| r.slot)
    }

    /// Both rotary-axis solutions for orientation `o`, each indexed like
    /// [`Transformation::orientation_slots`] (absent axes 0), positions within ±180° of
    /// `TRAFO5_ROT_AX_OFFSET`, sorted by the position of the first present rotary axis
    /// (lower first: CYCLE800's "minus" direction). In a pole the free axis is at its zero
    /// position; a one-axis variant returns its single solution twice.
    pub fn solutions(&self, o: &Vec3) -> Result<[[f64; 3]; 2], Unreachable> {
        let hint = self.hint(None);
        let mut s = self.raw_solutions(o, &hint)?.map(|a| self.by_role(&a, |r, x| r.position(x)));
        let first = self.role_to_chain.iter().position(Option::is_some).expect("at least one rotary axis");
        if s[1][first] < s[0][first] {
            s.swap(0, 1);
        }
        Ok(s)
    }

    /// [`Traori::solutions`] for an orientation `o` relative to the workpiece with the 7th axis
    /// (if any) at its position in `axes`.
    pub fn solutions_at(&self, o: &Vec3, axes: &AxisVec) -> Result<[[f64; 3]; 2], Unreachable> {
        self.solutions(&self.workpiece_to_chain(o, axes))
    }

    /// Both solutions as [`Traori::solutions`], but each axis shifted by whole turns to lie
    /// closest to its position in `prev` and the free axis of a pole kept at `prev`; not
    /// sorted, not checked against the limits.
    pub fn solutions_near(&self, o: &Vec3, prev: &AxisVec) -> Result<[[f64; 3]; 2], Unreachable> {
        let hint = self.hint(Some(prev));
        Ok(self.raw_solutions(o, &hint)?.map(|a| self.by_role(&a, |r, x| unwrap_near(r.position(x), prev[r.slot]))))
    }

    /// Positions of the orientation axes (by role, like the orientation slots) in the
    /// kinematic zero position, `TRAFO5_ROT_AX_OFFSET`: where ORIRESET without values goes.
    pub fn rest_positions(&self) -> [f64; 3] {
        self.by_role(&[0.0; 3], |r, _| r.offset)
    }

    /// The channel axis of the 3rd rotary axis (role [5]) of a generic 6-axis kinematics,
    /// which turns the tool about its own axis; `None` for 3- to 5-axis kinematics.
    pub fn third_slot(&self) -> Option<usize> {
        self.role_to_chain[2].and_then(|i| self.rot[i]).map(|r| r.slot)
    }

    /// The tool normal in the zero position (`TRAFO6_BASE_ORIENT_NORMAL` made perpendicular
    /// to the basic orientation): the basic rotation vector THETA refers to under ORIROTA.
    pub fn base_normal(&self) -> Vec3 {
        self.normal
    }

    /// The tool's rotation vector in the BCS at machine position `machine` (6-axis).
    pub fn rotation_vector(&self, machine: &AxisVec) -> Vec3 {
        let r = self.chain.rotation_vector(&self.chain.pose(&self.angles(machine)), &self.normal);
        self.chain_to_workpiece(&r, machine)
    }

    /// The positions of all three rotary axes (6-axis) that give orientation `o` and rotation
    /// vector `r` (unit, perpendicular), of the two solutions the one within the limits with
    /// the least weighted travel from `prev`, written into `axes`. With a 7th axis `o` and `r`
    /// are relative to the workpiece at the 7th axis position in `axes`.
    pub fn rotated_axes(&self, o: &Vec3, r: &Vec3, prev: &AxisVec, axes: &mut AxisVec) -> Result<(), Unreachable> {
        let o = self.workpiece_to_chain(&normalize(o).ok_or(Unreachable)?, axes);
        let r = &self.workpiece_to_chain(r, axes);
        let sols = self.chain.solve_rotated(&o, r, &self.normal, &self.hint(Some(prev))).ok_or(Unreachable)?;
        let best =
            sols.iter().filter_map(|s| self.placed(s, prev)).fold(None::<(f64, [f64; 3])>, |best, (c, p)| match best {
                Some((bc, _)) if bc <= c + 1e-12 => best,
                _ => Some((c, p)),
            });
        let (_, pos) = best.ok_or(Unreachable)?;
        self.write_rotary(&pos, axes);
        Ok(())
    }

    /// Effective angles (radians) of the rotary axes at `axes` (zero without).
    fn hint(&self, axes: Option<&AxisVec>) -> [f64; 3] {
        std::array::from_fn(|i| match (&self.rot[i], axes) {
            (Some(r), Some(a)) => r.angle(a[r.slot]),
            _ => 0.0,
        })
    }

    fn raw_solutions(&self, o: &Vec3, hint: &[f64; 3]) -> Result<[[f64; 3]; 2], Unreachable> {
        Ok(self.raw_turns(o, hint)?.map(|[a1, a2, _]| [a1.angle, a2.angle, hint[2]]))
    }

    #[inline]
    fn raw_turns(&self, o: &Vec3, hint: &[f64; 3]) -> Result<[[Turn; 3]; 2], Unreachable> {
        self.raw_turns_stepped(o, hint, &mut AngleMemo::default())
    }

    #[inline(always)]
    fn raw_turns_stepped(
        &self,
        o: &Vec3,
        hint: &[f64; 3],
        memo: &mut AngleMemo,
    ) -> Result<[[Turn; 3]; 2], Unreachable> {
        let o = normalize(o).ok_or(Unreachable)?;
        self.chain.solve_turns_paired(&self.pair, &o, hint, memo).ok_or(Unreachable)
    }

    /// Chain-ordered angles → role-ordered values via `f`.
    fn by_role(&self, angles: &[f64; 3], f: impl Fn(&Rotary, f64) -> f64) -> [f64; 3] {
        std::array::from_fn(|role| match self.role_to_chain[role] {
            Some(i) => f(self.rot[i].as_ref().expect("mapped rotary axis"), angles[i]),
            None => 0.0,
        })
    }

    fn angles(&self, axes: &AxisVec) -> [f64; 3] {
        self.hint(Some(axes))
    }

    fn linear(&self, machine: &AxisVec) -> Vec3 {
        std::array::from_fn(|i| self.lin[i].map_or(0.0, |k| machine[k]))
    }

    fn point(&self, bcs: &AxisVec) -> Vec3 {
        std::array::from_fn(|g| self.geo[g].map_or(0.0, |k| bcs[k]))
    }

    /// Linear axis values `m` (chain order) into their channel axes.
    fn write_linear(&self, m: &Vec3, machine: &mut AxisVec) {
        for (i, slot) in self.lin.iter().enumerate() {
            if let Some(k) = slot {
                machine[*k] = m[i];
            }
        }
    }

    /// Rotary positions `pos` (chain order) into their channel axes.
    fn write_rotary(&self, pos: &[f64; 3], axes: &mut AxisVec) {
        for (r, p) in self.rot.iter().zip(pos) {
            if let Some(r) = r {
                axes[r.slot] = *p;
            }
        }
    }

    /// Of the (up to) two solutions for orientation `o` the one whose axes all fit their
    /// software limits (after shifting by whole turns) with the least weighted travel from
    /// `prev`: its positions and its effective angles (with cosine and sine), in chain order.
    /// The angles are stepped from the last cycle's in `memo` (an empty one: direct).
    #[inline]
    fn nearest_solution(
        &self,
        o: &Vec3,
        prev: &AxisVec,
        memo: &mut AngleMemo,
    ) -> Result<([f64; 3], [Turn; 3]), Unreachable> {
        let sols = self.raw_turns_stepped(o, &self.hint(Some(prev)), memo)?;
        let (k, pos) = self.nearest_of(&sols, prev)?;
        Ok((pos, sols[k]))
    }

    /// Which of `sols` [`Traori::nearest_solution`] takes, with its positions.
    #[inline(always)]
    fn nearest_of(&self, sols: &[[Turn; 3]; 2], prev: &AxisVec) -> Result<(usize, [f64; 3]), Unreachable> {
        let mut best: Option<(f64, usize, [f64; 3])> = None;
        for (k, s) in sols.iter().enumerate() {
            let Some((cost, pos)) = self.placed(s, prev) else { continue };
            // Ties keep the first (the "+γ" root), so the choice is deterministic.
            if best.is_none_or(|(c, _, _)| cost < c - 1e-12) {
                best = Some((cost, k, pos));
            }
        }
        let (_, k, pos) = best.ok_or(Unreachable)?;
        Ok((k, pos))
    }

    /// The positions of solution `s` (chain order) nearest `prev` within the limits, with
    /// their weighted travel from `prev`; `None` if an axis cannot reach its angle.
    #[inline(always)]
    fn placed(&self, s: &[Turn; 3], prev: &AxisVec) -> Option<(f64, [f64; 3])> {
        let mut pos = [0.0; 3];
        let mut cost = 0.0;
        for ((r, t), p) in self.rot.iter().zip(s).zip(&mut pos) {
            let Some(r) = r else { continue };
            *p = r.place(r.position(t.angle), prev[r.slot])?;
            cost += (*p - prev[r.slot]).abs() * r.weight;
        }
        Some((cost, pos))
    }
}

impl Transformation for Traori {
    fn name(&self) -> &'static str {
        "TRAORI"
    }

    fn trafo_type(&self) -> u32 {
        self.trafo_type
    }

    fn geo_slots(&self) -> [Option<usize>; 3] {
        self.geo
    }

    fn machine_slots(&self) -> Vec<usize> {
        // Sized up front: a chained iterator's collect would grow the vector step by step.
        let mut slots = Vec::with_capacity(7);
        slots.extend(self.lin.iter().flatten());
        slots.extend(self.rot.iter().flatten().map(|r| r.slot));
        slots.extend(self.seventh_slot());
        slots
    }

    fn forward(&self, machine: &AxisVec, tool: &Vec3, bcs: &mut AxisVec) {
        let pose = self.chain.pose(&self.angles(machine));
        let p = self.chain.tip(&self.linear(machine), &pose, &scale(tool, -1.0));
        let p = self.chain_to_workpiece(&p, machine);
        for (g, slot) in self.geo.iter().enumerate() {
            if let Some(k) = slot {
                bcs[*k] = p[g];
            }
        }
        for k in self.rot.iter().flatten().map(|r| r.slot).chain(self.seventh_slot()) {
            bcs[k] = machine[k];
        }
    }

    fn inverse(&self, bcs: &AxisVec, _prev: &AxisVec, tool: &Vec3, machine: &mut AxisVec) -> Result<(), Unreachable> {
        let pose = self.chain.pose(&self.angles(bcs));
        let m = self.chain.linear(&self.workpiece_to_chain(&self.point(bcs), bcs), &pose, &scale(tool, -1.0));
        self.write_linear(&m, machine);
        for k in self.rot.iter().flatten().map(|r| r.slot).chain(self.seventh_slot()) {
            machine[k] = bcs[k];
        }
        Ok(())
    }

    fn orientation_slots(&self) -> [Option<usize>; 3] {
        self.ori_slots
    }

    /// Where a vector-interpolated orientation passes closest to the pole (the pole axis'
    /// rate peaks there), measured in the frame of the tool kinematics at the block start.
    fn critical_params(&self, path: &Path, _tool: &Vec3) -> Vec<f64> {
        let Some(ori) = path.ori.as_deref() else { return Vec::new() };
        let start = path.start;
        super::pole_approach::closest_to_pole(|u| self.pole_angle(&self.in_chain_frame(&ori.at(u), &start)))
            .into_iter()
            .collect()
    }

    fn orientation(&self, machine: &AxisVec) -> Option<Vec3> {
        Some(self.chain_to_workpiece(&self.chain.orientation(&self.chain.pose(&self.angles(machine))), machine))
    }

    /// Of the (up to) two solutions the one whose axes all fit their software limits (after
    /// shifting by whole turns) with the least weighted travel from `prev`; in a pole the free
    /// axis keeps its `prev` position. `Unreachable` if `o` cannot be reached or no solution
    /// fits the limits.
    /// With a 7th axis `o` is relative to the workpiece at the 7th axis position in `axes`.
    fn orientation_axes(&self, o: &Vec3, prev: &AxisVec, axes: &mut AxisVec) -> Result<(), Unreachable> {
        let (pos, _) = self.nearest_solution(&self.workpiece_to_chain(o, axes), prev, &mut AngleMemo::default())?;
        self.write_rotary(&pos, axes);
        Ok(())
    }

    /// One pass instead of [`Traori::orientation_axes`] then [`Traori::inverse`]: the pose for
    /// the linear axes is built from the chosen solution's own cosines and sines, so the rotary
    /// positions are not turned back into angles and no `sin_cos` is needed.
    /// The 3rd rotary axis of a 6-axis kinematics (tool rotation) is not part of the vector
    /// interpolation: it keeps its interpolated BCS value in `axes`, which goes linearly from
    /// the block start to the position the block's THETA demands.
    /// With a 7th axis `o` and the tip are relative to the workpiece, which the 7th axis (its
    /// interpolated value in `axes`) has turned.
    fn inverse_oriented(&self, o: &Vec3, prev: &AxisVec, tool: &Vec3, axes: &mut AxisVec) -> Result<(), Unreachable> {
        self.inverse_oriented_stepped(o, prev, tool, axes, &mut AngleMemo::default())
    }

    /// [`Traori::inverse_oriented`] with the solve's angles stepped from the last cycle's in
    /// `memo` instead of `atan2` (within 1e-12 rad of the direct solve, see
    /// [`super::orient::stepped`]).
    fn inverse_oriented_stepped(
        &self,
        o: &Vec3,
        prev: &AxisVec,
        tool: &Vec3,
        axes: &mut AxisVec,
        memo: &mut AngleMemo,
    ) -> Result<(), Unreachable> {
        let (o, tip) = match self.seventh {
            None => (*o, self.point(axes)),
            Some(s) => {
                let r = s.rotation(axes);
                (r.apply(o), r.apply(&self.point(axes)))
            }
        };
        // The solutions are chosen in place: the chosen one's turns build the pose uncopied.
        let (sols, (k, pos)) = match self.third_slot() {
            None => {
                let sols = self.raw_turns_stepped(&o, &self.hint(Some(prev)), memo)?;
                let chosen = self.nearest_of(&sols, prev)?;
                (sols, chosen)
            }
            Some(k) => {
                let mut p = *prev;
                p[k] = axes[k];
                let sols = self.raw_turns_stepped(&o, &self.hint(Some(&p)), memo)?;
                let chosen = self.nearest_of(&sols, &p)?;
                (sols, chosen)
            }
        };
        let pose = self.chain.pose_turns(&sols[k]);
        let m = self.chain.linear(&tip, &pose, &scale(tool, -1.0));
        self.write_rotary(&pos, axes);
        self.write_linear(&m, axes);
        Ok(())
    }
}

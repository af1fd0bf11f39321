//! Where the tool stands relative to the blank in one IPO cycle: its tip, its axis and its
//! length in the blank's frame, for `cut.rs`.
//!
//! On a machine with an orientation transformation (a TRAORI data set) the blank is fixed to
//! the workpiece side of the kinematic chain: the frame the transformation's BCS is, which on
//! a trunnion table turns and tilts with A/C. The chain's forward map gives tip and orientation
//! there from the machine positions every cycle, whether TRAORI is active or the rotary axes
//! were positioned directly (3+2, CYCLE800, TCARR): the table carries the blank either way.
//! Without TRAORI active, the tool's length is taken along the chain's basic orientation (the
//! length vector of the offsets may be turned by a toolholder, which the chain already does).
//! Other machines keep the plain 3-axis view: tip = machine − tool length, axis +Z.

use crate::channel::Channel;
use crate::interp::Offsets;
use crate::kinematics::AnyTrafo;
use crate::kinematics::Traori;
use crate::kinematics::orient::chain::ChainKind;
use crate::motion::AxisVec;

/// The tool in the blank's frame: tip (mm), unit axis (tip → holder), length (mm).
pub(in crate::channel) struct ToolPose {
    pub tip: [f64; 3],
    pub axis: [f64; 3],
    pub length: f64,
}

impl Channel {
    /// The orientation kinematics the blank is mounted on: the machine's first TRAORI data
    /// set, `None` for a 3-axis machine, a lathe or a data set that cannot be built.
    pub(in crate::channel) fn stock_kinematics(&self) -> Option<Box<Traori>> {
        let set = self.cfg.trafos.iter().find(|s| s.kind == crate::machine_data::TrafoKind::Traori)?;
        match crate::kinematics::build(set, &self.cfg, &Default::default()) {
            Ok(AnyTrafo::Traori(t)) => Some(t),
            _ => None,
        }
    }

    /// The tool tip in the stock's frame at machine position `machine` with the channel's
    /// offsets: on a rotary table (`table.rs`) or a TRAORI chain's workpiece side
    /// turned back with the table, in a lathe's spindle turned with it (no transformation
    /// active); the plain BCS tip elsewhere (the probe's ball centre).
    pub(in crate::channel) fn stock_tip_at(&self, machine: &AxisVec) -> [f64; 3] {
        let run = self.stock.as_deref();
        if let Some(t) = run.and_then(|r| r.table) {
            return self.table_tool_pose(&t, machine, self.machine_tool_vector(&self.offsets)).tip;
        }
        if let Some(run) = run
            && let (Some(m), crate::stock::Stock::Milling(_), None) = (run.mount, &run.stock, &self.trafo)
        {
            return self.mount_tip_at(&m, machine, self.machine_tool_vector(&self.offsets));
        }
        self.stock_tool_pose(machine, &self.offsets, run.and_then(|r| r.kin.as_deref())).tip
    }

    /// The tool at machine position `machine` for the stock mounted on `kin`, with the block's
    /// `offsets`.
    pub(in crate::channel) fn stock_tool_pose(
        &self,
        machine: &AxisVec,
        offsets: &Offsets,
        kin: Option<&Traori>,
    ) -> ToolPose {
        let geo = self.cfg.geo_axes;
        let toff = self.toff.current;
        let plain: [f64; 3] = std::array::from_fn(|g| geo[g].map_or(0.0, |k| offsets.tool[k]) + toff[g]);
        let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let active = self.trafo.as_ref().and_then(|a| match &a.trafo {
            AnyTrafo::Traori(t) => Some((t.as_ref(), a.tool)),
            _ => None,
        });
        let (kin, tool) = match (active, kin) {
            (Some((t, tool)), _) => (t, std::array::from_fn(|g| tool[g] + toff[g])),
            (None, Some(k)) => {
                let n = norm(plain);
                (k, k.chain().base.map(|c| c * n))
            }
            (None, None) => {
                let tip = std::array::from_fn(|g| geo[g].map_or(0.0, |k| machine[k] - offsets.tool[k] - toff[g]));
                return ToolPose { tip, axis: [0.0, 0.0, 1.0], length: norm(plain) };
            }
        };
        let (tip, axis) = kin.tip_and_orientation(machine, &tool);
        ToolPose { tip, axis, length: norm(tool) }
    }

    /// Where the stock's frame lies in the machine's Cartesian frame now (the frame of the
    /// linear axes and the tool, which the HMI draws the machine in): the rows of `[R | t]`
    /// with `machine = R·p + t` for a point `p` of the stock. `None` where the blank stands
    /// still in the BCS (a 3-axis mill, a lathe's spindle, which the HMI turns itself).
    ///
    /// On a TRAORI chain the forward map `P(M)` of the linear axes (tool length zero) is
    /// affine, `A·M + b`, with `A` the table's turn back: a workpiece-side chain's point lies at
    /// `M = Aᵀ·(P − b)`; a mixed chain's table (axis 2) at `R2·P + l3 + R2·l4`; a head's
    /// workpiece does not move (only a 7th axis turns it, `A` alone).
    pub(in crate::channel) fn stock_frame(&self) -> Option<[[f64; 4]; 3]> {
        let run = self.stock.as_deref()?;
        if let Some(t) = run.table {
            let r = t.pose(&self.machine);
            return Some(std::array::from_fn(|i| [r[i][0], r[i][1], r[i][2], 0.0]));
        }
        let kin = run.kin.as_deref()?;
        if kin.chain().kind == ChainKind::Tool && kin.seventh_slot().is_none() {
            return None; // a swivel head: the blank stands still in the BCS
        }
        let set = self.cfg.trafos.iter().find(|s| s.kind == crate::machine_data::TrafoKind::Traori)?;
        let lin = [set.axes_in[0]?, set.axes_in[1]?, set.axes_in[2]?];
        let at = |unit: Option<usize>| {
            let mut m = self.machine;
            for (i, k) in lin.iter().enumerate() {
                m[*k] = if unit == Some(i) { 1.0 } else { 0.0 };
            }
            kin.tip_and_orientation(&m, &[0.0; 3]).0
        };
        let b = at(None);
        // Rows of R = Aᵀ are the columns of A: the images of the unit moves.
        let r: [[f64; 3]; 3] = std::array::from_fn(|i| {
            let e = at(Some(i));
            [e[0] - b[0], e[1] - b[1], e[2] - b[2]]
        });
        let apply = |v: [f64; 3]| -> [f64; 3] { std::array::from_fn(|i| (0..3).map(|c| r[i][c] * v[c]).sum()) };
        let chain = kin.chain();
        let t = match chain.kind {
            ChainKind::Part => apply(b).map(|c| -c),
            ChainKind::Mixed => {
                let l4 = apply(chain.l4);
                std::array::from_fn(|i| chain.l3[i] + l4[i])
            }
            ChainKind::Tool => [0.0; 3],
        };
        Some(std::array::from_fn(|i| [r[i][0], r[i][1], r[i][2], t[i]]))
    }
}

//! What block preparation keeps over a channel reset (the active tool and cutting edge, the
//! toolholder with its G groups, the system frames, the R parameters, a transformation that
//! stays over reset and the online tool offset `$AA_TOFF`): read out for a server checkpoint and put back after a restart, so a
//! restored channel in reset state is the channel that was saved.
//!
//! The modal G groups are not part of it: in reset state they are at their reset values
//! anyway (MD20150), and a program that was active is re-established by a block search.

use super::eval::vars::R_PARAMS;
use super::frames::frame::SystemFrames;
use super::tools::toolholder::Holder;
use super::{Interpreter, tool_vector};
use crate::kinematics::SelectArgs;
use crate::machine_data::MachineConfig;
use crate::motion::AxisVec;

/// A transformation selected when the checkpoint was taken: its data set and the parameters
/// of its selection (TRACYL diameter, TRAANG angle, TRAORI vector, TRACON parameters).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RetainedTransformation {
    pub data_set: usize,
    pub args: SelectArgs,
}

/// The interpreter's state that survives a reset on the control.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Retained {
    /// Active tool T and cutting edge D (D0: no offset).
    pub tool: u32,
    pub edge: u32,
    /// The programmed (prepared) tool `$P_TOOLP`; `None` in checkpoints from before tool
    /// management: the tool in the spindle.
    #[cfg_attr(feature = "serde", serde(default))]
    pub prepared: Option<u32>,
    /// The orientable toolholder (TCARR) and G groups 22, 42, 52, 53.
    pub holder: Holder,
    /// `$P_PARTFRAME`, `$P_SETFRAME`, `$P_EXTFRAME`, `$P_WPFRAME`, `$P_TRAFRAME`,
    /// `$P_TOOLFRAME`, `$P_CYCFRAME`.
    pub frames: SystemFrames,
    /// R parameters up to the last non-zero one.
    pub r: Vec<f64>,
    /// The active transformation; restored only where it stays over reset (MD20110 bit 7).
    pub transformation: Option<RetainedTransformation>,
    /// The online tool length offset `$AA_TOFF` in the tool directions X, Y, Z: it stays over
    /// reset here (see `toff.rs`), and the saved machine position already includes it.
    #[cfg_attr(feature = "serde", serde(default))]
    pub toff: [f64; 3],
    /// The PLC data area (`$A_DBB`..) up to its last non-zero byte; PLC memory survives reset.
    #[cfg_attr(feature = "serde", serde(default))]
    pub plc: Vec<u8>,
}

impl Interpreter {
    /// The state a reset keeps, for a checkpoint.
    pub fn retained(&self) -> Retained {
        let used = self.vars.r.iter().rposition(|v| *v != 0.0).map_or(0, |i| i + 1);
        Retained {
            tool: self.offsets.t,
            edge: self.offsets.d,
            prepared: Some(self.offsets.prepared),
            holder: self.holder.clone(),
            frames: (*self.system).clone(),
            r: self.vars.r[..used].to_vec(),
            transformation: self.active_selection().map(|(data_set, args)| RetainedTransformation { data_set, args }),
            toff: self.offsets.toff,
            plc: self.plc.bytes().to_vec(),
        }
    }

    /// Puts `saved` back, as after a reset with the machine at `machine`. All or nothing: a
    /// cutting edge, toolholder or transformation the machine data no longer has, or a value
    /// that is not finite, leaves the interpreter as it was and names the problem.
    pub fn restore_retained(&mut self, saved: &Retained, cfg: &MachineConfig, machine: &AxisVec) -> Result<(), String> {
        self.lane_memo.forget();
        check(saved, cfg)?;
        let before = (self.offsets.clone(), self.holder.clone(), self.system.clone(), self.vars.r.clone());
        self.offsets.t = saved.tool;
        self.offsets.d = saved.edge;
        self.offsets.prepared = saved.prepared.unwrap_or(saved.tool);
        self.offsets.toff = saved.toff;
        self.holder = saved.holder.clone();
        *self.system = saved.frames.clone();
        self.vars.r[..saved.r.len()].copy_from_slice(&saved.r);
        self.vars.r[saved.r.len()..].fill(0.0);
        self.plc = super::io::plc_data::PlcData::from_bytes(&saved.plc);
        self.reset(cfg, machine);
        let Some(t) = saved.transformation.as_ref().filter(|_| cfg.reset_trafo.keep_active) else { return Ok(()) };
        // The reset may have put the tool into the reset transformation: start from the plain
        // tool vector, as a selection in a program does.
        self.offsets.tool = self.holder_tool(cfg, tool_vector(cfg, &self.modal, self.offsets.t, self.offsets.d));
        if let Err(alarm) = self.reselect_transformation(t.data_set, &t.args, cfg, machine) {
            (self.offsets, self.holder, self.system, self.vars.r) = before;
            self.reset(cfg, machine);
            return Err(format!("transformation data set {}: {}", t.data_set, alarm.message));
        }
        Ok(())
    }
}

fn check(saved: &Retained, cfg: &MachineConfig) -> Result<(), String> {
    if saved.edge != 0 && cfg.edge(saved.tool, saved.edge).is_none() {
        return Err(format!("tool T{} D{} has no offset data", saved.tool, saved.edge));
    }
    if saved.holder.number != 0 && !cfg.carriers.contains_key(&saved.holder.number) {
        return Err(format!("toolholder {} is not defined", saved.holder.number));
    }
    if saved.plc.len() > super::io::plc_data::PLC_DATA_BYTES {
        return Err(format!("PLC data: at most {} bytes", super::io::plc_data::PLC_DATA_BYTES));
    }
    if saved.r.len() > R_PARAMS || saved.r.iter().any(|v| !v.is_finite()) {
        return Err(format!("R parameters: at most {R_PARAMS} finite values"));
    }
    let h = &saved.holder;
    let angles = h.angles.iter().chain(h.second.iter().flatten());
    let f = &saved.frames;
    let frames = [&f.part, &f.set, &f.ext, &f.wp, &f.tra, &f.tool, &f.cycle];
    let frame_values =
        frames.iter().flat_map(|fr| fr.trans.iter().chain(fr.lin.iter().flatten()).chain(fr.factor.iter()));
    if angles.chain(frame_values).chain(saved.toff.iter()).any(|v| !v.is_finite()) {
        return Err("a toolholder angle, system frame value or online tool offset is not finite".into());
    }
    Ok(())
}

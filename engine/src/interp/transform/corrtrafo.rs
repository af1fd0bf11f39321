//! CORRTRAFO(Corr_Elem, Corr_Mode, Corr_Vect[, Corr_Chain][, No_Alarm]) in a program
//! (Transformations FM K12 §4.3.2): corrects one offset or axis direction of the active
//! TRAORI_DYN transformation defined by kinematic chains and returns the status.
//!
//! The correction acts at once (this product's reading: the function requires the transformation
//! to be active and corrects "the kinematic model of the machine"): the corrected `$NK_OFF_DIR`
//! is written (readable at once, exported with the chain data), the active transformation is
//! rebuilt from it without a new selection, and the channel's data set of the record follows,
//! so a later TRAFOON selects the corrected model too. The machine does not move; the BCS
//! position follows through the corrected model, and the next motion block uses it.
//!
//! Parameters (the manual summary gives no full list; this product's reading):
//! `Corr_Vect` is a REAL array of three components (`DEF REAL CORR[3]`, passed by name);
//! `Corr_Chain` 0 (default) takes `$NT_CORR_ELEM_T`, 1 `$NT_CORR_ELEM_P`; `No_Alarm` FALSE
//! (default) stops with alarm 14103 on an error, TRUE only returns the status.

use crate::alarm::{Alarm, Clear};
use crate::interp::eval::eval;
use crate::interp::eval::scope::{Ctx, sys_view};
use crate::interp::{CORRTRAFO, Interpreter, Item};
use crate::lang::Expr;
use crate::machine_data::chains::correct::{self, Chain, Request, status};
use crate::machine_data::chains::{self, KIN_TRAFO_NUMBER_BASE};
use crate::machine_data::{MachineConfig, TrafoKind};

/// 14103: CORRTRAFO failed (No_Alarm FALSE); the status says why.
fn failed(line: u32, status: i64) -> Alarm {
    let why = match status {
        status::NO_TRAFO => "no transformation active",
        status::NOT_ORIENTATION => "the active transformation is no orientation transformation",
        status::NOT_CHAIN => "the active orientation transformation is not defined by kinematic chains",
        status::BAD_MODE => "invalid Corr_Mode",
        status::BAD_ELEM => "Corr_Elem names no correction element or orientation axis",
        status::NOT_IN_SECTION => "the correction element does not lie in section Corr_Elem",
        status::NOT_BUILDABLE => "the corrected kinematic chain is invalid",
        status::LIN_LIMIT => "offset correction larger than SD41610 $SN_CORR_TRAFO_LIN_MAX",
        status::DIR_LIMIT => "direction correction larger than SD41611 $SN_CORR_TRAFO_DIR_MAX",
        _ => "error",
    };
    Alarm {
        number: 14103,
        message: format!("Channel 1 block {line} CORRTRAFO error {status}: {why}"),
        line: Some(line),
        clear: Clear::Reset,
    }
}

fn omitted(e: &Expr) -> bool {
    matches!(e, Expr::Call(n, a) if n == "_OMITTED" && a.is_empty())
}

impl Interpreter {
    /// Runs CORRTRAFO with `args`; returns the status (0 done). `cfg` is the channel's
    /// configuration (not the one derived while a transformation is active).
    pub(in crate::interp) fn corrtrafo(
        &mut self,
        args: &[Expr],
        cfg: &MachineConfig,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<i64, Alarm> {
        let usage = || {
            Alarm::syntax(
                line,
                "CORRTRAFO(Corr_Elem, Corr_Mode, Corr_Vect[, Corr_Chain][, No_Alarm]), Corr_Vect a REAL[3] array",
            )
        };
        if !(3..=5).contains(&args.len()) || args[..3].iter().any(omitted) {
            return Err(usage());
        }
        let (req, no_alarm) = {
            let derived = self.trafo.config();
            let sys = sys_view!(self, derived.as_deref().unwrap_or(cfg));
            let ctx = Ctx { vars: &self.vars, sys: &sys };
            let int = |e: &Expr| eval(e, &ctx, line)?.as_i64().map_err(|e| Alarm::type_error(line, &e.0));
            let Expr::Var { name, indices } = &args[2] else { return Err(usage()) };
            let var = self.vars.get(name).filter(|v| indices.is_empty() && v.data.len() >= 3).ok_or_else(usage)?;
            let mut vect = [0.0; 3];
            for (k, v) in vect.iter_mut().enumerate() {
                *v = var.data[k].as_f64().map_err(|e| Alarm::type_error(line, &e.0))?;
            }
            let (elem, mode) = (int(&args[0])?, int(&args[1])?);
            let chain = match args.get(3).filter(|e| !omitted(e)).map(int).transpose()? {
                None | Some(0) => Ok(Chain::Tool),
                Some(1) => Ok(Chain::Part),
                Some(_) => Err(status::BAD_ELEM),
            };
            let no_alarm = match args.get(4).filter(|e| !omitted(e)) {
                Some(e) => eval(e, &ctx, line)?.as_bool().map_err(|e| Alarm::type_error(line, &e.0))?,
                None => false,
            };
            let req = chain.map(|chain| Request { elem, mode, vect, chain });
            (req, no_alarm)
        };
        let result = req.and_then(|req| self.correct_active(&req, cfg, line, out));
        match result {
            Ok(()) => Ok(0),
            Err(status) if no_alarm => Ok(status),
            Err(status) => Err(failed(line, status)),
        }
    }

    /// Corrects the active transformation; `Err` is the status.
    fn correct_active(
        &mut self,
        req: &Request,
        cfg: &MachineConfig,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<(), i64> {
        let number = self.active_data_set().ok_or(status::NO_TRAFO)?;
        let set = cfg.trafos.iter().find(|s| s.number == number).ok_or(status::NO_TRAFO)?;
        if set.kind != TrafoKind::Traori {
            return Err(status::NOT_ORIENTATION);
        }
        if set.chain.is_none() || number <= KIN_TRAFO_NUMBER_BASE {
            return Err(status::NOT_CHAIN);
        }
        let n = number - KIN_TRAFO_NUMBER_BASE;
        let axes = (&cfg.channel_axes[..], &cfg.machine_axes[..]);
        let c = correct::correct(&cfg.kin, &cfg.kin_build, axes.0, axes.1, n, req, cfg.corr_limits)?;
        let mut kin = cfg.kin.clone();
        kin.set_off_dir(c.record, c.off_dir);
        let rebuilt =
            chains::rebuild_traori(&kin, &cfg.kin_build, axes.0, axes.1, n).map_err(|_| status::NOT_BUILDABLE)?;
        self.replace_active_set(&rebuilt, cfg, line).map_err(|_| status::NOT_BUILDABLE)?;
        for (k, v) in c.off_dir.iter().enumerate() {
            self.data_writes.push((line, format!("$NK_OFF_DIR[{},{k}]={v:?}", c.record)));
        }
        self.data_writes.push((line, format!("{CORRTRAFO}{n}")));
        out.push(Item::Offsets { line, offsets: self.shared_offsets() });
        Ok(())
    }
}

//! Directly programmed rotary axes (`A30 C90`) under vector interpolation (MD21104 = 1 with
//! ORIVECT, ORICONxx, ...): the orientation runs on the programmed path and the rotary axes
//! follow it continuously, which on a two-axis kinematics keeps them on one branch of the two
//! solutions. If that branch ends on the other solution than the programmed positions, the
//! block is interpolated through the rotary axes instead (as ORIAXES), so a direct rotary-axis
//! program always reaches exactly its values. (The manual's text is silent; this is our
//! reading of "the programmed axis positions are the end point".)

use crate::alarm::Alarm;
use crate::interp::Interpreter;
use crate::interp::frames::frame::Frame;
use crate::kinematics::{AnyTrafo, Transformation};
use crate::machine_data::MachineConfig;
use crate::motion::{AxisVec, OriPath};

/// Samples of the orientation path used to follow the rotary axes' branch in preparation.
const FOLLOW_SAMPLES: usize = 64;

impl Interpreter {
    /// [`Interpreter::orientation_block_unchecked`], falling back to rotary-axis interpolation
    /// when directly programmed rotary axes would end on the other solution.
    #[allow(clippy::too_many_arguments)]
    pub(in crate::interp) fn orientation_block(
        &self,
        words: &crate::interp::modal::Words,
        cfg: &MachineConfig,
        frame: &Frame,
        start: &AxisVec,
        end: &mut AxisVec,
        tangent: Option<crate::kinematics::Vec3>,
        line: u32,
    ) -> Result<Option<OriPath>, Alarm> {
        let programmed = *end;
        let path = self.orientation_block_unchecked(words, cfg, frame, start, end, tangent, line)?;
        let (Some(p), Some((active, machine))) = (path.as_ref(), self.orientation_transformation()) else {
            return Ok(path);
        };
        let slots = active.trafo.orientation_slots();
        let direct = words.axes.iter().any(|(k, ..)| slots.contains(&Some(*k)));
        if !direct {
            return Ok(path);
        }
        let mut prev = *machine;
        for k in slots.iter().flatten() {
            prev[*k] = start[*k];
        }
        // The 7th axis of a 7-axis TRAORI turns with the path parameter like the tip.
        let seventh = match &active.trafo {
            AnyTrafo::Traori(t) => t.seventh_slot(),
            _ => None,
        };
        let mut next = prev;
        for i in 1..=FOLLOW_SAMPLES {
            let u = i as f64 / FOLLOW_SAMPLES as f64;
            if let Some(k) = seventh {
                next[k] = start[k] + u * (programmed[k] - start[k]);
            }
            if active.trafo.orientation_axes(&p.at(u), &prev, &mut next).is_err() {
                break;
            }
            prev = next;
        }
        let same = slots.iter().flatten().all(|&k| {
            let d = prev[k] - programmed[k];
            let d = if cfg.axis(k).modulo.is_some() { (d + 180.0).rem_euclid(360.0) - 180.0 } else { d };
            d.abs() < 1e-6
        });
        if same {
            return Ok(path);
        }
        for k in slots.iter().flatten() {
            end[*k] = programmed[*k];
        }
        Ok(None)
    }
}

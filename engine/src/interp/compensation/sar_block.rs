//! The SAR words of a motion block turned into what the tool radius compensation runs
//! ([`Sar`]): the checks that need the interpreter (is TRC selected or deselected in this
//! block, DISR, the DISCL plane in the WCS, FAD as a path feed). The geometry is in
//! `compensation/sar.rs`, the moves in `compensation/sar_run.rs`.

use crate::alarm::Alarm;
use crate::interp::compensation::sar::{Clearance, Sar, Shape};
use crate::interp::compensation::trc::{Compensation, Side};
use crate::interp::{Interpreter, modal};
use crate::machine_data::MachineConfig;
use crate::motion::{AxisVec, Feed, Move};

impl Interpreter {
    /// The SAR request of a motion block, None without G147..G348. `before` is the path feed
    /// that was active before the block (rapid after G0).
    pub(in crate::interp) fn sar_request(
        &mut self,
        words: &modal::Words,
        cfg: &MachineConfig,
        mv: &Move,
        comp: Option<&Compensation>,
        before: Option<Feed>,
        line: u32,
    ) -> Result<Option<Box<Sar>>, Alarm> {
        let (sw, before) = match words.sar.contour {
            Some(_) => (words.sar, before),
            None => match self.trc.take_deferred_sar() {
                Some(deferred) => deferred,
                None => return Ok(None),
            },
        };
        let Some((shape, retract)) = sw.contour else { return Ok(None) };
        // Approach: TRC selected in this block; retract: deselected in it (see sar.rs).
        let selects = comp.is_some() && self.trc.idle();
        let without = comp.is_none() && self.trc.idle() && self.modal.trc.is_none();
        let deselects = comp.is_none() && !self.trc.idle();
        if (!retract && !selects && !without) || (retract && !deselects) {
            return Err(Alarm::sar_direction(line));
        }
        let disr = sw.disr.ok_or_else(|| Alarm::sar_distance(line))?;
        if disr < 0.0 || (shape != Shape::Line && disr <= 0.0) {
            return Err(Alarm::sar_distance(line));
        }
        let (pa, po, papp) = self.modal.plane.axes();
        let geo = &cfg.geo_axes;
        let plane_programmed = words.axes.iter().any(|&(k, _, _)| Some(k) == geo[pa] || Some(k) == geo[po]);
        let frame = self.block_frame(words, cfg);
        let normal = unit(frame.geo_direction(geo, papp));
        // The machining plane goes through P4: the block's end on approach, its start (the
        // contour's end) on retract.
        let p4 = if retract { mv.path.start } else { mv.path.end };
        let height = |c: Clearance| -> Result<f64, Alarm> {
            match c {
                Clearance::Distance(d) => Ok(d),
                Clearance::Absolute(z) => {
                    let tool = self.offsets.tool;
                    let basic: AxisVec = std::array::from_fn(|k| p4[k] - tool[k]);
                    let wcs = frame
                        .unapply(geo, &basic)
                        .ok_or_else(|| Alarm::value_out_of_range(line, "frame with scale 0"))?;
                    let Some(k) = geo[papp] else { return Err(Alarm::sar_direction(line)) };
                    Ok(z - wcs[k])
                }
            }
        };
        let clearance = sw.discl.map_or(Ok(0.0), height)?;
        let retract_plane = sw.disrp.map(height).transpose()?;
        let path_feed = |v: f64, per_rev: bool| -> Result<Feed, Alarm> {
            let per_min = if per_rev { v * self.spindles.reference_speed() } else { v } * self.modal.feed_factor();
            if per_min <= 0.0 {
                return Err(Alarm::feed_not_positive(line));
            }
            Ok(Feed::Path(per_min / 60.0))
        };
        let fad = match sw.fad {
            None => None,
            Some((v, per_rev)) => Some(path_feed(v, per_rev.unwrap_or(self.modal.feed_per_rev))?),
        };
        let feed = match self.modal.feed {
            Some(f) => Some(path_feed(f, self.modal.feed_per_rev)?),
            None => None,
        };
        Ok(Some(Box::new(Sar {
            shape,
            retract,
            in_plane: self.modal.sar.in_plane,
            side: self.modal.sar.side,
            disr,
            clearance,
            retract_plane,
            normal,
            fad,
            before: before.unwrap_or(Feed::Rapid),
            feed,
            end_in_plane: plane_programmed,
            zero: (!retract && without).then(|| Compensation {
                side: Side::Left,
                radius: 0.0,
                corners: self.modal.trc_corners,
                disc: self.modal.disc,
                arc_feed: self.modal.arc_feed,
                u: unit(frame.geo_direction(geo, pa)),
                v: unit(frame.geo_direction(geo, po)),
                tip: (0.0, 0.0),
                max_dummy_blocks: cfg.cutcom_max_dummy_blocks,
                max_check_blocks: cfg.cutcom_max_check_blocks,
                corner_limit: cfg.cutcom_corner_limit,
                collision_detection: self.modal.collision_detection,
                groove_wall: None,
            }),
            line,
        })))
    }
}

/// `v` scaled to length 1 (unchanged when it is zero).
fn unit(v: AxisVec) -> AxisVec {
    let len = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    if len > 0.0 { v.map(|x| x / len) } else { v }
}

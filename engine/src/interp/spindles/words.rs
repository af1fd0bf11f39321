//! A block's spindle words, sorted out of its words by `modal.rs`: `S<n>=`, `SPOS`,
//! `SPOS[n]`, `SPOSA` (with `DC`/`ACP`/`ACN`/`IC`), `M19`, `M70`, `LIMS=`, `SF=`, `DITS=`/`DITE=`,
//! G25/G26 (the block's S is a limit), the feed types of G group 15 and the thread functions.

use super::{FeedType, Thread};
use crate::alarm::Alarm;
use crate::lang::CoordMode;

/// SPOS/SPOSA/M19: position spindle `spindle` (`None`: the master) to `angle`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spos {
    pub spindle: Option<u32>,
    pub angle: f64,
    pub mode: Option<CoordMode>,
}

impl SpindleWords {
    /// G25/G26 with axis words and no S: a working-area limit (`path_control/work_area.rs`),
    /// `Some(true)` for G26's upper one; `None` when the block's G25/G26 limit the spindle.
    pub(in crate::interp) fn work_area_limit(&self, w: &crate::interp::modal::Words) -> Option<bool> {
        let limit = self.limit.filter(|_| w.speed.is_none() && !w.axes.is_empty())?;
        Some(limit == SpeedLimit::G26)
    }
}

/// G25 (lower) or G26 (upper speed limit) in the block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpeedLimit {
    G25,
    G26,
}

#[derive(Debug, Clone, Default)]
pub struct SpindleWords {
    /// `S<n>=`: speed of spindle n.
    pub speeds: Vec<(u32, f64)>,
    pub spos: Option<Spos>,
    /// M70: the master spindle changes to axis mode where it stands.
    pub axis_mode: bool,
    pub lims: Option<f64>,
    pub limit: Option<SpeedLimit>,
    pub feed_type: Option<FeedType>,
    pub thread: Option<Thread>,
    /// G63 (tapping with a compensating chuck, non-modal).
    pub g63: bool,
    pub sf: Option<f64>,
    /// DIAMON/DIAMOF/DIAM90/DIAMCYCOF (G group 29).
    pub diameter: Option<super::diameter::DiamMode>,
    /// DIAMONA[ax] .. DIAMCHAN in the order written (`diameter_axes.rs`).
    pub axis_diameter: Vec<super::diameter_axes::AxisDiamOp>,
    /// FPR(axis): the channel axis a feed per revolution follows from now on (`fpr.rs`).
    pub fpr: Option<usize>,
    /// SCC[axis]: the transverse axis of constant cutting speed from now on.
    pub css_axis: Option<usize>,
    /// M40..M45 (`gears.rs`).
    pub gear: Option<super::gears::GearWord>,
    /// SPCON/SPCOF (`position_control.rs`).
    pub position_control: Option<super::position_control::Switch>,
}

/// A keyword of this module without arguments (G group 29); false for any other name.
pub(in crate::interp) fn keyword(w: &mut SpindleWords, name: &str, line: u32) -> Result<bool, Alarm> {
    let Some(mode) = super::diameter::DiamMode::of_keyword(name) else { return Ok(false) };
    if w.diameter.replace(mode).is_some() {
        return Err(Alarm::conflicting_functions(line, "DIAMON/DIAMOF/DIAM90/DIAMCYCOF"));
    }
    Ok(true)
}

/// The G functions of this module; false for any other code.
pub(in crate::interp) fn g_code(w: &mut SpindleWords, code: u32, line: u32) -> Result<bool, Alarm> {
    let feed = |w: &mut SpindleWords, t| {
        if w.feed_type.replace(t).is_some() {
            Err(Alarm::conflicting_functions(line, "G93/G94/G95/G96/G961/G97/G971"))
        } else {
            Ok(true)
        }
    };
    match code {
        25 => w.limit = Some(SpeedLimit::G25),
        26 => w.limit = Some(SpeedLimit::G26),
        33 => w.thread = Some(Thread::G33),
        34 => w.thread = Some(Thread::G34),
        35 => w.thread = Some(Thread::G35),
        331 => w.thread = Some(Thread::G331),
        332 => w.thread = Some(Thread::G332),
        63 => w.g63 = true,
        93 => return feed(w, FeedType::G93),
        96 => return feed(w, FeedType::G96),
        961 => return feed(w, FeedType::G961),
        97 => return feed(w, FeedType::G97),
        971 => return feed(w, FeedType::G971),
        _ => return Ok(false),
    }
    Ok(true)
}

/// M19 (position the master spindle to SD43240 `M19_SPOS`, 0° here), M70 (axis mode) and
/// the gear stages M40..M45.
pub(in crate::interp) fn m_code(w: &mut SpindleWords, code: u32) -> bool {
    if let Some(g) = super::gears::of_m(code, None) {
        w.gear = Some(g);
        return true;
    }
    match code {
        19 => w.spos = Some(Spos { spindle: None, angle: 0.0, mode: None }),
        70 => w.axis_mode = true,
        _ => return false,
    }
    true
}

/// Whether `name` may carry an index (`SPOS[2]=90`).
pub(in crate::interp) fn indexed(name: &str) -> bool {
    matches!(name, "SPOS" | "SPOSA")
}

/// Whether `name` is an address of this module.
pub(in crate::interp) fn is_address(name: &str) -> bool {
    matches!(name, "SPOS" | "SPOSA" | "LIMS" | "SF" | "DITS" | "DITE")
}

/// An address word of this module with its value; false for any other name.
pub(in crate::interp) fn address(
    w: &mut SpindleWords,
    name: &str,
    index: Option<f64>,
    v: f64,
    mode: Option<CoordMode>,
    line: u32,
) -> Result<bool, Alarm> {
    let spindle_number = |n: f64| -> Result<u32, Alarm> {
        if (1.0..=32.0).contains(&n) && n.fract() == 0.0 {
            Ok(n as u32)
        } else {
            Err(Alarm::value_out_of_range(line, &format!("{name}[{n}]")))
        }
    };
    match name {
        "SPOS" | "SPOSA" => {
            let spindle = index.map(spindle_number).transpose()?;
            if mode == Some(CoordMode::Ac) || !v.is_finite() {
                return Err(Alarm::value_out_of_range(line, &format!("{name}={v}")));
            }
            w.spos = Some(Spos { spindle, angle: v, mode });
        }
        "LIMS" => {
            if v <= 0.0 {
                return Err(Alarm::value_out_of_range(line, &format!("LIMS={v}")));
            }
            w.lims = Some(v);
        }
        "SF" => w.sf = Some(v),
        // Run-in and run-out paths of G33 (DITS/DITE): the thread axis accelerates and brakes
        // with its own acceleration here, so the values are checked and have no further effect.
        "DITS" | "DITE" => {
            if v < -1.0 {
                return Err(Alarm::value_out_of_range(line, &format!("{name}={v}")));
            }
        }
        _ => {
            let Some(n) = name.strip_prefix('S').filter(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
            else {
                return Ok(false);
            };
            let n = spindle_number(n.parse::<f64>().unwrap_or(0.0))?;
            if v < 0.0 {
                return Err(Alarm::value_out_of_range(line, &format!("S{n}={v}")));
            }
            w.speeds.push((n, v));
        }
    }
    Ok(true)
}

/// `M<n>=40..45`: a gear word for spindle n; false for any other value.
pub(in crate::interp) fn extended_m(w: &mut SpindleWords, spindle: u32, value: f64) -> bool {
    let code = value as u32;
    match super::gears::of_m(code, Some(spindle)).filter(|_| value.fract() == 0.0) {
        Some(g) => {
            w.gear = Some(g);
            true
        }
        None => false,
    }
}

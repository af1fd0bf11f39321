//! The NC words of continuous-path control (Function Manual B1, Programming Manual "Job
//! planning"): G group 10 beyond G60/G64 (`G641` with `ADIS`/`ADISPOS`, `G642`..`G645`), G group
//! 12 (`G601`/`G602`/`G603`), the programmable tolerances `CTOL`/`OTOL`/`ATOL`, the compressors
//! `COMPON`/`COMPCURV`/`COMPCAD`/`COMPSURF`/`COMPOF`, `UPATH`/`SPATH` and G group 61
//! `ORISOF`/`ORISON` (smoothing of the orientation characteristic, `motion/orison.rs`).
//!
//! What the words turn into: each move of a block in continuous-path mode carries a
//! [`Blend`] (read from the machine data at block preparation) that tells the channel how to
//! round the corner at its end (`motion::blend`).
//!
//! Modelled as follows where the manuals leave room:
//! - `G643` (block-internal rounding) rounds each axis within its own tolerance over its
//!   own distance (`motion/blend_axial.rs`): the geometry axes by the tolerance G642 would
//!   use where one is set (CTOL, SD42465 by MD20480, ATOL), else each axis by its MD33100,
//!   the other axes by ATOL or their MD33100. Next to an arc, under a transformation or with
//!   an orientation it rounds as G642 with the smallest of the geometry axes' tolerances.
//! - MD20480 `$MC_SMOOTHING_MODE` picks the data each function rounds by (B1 "Rounding
//!   behavior"): its units digit for G643, its tens digit for G642 and for G645 (which B1
//!   treats "virtually always" like G642). Per digit: 0 every axis by MD33100; 1 the geometry
//!   axes by SD42465, the others by MD33100; 2 the orientation by SD42466, the others by
//!   MD33100; 3 both. The hundreds digit (the velocity profile in the rounding element) and
//!   the ten-thousands digit (jerk limitation in the element: BRISK without, SOFT with, as
//!   NCTwin's elements run anyway) are not read.
//! - `G644` (rounding with the greatest possible dynamics, for moves in air) follows MD20480's
//!   thousands digit: 1 and 5 round by `ADIS`/`ADISPOS` as G641 does, every other value by
//!   the axial tolerance MD33100 (3, "neither tolerance nor distance", is read as 0). The
//!   programmed `CTOL`/`ATOL` do not act on G644 (Function Manual B1, "Programmable contour
//!   and orientation tolerance").
//! - `G645` rounds corners like `G642` (same tolerance rule) and smooths tangential
//!   transitions with a jump in curvature within MD33120 `$MA_PATH_TRANS_POS_TOL` (the
//!   smallest of the geometry axes'), which `CTOL` does not change (B1, as for G644).
//! - The tolerance of G642, G645 is one distance for the geometry axes: `CTOL` when
//!   programmed, else SD42465 when MD20480's tens digit is 1 or 3, else `ATOL`, else the
//!   smallest MD33100 of the geometry axes (G644: always that MD33100). A negative `CTOL`/`OTOL`/`ATOL` returns to the data.
//! - `G601`/`G602`/`G603` travel with the block (`GCodes::stop_window`) to the main run,
//!   where the block change after G60/G9 waits for the window (`channel/exact_stop.rs`); under
//!   FFWON the following error is zero and the three are alike.
//! - `ADIS`/`ADISPOS` are modal and 0 after reset: G641 without them rounds nothing.
//! - `OTOL` and the orientation: under an orientation transformation the corner is rounded in
//!   the BCS (the tool tip within the contour tolerance) and the orientation within the
//!   orientation tolerance ([`PathControl::ori_tolerance`]; `channel/smoothing/blending_trafo.rs`).
//! - G group 34 (orientation smoothing at block transitions): `OSOF`, its reset value, is
//!   accepted and changes nothing; `OSC`, `OSS`, `OSSE`, `OSD`, `OST` are refused with 12550
//!   naming the function (not modelled: CAM programs smooth the orientation with ORISON or
//!   the corner rounding's OTOL, which NCTwin models).
//! - `UPATH`/`SPATH` (the path parameter of the axes outside FGROUP) are accepted and
//!   change nothing: FGROUP is not modelled, so every axis moves with the geometry axes' path
//!   length, and lines, circles and the rounding and compressor elements run at uniform path
//!   speed, where the curve parameter is proportional to the length. (They would differ for
//!   POLY/spline blocks moving further axes, whose parameter is not the length.)
//! - Under TRC the rounding acts on the compensated moves (`compensation/trc.rs` hands the
//!   block's [`Blend`] to each equidistant piece): the corners of the offset contour are
//!   rounded, and G645 smooths the tangential joints of G450's transition circles.

pub(super) mod feed_group;
pub(super) mod fixed_point;
pub mod oscillation;
pub(crate) mod positioning;
pub(super) mod rapid_apart;
pub(super) mod spline;
pub(super) mod work_area;
use crate::alarm::Alarm;
use crate::machine_data::MachineConfig;
use crate::motion::blend::Blend;
use crate::motion::compress::Compress;
use crate::motion::orison::OriSmoothing;

/// G group 10 in continuous-path mode (G60 is `Modal::exact_stop`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Smoothing {
    #[default]
    G64,
    G641,
    G642,
    G643,
    G644,
    G645,
}

/// G group 12: when an exact stop counts as reached.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum StopWindow {
    /// G601: within MD36010 STOP_LIMIT_FINE (reset value).
    #[default]
    Fine,
    /// G602: within MD36000 STOP_LIMIT_COARSE.
    Coarse,
    /// G603: at the interpolator's end.
    IpoEnd,
}

/// G group 30: the compressor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Compressor {
    #[default]
    Off,
    On,
    Curv,
    Cad,
    Surf,
}

/// The modal state of continuous-path control.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PathControl {
    pub smoothing: Smoothing,
    pub window: StopWindow,
    /// ADIS (G1, G2, G3 ...) and ADISPOS (G0): G641's rounding distances.
    pub adis: f64,
    pub adispos: f64,
    /// Programmed contour, orientation and axial tolerances (`None`: the machine data's).
    pub ctol: Option<f64>,
    pub otol: Option<f64>,
    pub atol: Option<f64>,
    pub compressor: Compressor,
    /// UPATH (true) or SPATH.
    pub upath: bool,
    /// G group 61: ORISON (true) or ORISOF (the reset value).
    pub orison: bool,
}

/// The words of one block that change [`PathControl`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PathWords {
    smoothing: Option<Smoothing>,
    window: Option<StopWindow>,
    adis: Option<f64>,
    adispos: Option<f64>,
    ctol: Option<f64>,
    otol: Option<f64>,
    atol: Option<f64>,
    compressor: Option<Compressor>,
    upath: Option<bool>,
    orison: Option<bool>,
}

impl PathWords {
    /// G641..G645 and G601..G603; false for any other G function. G641..G645 also select
    /// continuous-path mode: `exact_stop` is set to `Some(false)` for the caller's group 10.
    pub fn g_function(&mut self, code: u32, exact_stop: &mut Option<bool>) -> bool {
        let smoothing = match code {
            64 => Smoothing::G64,
            641 => Smoothing::G641,
            642 => Smoothing::G642,
            643 => Smoothing::G643,
            644 => Smoothing::G644,
            645 => Smoothing::G645,
            601..=603 => {
                self.window = Some([StopWindow::Fine, StopWindow::Coarse, StopWindow::IpoEnd][code as usize - 601]);
                return true;
            }
            _ => return false,
        };
        self.smoothing = Some(smoothing);
        *exact_stop = Some(false);
        true
    }

    /// `ADIS=`, `ADISPOS=`, `CTOL=`, `OTOL=`, `ATOL=`; false for any other address.
    pub fn address(&mut self, name: &str, value: f64, line: u32) -> Result<bool, Alarm> {
        let slot = match name {
            "ADIS" => &mut self.adis,
            "ADISPOS" => &mut self.adispos,
            "CTOL" => &mut self.ctol,
            "OTOL" => &mut self.otol,
            "ATOL" => &mut self.atol,
            _ => return Ok(false),
        };
        if !value.is_finite() || name.starts_with("ADIS") && value < 0.0 {
            return Err(Alarm::value_out_of_range(line, &format!("{name}={value}")));
        }
        *slot = Some(value);
        Ok(true)
    }

    /// COMPON, COMPCURV, COMPCAD, COMPSURF, COMPOF, UPATH, SPATH, ORISON, ORISOF, OSOF; false
    /// for any other keyword.
    pub fn keyword(&mut self, name: &str) -> bool {
        let compressor = match name {
            "ORISON" | "ORISOF" => {
                self.orison = Some(name == "ORISON");
                return true;
            }
            // G group 34's reset value: the orientation smoothing at block transitions it
            // deselects (OSC, OSS, OSSE, OSD, OST) is not modelled, so there is nothing to
            // switch off. Those five stay unknown names (12550, "option/function not
            // available", as on a control without the function).
            "OSOF" => return true,
            "COMPOF" => Compressor::Off,
            "COMPON" => Compressor::On,
            "COMPCURV" => Compressor::Curv,
            "COMPCAD" => Compressor::Cad,
            "COMPSURF" => Compressor::Surf,
            "UPATH" | "SPATH" => {
                self.upath = Some(name == "UPATH");
                return true;
            }
            _ => return false,
        };
        self.compressor = Some(compressor);
        true
    }
}

/// True for the addresses of this module (so an assignment `CTOL=0.01` is an NC address).
pub fn is_address(name: &str) -> bool {
    matches!(name, "ADIS" | "ADISPOS" | "CTOL" | "OTOL" | "ATOL")
}

impl PathControl {
    /// Takes over the block's words; programmed scaled lengths (`factor`: inch) in mm.
    pub fn apply(&mut self, w: &PathWords, factor: f64) {
        if let Some(s) = w.smoothing {
            self.smoothing = s;
        }
        if let Some(s) = w.window {
            self.window = s;
        }
        if let Some(v) = w.adis {
            self.adis = v * factor;
        }
        if let Some(v) = w.adispos {
            self.adispos = v * factor;
        }
        // A negative tolerance switches back to the machine data's.
        let tol = |v: Option<f64>, old: Option<f64>, f: f64| match v {
            Some(v) if v < 0.0 => None,
            Some(v) => Some(v * f),
            None => old,
        };
        self.ctol = tol(w.ctol, self.ctol, factor);
        self.otol = tol(w.otol, self.otol, 1.0);
        self.atol = tol(w.atol, self.atol, factor);
        if let Some(c) = w.compressor {
            self.compressor = c;
        }
        if let Some(u) = w.upath {
            self.upath = u;
        }
        if let Some(o) = w.orison {
            self.orison = o;
        }
    }

    /// ORISON's limits for a move of this block (`None` under ORISOF, or while MD28590
    /// reserves fewer than the 4 blocks the function needs).
    pub fn orison(&self, cfg: &MachineConfig) -> Option<OriSmoothing> {
        let data = &cfg.path_control;
        (self.orison && data.orison_blocks >= 4).then(|| OriSmoothing {
            tol: data.orison_tol.to_radians(),
            dist: data.orison_dist,
            block_limit: data.orison_block_limit,
            reach: OriSmoothing::reach_of(data.orison_blocks),
        })
    }

    /// The rounding at the end of a move of this block (`None` under G60/G9 and G64).
    pub fn blend(&self, exact_stop: bool, rapid: bool, cfg: &MachineConfig) -> Option<Blend> {
        if exact_stop {
            return None;
        }
        match self.smoothing {
            Smoothing::G64 => None,
            Smoothing::G641 => {
                let d = if rapid { self.adispos } else { self.adis };
                (d > 0.0).then_some(Blend::Distance(d))
            }
            Smoothing::G642 => {
                let mode = ModeDigit::of_g642(cfg);
                Some(Blend::Tolerance { contour: self.tolerance(cfg, mode), ori: self.ori_tolerance(cfg, mode) })
            }
            Smoothing::G643 => Some(self.g643(cfg)),
            Smoothing::G644 => Some(self.g644(rapid, cfg)),
            Smoothing::G645 => {
                let tangent = geo_min(cfg, &cfg.path_control.trans_tol);
                let mode = ModeDigit::of_g642(cfg);
                Some(Blend::Smooth { corner: self.tolerance(cfg, mode), ori: self.ori_tolerance(cfg, mode), tangent })
            }
        }
    }

    /// The compressor's limits for a move of this block (`None` under COMPOF).
    pub fn compress(&self, cfg: &MachineConfig) -> Option<Compress> {
        if self.compressor == Compressor::Off {
            return None;
        }
        let data = &cfg.path_control;
        let axial = cfg.geo_axes.iter().flatten().filter_map(|&k| data.axis_tol.get(k).copied());
        Some(Compress {
            tol: self.ctol.or(self.atol).unwrap_or_else(|| axial.fold(f64::INFINITY, f64::min)),
            block_limit: data.block_path_limit,
            velo_tol: data.velo_tol / 60.0,
            ori: self.otol.unwrap_or_else(|| rotary_min(cfg, &data.axis_tol)),
        })
    }

    /// G643's axial tolerances (see the module doc): the geometry axes' as G642's rule gives
    /// one (CTOL, SD42465, ATOL), the other axes' ATOL, else each axis' MD33100 (negative).
    fn g643(&self, cfg: &MachineConfig) -> Blend {
        let mode = ModeDigit::of_g643(cfg);
        let sd = mode.contour().then_some(cfg.path_control.contour_tol);
        let geo = self.ctol.or(sd).or(self.atol).unwrap_or(-1.0);
        Blend::Axial { geo, other: self.atol.unwrap_or(-1.0), ori: self.ori_tolerance(cfg, mode) }
    }

    /// G644's rounding by MD20480's thousands digit (see the module doc).
    fn g644(&self, rapid: bool, cfg: &MachineConfig) -> Blend {
        if matches!(cfg.path_control.smoothing_mode / 1000 % 10, 1 | 5) {
            Blend::Distance(if rapid { self.adispos } else { self.adis })
        } else {
            Blend::Tolerance { contour: geo_min(cfg, &cfg.path_control.axis_tol), ori: f64::INFINITY }
        }
    }

    /// The path tolerance of G642 and G645 by MD20480's digit `mode` (see the module doc).
    fn tolerance(&self, cfg: &MachineConfig, mode: ModeDigit) -> f64 {
        let data = &cfg.path_control;
        if let Some(c) = self.ctol {
            return c;
        }
        if mode.contour() {
            return data.contour_tol;
        }
        if let Some(a) = self.atol {
            return a;
        }
        cfg.geo_axes.iter().flatten().filter_map(|&k| data.axis_tol.get(k).copied()).fold(f64::INFINITY, f64::min)
    }

    /// The orientation tolerance of G642, G643, G645 in radians (it acts under an orientation
    /// transformation only): `OTOL` when programmed, else SD42466 when MD20480's digit `mode`
    /// is 2 or 3 (the orientation axes by the orientation tolerance), else the smallest
    /// MD33100 of the rotary axes, read as an angle of the orientation (the rotary axes by
    /// their axial tolerance); infinite on a machine without rotary axes.
    fn ori_tolerance(&self, cfg: &MachineConfig, mode: ModeDigit) -> f64 {
        let data = &cfg.path_control;
        let degrees = match self.otol {
            Some(o) => o,
            None if mode.orientation() => data.ori_tol,
            None => rotary_min(cfg, &data.axis_tol),
        };
        degrees.to_radians()
    }

    /// `$P_GG[10]`'s number in G group 10 when not under G60.
    pub fn group10(&self) -> i64 {
        self.smoothing as i64 + 2
    }

    /// `$P_GG[12]`.
    pub fn group12(&self) -> i64 {
        self.window as i64 + 1
    }
}

/// One digit of MD20480 `$MC_SMOOTHING_MODE`: which data a rounding function keeps (B1
/// "Rounding behavior": 0 MD33100 for every axis, 1 SD42465 for the geometry axes, 2 SD42466
/// for the orientation, 3 both; the axes not named by MD33100).
#[derive(Debug, Clone, Copy)]
struct ModeDigit(i64);

impl ModeDigit {
    /// G642's digit, the tens (G645 rounds its corners as G642 does).
    fn of_g642(cfg: &MachineConfig) -> ModeDigit {
        ModeDigit(cfg.path_control.smoothing_mode / 10 % 10)
    }

    /// G643's digit, the units.
    fn of_g643(cfg: &MachineConfig) -> ModeDigit {
        ModeDigit(cfg.path_control.smoothing_mode % 10)
    }

    /// The geometry axes keep the contour tolerance SD42465.
    fn contour(self) -> bool {
        matches!(self.0, 1 | 3)
    }

    /// The orientation keeps the orientation tolerance SD42466.
    fn orientation(self) -> bool {
        matches!(self.0, 2 | 3)
    }
}

/// The smallest of an axial datum over the geometry axes (`per_axis` by channel axis).
fn geo_min(cfg: &MachineConfig, per_axis: &[f64]) -> f64 {
    cfg.geo_axes.iter().flatten().filter_map(|&k| per_axis.get(k).copied()).fold(f64::INFINITY, f64::min)
}

/// The smallest of the rotary axes' entries of the axial datum `per_axis` (MD33100: the
/// orientation's tolerance where the rotary axes carry it); infinite without rotary axes. A
/// spindle is no orientation axis (its MD33100 took part before: the mill's tool spindle).
fn rotary_min(cfg: &MachineConfig, per_axis: &[f64]) -> f64 {
    (0..cfg.channel_axes.len())
        .filter(|&k| cfg.axis(k).rotary && cfg.axis(k).spindle.is_none())
        .filter_map(|k| per_axis.get(k).copied())
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::{PathControl, Smoothing};
    use crate::Channel;
    use crate::motion::blend::Blend;

    /// The orientation tolerance (degrees) G642 and G643 round by on the 5-axis head with
    /// MD33100 = 0.5° on its rotary axes A and C (0.1 on the tool spindle, no orientation
    /// axis), SD42466 = 0.2° and MD20480 = `mode`.
    fn ori(mode: u32, smoothing: Smoothing) -> f64 {
        let md = format!(
            "$MA_COMPRESS_POS_TOL[A]=0.5\n$MA_COMPRESS_POS_TOL[C]=0.5\n$SC_SMOOTH_ORI_TOL=0.2\n$MC_SMOOTHING_MODE={mode}"
        );
        let ch = Channel::from_preset("mill5-head-ca", &md).expect("preset");
        let pc = PathControl { smoothing, ..Default::default() };
        match pc.blend(false, false, ch.config()) {
            Some(Blend::Tolerance { ori, .. } | Blend::Axial { ori, .. }) => ori.to_degrees(),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn the_orientation_keeps_sd42466_where_the_functions_digit_is_2_or_3() {
        // B1: digit 2 or 3 rounds the orientation within SD42466 (0.2°), 0 or 1 by the
        // rotary axes' MD33100 (0.5°). G642 reads the tens digit, G643 the units digit.
        for (mode, g642, g643) in [(0, 0.5, 0.5), (2, 0.5, 0.2), (20, 0.2, 0.5), (31, 0.2, 0.5), (13, 0.5, 0.2)] {
            assert!((ori(mode, Smoothing::G642) - g642).abs() < 1e-9, "G642 MD20480={mode}");
            assert!((ori(mode, Smoothing::G643) - g643).abs() < 1e-9, "G643 MD20480={mode}");
        }
    }
}

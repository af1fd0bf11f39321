//! The modal state (G groups, feed) and the words of one block sorted by meaning.

pub(crate) mod vocabulary;

use super::StopKind;
use super::calls::{Programs, targets};
use super::compensation::approach::ApproachMode;
use super::compensation::trc::{ArcFeed, CornerMode, Side};
use super::contour::corners::Corner;
use super::eval::scope::{Ctx, SysView};
use super::eval::value::Value;
use super::eval::value_lists::List;
use super::eval::vars::Variables;
use super::eval::{eval, eval_f64};
use super::frames::frame::Frame;
use super::frames::vars::{ChainFrame, Suppress};
use super::orientation::words::{self, OriModal, OriWords};
use super::tools::toolholder::{CutMode, TcoMode, g53_code};
use crate::alarm::Alarm;
use crate::lang::{Block, CoordMode, Expr, Goto, JumpTarget, Word};
use crate::machine_data::MachineConfig;

/// G group 1: motion type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MotionMode {
    /// G0.
    Rapid,
    /// G1.
    Linear,
    /// G2.
    Cw,
    /// G3.
    Ccw,
}

/// How a circle of G group 1 is given: the G2/G3 forms (centre, radius, angle, polar), `CT`
/// (tangential to the path before, `contour/tangent_circle.rs`) or `CIP` (through an
/// intermediate point, `contour/through_point.rs`). For CT and CIP [`MotionMode`] holds the
/// turn of the last circle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CircleForm {
    #[default]
    Standard,
    Tangent,
    ThroughPoint,
}

/// G group 6: working plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Plane {
    G17,
    G18,
    G19,
}

impl Plane {
    /// Geometry axis indices (0 = 1st) of abscissa, ordinate and applicate.
    pub fn axes(self) -> (usize, usize, usize) {
        match self {
            Plane::G17 => (0, 1, 2),
            Plane::G18 => (2, 0, 1),
            Plane::G19 => (1, 2, 0),
        }
    }
}

/// The modal state of block preparation.
#[derive(Debug, Clone, PartialEq)]
pub struct Modal {
    pub motion: MotionMode,
    pub plane: Plane,
    /// G90 (true) or G91.
    pub absolute: bool,
    /// G70/G700: geometry in inch.
    pub inch: bool,
    /// G700/G710: feed follows the unit system too.
    pub inch_feed: bool,
    /// G95 (feed per spindle revolution) instead of G94.
    pub feed_per_rev: bool,
    /// G group 15 beyond G94/G95 for the display: index into its names (0: from
    /// `feed_per_rev`), set by `spindles/block.rs`.
    pub feed_type_index: u8,
    /// G group 29 as `spindles::diameter::Diameter::gcode_slot` gives it.
    pub diameter_slot: u8,
    /// Channel axes other than the transverse axis whose WCS display shows diameters
    /// (bit k: channel axis k; `spindles::diameter::Diameter::display_mask`).
    pub diameter_display_axes: u32,
    /// G60 (true) or G64.
    pub exact_stop: bool,
    /// Active settable frame: 0 = G500, 1..4 = G54..G57, 5.. = G505...
    pub work_offset: usize,
    /// Programmed F (mm/min, or mm/rev under G95), in program units.
    pub feed: Option<f64>,
    /// Pole of polar coordinates (abscissa, ordinate of the working plane, WCS).
    pub pole: (f64, f64),
    /// Tool radius compensation: G40 (None), G41, G42.
    pub trc: Option<Side>,
    /// RNDM=: modal rounding radius of every following contour corner (None: RNDM=0).
    pub rndm: Option<f64>,
    /// TOFFL/TOFF[axis]: programmed tool offsets (`tools/programmable_offset.rs`).
    pub tool_offsets: super::tools::programmable_offset::ProgrammedOffsets,
    /// FRCM=: modal feed of chamfers and roundings (None: FRCM=0, F applies).
    pub frcm: Option<f64>,
    /// CT or CIP (G group 1) instead of G2/G3 when `motion` is a circle.
    pub circle_form: CircleForm,
    /// G450 (transition circle) or G451 (intersection) at outer corners.
    pub trc_corners: CornerMode,
    /// G groups 43 and 44 of smooth approach and retract (`compensation/sar.rs`).
    pub sar: super::compensation::sar::SarModal,
    /// Spline type (G group 1 beside G1), G groups 19/20 and SD (`path_control/spline.rs`).
    pub spline: super::path_control::spline::SplineModal,
    /// OFFN contour offset.
    pub offn: f64,
    /// G group 17: NORM, KONT, KONTT, KONTC (approach and retract).
    pub approach: ApproachMode,
    /// DISC: how far G450's transition circle is pulled towards the intersection (0..100).
    pub disc: f64,
    /// Where the feed applies on compensated arcs (G group 16).
    pub arc_feed: ArcFeed,
    /// G group 23: CDON, the radius compensation's bottleneck detection over MD20240 blocks
    /// (false: CDOF, the reset value).
    pub collision_detection: bool,
    /// Last polar angle AP (degrees) and radius RP.
    pub polar: (f64, f64),
    /// G groups 25, 50 and 51 of orientation programming.
    pub ori: OriModal,
    /// G group 49: Cartesian path (CP) or point-to-point travel.
    pub ptp: PtpMode,
    /// G groups 21, 24, 59 and ACC/JERKLIM/VELOLIM.
    pub dynamics: super::dynamics::DynModal,
    /// G groups 10 (G64x), 12 and 30, ADIS and the tolerances (`path_control.rs`).
    pub path: super::path_control::PathControl,
    /// G group 55: RTLIOF (true) or RTLION, the reset value (`path_control/rapid_apart.rs`).
    pub rtliof: bool,
    /// G group 28: WALIMOF (true) or WALIMON, the reset value (`path_control/work_area.rs`).
    pub walimof: bool,
    /// FGROUP/FGREF (`path_control/feed_group.rs`); `None` until a program writes one.
    pub feed_group: Option<Box<super::path_control::feed_group::FeedGroup>>,
}

/// G group 49: how a transformation's machine axes travel between the block end points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PtpMode {
    /// CP: the Cartesian path is interpolated (default).
    Cp,
    /// PTP: only the end point is transformed; the machine axes move linearly together.
    Ptp,
    /// PTPG0: PTP for G0 blocks, CP otherwise.
    PtpG0,
    /// PTPWOC: PTP without compensating motion (handling robots); like PTP here.
    PtpWoc,
}

impl PtpMode {
    /// True if a block with this motion travels point to point.
    pub fn applies(self, rapid: bool) -> bool {
        match self {
            PtpMode::Cp => false,
            PtpMode::Ptp | PtpMode::PtpWoc => true,
            PtpMode::PtpG0 => rapid,
        }
    }
}

impl Modal {
    /// Reset values (MD20150 GCODE_RESET_VALUES defaults): G1, the plane of MD20150[5] (G17 by
    /// default; G18 on a machine without a 2nd geometry axis), G90, G71, G94, G60, G500; no feed.
    pub fn reset(cfg: &MachineConfig) -> Modal {
        Modal {
            motion: MotionMode::Linear,
            plane: match cfg.plane_reset {
                2 => Plane::G18,
                3 => Plane::G19,
                _ if cfg.geo_axes[1].is_none() => Plane::G18,
                _ => Plane::G17,
            },
            absolute: true,
            inch: false,
            inch_feed: false,
            feed_per_rev: false,
            feed_type_index: 0,
            diameter_slot: 0,
            diameter_display_axes: 0,
            exact_stop: true,
            work_offset: 0,
            feed: None,
            pole: (0.0, 0.0),
            polar: (0.0, 0.0),
            trc: None,
            rndm: None,
            circle_form: CircleForm::Standard,
            frcm: None,
            tool_offsets: Default::default(),
            trc_corners: CornerMode::Circle,
            sar: Default::default(),
            spline: Default::default(),
            offn: 0.0,
            approach: ApproachMode::Norm,
            disc: 0.0,
            arc_feed: ArcFeed::Contour,
            collision_detection: false,
            ori: OriModal::reset(),
            ptp: PtpMode::Cp,
            dynamics: super::dynamics::DynModal::reset(cfg),
            path: Default::default(),
            feed_group: None,
            walimof: false,
            rtliof: false,
        }
    }

    /// Millimetres per programmed length unit.
    pub fn length_factor(&self) -> f64 {
        if self.inch { 25.4 } else { 1.0 }
    }

    /// Millimetres per programmed feed length unit.
    pub fn feed_factor(&self) -> f64 {
        if self.inch && self.inch_feed { 25.4 } else { 1.0 }
    }

    /// Applies the modal G functions of a block.
    pub(super) fn apply(&mut self, w: &Words, cfg: &MachineConfig, line: u32) -> Result<(), Alarm> {
        if let Some(m) = w.motion {
            self.motion = m;
            self.circle_form = w.circle_form;
        }
        self.tool_offsets.apply(&w.tool_offsets);
        self.spline.apply(&w.spline, w.motion.is_some());
        if w.spline.kind.is_some() {
            // A spline block is prepared like a G1 block (`path_control/spline.rs`).
            self.motion = MotionMode::Linear;
        }
        if let Some(p) = w.plane {
            // The compensation plane changes only with G40 (in this block or before).
            if self.trc.is_some() && p != self.plane && w.trc != Some(None) {
                return Err(Alarm::trc_plane_change(line));
            }
            self.plane = p;
        }
        if let Some(a) = w.absolute {
            self.absolute = a;
        }
        if let Some((inch, feed)) = w.units {
            self.inch = inch;
            self.inch_feed = feed;
        }
        if let Some(f) = w.feed_per_rev {
            self.feed_per_rev = f;
        }
        if let Some(e) = w.exact_stop {
            self.exact_stop = e;
        }
        self.path.apply(&w.path, self.length_factor());
        super::path_control::feed_group::FeedGroup::apply(&mut self.feed_group, &w.feed_group);
        if let Some(off) = w.walimof {
            self.walimof = off;
        }
        if let Some(off) = w.rtliof {
            self.rtliof = off;
        }
        if let Some(side) = w.trc {
            self.trc = side;
        }
        if let Some(c) = w.trc_corners {
            self.trc_corners = c;
        }
        self.sar.apply(&w.sar);
        if let Some(o) = w.offn {
            self.offn = o;
        }
        if let Some(a) = w.approach {
            self.approach = a;
        }
        if let Some(d) = w.disc {
            if !(0.0..=100.0).contains(&d) {
                return Err(Alarm::value_out_of_range(line, &format!("DISC={d} (0..100)")));
            }
            self.disc = d;
        }
        if let Some(f) = w.arc_feed {
            self.arc_feed = f;
        }
        if let Some(c) = w.collision_detection {
            self.collision_detection = c;
        }
        self.ori.apply(&w.ori);
        if let Some(p) = w.ptp {
            self.ptp = p;
        }
        self.dynamics.apply(&w.dynamics);
        if let Some(frame) = w.work_offset {
            if frame >= cfg.work_offsets.len() {
                return Err(Alarm::value_out_of_range(
                    line,
                    &format!("settable frame {frame} (MD28080 MM_NUM_USER_FRAMES = {})", cfg.work_offsets.len()),
                ));
            }
            self.work_offset = frame;
        }
        Ok(())
    }
}

/// What the coordinates of a pole definition refer to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PoleRef {
    /// G110: the last programmed position.
    LastPosition,
    /// G111: the workpiece zero.
    WorkpieceZero,
    /// G112: the last pole.
    LastPole,
}

/// The oblique plunge functions of TRAANG (non-modal here).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Oblique {
    /// G07: move along Z to where a plunge along the inclined axis reaches the end point.
    Approach,
    /// G05: plunge along the inclined axis to the programmed X.
    Plunge,
}

/// The kind of a programmable frame instruction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameKind {
    Trans,
    Rot,
    /// ROTS/AROTS: two solid angles.
    Rots,
    Scale,
    Mirror,
}

/// A programmable frame instruction: absolute (replaces the programmable frame) or additive.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FrameOp {
    pub kind: FrameKind,
    pub additive: bool,
}

fn frame_op(name: &str) -> Option<FrameOp> {
    let (additive, base) = match name.strip_prefix('A') {
        Some(rest) if matches!(rest, "TRANS" | "ROT" | "ROTS" | "SCALE" | "MIRROR") => (true, rest),
        _ => (false, name),
    };
    let kind = match base {
        "TRANS" => FrameKind::Trans,
        "ROT" => FrameKind::Rot,
        "ROTS" => FrameKind::Rots,
        "SCALE" => FrameKind::Scale,
        "MIRROR" => FrameKind::Mirror,
        _ => return None,
    };
    Some(FrameOp { kind, additive })
}

/// The words of one block, sorted by meaning and evaluated.
#[derive(Debug, Clone, Default)]
pub(super) struct Words {
    pub motion: Option<MotionMode>,
    pub plane: Option<Plane>,
    pub absolute: Option<bool>,
    pub units: Option<(bool, bool)>,
    pub feed_per_rev: Option<bool>,
    pub exact_stop: Option<bool>,
    /// G641..G645, G601..G603, ADIS, CTOL ... (`path_control.rs`).
    pub path: super::path_control::PathWords,
    /// G140..G143, G147..G348, G340/G341, DISR, DISCL, FAD (`compensation/sar.rs`).
    pub sar: super::compensation::sar::SarWords,
    /// ASPLINE/BSPLINE/CSPLINE/POLY, PW, SD, PL, PO[..] (`path_control/spline.rs`).
    pub spline: super::path_control::spline::SplineWords,
    pub work_offset: Option<usize>,
    /// G4 dwell (F and S of the block are dwell values then).
    pub dwell: bool,
    /// RTLION (`Some(false)`) / RTLIOF (`Some(true)`).
    pub rtliof: Option<bool>,
    /// WALIMON (`Some(false)`) / WALIMOF (`Some(true)`).
    pub walimof: Option<bool>,
    /// FGROUP(..), FGREF[ax]= (`path_control/feed_group.rs`).
    pub feed_group: super::path_control::feed_group::FeedGroupWords,
    /// G74/G75: the block's axes travel to the reference or a fixed point (`FP=`).
    pub fixed_point: Option<super::path_control::fixed_point::Approach>,
    pub fixed_point_number: Option<u32>,
    /// G9 non-modal exact stop.
    pub g9: bool,
    /// G07 (approach the start of an oblique plunge) or G05 (oblique plunge), TRAANG.
    pub oblique: Option<Oblique>,
    /// G53, G153, SUPA: frames suppressed for this block.
    pub suppress: Option<Suppress>,
    /// Channel axis, value, coordinate mode.
    pub axes: Vec<(usize, f64, Option<CoordMode>)>,
    /// I, J, K by geometry axis: value and whether it is absolute (`AC`).
    pub ijk: [Option<(f64, bool)>; 3],
    pub cr: Option<f64>,
    pub feed: Option<f64>,
    pub speed: Option<f64>,
    pub tool: Option<u32>,
    /// `T="name"`: a tool by its name (`$TC_TP2`); `TCA("name", duplo)` adds the duplo number.
    pub tool_name: Option<super::tools::management::NamedTool>,
    /// The tool-change M function (MD22560, M6).
    pub tool_change: bool,
    pub edge: Option<u32>,
    pub spindle_dir: Option<i8>,
    /// The spindle number of an `M<n>=3/4/5` (address extension).
    pub spindle_ext: Option<u32>,
    /// SETMS(n): spindle n becomes the master spindle (`Some(None)`: SETMS, back to MD20090).
    pub set_master: Option<Option<u32>>,
    /// SETPIECE(n[, spindle]): the piece count of count-monitored tools (`tools/setpiece.rs`).
    pub set_piece: Option<super::tools::setpiece::SetPiece>,
    /// POS/POSA/FA[ax] words (`path_control/positioning.rs`).
    pub positioning: Vec<super::path_control::positioning::PosWord>,
    /// OS/OSP1/OSP2/OST1/OST2/OSE/OSB/OSNSC/OSCTRL[ax] words (`path_control/oscillation.rs`).
    pub oscillation: Vec<super::path_control::oscillation::OscWord>,
    /// WAITP(ax, ..): the axes as a bit mask.
    pub waitp: u32,
    pub stop: Option<StopKind>,
    /// A jump at the end of the block (`... GOTOF LABEL`).
    pub goto: Option<Goto>,
    /// A subprogram call at the end of the block, with its arguments.
    pub call: Option<(String, Vec<Expr>)>,
    /// `P`: number of runs of the call.
    pub repeat: Option<u32>,
    /// MCALL: the block's call becomes the modal call (without one, the modal call ends).
    pub mcall: bool,
    /// `CALL [NAME] BLOCK START TO END`: program, first and last block of the section.
    pub section_call: Option<Box<(Option<String>, JumpTarget, JumpTarget)>>,
    /// A frame instruction; the block's axis words are its values.
    pub frame_op: Option<FrameOp>,
    /// `RPL=`: rotation angle in the working plane (with ROT/AROT).
    pub rpl: Option<f64>,
    /// G110/G111/G112: the block's plane-axis words define the pole.
    pub pole: Option<PoleRef>,
    /// `AP=` polar angle, `RP=` polar radius.
    pub ap: Option<f64>,
    pub rp: Option<f64>,
    /// Tool, frame and machine data written by the block, as NC data text lines.
    pub data_writes: Vec<String>,
    /// Online tool length offset instructions (`$AA_TOFF[..]=`, TOFFON, TOFFOF).
    pub toff: Vec<super::compensation::toff::ToffOp>,
    /// NEWCONF: activate machine data written by the program.
    pub newconf: bool,
    /// MSG: text for the operator (empty clears it).
    pub message: Option<String>,
    /// SETAL: a cycle alarm raised by the program.
    pub user_alarm: Option<Alarm>,
    /// G40 (`Some(None)`), G41, G42.
    pub trc: Option<Option<Side>>,
    /// G450/G451.
    pub trc_corners: Option<CornerMode>,
    /// OFFN=: contour offset added to the tool radius.
    pub offn: Option<f64>,
    /// NORM, KONT, KONTT, KONTC.
    pub approach: Option<ApproachMode>,
    /// DISC=.
    pub disc: Option<f64>,
    /// CFC, CFTCP, CFIN.
    pub arc_feed: Option<ArcFeed>,
    /// CDON (true), CDOF/CDOF2 (false).
    pub collision_detection: Option<bool>,
    /// SPOS=: position the master spindle (it becomes a rotary axis).
    /// Spindle words beyond S and M3/M4/M5 (see `spindles/words.rs`).
    pub spindle: super::spindles::words::SpindleWords,
    /// MEAS=/MEAW=: measure with a probe in this block's motion (`measuring.rs`).
    pub measure: Option<super::measuring::Request>,
    /// `$P_PFRAME=...`, `$P_SETFRAME=...`: links of the frame chain the block assigns.
    pub frame_writes: Vec<(ChainFrame, Frame)>,
    /// RND=, CHF=, CHR=: the corner at the end of this block.
    pub corner: Option<Corner>,
    /// RNDM=: the modal rounding radius (0 switches it off).
    pub rndm: Option<f64>,
    /// TOFFL=, TOFFL[i]=, TOFF[axis]= in the order written (mm).
    pub tool_offsets: Vec<(super::tools::programmable_offset::Slot, f64)>,
    /// ANG=: the angle of a straight line given by one end coordinate (`contour/angle_line.rs`).
    pub ang: Option<f64>,
    /// FRC= / FRCM=: feed of the corner (`contour/corner_feed.rs`).
    pub frc: Option<f64>,
    pub frcm: Option<f64>,
    /// CT or CIP: the circle's form (G group 1, with `motion` a circle).
    pub circle_form: CircleForm,
    /// `I1=`, `J1=`, `K1=`: the intermediate point of CIP per geometry axis (value, AC/IC).
    pub ijk1: [Option<(f64, Option<CoordMode>)>; 3],
    /// CONTCAPON(table, count) / CONTCAPOF: contour capture (`contour/capture.rs`).
    pub capture: Option<super::contour::capture::CaptureOp>,
    /// `AR=` opening angle of a circle, `TURN=` extra full turns of a helix.
    pub ar: Option<f64>,
    pub turn: Option<u32>,
    /// Orientation words and G functions.
    pub ori: OriWords,
    /// CP, PTP, PTPG0, PTPWOC.
    pub ptp: Option<PtpMode>,
    /// BRISK/SOFT/DRIVE, FFWON/FFWOF, DYNNORM.., ACC[..]=, JERKLIM[..]=, VELOLIM[..]=.
    pub dynamics: super::dynamics::DynWords,
    /// `STAT=`: joint configuration for PTP; `TU=`: turn direction of the rotary axes.
    pub stat: Option<u32>,
    pub tu: Option<u32>,
    /// `TCARR=n` or `TCARR="name"`.
    pub tcarr: Option<Value>,
    /// G group 42: TCOABS, TCOFR, TCOFRZ/Y/X.
    pub tco: Option<TcoMode>,
    /// G group 52: PAROT (true), PAROTOF.
    pub parot: Option<bool>,
    /// G group 53: TOROTOF .. TOFRAMEX by its code (1..9).
    pub g53_group: Option<i64>,
    /// G group 22: CUT2D, CUT2DF, CUT3DFS, CUT3DFF.
    pub cut: Option<CutMode>,
    /// `WORKPIECE(..)`: the blank (`workpiece.rs`).
    pub workpiece: Option<crate::stock::blank::Request>,
    /// `CYCLE800(...)`: the evaluated arguments (`None` = omitted).
    pub swivel: Option<Vec<Option<Value>>>,
    /// M and H functions for the PLC, in the order written.
    pub aux: Vec<super::auxiliary::AuxFunction>,
    /// `$A_DBB[n]=..`: PLC data the block writes (offset, bytes; `io/plc_data.rs`).
    pub plc_writes: Vec<(usize, Vec<u8>)>,
    /// `$A_OUT[n]=..`: digital outputs the block sets (signal, level).
    pub digital_outputs: Vec<(usize, bool)>,
    /// `$AC_MARKER[n]=..`, `$AC_ACTUAL_PARTS=..`: writes the main run does at the block.
    pub main_run_writes: Vec<super::synchronized::MainRunWrite>,
    /// `PRESETON(ax, v)`: channel axes and their new machine positions (`frames/preset.rs`).
    pub presets: Vec<(usize, f64)>,
    /// CALLPATH: `Some(path)` extends the call search path, `Some("")` ends the extension.
    pub callpath: Option<String>,
}

impl Words {
    /// Centre parameters of the plane's abscissa and ordinate; a missing one counts as 0.
    pub fn center(&self, a: usize, o: usize) -> Option<((f64, bool), (f64, bool))> {
        if self.ijk[a].is_none() && self.ijk[o].is_none() {
            return None;
        }
        Some((self.ijk[a].unwrap_or((0.0, false)), self.ijk[o].unwrap_or((0.0, false))))
    }

    pub fn arc_params_given(&self) -> bool {
        self.cr.is_some()
            || self.ar.is_some()
            || self.ijk.iter().any(Option::is_some)
            || self.ijk1.iter().any(Option::is_some)
    }

    /// Polar coordinates in the block.
    pub fn polar(&self) -> bool {
        self.ap.is_some() || self.rp.is_some()
    }
}

/// The `Words` of the last block, kept so that the next block's reuse its room: scratch
/// space, not state (its `Debug` shows nothing, so states compare equal whatever it holds).
#[derive(Clone, Default)]
pub(super) struct SpareWords(pub Option<Box<Words>>);

impl std::fmt::Debug for SpareWords {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("SpareWords")
    }
}

impl Words {
    /// Empties the words for the next block, keeping the lists' allocations: one `Words` is
    /// reused block after block, so a plain block allocates nothing and the large struct is
    /// not moved out of `collect`.
    pub fn clear(&mut self) {
        let mut axes = std::mem::take(&mut self.axes);
        let mut data_writes = std::mem::take(&mut self.data_writes);
        let mut toff = std::mem::take(&mut self.toff);
        let mut frame_writes = std::mem::take(&mut self.frame_writes);
        let mut aux = std::mem::take(&mut self.aux);
        aux.clear();
        axes.clear();
        data_writes.clear();
        toff.clear();
        frame_writes.clear();
        *self = Words::default();
        (self.axes, self.data_writes, self.toff, self.frame_writes, self.aux) =
            (axes, data_writes, toff, frame_writes, aux);
    }
}

/// Sorts and evaluates the words of `block` into `w` (cleared first). Assignments (`R1=5`,
/// `A[2]=R1`) take effect in block order, so a later word of the same block sees the new value.
pub(super) fn collect(
    w: &mut Words,
    block: &Block,
    cfg: &MachineConfig,
    vars: &mut Variables,
    sys: &SysView,
    programs: &Programs,
) -> Result<(), Alarm> {
    let line = block.line;
    w.clear();
    // Addresses seen so far (each may appear once per block).
    let mut seen = Seen::default();
    for word in &block.words {
        match word {
            Word::G(code) => g_function(w, *code, line)?,
            Word::M(code) => {
                m_function(w, *code, line)?;
                w.tool_change |= *code == cfg.tool_change.m_code;
            }
            Word::Goto(goto) => w.goto = Some(goto.clone()),
            Word::Keyword { name, args }
                if args.is_empty()
                    && matches!(
                        name.as_str(),
                        "SUPA"
                            | "STOPRE"
                            | "NEWCONF"
                            | "CFC"
                            | "CFTCP"
                            | "CFIN"
                            | "NORM"
                            | "KONT"
                            | "KONTT"
                            | "KONTC"
                            | "CDON"
                            | "CDOF"
                            | "CDOF2"
                    ) =>
            {
                match name.as_str() {
                    "SUPA" => w.suppress = Some(Suppress::All),
                    "NEWCONF" => w.newconf = true,
                    "CFC" => w.arc_feed = Some(ArcFeed::Contour),
                    "CFTCP" => w.arc_feed = Some(ArcFeed::CentrePath),
                    "CFIN" => w.arc_feed = Some(ArcFeed::InnerOnly),
                    "NORM" => w.approach = Some(ApproachMode::Norm),
                    "KONT" => w.approach = Some(ApproachMode::Kont),
                    "KONTT" => w.approach = Some(ApproachMode::Tangent),
                    "KONTC" => w.approach = Some(ApproachMode::Curvature),
                    // G group 23; CDOF2 differs from CDOF only in 3D circumferential milling.
                    "CDON" => w.collision_detection = Some(true),
                    "CDOF" | "CDOF2" => w.collision_detection = Some(false),
                    _ => {}
                }
            }
            Word::Keyword { name, args } if args.is_empty() && w.ori.keyword(name) => {}
            Word::Keyword { name, args } if args.is_empty() && w.path.keyword(name) => {}
            Word::Keyword { name, args } if args.is_empty() && w.spline.keyword(name) => {}
            Word::Keyword { name, args } if args.is_empty() && matches!(name.as_str(), "CT" | "CIP") => {
                if w.motion.is_some() {
                    return Err(Alarm::syntax(line, &format!("{name} and another G function of group 1 in a block")));
                }
                // The turn follows from the geometry when the block is prepared.
                let form = if name == "CT" { CircleForm::Tangent } else { CircleForm::ThroughPoint };
                (w.motion, w.circle_form) = (Some(MotionMode::Ccw), form);
            }
            Word::Keyword { name, args }
                if args.is_empty() && matches!(name.as_str(), "CP" | "PTP" | "PTPG0" | "PTPWOC") =>
            {
                w.ptp = Some(match name.as_str() {
                    "CP" => PtpMode::Cp,
                    "PTP" => PtpMode::Ptp,
                    "PTPG0" => PtpMode::PtpG0,
                    _ => PtpMode::PtpWoc,
                });
            }
            Word::Keyword { name, args } if args.is_empty() && w.dynamics.keyword(name) => {}
            Word::Keyword { name, args }
                if args.is_empty() && super::spindles::words::keyword(&mut w.spindle, name, line)? => {}
            Word::Keyword { name, args } if args.is_empty() && holder_keyword(w, name, line)? => {}
            Word::Keyword { name, args } if name == "CYCLE800" => {
                if w.swivel.is_some() {
                    return Err(Alarm::syntax(line, "one CYCLE800 per block"));
                }
                let mut values = Vec::new();
                for e in args {
                    values.push(match e {
                        Expr::Call(n, a) if n == "_OMITTED" && a.is_empty() => None,
                        e => Some(eval(e, &Ctx { vars, sys }, line)?),
                    });
                }
                w.swivel = Some(values);
            }
            Word::Keyword { name, args } if args.is_empty() && frame_op(name).is_some() => {
                if w.frame_op.is_some() {
                    return Err(Alarm::syntax(line, "one frame instruction per block"));
                }
                w.frame_op = frame_op(name);
            }
            Word::Keyword { name, args } if programs.contains_key(name) || targets::is_l_call(name) => {
                set_call(w, name.clone(), args.clone(), line)?
            }
            Word::Keyword { name, args } if name == "MCALL" && args.is_empty() => w.mcall = true,
            Word::Keyword { name, args } if name == "WORKPIECE" => {
                w.workpiece = Some(super::workpiece::read(args, &Ctx { vars, sys }, line)?);
            }
            Word::Keyword { name, args } if super::everyday::is_inert_keyword(name, !args.is_empty()) => {}
            Word::Keyword { name, args } if name == "PCALL" => {
                let Some(Expr::Str(path)) = args.first() else {
                    return Err(Alarm::syntax(line, "PCALL needs a program path"));
                };
                set_call(w, targets::program_of_path(path), args[1..].to_vec(), line)?;
            }
            Word::Keyword { name, args } if name == "CALLPATH" => {
                w.callpath = Some(match args.as_slice() {
                    [] => String::new(),
                    [e] => eval(e, &Ctx { vars, sys }, line)?.as_text(),
                    _ => return Err(Alarm::syntax(line, "CALLPATH takes one path")),
                });
            }
            Word::Keyword { name, args } if name == "EXTCALL" => {
                let target = match args.as_slice() {
                    [e] => eval(e, &Ctx { vars, sys }, line)?.as_text(),
                    _ => return Err(Alarm::syntax(line, "EXTCALL needs one program name")),
                };
                set_call(w, targets::program_of_path(&target), Vec::new(), line)?;
            }
            Word::Keyword { name, args } if name == "MSG" => {
                w.message = Some(match args.as_slice() {
                    [] => String::new(),
                    [e] => eval(e, &Ctx { vars, sys }, line)?.as_text(),
                    _ => return Err(Alarm::syntax(line, "MSG takes one text")),
                });
            }
            Word::Keyword { name, args } if name == "CONTCAPON" || name == "CONTCAPOF" => {
                use super::contour::capture::CaptureOp;
                w.capture = Some(match (name.as_str(), args.as_slice()) {
                    ("CONTCAPON", [Expr::Var { name: table, indices: t }, Expr::Var { name: count, indices: c }])
                        if t.is_empty() && c.is_empty() =>
                    {
                        CaptureOp::On { table: table.clone(), count: count.clone() }
                    }
                    ("CONTCAPOF", []) => CaptureOp::Off,
                    _ => return Err(Alarm::syntax(line, "CONTCAPON(table, count) or CONTCAPOF")),
                });
            }
            Word::Keyword { name, args } if name == "SETAL" => {
                let ctx = Ctx { vars, sys };
                let number = match args.first() {
                    Some(e) => eval(e, &ctx, line)?.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?,
                    None => return Err(Alarm::syntax(line, "SETAL needs an alarm number")),
                };
                if !(60000..=67999).contains(&number) {
                    return Err(Alarm::value_out_of_range(
                        line,
                        &format!("SETAL({number}): cycle alarms are 60000..67999"),
                    ));
                }
                let text = match args.get(1) {
                    Some(e) => eval(e, &ctx, line)?.as_text(),
                    None => String::new(),
                };
                w.user_alarm = Some(Alarm::user(line, number as u32, &text));
            }
            Word::Keyword { name, args } if name == "ORIRESET" => {
                if args.len() > 3 {
                    return Err(Alarm::syntax(line, "ORIRESET takes at most three axis positions"));
                }
                let mut values = [None; 3];
                for (v, e) in values.iter_mut().zip(args) {
                    if !matches!(e, Expr::Call(n, a) if n == "_OMITTED" && a.is_empty()) {
                        *v = Some(eval_f64(e, &Ctx { vars, sys }, line)?);
                    }
                }
                w.ori.reset = Some(values);
            }
            Word::Keyword { name, args } if name == "TOFFON" || name == "TOFFOF" => {
                use super::compensation::toff::{ToffOp, direction};
                let dir = |e: &Expr| -> Result<usize, Alarm> {
                    let v = eval(e, &Ctx { vars, sys }, line)?;
                    direction(cfg, &v.as_text().to_ascii_uppercase(), line)
                };
                let value = |e: &Expr| eval_f64(e, &Ctx { vars, sys }, line);
                w.toff.push(match (name.as_str(), args.as_slice()) {
                    ("TOFFON", [d]) => ToffOp::On { dir: dir(d)?, value: None },
                    ("TOFFON", [d, v]) => ToffOp::On { dir: dir(d)?, value: Some(value(v)?) },
                    ("TOFFOF", []) => ToffOp::Off { dir: None },
                    ("TOFFOF", [d]) => ToffOp::Off { dir: Some(dir(d)?) },
                    _ => {
                        return Err(Alarm::syntax(
                            line,
                            &format!(
                                "{name} takes a tool direction (X, Y, Z){}",
                                if name == "TOFFON" { " and an offset" } else { "" }
                            ),
                        ));
                    }
                });
            }
            Word::Keyword { name, args } if name == "TCA" => {
                w.tool_name = Some(super::tools::management::tca(args, &Ctx { vars, sys }, line)?);
            }
            Word::Keyword { name, args } if name == "DELOBJ" => {
                w.data_writes.push(super::calls::delobj::statement(args, &Ctx { vars, sys }, line)?);
            }
            Word::Keyword { name, args } if name == "SETMS" => {
                let spindle = match args.as_slice() {
                    [] => None,
                    [e] => {
                        Some(eval(e, &Ctx { vars, sys }, line)?.as_f64().map_err(|e| Alarm::type_error(line, &e.0))?)
                    }
                    _ => return Err(Alarm::syntax(line, "SETMS takes one spindle number")),
                };
                if spindle.is_some_and(|n| !(1.0..=32.0).contains(&n) || n.fract() != 0.0) {
                    return Err(Alarm::value_out_of_range(line, &format!("SETMS({})", spindle.unwrap_or_default())));
                }
                w.set_master = Some(spindle.map(|n| n as u32));
            }
            Word::Keyword { name, args } if super::spindles::is_diameter_axis_keyword(name) => {
                super::spindles::diameter_axis_word(&mut w.spindle, name, args, &Ctx { vars, sys }, cfg, line)?;
            }
            Word::Keyword { name, args } if name == "SPCON" || name == "SPCOF" => {
                let switch = super::spindles::position_control::statement(name, args, &Ctx { vars, sys }, line)?;
                if w.spindle.position_control.replace(switch).is_some() {
                    return Err(Alarm::syntax(line, "one SPCON/SPCOF per block"));
                }
            }
            Word::Keyword { name, args } if name == "SCC" => {
                w.spindle.css_axis = Some(super::spindles::css_axis_word(args, cfg, line)?);
            }
            Word::Keyword { name, args } if name == "FPR" => {
                w.spindle.fpr = Some(super::spindles::fpr_statement(args, &Ctx { vars, sys }, cfg, line)?);
            }
            Word::Keyword { name, args } if super::synchronized::channel_coordination::is_keyword(name) => {
                super::synchronized::channel_coordination::statement(name, args, cfg, &Ctx { vars, sys }, line)?;
            }
            Word::Keyword { name, args } if name == "WAITM" || name == "WAITMC" => {
                super::synchronized::wait_markers::statement(name, args, &Ctx { vars, sys }, line)?;
            }
            Word::Keyword { name, args } if args.is_empty() && (name == "WALIMON" || name == "WALIMOF") => {
                w.walimof = Some(name == "WALIMOF");
            }
            Word::Keyword { name, args } if args.is_empty() && (name == "RTLION" || name == "RTLIOF") => {
                w.rtliof = Some(name == "RTLIOF");
            }
            Word::Keyword { name, args } if name == "GETSELT" => {
                // GETSELT(VAR INT tool[, spindle]): the tool selected for the (master) spindle
                // and not yet changed in, `$P_TOOLP`, written into the variable.
                let (target, indices) = match args.first() {
                    Some(Expr::Var { name, indices }) => (name.as_str(), indices.as_slice()),
                    Some(Expr::RParam(i)) => ("R", std::slice::from_ref(&**i)),
                    _ => return Err(Alarm::syntax(line, "GETSELT needs a variable for the tool number")),
                };
                let tool = Expr::Number(f64::from(sys.offsets.prepared));
                if assign(target, indices, &tool, cfg, vars, sys, line)? != Assigned::Variable {
                    return Err(Alarm::syntax(line, "GETSELT needs a variable for the tool number"));
                }
            }
            // CLEARM(n, ..) in a block deletes wait markers of channel coordination (WAITM);
            // with one channel no marker waits for another, so nothing is left to delete.
            Word::Keyword { name, .. } if name == "CLEARM" => {}
            Word::Keyword { name, args } if name == "FGROUP" => {
                w.feed_group.axes = Some(super::path_control::feed_group::axes(args, cfg, line)?);
            }
            Word::Address { name, indices, value }
                if super::tools::programmable_offset::is_word(name) && vars.get(name).is_none() =>
            {
                let ctx = Ctx { vars, sys };
                let slot = super::tools::programmable_offset::slot(name, indices, cfg, &ctx, line)?;
                let v = eval_f64(&value.expr, &ctx, line)? * sys.modal.length_factor();
                w.tool_offsets.push((slot, v));
            }
            Word::Address { name, indices, value }
                if name == "FGREF"
                    && let [Expr::Var { name: axis, indices: none }] = indices.as_slice()
                    && none.is_empty()
                    && vars.get(name).is_none() =>
            {
                let k = cfg.program_axis(axis).ok_or_else(|| Alarm::unknown_name(line, &format!("FGREF[{axis}]")))?;
                let r = eval_f64(&value.expr, &Ctx { vars, sys }, line)? * sys.modal.length_factor();
                w.feed_group.fgref.push(super::path_control::feed_group::fgref(cfg, k, r, line)?);
            }
            Word::Keyword { name, args } if name == "PRESETON" => {
                w.presets.extend(super::frames::preset::preset_pairs(args, vars, sys, line)?);
            }
            Word::Keyword { name, args } if name == "WAITP" => {
                w.waitp |= super::path_control::positioning::waitp(args, vars, sys, line)?;
            }
            Word::Address { name, indices, value }
                if indices.len() == 1
                    && super::path_control::positioning::is_word(name)
                    && vars.get(name).is_none() =>
            {
                let (index, mode) = (&indices[0], value.mode);
                super::path_control::positioning::word(
                    &mut w.positioning,
                    name,
                    index,
                    &value.expr,
                    mode,
                    vars,
                    sys,
                    line,
                )?;
            }
            Word::Address { name, indices, value }
                if indices.len() == 1
                    && super::path_control::oscillation::is_word(name)
                    && vars.get(name).is_none() =>
            {
                super::path_control::oscillation::word(
                    &mut w.oscillation,
                    name,
                    &indices[0],
                    &value.expr,
                    vars,
                    sys,
                    line,
                )?;
            }
            Word::Keyword { name, args } if name == "SETPIECE" => {
                w.set_piece = Some(super::tools::setpiece::statement(args, &Ctx { vars, sys }, line)?);
            }
            Word::Keyword { name, args } if name == "CALL" => {
                let program = match args.first() {
                    Some(e) if !targets::is_omitted(e) => {
                        Some(targets::program_of_path(&eval(e, &Ctx { vars, sys }, line)?.as_text()))
                    }
                    Some(_) => None,
                    None => return Err(Alarm::syntax(line, "CALL needs a program name or BLOCK")),
                };
                match (program, &args[1..]) {
                    (Some(program), []) => set_call(w, program, Vec::new(), line)?,
                    (program, [Expr::Str(start), Expr::Str(end)]) => {
                        let target = |t: &str| match t.strip_prefix('N').and_then(|n| n.parse().ok()) {
                            Some(n) => JumpTarget::BlockNumber(n),
                            None => JumpTarget::Label(t.to_string()),
                        };
                        w.section_call = Some(Box::new((program, target(start), target(end))));
                    }
                    _ => return Err(Alarm::syntax(line, "CALL needs a program name or BLOCK")),
                }
            }
            Word::Keyword { name, .. } if super::transform::selection::is_keyword(name) => {}
            Word::Keyword { name, .. } => return Err(Alarm::unknown_name(line, name)),
            Word::Address { name, indices, value }
                if !indices.is_empty()
                    && let Some(which) = super::dynamics::Percent::of(name)
                    && vars.get(name).is_none() =>
            {
                w.dynamics.percent(which, indices, &value.expr, cfg, vars, sys, line)?;
            }
            Word::Address { name, indices, value }
                if name == "PO"
                    && let Some(axis) = po_axis(indices, cfg) =>
            {
                // POLY: PO[axis]=(end, a2, a3, a4, a5); the end is the axis word of the block.
                // (PO[PHI], PO[XH].. are the orientation polynomials, handled by `assign`.)
                let ctx = Ctx { vars, sys };
                let list = match &value.expr {
                    Expr::Call(n, args) if n == crate::lang::COEFFICIENTS => {
                        args.iter().map(|e| eval_f64(e, &ctx, line)).collect::<Result<Vec<_>, _>>()?
                    }
                    e => vec![eval_f64(e, &ctx, line)?],
                };
                if list.is_empty() || list.len() > 5 || w.axes.iter().any(|a| a.0 == axis) {
                    return Err(Alarm::syntax(line, "PO[axis]=(end, a2, a3, a4, a5) once per axis"));
                }
                let mut a = [0.0; 4];
                a[..list.len() - 1].copy_from_slice(&list[1..]);
                w.axes.push((axis, list[0], None));
                w.spline.po.push((axis, a));
            }
            Word::Address { name, indices, value } => {
                let axis = match assign(name, indices, &value.expr, cfg, vars, sys, line)? {
                    Assigned::Variable => continue,
                    Assigned::Data(text) => {
                        w.data_writes.push(text);
                        continue;
                    }
                    Assigned::ChainFrame(which, f) => {
                        w.frame_writes.push((which, *f));
                        continue;
                    }
                    Assigned::OnlineToolOffset(op) => {
                        w.toff.push(op);
                        continue;
                    }
                    Assigned::PlcData(at, bytes) => {
                        w.plc_writes.push((at, bytes));
                        continue;
                    }
                    Assigned::DigitalOutput(signal, on) => {
                        w.digital_outputs.push((signal, on));
                        continue;
                    }
                    Assigned::MainRun(write) => {
                        w.main_run_writes.push(write);
                        continue;
                    }
                    Assigned::Address(axis) => axis,
                };
                if name == "T"
                    && let Some(named) = super::tools::management::named_t(&value.expr, &Ctx { vars, sys }, line)?
                {
                    if !seen.insert(name) {
                        return Err(Alarm::repeated_address(line, name));
                    }
                    w.tool_name = Some(named);
                    continue;
                }
                if name == "FAD" {
                    if !seen.insert(name) {
                        return Err(Alarm::repeated_address(line, name));
                    }
                    let (e, per_rev) = super::compensation::sar::SarWords::fad_form(&value.expr);
                    w.sar.fad = Some((eval_f64(e, &Ctx { vars, sys }, line)?, per_rev));
                    continue;
                }
                if name == "TCARR" {
                    if !seen.insert(name) {
                        return Err(Alarm::repeated_address(line, name));
                    }
                    w.tcarr = Some(eval(&value.expr, &Ctx { vars, sys }, line)?);
                    continue;
                }
                let v = eval_f64(&value.expr, &Ctx { vars, sys }, line)?;
                let whole = |what: &str| -> Result<u32, Alarm> {
                    if v < 0.0 || v.fract() != 0.0 || v > u32::MAX as f64 {
                        Err(Alarm::value_out_of_range(line, &format!("{what}{v}")))
                    } else {
                        Ok(v as u32)
                    }
                };
                // `M=3`, `M=R1`: an M function by expression, as `M3` (several per block).
                if &**name == "M" {
                    let code = whole("M=")?;
                    m_function(w, code, line)?;
                    w.tool_change |= code == cfg.tool_change.m_code;
                    continue;
                }
                // AX[...] words are told apart by the axis they name (below), not by "AX".
                if &**name != "AX" && !seen.insert(name) {
                    return Err(Alarm::repeated_address(line, name));
                }
                let index = match indices.first() {
                    Some(e) if super::spindles::words::indexed(name) => Some(eval_f64(e, &Ctx { vars, sys }, line)?),
                    _ => None,
                };
                match &**name {
                    _ if super::spindles::words::address(&mut w.spindle, name, index, v, value.mode, line)? => {}
                    _ if super::measuring::address(&mut w.measure, name, v, line)? => {}
                    "F" => w.feed = Some(v),
                    "S" => w.speed = Some(v),
                    "T" => w.tool = Some(whole("T")?),
                    "D" => w.edge = Some(whole("D")?),
                    "CR" => w.cr = Some(v),
                    "RPL" => w.rpl = Some(v),
                    "OFFN" => w.offn = Some(v * sys.modal.length_factor()),
                    "DISC" => w.disc = Some(v),
                    "RND" => w.corner = Some(Corner::Round(v * sys.modal.length_factor())),
                    "RNDM" => w.rndm = Some(v * sys.modal.length_factor()),
                    "FRC" => w.frc = Some(v),
                    "ANG" => w.ang = Some(v),
                    "FRCM" => w.frcm = Some(v),
                    "CHF" => w.corner = Some(Corner::Chamfer(v * sys.modal.length_factor())),
                    "CHR" => w.corner = Some(Corner::ChamferLeg(v * sys.modal.length_factor())),
                    "AP" => w.ap = Some(v),
                    "RP" => w.rp = Some(v),
                    "AR" => w.ar = Some(v),
                    "TURN" => w.turn = Some(whole("TURN=")?),
                    // H: auxiliary function for the PLC.
                    "H" => w.aux.push(super::auxiliary::AuxFunction { letter: 'H', extension: 0, value: v }),
                    _ if w.path.address(name, v, line)? => {}
                    _ if w.sar.address(name, v, value.mode, sys.modal.length_factor(), line)? => {}
                    _ if w.spline.address(name, v, line)? => {}
                    "STAT" => w.stat = Some(whole("STAT=")?),
                    "TU" => w.tu = Some(whole("TU=")?),
                    "FP" => w.fixed_point_number = Some(whole("FP=")?),
                    _ if super::everyday::retraction_address(name, v, line)? => {}
                    // `P3`: three runs of the block's subprogram call.
                    "P" => w.repeat = Some(whole("P")?),
                    _ if super::everyday::extended_address(name).is_some() => {
                        let Some((letter, ext)) = super::everyday::extended_address(name) else { continue };
                        let function =
                            super::auxiliary::AuxFunction { letter: letter as char, extension: ext, value: v };
                        w.aux.push(function);
                        if letter == b'M'
                            && !super::spindles::words::extended_m(&mut w.spindle, ext, v)
                            && let Some(dir) = super::everyday::extended_m(ext, v, line)?
                        {
                            if w.spindle_dir.is_some() {
                                return Err(Alarm::conflicting_functions(line, "M3/M4/M5"));
                            }
                            (w.spindle_dir, w.spindle_ext) = (Some(dir), Some(ext));
                        }
                    }
                    "THETA" => w.ori.theta = Some((v, value.mode == Some(CoordMode::Ic))),
                    _ if words::is_address(name) => {
                        w.ori.address(name, v);
                    }
                    "I" | "J" | "K" => {
                        let g = (name.as_bytes()[0] - b'I') as usize;
                        w.ijk[g] = Some((v, value.mode == Some(CoordMode::Ac)));
                    }
                    "I1" | "J1" | "K1" => {
                        let g = (name.as_bytes()[0] - b'I') as usize;
                        w.ijk1[g] = Some((v, value.mode));
                    }
                    _ => {
                        let k = axis.ok_or_else(|| Alarm::unknown_name(line, name))?;
                        if cfg.axis(k).spindle.is_some() && !sys.positioned[k] {
                            return Err(Alarm::unknown_name(
                                line,
                                &format!("{name} (spindle positioning comes with SPOS)"),
                            ));
                        }
                        if &**name == "AX" && w.axes.iter().any(|a| a.0 == k) {
                            return Err(Alarm::repeated_address(line, cfg.program_axis_name(k)));
                        }
                        w.axes.push((k, v, value.mode));
                    }
                }
            }
        }
    }
    Ok(())
}

/// Performs `name[indices] = expr` if `name` is an R parameter or a variable; returns false
/// for addresses (axes, F, S, ...), which the caller handles.
/// The addresses of a block seen so far (each may appear once): the first few on the stack,
/// so a plain block allocates nothing for the check.
#[derive(Default)]
struct Seen<'a> {
    first: [&'a str; 8],
    len: usize,
    more: Vec<&'a str>,
}

impl<'a> Seen<'a> {
    /// Notes `name`; false if it was seen before.
    fn insert(&mut self, name: &'a str) -> bool {
        // Mostly one-letter names from the parser's static table: a differing first byte or
        // length settles nearly every comparison without a call to `memcmp`.
        let same = |seen: &&str| {
            seen.len() == name.len()
                && seen.as_bytes().first() == name.as_bytes().first()
                && (seen.as_ptr() == name.as_ptr() || *seen == name)
        };
        if self.first[..self.len].iter().any(same) || self.more.iter().any(same) {
            return false;
        }
        if self.len < self.first.len() {
            self.first[self.len] = name;
            self.len += 1;
        } else {
            self.more.push(name);
        }
        true
    }
}

/// What an assignment-shaped word turned out to be.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Assigned {
    /// A variable or R parameter was written.
    Variable,
    /// An NC address (axis, F, S, ...): the caller handles it. Carries the channel axis the
    /// name resolves to, if any, so the caller need not look it up a second time.
    Address(Option<usize>),
    /// Tool data, frame data or machine data, as NC data text.
    Data(String),
    /// A new value of a link of the frame chain (`$P_PFRAME=...`, `$P_SETFRAME=...`).
    ChainFrame(ChainFrame, Box<Frame>),
    /// `$AA_TOFF[dir] = value`: the online tool length offset.
    OnlineToolOffset(super::compensation::toff::ToffOp),
    /// `$A_OUT[n] = value`: digital output n set (true) or cleared.
    DigitalOutput(usize, bool),
    /// `$A_DBB[n] = value` ..: the bytes written into the PLC data area at an offset.
    PlcData(usize, Vec<u8>),
    /// `$AC_MARKER[n] = value`, a workpiece counter ..: done in the main run.
    MainRun(super::synchronized::MainRunWrite),
}

pub(super) fn assign(
    name: &str,
    indices: &[Expr],
    expr: &Expr,
    cfg: &MachineConfig,
    vars: &mut Variables,
    sys: &SysView,
    line: u32,
) -> Result<Assigned, Alarm> {
    let r_index = match name {
        "R" | "$R" if indices.len() == 1 => {
            Some(eval(&indices[0], &Ctx { vars, sys }, line)?.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?)
        }
        _ if indices.is_empty() => name.strip_prefix('R').and_then(|n| n.parse::<i64>().ok()),
        _ => None,
    };
    if let Some(n) = r_index {
        let v = eval_f64(expr, &Ctx { vars, sys }, line)?;
        let slot = usize::try_from(n)
            .ok()
            .and_then(|i| vars.r.get_mut(i))
            .ok_or_else(|| Alarm::unknown_name(line, &format!("R{n}")))?;
        *slot = v;
        return Ok(Assigned::Variable);
    }
    if name == "$AA_TOFF" {
        let dir = match indices {
            [i] => {
                let v = eval(i, &Ctx { vars, sys }, line)?;
                super::compensation::toff::direction(cfg, &v.as_text().to_ascii_uppercase(), line)?
            }
            _ => return Err(Alarm::index_error(line, name, "needs one tool direction X, Y or Z")),
        };
        let value = eval_f64(expr, &Ctx { vars, sys }, line)?;
        return Ok(Assigned::OnlineToolOffset(super::compensation::toff::ToffOp::Write { dir, value }));
    }
    if name == "PO"
        && let Some(alarm) = super::orientation::poly::refused(indices, sys.trafo.tool_vectors().is_some(), line)
    {
        return Err(alarm);
    }
    if let Some(which) = ChainFrame::of(name).filter(|w| w.writable()) {
        return chain_frame(which, name, indices, expr, vars, sys, line)
            .map(|f| Assigned::ChainFrame(which, Box::new(f)));
    }
    if super::io::is_io_name(name) {
        let ctx = Ctx { vars, sys };
        let idx = indices.iter().map(|e| eval(e, &ctx, line)).collect::<Result<Vec<_>, _>>()?;
        if name == "$A_IN" || name == "$A_INA" {
            return Err(Alarm::write_protected(line, name));
        }
        if name == "$A_OUTA" {
            // Analog outputs are written by synchronized actions only in NCTwin.
            return Err(Alarm::unknown_name(line, name));
        }
        let signal = super::io::signal(name, &idx, sys.io.counts().1, line)?;
        return Ok(Assigned::DigitalOutput(signal, super::io::level(&eval(expr, &ctx, line)?, line)?));
    }
    if super::io::plc_data::is_name(name) {
        let ctx = Ctx { vars, sys };
        let idx = indices.iter().map(|e| eval(e, &ctx, line)).collect::<Result<Vec<_>, _>>()?;
        let (at, bytes) = super::io::plc_data::write(name, &idx, &eval(expr, &ctx, line)?, line)?;
        return Ok(Assigned::PlcData(at, bytes));
    }
    if name.starts_with('$') {
        if let Some(write) = super::synchronized::program_write(name, indices, expr, cfg, &Ctx { vars, sys }, line)? {
            return Ok(Assigned::MainRun(write));
        }
        return data_write(name, indices, expr, vars, sys, line).map(Assigned::Data);
    }
    if name == "AX" && indices.len() == 1 && vars.get(name).is_none() {
        return super::eval::indirect_axis::resolve(&indices[0], vars, sys, line).map(|k| Assigned::Address(Some(k)));
    }
    if vars.get(name).is_none() {
        let axis = cfg.program_axis(name);
        let extended = || super::everyday::extended_address(name).is_some();
        if !indices.is_empty() && !super::spindles::words::indexed(name)
            || axis.is_none() && !is_nc_address(name) && !extended()
        {
            return Err(Alarm::unknown_name(line, name));
        }
        return Ok(Assigned::Address(axis));
    }
    let ctx = Ctx { vars, sys };
    let idx = indices
        .iter()
        .map(|e| eval(e, &ctx, line)?.as_i64().map_err(|e| Alarm::type_error(line, &e.0)))
        .collect::<Result<Vec<_>, _>>()?;
    if let Some(list) = List::of_expr(expr).filter(|_| !indices.is_empty()) {
        // The values are worked out before the array changes: `A[0]=SET(A[1], A[0])` swaps.
        let mut var = vars.get(name).expect("checked above").clone();
        let start = var.index(&idx).map_err(|e| Alarm::index_error(line, name, &e.0))?;
        list.write(&mut var, start, name, line, |e| eval(e, &Ctx { vars, sys }, line))?;
        *vars.get_mut(name).expect("checked above") = var;
        return Ok(Assigned::Variable);
    }
    let value = eval(expr, &ctx, line)?;
    let var = vars.get_mut(name).expect("checked above");
    let i = var.index(&idx).map_err(|e| Alarm::index_error(line, name, &e.0))?;
    var.data[i] = value.convert(var.ty).map_err(|e| Alarm::type_error(line, &e.0))?;
    Ok(Assigned::Variable)
}

/// `$P_PFRAME = <frame>` or `$P_PFRAME[axis, TR] = <value>` (the same for the other writable
/// links of the chain): the link's new value.
fn chain_frame(
    which: ChainFrame,
    name: &str,
    indices: &[Expr],
    expr: &Expr,
    vars: &Variables,
    sys: &SysView,
    line: u32,
) -> Result<Frame, Alarm> {
    let ctx = Ctx { vars, sys };
    match indices {
        [] => match eval(expr, &ctx, line)? {
            Value::Frame(f) => Ok(*f),
            other => Err(Alarm::type_error(line, &format!("{name} needs a frame, not {other:?}"))),
        },
        [Expr::Var { name: axis, .. }, Expr::Var { name: component, .. }] if component == "TR" || component == "FI" => {
            let k = sys.cfg.program_axis(axis).ok_or_else(|| Alarm::unknown_name(line, axis))?;
            let mut f = sys.chain_frame(which);
            f.trans[k] = eval_f64(expr, &ctx, line)?;
            Ok(f)
        }
        _ => Err(Alarm::index_error(line, name, "components other than [axis, TR] are set with CROT/CSCALE/CMIRROR")),
    }
}

/// `$P_UIFR[n] = <frame>` (or `$P_CHBFR[n]`) as NC data text: every component of every axis,
/// so the stored frame is replaced as a whole. A frame whose linear part is not a rotation with
/// scale and mirror cannot be stored and is refused.
fn stored_frame_lines(
    var: &str,
    index: &Expr,
    expr: &Expr,
    ctx: &Ctx,
    sys: &SysView,
    line: u32,
) -> Result<String, Alarm> {
    let n = eval(index, ctx, line)?.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
    let Value::Frame(f) = eval(expr, ctx, line)? else {
        return Err(Alarm::type_error(line, &format!("{var}[n] needs a frame")));
    };
    let cfg = sys.cfg;
    let count = cfg.channel_axes.len();
    let data = f
        .to_data(&cfg.geo_axes, count, cfg.frame_angles)
        .ok_or_else(|| Alarm::value_out_of_range(line, &format!("{var}[{n}]: the frame's rotation part is sheared")))?;
    let mut lines = Vec::new();
    for k in 0..count {
        let axis = cfg.program_axis_name(k);
        lines.push(format!("{var}[{n},{axis},TR]={:?}", data.trans[k]));
        lines.push(format!("{var}[{n},{axis},FI]=0.0"));
        lines.push(format!("{var}[{n},{axis},SC]={:?}", data.scale[k]));
        lines.push(format!("{var}[{n},{axis},MI]={}", u8::from(data.mirror[k])));
        if let Some(g) = cfg.geo_axes.iter().position(|a| *a == Some(k)) {
            lines.push(format!("{var}[{n},{axis},RT]={:?}", data.rot[g]));
        }
    }
    Ok(lines.join("\n"))
}

/// A write to tool data (`$TC_DP..`), settable frames (`$P_UIFR`), kinematic chain data
/// (`$NK_..`, `$NT_..`) or machine and setting data (`$MC_..`, `$MA_..`, ...) as one line of NC
/// data text. Bare names among the indices
/// (`$P_UIFR[1,X,TR]`) are taken literally.
fn data_write(
    name: &str,
    indices: &[Expr],
    expr: &Expr,
    vars: &Variables,
    sys: &SysView,
    line: u32,
) -> Result<String, Alarm> {
    if super::eval::nc_constants::is_constant(name) {
        return Err(Alarm::write_protected(line, name));
    }
    let writable = name.starts_with("$TC_DP")
        || crate::machine_data::tools_mgmt::ToolMgmtData::handles(name)
        || name.starts_with("$TC_CARR")
        || crate::machine_data::chains::is_chain_name(name)
        || matches!(name, "$P_UIFR" | "$P_CHBFR" | "$P_NCBFR" | "$P_UBFR")
        || ["$MN_", "$MC_", "$MA_", "$SN_", "$SC_", "$SA_"].iter().any(|p| name.starts_with(p));
    if !writable || name == "$NT_ROT_AX_CNT" {
        return Err(Alarm::unknown_name(line, &format!("{name} (not writable from a program)")));
    }
    let ctx = Ctx { vars, sys };
    if matches!(name, "$P_UIFR" | "$P_CHBFR" | "$P_NCBFR") && indices.len() == 1 {
        return stored_frame_lines(name, &indices[0], expr, &ctx, sys, line);
    }
    if name == "$P_UBFR" && indices.is_empty() {
        return stored_frame_lines("$P_CHBFR", &Expr::Number(0.0), expr, &ctx, sys, line);
    }
    let mut idx = Vec::new();
    for e in indices {
        idx.push(match e {
            Expr::Var { name, indices } if indices.is_empty() && vars.get(name).is_none() => name.clone(),
            e => match eval(e, &ctx, line)? {
                Value::Axis(a) | Value::Str(a) => a,
                v => v.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?.to_string(),
            },
        });
    }
    if super::eval::machine_data::is_data_name(name)
        && let Some(axis) = idx.pop()
    {
        idx.push(super::eval::machine_data::axis_index_for_text(sys.stored, sys.cfg, name, axis));
    }
    let value = match eval(expr, &ctx, line)? {
        Value::Bool(b) => if b { "TRUE" } else { "FALSE" }.to_string(),
        Value::Str(s) => format!("\"{s}\""),
        Value::Axis(a) => a,
        v => format!("{:?}", v.as_f64().map_err(|e| Alarm::type_error(line, &e.0))?),
    };
    if name == "$TC_CARR23" && !matches!(value.trim_matches('"').to_ascii_uppercase().as_str(), "T" | "P" | "M") {
        return Err(super::tools::swivel::invalid_kind(line, &value));
    }
    let index = if idx.is_empty() { String::new() } else { format!("[{}]", idx.join(",")) };
    Ok(format!("{name}{index}={value}"))
}

/// Addresses with a fixed meaning in a block.
fn is_nc_address(name: &str) -> bool {
    // A `match` compares by length first: no string comparison for most names.
    matches!(
        name,
        "F" | "S"
            | "M"
            | "T"
            | "D"
            | "CR"
            | "H"
            | "I"
            | "J"
            | "K"
            | "I1"
            | "J1"
            | "K1"
            | "L"
            | "P"
            | "RPL"
            | "AP"
            | "RP"
            | "AR"
            | "TURN"
            | "RND"
            | "RNDM"
            | "FRC"
            | "FRCM"
            | "ANG"
            | "CHF"
            | "CHR"
            | "STAT"
            | "TU"
            | "FP"
            | "ALF"
            | "DILF"
            | "OFFN"
            | "DISC"
            | "TCARR"
            | "THETA"
    ) || words::is_address(name)
        || super::spindles::words::is_address(name)
        || super::measuring::is_address(name)
        || super::path_control::is_address(name)
        || super::compensation::sar::is_address(name)
        || super::path_control::spline::is_address(name)
}

/// The keywords of G groups 22, 42, 52 and 53; false for any other word.
fn holder_keyword(w: &mut Words, name: &str, line: u32) -> Result<bool, Alarm> {
    let set = |slot: bool| {
        if slot {
            Err(Alarm::syntax(line, &format!("{name}: two G functions of one group in a block")))
        } else {
            Ok(true)
        }
    };
    if let Some(code) = g53_code(name) {
        set(w.g53_group.is_some())?;
        w.g53_group = Some(code);
        return Ok(true);
    }
    let tco = match name {
        "TCOABS" => Some(TcoMode::Abs),
        "TCOFR" | "TCOFRZ" => Some(TcoMode::Frame(2)),
        "TCOFRY" => Some(TcoMode::Frame(1)),
        "TCOFRX" => Some(TcoMode::Frame(0)),
        _ => None,
    };
    if let Some(t) = tco {
        set(w.tco.is_some())?;
        w.tco = Some(t);
        return Ok(true);
    }
    let cut = match name {
        "CUT2D" => Some(CutMode::Cut2d),
        "CUT2DF" => Some(CutMode::Cut2dF),
        "CUT3DFS" => Some(CutMode::Cut3dFs),
        "CUT3DFF" => Some(CutMode::Cut3dFf),
        _ => None,
    };
    if let Some(c) = cut {
        set(w.cut.is_some())?;
        w.cut = Some(c);
        return Ok(true);
    }
    match name {
        "PAROT" | "PAROTOF" => {
            set(w.parot.is_some())?;
            w.parot = Some(name == "PAROT");
            Ok(true)
        }
        _ => Ok(false),
    }
}

fn g_function(w: &mut Words, code: u32, line: u32) -> Result<(), Alarm> {
    match code {
        0 => w.motion = Some(MotionMode::Rapid),
        1 => w.motion = Some(MotionMode::Linear),
        2 => w.motion = Some(MotionMode::Cw),
        3 => w.motion = Some(MotionMode::Ccw),
        4 => w.dwell = true,
        74 => w.fixed_point = Some(super::path_control::fixed_point::Approach::Reference),
        75 => w.fixed_point = Some(super::path_control::fixed_point::Approach::FixedPoint),
        9 => w.g9 = true,
        5 => w.oblique = Some(Oblique::Plunge),
        7 => w.oblique = Some(Oblique::Approach),
        17 => w.plane = Some(Plane::G17),
        18 => w.plane = Some(Plane::G18),
        19 => w.plane = Some(Plane::G19),
        // G53 suppresses the settable and programmable frames for the block (and the system
        // frames above the basic frame); G153 also the basic frames (see `frame_vars.rs`).
        53 => w.suppress = Some(Suppress::G53),
        153 => w.suppress = Some(Suppress::All),
        40 => w.trc = Some(None),
        41 => w.trc = Some(Some(Side::Left)),
        42 => w.trc = Some(Some(Side::Right)),
        450 => w.trc_corners = Some(CornerMode::Circle),
        451 => w.trc_corners = Some(CornerMode::Intersection),
        54..=57 => w.work_offset = Some(code as usize - 53),
        500 => w.work_offset = Some(0),
        505..=599 => w.work_offset = Some(code as usize - 500),
        110 => w.pole = Some(PoleRef::LastPosition),
        111 => w.pole = Some(PoleRef::WorkpieceZero),
        112 => w.pole = Some(PoleRef::LastPole),
        60 => w.exact_stop = Some(true),
        70 => w.units = Some((true, false)),
        71 => w.units = Some((false, false)),
        700 => w.units = Some((true, true)),
        710 => w.units = Some((false, true)),
        90 => w.absolute = Some(true),
        91 => w.absolute = Some(false),
        94 => w.feed_per_rev = Some(false),
        95 => w.feed_per_rev = Some(true),
        _ if super::spindles::words::g_code(&mut w.spindle, code, line)? => {}
        _ if w.path.g_function(code, &mut w.exact_stop) => {}
        _ if w.sar.g_function(code, line)? => {}
        _ => return Err(Alarm::unknown_g(line, code)),
    }
    Ok(())
}

/// The channel axis `PO[axis]` names, if it names one.
fn po_axis(indices: &[Expr], cfg: &MachineConfig) -> Option<usize> {
    match indices {
        [Expr::Var { name, indices }] if indices.is_empty() => cfg.program_axis(name),
        _ => None,
    }
}

/// The block's subprogram call (one per block).
fn set_call(w: &mut Words, name: String, args: Vec<Expr>, line: u32) -> Result<(), Alarm> {
    if w.call.is_some() {
        return Err(Alarm::syntax(line, "one subprogram call per block"));
    }
    w.call = Some((name, args));
    Ok(())
}

fn m_function(w: &mut Words, code: u32, line: u32) -> Result<(), Alarm> {
    w.aux.push(super::auxiliary::AuxFunction { letter: 'M', extension: 0, value: f64::from(code) });
    let stop = match code {
        0 => Some(StopKind::M0),
        1 => Some(StopKind::M1),
        2 | 17 | 30 => Some(StopKind::End),
        _ => None,
    };
    if let Some(kind) = stop {
        if w.stop.is_some() {
            return Err(Alarm::conflicting_functions(line, "M0/M1/M2/M17/M30"));
        }
        w.stop = Some(kind);
    }
    let dir = match code {
        3 => Some(1),
        4 => Some(-1),
        5 => Some(0),
        _ => None,
    };
    if let Some(d) = dir {
        if w.spindle_dir.is_some() {
            return Err(Alarm::conflicting_functions(line, "M3/M4/M5"));
        }
        w.spindle_dir = Some(d);
    }
    super::spindles::words::m_code(&mut w.spindle, code);
    // Other M functions go to the PLC and need no NC reaction here.
    Ok(())
}

#[cfg(test)]
mod seen_tests {
    use super::Seen;

    #[test]
    fn a_name_is_seen_once_on_the_stack_and_beyond() {
        let names = ["X", "Y", "Z", "F", "S", "T", "D", "I", "J", "K", "CR"];
        let mut seen = Seen::default();
        for n in names {
            assert!(seen.insert(n), "{n} is new");
        }
        // "X" sits in the fixed part, "K" and "CR" (9th and 11th) in the overflow.
        for n in ["X", "K", "CR"] {
            assert!(!seen.insert(n), "{n} is repeated");
        }
        assert!(seen.insert("A"));
    }
}

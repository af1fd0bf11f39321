//! The active G functions of a block in a compact form that travels with the block to the
//! main run, so the display shows the G codes of the block being executed rather than of the
//! block being prepared.

use super::compensation::approach::ApproachMode;
use super::compensation::trc::{ArcFeed, CornerMode, Side};
use super::modal::{CircleForm, Modal, MotionMode, Plane, PtpMode};
use super::orientation::rotation::RotReference;
use super::orientation::words::{AngleDefinition, OriInterpolation, OriReference};

/// One entry per displayed G group: the index of the active function in that group's list;
/// then G group 12 (G601/G602/G603, [`WINDOW_SLOT`]), which the main run's exact stop reads
/// but the display does not list.
#[derive(Debug, Clone, Copy, Eq, Default)]
pub struct GCodes([u8; GROUPS.len() + 1]);

/// Compared once or twice per block: the first 16 groups as one 128-bit number, the rest
/// byte by byte.
impl PartialEq for GCodes {
    fn eq(&self, other: &GCodes) -> bool {
        let wide = |g: &GCodes| u128::from_ne_bytes(g.0[..16].try_into().expect("16 groups"));
        wide(self) == wide(other) && self.0[16..] == other.0[16..]
    }
}

/// The displayed groups in Operate's order: (group number, names by index). Group 8 (settable
/// frame) is named from its number instead.
const GROUPS: [(u8, &[&str]); 20] = [
    (1, &["G0", "G1", "G2", "G3", "CIP", "CT"]),
    (6, &["G17", "G18", "G19"]),
    (7, &["G40", "G41", "G42"]),
    (8, &[]),
    (10, &["G60", "G64", "G641", "G642", "G643", "G644", "G645"]),
    (13, &["G70", "G71", "G700", "G710"]),
    (14, &["G90", "G91"]),
    (15, &["G94", "G95", "G93", "G96", "G961", "G97", "G971"]),
    (16, &["CFC", "CFTCP", "CFIN"]),
    (17, &["NORM", "KONT", "KONTT", "KONTC"]),
    (18, &["G450", "G451"]),
    (25, &["ORIMKS", "ORIWKS"]),
    (49, &["CP", "PTP", "PTPG0", "PTPWOC"]),
    (50, &["ORIEULER", "ORIRPY", "ORIRPY2", "ORIVIRT1", "ORIVIRT2"]),
    (51, &["ORIVECT", "ORIAXES", "ORICONCW", "ORICONCCW", "ORIPATH", "ORICONIO", "ORICONTO", "ORICURVE", "ORIPATHS"]),
    (54, &["ORIROTA", "ORIROTR", "ORIROTT", "ORIROTC"]),
    (21, &["BRISK", "SOFT", "DRIVE"]),
    (24, &["FFWOF", "FFWON"]),
    (59, &["DYNNORM", "DYNPOS", "DYNROUGH", "DYNSEMIFIN", "DYNFINISH"]),
    (29, &["DIAMOF", "DIAMON", "DIAM90", "DIAMCYCOF"]),
];

/// Position of G group 29 (diameter programming) in [`GROUPS`].
const DIAMETER_SLOT: usize = 19;

/// Position of G group 12 (exact-stop window) after the displayed groups.
const WINDOW_SLOT: usize = GROUPS.len();

/// Position of G group 24 (feed-forward) in [`GROUPS`].
const FFW_SLOT: usize = 17;

impl GCodes {
    /// The G functions of the modal state `m`.
    pub fn of(m: &Modal) -> GCodes {
        let ori = &m.ori;
        GCodes([
            match (m.motion, m.circle_form) {
                (MotionMode::Rapid, _) => 0,
                (MotionMode::Linear, _) => 1,
                (MotionMode::Cw | MotionMode::Ccw, CircleForm::ThroughPoint) => 4,
                (MotionMode::Cw | MotionMode::Ccw, CircleForm::Tangent) => 5,
                (MotionMode::Cw, CircleForm::Standard) => 2,
                (MotionMode::Ccw, CircleForm::Standard) => 3,
            },
            match m.plane {
                Plane::G17 => 0,
                Plane::G18 => 1,
                Plane::G19 => 2,
            },
            match m.trc {
                None => 0,
                Some(Side::Left) => 1,
                Some(Side::Right) => 2,
            },
            u8::try_from(m.work_offset).unwrap_or(u8::MAX),
            if m.exact_stop { 0 } else { m.path.group10() as u8 - 1 },
            match (m.inch, m.inch_feed) {
                (true, false) => 0,
                (false, false) => 1,
                (true, true) => 2,
                (false, true) => 3,
            },
            u8::from(!m.absolute),
            if m.feed_type_index != 0 { m.feed_type_index } else { u8::from(m.feed_per_rev) },
            match m.arc_feed {
                ArcFeed::Contour => 0,
                ArcFeed::CentrePath => 1,
                ArcFeed::InnerOnly => 2,
            },
            match m.approach {
                ApproachMode::Norm => 0,
                ApproachMode::Kont => 1,
                ApproachMode::Tangent => 2,
                ApproachMode::Curvature => 3,
            },
            u8::from(m.trc_corners == CornerMode::Intersection),
            u8::from(ori.reference == OriReference::Workpiece),
            match m.ptp {
                PtpMode::Cp => 0,
                PtpMode::Ptp => 1,
                PtpMode::PtpG0 => 2,
                PtpMode::PtpWoc => 3,
            },
            match ori.angles {
                AngleDefinition::Euler => 0,
                AngleDefinition::Rpy => 1,
                AngleDefinition::Rpy2 => 2,
                AngleDefinition::Virtual1 => 3,
                AngleDefinition::Virtual2 => 4,
            },
            match ori.interpolation {
                OriInterpolation::Vector => 0,
                OriInterpolation::Axes => 1,
                OriInterpolation::Cone { clockwise: true } => 2,
                OriInterpolation::Cone { clockwise: false } => 3,
                OriInterpolation::Path => 4,
                OriInterpolation::ConeIntermediate => 5,
                OriInterpolation::ConeTangential => 6,
                OriInterpolation::Curve => 7,
                OriInterpolation::Unmodelled(_) => 8,
            },
            match ori.rotation {
                RotReference::Absolute => 0,
                RotReference::Plane => 1,
                RotReference::OriChange => 2,
                RotReference::PathTangent => 3,
            },
            m.dynamics.profile as u8,
            u8::from(m.dynamics.ffw),
            m.dynamics.mode as u8,
            m.diameter_slot,
            m.path.window as u8,
        ])
    }

    /// The exact-stop window of G group 12 (G601/G602/G603) of the block.
    pub fn stop_window(&self) -> super::path_control::StopWindow {
        use super::path_control::StopWindow;
        [StopWindow::Fine, StopWindow::Coarse, StopWindow::IpoEnd][usize::from(self.0[WINDOW_SLOT].min(2))]
    }

    /// FFWON (G group 24) is active in the block: the main run's servo model reads it.
    pub fn ffw_on(&self) -> bool {
        self.0[FFW_SLOT] == 1
    }

    /// Whether the WCS display shows the transverse axis as a diameter (G group 29).
    pub fn diameter_display(&self) -> bool {
        super::spindles::diameter::slot_shows_diameter(self.0[DIAMETER_SLOT])
    }

    /// The names of the active functions, one per displayed group (`G1`, `G17`, `G54`, ...).
    pub fn names(&self) -> Vec<String> {
        let mut names = Vec::new();
        self.write_names(&mut names);
        names
    }

    /// [`GCodes::names`] written over `names`, reusing its strings (the state display refreshes
    /// them many times a second).
    pub fn write_names(&self, names: &mut Vec<String>) {
        use std::fmt::Write as _;
        names.resize_with(GROUPS.len(), String::new);
        for (((group, list), i), name) in GROUPS.iter().zip(self.0).zip(names.iter_mut()) {
            name.clear();
            // Writing into a String cannot fail.
            let _ = match (group, i) {
                (8, 0) => name.write_str("G500"),
                (8, n @ 1..=4) => write!(name, "G{}", 53 + n),
                (8, n) => write!(name, "G{}", 500 + u32::from(n)),
                // The slot carries the display flag in bit 2.
                (29, i) => name.write_str(list.get(usize::from(i & 3)).copied().unwrap_or("?")),
                (_, i) => name.write_str(list.get(usize::from(i)).copied().unwrap_or("?")),
            };
        }
    }
}

//! Diameter programming of the transverse axis (Programming Manual "Fundamentals":
//! DIAMON, DIAMOF, DIAM90, DIAMCYCOF; G group 29).
//!
//! The transverse axis is the geometry axis MD20100 `$MC_DIAMETER_AX_DEF` names; its
//! programmed values are diameters while diameter programming is on: DIAMON for absolute and
//! incremental values, DIAM90 for absolute values only (G91 increments stay radii). DIAMCYCOF
//! switches diameter programming off for the cycles' own computations while the display keeps
//! showing the diameter when it did before. The group's reset value comes from MD20150
//! `$MC_GCODE_RESET_VALUES[28]`. Centre points (I, J, K) are radii in every mode.
//!
//! `$P_GG[29]` reads the position in the group: DIAMOF 1, DIAMON 2, DIAM90 3, DIAMCYCOF 4.

use crate::alarm::Alarm;
use crate::machine_data::MachineConfig;

/// G group 29.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DiamMode {
    /// Radius programming.
    #[default]
    Of,
    /// Diameter programming for absolute and incremental values.
    On,
    /// Diameter for absolute values (G90, AC), radius for increments (G91, IC).
    D90,
    /// Radius in the cycles' own blocks; the display as before.
    CycOf,
}

impl DiamMode {
    /// The position in G group 29 ($P_GG[29]; MD20150 value), from 1.
    pub fn position(self) -> u8 {
        match self {
            DiamMode::Of => 1,
            DiamMode::On => 2,
            DiamMode::D90 => 3,
            DiamMode::CycOf => 4,
        }
    }

    /// The mode at position `n` of the group (MD20150), if there is one.
    pub fn from_position(n: u8) -> Option<DiamMode> {
        Some(match n {
            1 => DiamMode::Of,
            2 => DiamMode::On,
            3 => DiamMode::D90,
            4 => DiamMode::CycOf,
            _ => return None,
        })
    }

    /// The keyword's mode, for the words of a block.
    pub fn of_keyword(name: &str) -> Option<DiamMode> {
        Some(match name {
            "DIAMOF" => DiamMode::Of,
            "DIAMON" => DiamMode::On,
            "DIAM90" => DiamMode::D90,
            "DIAMCYCOF" => DiamMode::CycOf,
            _ => return None,
        })
    }
}

/// The diameter programming state of preparation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Diameter {
    pub mode: DiamMode,
    /// The mode DIAMCYCOF replaced: what the display keeps showing.
    shown: DiamMode,
}

impl Diameter {
    /// The reset state of MD20150 `$MC_GCODE_RESET_VALUES[28]`.
    pub fn reset(cfg: &MachineConfig) -> Diameter {
        let mode = DiamMode::from_position(cfg.diameter_reset).unwrap_or_default();
        Diameter { mode, shown: mode }
    }

    /// Whether programmed values of any axis are diameters now (the fast lane leaves such
    /// blocks to the full preparation).
    pub fn active(&self) -> bool {
        matches!(self.mode, DiamMode::On | DiamMode::D90)
    }

    /// Selects `mode` in line `line`; alarm 16510 without a transverse axis (MD20100 empty).
    pub fn select(&mut self, mode: DiamMode, cfg: &MachineConfig, line: u32) -> Result<(), Alarm> {
        if mode != DiamMode::Of && cfg.transverse_axis.is_none() {
            return Err(Alarm::no_transverse_axis(line));
        }
        self.shown = match mode {
            DiamMode::CycOf if self.mode == DiamMode::CycOf => self.shown,
            DiamMode::CycOf => self.mode,
            m => m,
        };
        self.mode = mode;
        Ok(())
    }

    /// The factor from a programmed value of channel axis `k` to the radius: ½ on the
    /// transverse axis while its values are diameters (`absolute`: the value is absolute).
    pub fn factor(&self, cfg: &MachineConfig, k: usize, absolute: bool) -> f64 {
        let diameter = match self.mode {
            DiamMode::On => true,
            DiamMode::D90 => absolute,
            DiamMode::Of | DiamMode::CycOf => false,
        };
        if diameter && cfg.transverse_axis == Some(k) { 0.5 } else { 1.0 }
    }

    /// Group 29 as the main run carries it with the block ([`crate::interp::gcodes::GCodes`]):
    /// the position − 1, plus 4 when the display shows diameters.
    pub fn gcode_slot(&self) -> u8 {
        let display = matches!(self.shown, DiamMode::On | DiamMode::D90);
        self.mode.position() - 1 + if display { 4 } else { 0 }
    }
}

/// Whether the G group 29 slot `slot` (see [`Diameter::gcode_slot`]) shows the transverse
/// axis as a diameter.
pub fn slot_shows_diameter(slot: u8) -> bool {
    slot >= 4
}

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
//!
//! Axis-specific diameter programming (`diameter_axes.rs`: DIAMONA[ax], DIAM90A[ax],
//! DIAMOFA[ax], DIACYCOFA[ax], DIAMCHANA[ax], DIAMCHAN) gives an axis its own mode or links it
//! to the channel's group 29. After reset the transverse axis follows the channel and every
//! other axis is radius-programmed.

use crate::alarm::Alarm;
use crate::machine_data::MachineConfig;
use crate::machine_data::registry::MAX_CHANNEL_AXES;

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

/// How one channel axis takes its programmed values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AxisDiam {
    /// It follows the channel's G group 29 (the transverse axis after reset, DIAMCHANA).
    Channel,
    /// Its own mode (DIAMONA, DIAM90A, DIAMOFA, DIACYCOFA) and what its display shows.
    Own { mode: DiamMode, shown: DiamMode },
    /// Radius programming, not linked to the channel (every other axis after reset).
    #[default]
    Radius,
}

/// The diameter programming state of preparation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Diameter {
    pub mode: DiamMode,
    /// The mode DIAMCYCOF replaced: what the display keeps showing.
    shown: DiamMode,
    /// Each channel axis' rule.
    axes: [AxisDiam; MAX_CHANNEL_AXES],
    /// The transverse axis of MD20100 (its display is the one the main run shows).
    transverse: Option<usize>,
    /// Some axis takes diameters now (kept up to date by every change).
    active: bool,
}

/// The mode DIAMCYCOF-like `mode` leaves shown after `before` (shown `shown`).
fn shown_after(mode: DiamMode, before: DiamMode, shown: DiamMode) -> DiamMode {
    match mode {
        DiamMode::CycOf if before == DiamMode::CycOf => shown,
        DiamMode::CycOf => before,
        m => m,
    }
}

impl Diameter {
    /// The reset state of MD20150 `$MC_GCODE_RESET_VALUES[28]`: the transverse axis follows
    /// the channel, every other axis is radius-programmed.
    pub fn reset(cfg: &MachineConfig) -> Diameter {
        let mode = DiamMode::from_position(cfg.diameter_reset).unwrap_or_default();
        let mut axes = [AxisDiam::Radius; MAX_CHANNEL_AXES];
        if let Some(tx) = cfg.transverse_axis {
            axes[tx] = AxisDiam::Channel;
        }
        let mut d = Diameter { mode, shown: mode, axes, transverse: cfg.transverse_axis, active: false };
        d.refresh();
        d
    }

    fn refresh(&mut self) {
        let channel = matches!(self.mode, DiamMode::On | DiamMode::D90);
        self.active = self.axes.iter().any(|a| match a {
            AxisDiam::Channel => channel,
            AxisDiam::Own { mode, .. } => matches!(mode, DiamMode::On | DiamMode::D90),
            AxisDiam::Radius => false,
        });
    }

    /// Whether programmed values of any axis are diameters now (the fast lane leaves such
    /// blocks to the full preparation).
    pub fn active(&self) -> bool {
        self.active
    }

    /// Selects `mode` in line `line`; alarm 16510 without a transverse axis (MD20100 empty).
    pub fn select(&mut self, mode: DiamMode, cfg: &MachineConfig, line: u32) -> Result<(), Alarm> {
        if mode != DiamMode::Of && cfg.transverse_axis.is_none() {
            return Err(Alarm::no_transverse_axis(line));
        }
        self.shown = shown_after(mode, self.mode, self.shown);
        self.mode = mode;
        self.refresh();
        Ok(())
    }

    /// Gives channel axis `k` its own `mode` (`Some`) or links it to the channel (`None`).
    /// The axis must be released for it by MD30460 `$MA_BASE_FUNCTION_MASK` bit 2; else
    /// alarm 16510.
    pub fn select_axis(
        &mut self,
        k: usize,
        mode: Option<DiamMode>,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<(), Alarm> {
        if cfg.diameter_axes & 1 << k == 0 {
            return Err(Alarm::no_transverse_axis(line));
        }
        self.axes[k] = match (mode, self.axes[k]) {
            (None, _) => AxisDiam::Channel,
            (Some(m), AxisDiam::Own { mode: before, shown }) => {
                AxisDiam::Own { mode: m, shown: shown_after(m, before, shown) }
            }
            (Some(m), AxisDiam::Channel) => AxisDiam::Own { mode: m, shown: shown_after(m, self.mode, self.shown) },
            (Some(m), AxisDiam::Radius) => AxisDiam::Own { mode: m, shown: shown_after(m, DiamMode::Of, DiamMode::Of) },
        };
        self.refresh();
        Ok(())
    }

    /// DIAMCHAN: every axis released for diameter programming (MD30460 bit 2) follows the
    /// channel's mode.
    pub fn link_all(&mut self, cfg: &MachineConfig) {
        for (k, a) in self.axes.iter_mut().enumerate().take(cfg.channel_axes.len()) {
            if cfg.diameter_axes & 1 << k != 0 {
                *a = AxisDiam::Channel;
            }
        }
        self.refresh();
    }

    /// The rule of channel axis `k`.
    pub fn axis(&self, k: usize) -> AxisDiam {
        self.axes[k]
    }

    /// The factor from a programmed value of channel axis `k` to the radius: ½ while its
    /// values are diameters (`absolute`: the value is absolute).
    pub fn factor(&self, _cfg: &MachineConfig, k: usize, absolute: bool) -> f64 {
        let mode = match self.axes[k] {
            AxisDiam::Channel => self.mode,
            AxisDiam::Own { mode, .. } => mode,
            AxisDiam::Radius => return 1.0,
        };
        let diameter = match mode {
            DiamMode::On => true,
            DiamMode::D90 => absolute,
            DiamMode::Of | DiamMode::CycOf => false,
        };
        if diameter { 0.5 } else { 1.0 }
    }

    /// Group 29 as the main run carries it with the block ([`crate::interp::gcodes::GCodes`]):
    /// the channel's position − 1, plus 4 when the display shows the transverse axis as a
    /// diameter (by the channel's mode or the axis' own).
    pub fn gcode_slot(&self) -> u8 {
        let shown = match self.transverse.map(|k| self.axes[k]) {
            Some(AxisDiam::Own { shown, .. }) => shown,
            Some(AxisDiam::Channel) => self.shown,
            _ => DiamMode::Of,
        };
        let display = matches!(shown, DiamMode::On | DiamMode::D90);
        self.mode.position() - 1 + if display { 4 } else { 0 }
    }
}

impl Diameter {
    /// The channel axes other than the transverse axis whose WCS display shows diameters
    /// (bit k: channel axis k): an axis with its own DIAMONA/DIAM90A (or DIACYCOFA after one),
    /// or linked to the channel (DIAMCHANA) while the channel shows diameters. The control
    /// shows such an axis as a diameter like the transverse axis (Programming Manual
    /// "Axis-specific diameter programming").
    pub fn display_mask(&self) -> u32 {
        let channel = matches!(self.shown, DiamMode::On | DiamMode::D90);
        let mut mask = 0;
        for (k, a) in self.axes.iter().enumerate() {
            let shown = match a {
                AxisDiam::Channel => channel,
                AxisDiam::Own { shown, .. } => matches!(shown, DiamMode::On | DiamMode::D90),
                AxisDiam::Radius => false,
            };
            if shown && Some(k) != self.transverse {
                mask |= 1 << k;
            }
        }
        mask
    }
}

/// Whether the G group 29 slot `slot` (see [`Diameter::gcode_slot`]) shows the transverse
/// axis as a diameter.
pub fn slot_shows_diameter(slot: u8) -> bool {
    slot >= 4
}

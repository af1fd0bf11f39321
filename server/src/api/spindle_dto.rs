//! The state's `spindle_info`: each spindle's speed, mode and angle by the name the state's
//! `spindles` gives it (`S1` for a spindle without axis function, else its channel axis
//! name). Additive to the contract's state object; `spindles` (the signed speeds) stays as it
//! was for clients that read only the speed.

use nctwin_engine::SpindleState;
use serde::{Serialize, Serializer};
use utoipa::ToSchema;

/// One spindle as the T/F/S display shows it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct SpindleInfo {
    /// Spindle number (MD35000 `$MA_SPIND_ASSIGN_TO_MACHAX`).
    pub number: u32,
    /// Actual speed in rev/min, signed (+ = M3); in position control the speed of the
    /// positioning motion.
    pub speed: f64,
    /// `M3`, `M4`, `M5` (speed control) or `SPOS` (position control: SPOS, M19, M70, G331/G332).
    pub mode: &'static str,
    /// Angle in degrees, 0 ≤ angle < 360.
    pub position: f64,
    /// Whether this is the master spindle (MD20090, or the one SETMS selected).
    pub master: bool,
    /// The gear stage engaged (M40..M45); `null` for a spindle without gear stages.
    pub gear: Option<u8>,
    /// The T/F/S display's spindle load symbol: the master spindle turns while the path moves
    /// at feed and the last stretch cut (at most 8 mm) removed material from the stock. A flag,
    /// not a load: no cutting forces are modelled.
    pub cutting: bool,
    /// Position control: SPCON (until SPCOF) or a spindle moved as an axis (SPOS, M19, M70,
    /// G331/G332).
    pub position_control: bool,
}

impl From<&SpindleState> for SpindleInfo {
    fn from(s: &SpindleState) -> Self {
        SpindleInfo {
            number: s.number,
            speed: s.speed,
            mode: s.mode.name(),
            position: s.position,
            master: s.master,
            gear: s.gear,
            cutting: s.cutting,
            position_control: s.position_control,
        }
    }
}

/// Spindles by name, serialized as a JSON object in the engine's order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SpindleInfos(pub Vec<(String, SpindleInfo)>);

impl SpindleInfos {
    pub fn of(list: &[(String, SpindleState)]) -> Self {
        SpindleInfos(list.iter().map(|(n, s)| (n.clone(), SpindleInfo::from(s))).collect())
    }
}

impl Serialize for SpindleInfos {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (name, value) in &self.0 {
            map.serialize_entry(name, value)?;
        }
        map.end()
    }
}

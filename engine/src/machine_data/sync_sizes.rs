//! The sizes of the synchronized actions' data and of the fast NCK inputs and outputs, read
//! from the machine data that configure them on the control (Function Manual "Synchronized
//! actions", "Digital and analog NCK I/Os"), so a session's data matches its machine's:
//! MD28254 `$MC_MM_NUM_AC_PARAM` (`$AC_PARAM[0..n-1]`), MD28256 `$MC_MM_NUM_AC_MARKER`
//! (`$AC_MARKER[0..n-1]`), MD28258 `$MC_MM_NUM_AC_TIMER` (`$AC_TIMER[0..n-1]`), MD10350/10360
//! `$MN_FASTIO_DIG_NUM_INPUTS/OUTPUTS` (bytes of 8 signals: `$A_IN[1..8n]`, `$A_OUT[1..8n]`),
//! MD10300/10310 `$MN_FASTIO_ANA_NUM_INPUTS/OUTPUTS` (signals: `$A_INA[1..n]`, `$A_OUTA[1..n]`).
//! MD28250 `$MC_MM_NUM_SYNC_ELEMENTS` bounds the active actions, in elements
//! (`interp/synchronized/elements.rs`).
//! The defaults: 8 markers and timers, 50 parameters (NCTwin's sizes of before), 2 bytes (16)
//! of digital and 4 analog signals each (a small machine's simulated PLC; up to 5 bytes, 40).

use super::MachineData;

/// Element counts of the synchronized actions' arrays and the NCK signals.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SyncSizes {
    /// Elements all active synchronized actions may occupy together (MD28250).
    pub elements: usize,
    pub markers: usize,
    pub params: usize,
    pub timers: usize,
    /// Digital inputs and outputs (8 per configured byte).
    pub digital_in: usize,
    pub digital_out: usize,
    pub analog_in: usize,
    pub analog_out: usize,
}

/// Bytes of digital signals at most (MD10350/MD10360's upper limit): the image is one `u64`.
pub const MAX_DIGITAL_BYTES: usize = 5;
/// Analog signals at most (MD10300/MD10310's upper limit).
pub const MAX_ANALOG: usize = 8;

impl Default for SyncSizes {
    fn default() -> Self {
        SyncSizes {
            elements: 159,
            markers: 8,
            params: 50,
            timers: 8,
            digital_in: 8 * MAX_DIGITAL_BYTES,
            digital_out: 8 * MAX_DIGITAL_BYTES,
            analog_in: 4,
            analog_out: 4,
        }
    }
}

impl SyncSizes {
    /// Reads the sizes (the registry bounds each datum, so none exceeds the image).
    pub(super) fn read(md: &MachineData) -> SyncSizes {
        let n = |name: &str| md.num(name, 0, 0).max(0.0) as usize;
        SyncSizes {
            elements: n("$MC_MM_NUM_SYNC_ELEMENTS"),
            markers: n("$MC_MM_NUM_AC_MARKER"),
            params: n("$MC_MM_NUM_AC_PARAM"),
            timers: n("$MC_MM_NUM_AC_TIMER"),
            digital_in: 8 * n("$MN_FASTIO_DIG_NUM_INPUTS"),
            digital_out: 8 * n("$MN_FASTIO_DIG_NUM_OUTPUTS"),
            analog_in: n("$MN_FASTIO_ANA_NUM_INPUTS"),
            analog_out: n("$MN_FASTIO_ANA_NUM_OUTPUTS"),
        }
    }
}

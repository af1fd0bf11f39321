//! Measuring with a touch-trigger probe (Programming Manual "Job planning", "Measurements with
//! touch trigger probe (MEAS, MEAW)").
//!
//! - `MEAS=±n` in a motion block: measure with probe n (1 or 2) on the rising (+) or falling
//!   (−) edge of its signal and delete the distance to go when it switches; the block after
//!   waits for the main run (it starts where the probe stopped).
//! - `MEAW=±n`: measure the same way, without deleting the distance to go.
//!
//! This module reads the words and hands a [`Request`] to the main run before the block's
//! move ([`super::Item::Measure`]); the main run's probe (`channel/probe.rs`) finds the switching
//! point and hands back the [`Results`] that `$AC_MEA[n]`, `$AA_MM[ax]` and `$AA_MW[ax]` read.

use super::eval::value::Value;
use crate::alarm::Alarm;
use crate::machine_data::MachineConfig;
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::AxisVec;

/// One measuring job: the probe, its edge and whether the distance to go is deleted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Request {
    /// Probe 1 or 2.
    pub probe: u8,
    /// Rising edge (`MEAS=1`: the probe is deflected) or falling edge (`MEAS=-1`).
    pub rising: bool,
    /// MEAS (true) or MEAW (false).
    pub delete_distance: bool,
}

/// What the last measuring jobs found, as the main run hands it over.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Results {
    /// `$AC_MEA[1..2]`: the probe switched in its last job.
    pub triggered: [bool; 2],
    /// `$AA_MM[ax]`: machine position per channel axis at the switching point.
    pub machine: AxisVec,
    /// `$AA_MW[ax]`: workpiece position (WCS of the active frame and tool) at that point.
    pub workpiece: AxisVec,
}

impl Default for Results {
    fn default() -> Results {
        Results { triggered: [false; 2], machine: [0.0; MAX_CHANNEL_AXES], workpiece: [0.0; MAX_CHANNEL_AXES] }
    }
}

/// Whether `name` is an address of this module.
pub(super) fn is_address(name: &str) -> bool {
    matches!(name, "MEAS" | "MEAW")
}

/// `MEAS=` / `MEAW=` with its value; false for any other name. Only ±1 and ±2 name a probe
/// (the control has two probe inputs); anything else is a value out of range.
pub(super) fn address(request: &mut Option<Request>, name: &str, v: f64, line: u32) -> Result<bool, Alarm> {
    let delete_distance = match name {
        "MEAS" => true,
        "MEAW" => false,
        _ => return Ok(false),
    };
    if !matches!(v, -2.0 | -1.0 | 1.0 | 2.0) {
        return Err(Alarm::value_out_of_range(line, &format!("{name}={v} (probe ±1 or ±2)")));
    }
    if request.is_some() {
        return Err(Alarm::conflicting_functions(line, "MEAS and MEAW"));
    }
    *request = Some(Request { probe: v.abs() as u8, rising: v > 0.0, delete_distance });
    Ok(true)
}

impl Results {
    /// `$AC_MEA[n]`, `$AA_MM[ax]`, `$AA_MW[ax]`; `None` for any other name.
    pub(crate) fn read(
        &self,
        cfg: &MachineConfig,
        name: &str,
        indices: &[Value],
        line: u32,
    ) -> Option<Result<Value, Alarm>> {
        let list = match name {
            "$AC_MEA" => {
                return Some(match indices {
                    [n] => match n.as_i64() {
                        Ok(n @ 1..=2) => Ok(Value::Int(self.triggered[n as usize - 1].into())),
                        Ok(n) => Err(Alarm::index_error(line, name, &format!("probe {n} (1 or 2)"))),
                        Err(e) => Err(Alarm::type_error(line, &e.0)),
                    },
                    _ => Err(Alarm::index_error(line, name, "needs the probe number")),
                });
            }
            "$AA_MM" => &self.machine,
            "$AA_MW" => &self.workpiece,
            _ => return None,
        };
        Some(match indices {
            [Value::Axis(a) | Value::Str(a)] => cfg
                .program_axis(a)
                .map(|k| Value::Real(list[k]))
                .ok_or_else(|| Alarm::unknown_name(line, &format!("{name}[{a}]"))),
            _ => Err(Alarm::index_error(line, name, "needs one axis name")),
        })
    }
}

impl super::Interpreter {
    /// The main run's measuring results, after each job.
    pub fn set_measured(&mut self, results: Results) {
        self.measured = results;
    }

    /// A block with `MEAS`/`MEAW`: the request goes to the main run before the block's move.
    /// Called before the motion is prepared; [`super::Interpreter::measure_block_end`] after.
    pub(super) fn measure_request(&self, request: Option<Request>, line: u32) -> Result<(), Alarm> {
        if request.is_some() && self.offsets.trafo.is_some() {
            // The probe is simulated in the BCS; a transformation's machine axes are not.
            return Err(Alarm::unknown_name(line, "MEAS/MEAW with an active transformation"));
        }
        Ok(())
    }

    /// After the motion of a measuring block: the request goes before the block's move, the
    /// move ends with an exact stop, and MEAS makes the next block wait for the main run
    /// (it continues from where the probe stopped the axes).
    pub(super) fn measure_block_end(
        &mut self,
        request: Option<Request>,
        mark: usize,
        line: u32,
        out: &mut Vec<super::Item>,
    ) -> Result<(), Alarm> {
        let Some(request) = request else { return Ok(()) };
        if !self.trc.idle() {
            // The compensated move would be held for the next block, which itself waits for
            // the measurement: NCTwin measures without TRC only.
            return Err(Alarm::unknown_name(line, "MEAS/MEAW with tool radius compensation G41/G42"));
        }
        let Some(first) = out[mark..].iter().position(|i| matches!(i, super::Item::Move { .. })) else {
            return Err(Alarm::syntax(line, "MEAS/MEAW needs a motion in its block"));
        };
        for item in &mut out[mark..] {
            if let super::Item::Move { mv, .. } = item {
                mv.exact_stop = true;
            }
        }
        out.insert(mark + first, super::Item::Measure { request, line });
        if request.delete_distance {
            self.sync_wait = super::synchronized::PrepWait::UntilIdle;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn meas_and_meaw_name_probe_and_edge() {
        let mut r = None;
        assert!(address(&mut r, "MEAS", -2.0, 5).unwrap());
        assert_eq!(r, Some(Request { probe: 2, rising: false, delete_distance: true }));
        let mut r = None;
        assert!(address(&mut r, "MEAW", 1.0, 5).unwrap());
        assert_eq!(r, Some(Request { probe: 1, rising: true, delete_distance: false }));
        assert!(!address(&mut r, "X", 1.0, 5).unwrap());
    }

    #[test]
    fn a_probe_other_than_one_or_two_is_refused() {
        for v in [0.0, 3.0, 1.5, -3.0] {
            assert!(address(&mut None, "MEAS", v, 7).is_err(), "MEAS={v}");
        }
        let mut r = None;
        address(&mut r, "MEAS", 1.0, 7).unwrap();
        assert!(address(&mut r, "MEAW", 1.0, 7).is_err());
    }
}

//! The channel's digital NCK inputs and outputs as a program sees them: `$A_IN[n]` (read only)
//! and `$A_OUT[n]` (read and written), n = 1..[`DIGITAL_IO`].
//!
//! Both are main-run variables: a block that reads them waits until the main run has caught
//! up (the control's implicit preprocessing stop), and a write from a program takes effect
//! when its block reaches the main run ([`crate::interp::Item::DigitalOutput`]), in order with
//! the motion before it. The inputs are set from outside (the server's `PUT .../io`, standing
//! in for the machine's wiring); a program writing `$A_IN` gets alarm 17070.

pub mod plc_data;

use crate::alarm::Alarm;
use crate::interp::eval::value::Value;

/// Digital inputs and outputs of the image at most: 5 bytes of each, the most MD10350/MD10360
/// (FASTIO_DIG_NUM_INPUTS/OUTPUTS, in bytes) configure.
pub const DIGITAL_IO: usize = 8 * crate::machine_data::sync_sizes::MAX_DIGITAL_BYTES;

/// The image of the digital inputs and outputs, bit n-1 for signal n, and how many of each
/// the machine data configure (MD10350/MD10360).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DigitalIo {
    pub inputs: u64,
    pub outputs: u64,
    input_count: u8,
    output_count: u8,
}

/// All [`DIGITAL_IO`] signals of each, all off.
impl Default for DigitalIo {
    fn default() -> Self {
        DigitalIo { inputs: 0, outputs: 0, input_count: DIGITAL_IO as u8, output_count: DIGITAL_IO as u8 }
    }
}

impl DigitalIo {
    /// The image with `inputs` and `outputs` signals (at most [`DIGITAL_IO`] each); the
    /// signals beyond go off.
    pub fn sized(mut self, inputs: usize, outputs: usize) -> DigitalIo {
        self.input_count = inputs.min(DIGITAL_IO) as u8;
        self.output_count = outputs.min(DIGITAL_IO) as u8;
        self.inputs &= mask(self.input_count.into());
        self.outputs &= mask(self.output_count.into());
        self
    }

    /// How many inputs and outputs there are.
    pub fn counts(&self) -> (usize, usize) {
        (self.input_count.into(), self.output_count.into())
    }

    /// Input `n` (1-based), if it exists.
    pub fn input(&self, n: usize) -> Option<bool> {
        bit(self.inputs, n, self.input_count.into())
    }

    /// Output `n` (1-based), if it exists.
    pub fn output(&self, n: usize) -> Option<bool> {
        bit(self.outputs, n, self.output_count.into())
    }

    /// Sets input `n` (1-based); `false` if there is no such input.
    pub fn set_input(&mut self, n: usize, on: bool) -> bool {
        set(&mut self.inputs, n, on, self.input_count.into())
    }

    /// Sets output `n` (1-based); `false` if there is no such output.
    pub fn set_output(&mut self, n: usize, on: bool) -> bool {
        set(&mut self.outputs, n, on, self.output_count.into())
    }

    /// `$A_IN[n]` / `$A_OUT[n]`; `None` for any other name.
    pub(crate) fn read(&self, name: &str, indices: &[Value], line: u32) -> Option<Result<Value, Alarm>> {
        let (bits, count) = match name {
            "$A_IN" => (self.inputs, self.input_count),
            "$A_OUT" => (self.outputs, self.output_count),
            _ => return None,
        };
        let count = count.into();
        Some(signal(name, indices, count, line).map(|n| Value::Bool(bit(bits, n, count).unwrap_or(false))))
    }
}

/// True for the names of NCK signals, which are main-run variables: this module's digital
/// ones and the analog `$A_INA`/`$A_OUTA` (read through `synchronized.rs`).
pub(crate) fn is_io_name(name: &str) -> bool {
    matches!(name, "$A_IN" | "$A_OUT" | "$A_INA" | "$A_OUTA")
}

/// The signal number of `name[n]`, checked against the `count` signals configured (17020
/// outside).
pub(crate) fn signal(name: &str, indices: &[Value], count: usize, line: u32) -> Result<usize, Alarm> {
    let [n] = indices else { return Err(Alarm::index_error(line, name, "needs one signal number")) };
    let n = n.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
    usize::try_from(n)
        .ok()
        .filter(|n| (1..=count).contains(n))
        .ok_or_else(|| Alarm::index_error(line, name, &format!("signal {n} (1..{count})")))
}

/// The value a program assigns to an output: 0/FALSE is off, anything else on (the control's
/// conversion of a number to BOOL).
pub(crate) fn level(value: &Value, line: u32) -> Result<bool, Alarm> {
    value.as_bool().map_err(|e| Alarm::type_error(line, &e.0))
}

fn mask(count: usize) -> u64 {
    (1u64 << count) - 1
}

fn bit(bits: u64, n: usize, count: usize) -> Option<bool> {
    (1..=count).contains(&n).then(|| bits >> (n - 1) & 1 == 1)
}

fn set(bits: &mut u64, n: usize, on: bool, count: usize) -> bool {
    if !(1..=count).contains(&n) {
        return false;
    }
    if on {
        *bits |= 1 << (n - 1);
    } else {
        *bits &= !(1 << (n - 1));
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signals_are_numbered_from_one_to_forty() {
        let mut io = DigitalIo::default();
        assert!(io.set_input(1, true) && io.set_input(40, true));
        assert!(!io.set_input(0, true) && !io.set_input(41, true));
        assert_eq!(io.inputs, 1 | 1 << 39);
        assert_eq!(io.input(40), Some(true));
        assert_eq!(io.input(2), Some(false));
        assert_eq!(io.output(41), None);
        assert!(io.set_output(3, true) && io.set_output(3, false));
        assert_eq!(io.outputs, 0);
    }

    #[test]
    fn reads_check_the_signal_number() {
        let mut io = DigitalIo::default();
        io.set_output(5, true);
        assert_eq!(io.read("$A_OUT", &[Value::Int(5)], 3), Some(Ok(Value::Bool(true))));
        assert_eq!(io.read("$A_IN", &[Value::Int(5)], 3), Some(Ok(Value::Bool(false))));
        assert_eq!(io.read("$A_IN", &[Value::Int(41)], 3).unwrap().unwrap_err().number, 17020);
        assert!(io.read("$A_INA", &[Value::Int(1)], 3).is_none());
    }

    #[test]
    fn the_machine_data_size_the_image() {
        // MD10350 = 2 bytes of inputs: 16 inputs; MD10360 = 1 byte: 8 outputs.
        let mut io = DigitalIo::default();
        io.set_input(17, true);
        let mut io = io.sized(16, 8);
        assert_eq!(io.counts(), (16, 8));
        assert_eq!(io.inputs, 0, "input 17 no longer exists");
        assert!(io.set_input(16, true) && !io.set_input(17, true));
        assert!(io.set_output(8, true) && !io.set_output(9, true));
        assert_eq!(io.read("$A_IN", &[Value::Int(16)], 3), Some(Ok(Value::Bool(true))));
        assert_eq!(io.read("$A_OUT", &[Value::Int(9)], 3).unwrap().unwrap_err().number, 17020);
    }
}

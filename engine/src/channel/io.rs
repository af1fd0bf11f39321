//! The channel's side of the digital I/O image and of the machine data programs read: the
//! main run executes `$A_OUT` writes, the shell sets inputs (`set_inputs`), and the interpreter
//! is handed each new state of both.

use std::sync::Arc;

use super::{Channel, CommandError, Event};
use crate::interp::io::DigitalIo;

impl Channel {
    /// The digital inputs and outputs as the main run holds them.
    pub fn digital_io(&self) -> DigitalIo {
        self.io
    }

    /// Sets digital inputs and outputs from outside (the machine's wiring, a test bench),
    /// each `(signal, level)` with signal 1.. the count of MD10350 (inputs) or MD10360
    /// (outputs). All or nothing: a signal out of range changes nothing.
    pub fn set_signals(&mut self, inputs: &[(usize, bool)], outputs: &[(usize, bool)]) -> Result<(), CommandError> {
        let (ins, outs) = self.io.counts();
        if let Some((n, _)) = inputs.iter().find(|(n, _)| !(1..=ins).contains(n)) {
            return Err(CommandError::Invalid(format!(
                "signal {n} does not exist: digital inputs are 1..{ins} (MD10350 FASTIO_DIG_NUM_INPUTS, bytes of 8)"
            )));
        }
        if let Some((n, _)) = outputs.iter().find(|(n, _)| !(1..=outs).contains(n)) {
            return Err(CommandError::Invalid(format!(
                "signal {n} does not exist: digital outputs are 1..{outs} (MD10360 FASTIO_DIG_NUM_OUTPUTS, bytes of 8)"
            )));
        }
        let mut io = self.io;
        for &(n, on) in inputs {
            io.set_input(n, on);
        }
        for &(n, on) in outputs {
            io.set_output(n, on);
        }
        self.set_digital_io(io);
        let record = super::sync::InputRecord {
            tick: self.tick,
            inputs: inputs.to_vec(),
            outputs: outputs.to_vec(),
            analog: Vec::new(),
        };
        self.log_inputs(record);
        Ok(())
    }

    /// Main run: a program's `$A_OUT[signal]` write takes effect (and is published).
    pub(super) fn execute_digital_output(&mut self, signal: usize, on: bool, line: u32) {
        let mut io = self.io;
        io.set_output(signal, on);
        self.set_digital_io(io);
        self.events.push(Event::DigitalOutput { signal, on, line });
    }

    /// The signal counts and array sizes of the machine data in force (at creation, reset,
    /// NEWCONF).
    pub(super) fn size_signals(&mut self) {
        let z = self.cfg.sync_sizes;
        if self.io.counts() != (z.digital_in, z.digital_out) {
            self.set_digital_io(self.io.sized(z.digital_in, z.digital_out));
        }
        if self.sync.markers.len() != z.markers
            || self.sync.params.len() != z.params
            || self.sync.timers.len() != z.timers
            || self.sync.analog_in.len() != z.analog_in
            || self.sync.analog_out.len() != z.analog_out
        {
            self.sync.resize(&z);
            self.interp.set_sync_data(self.sync.main_run_data());
            self.sync.dirty = false;
        }
    }

    pub(super) fn set_digital_io(&mut self, io: DigitalIo) {
        self.io = io;
        self.sync.wake();
        self.interp.set_io(io);
    }

    /// The PLC data area `$A_DBB[n]`.. as programs wrote it (bytes up to the last non-zero one).
    pub fn plc_data(&self) -> &[u8] {
        self.interp.plc_data().bytes()
    }

    /// Writes `bytes` into the PLC data area from byte `at` on, as the PLC would (the shell's
    /// `PUT .../io`); blocks prepared after this read them. Beyond the area: nothing changes.
    pub fn set_plc_data(&mut self, at: usize, bytes: &[u8]) -> Result<(), CommandError> {
        use crate::interp::io::plc_data::PLC_DATA_BYTES;
        if at.checked_add(bytes.len()).is_none_or(|end| end > PLC_DATA_BYTES) {
            return Err(CommandError::Invalid(format!(
                "PLC data: {} bytes from byte {at} reach beyond the area of {PLC_DATA_BYTES} bytes",
                bytes.len()
            )));
        }
        self.interp.write_plc_data(at, bytes);
        Ok(())
    }

    /// Marks this channel's program runs as a simulation: `$P_SIM` reads TRUE (the HMI's
    /// preview copy; a session's own channel is the machine and reads FALSE).
    pub fn set_simulation(&mut self, simulation: bool) {
        self.interp.set_simulation(simulation);
    }

    /// Hands the stored machine data to the interpreter, after every change of it, for the
    /// programs' `$MN_`... reads.
    pub(super) fn publish_stored_data(&mut self) {
        self.interp.set_stored_data(Arc::new(self.data.clone()));
    }
}

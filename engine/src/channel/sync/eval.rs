//! The main run's side of a synchronized action's flat code (`interp/synchronized/flat.rs`):
//! the variables it reads in this IPO cycle ([`Reader`] for the channel) and the actions it
//! runs (assignments, M/H output, DELDTG).

use crate::alarm::Alarm;
use crate::channel::{Channel, Event};
use crate::interp::auxiliary::AuxFunction;
use crate::interp::synchronized::flat::{
    self, ANALOG_IN_BITS, Act, Array, DIGITAL_IN_BIT, DIGITAL_OUT_BIT, Fault, Reader, Slot, SyncSizes, TIMER_BIT,
    Target,
};

/// Which main-run data (and which events, `flat::BLOCK_BIT`...) changed lately: a condition
/// asleep (`actions.rs`) is evaluated again when data it reads changed in this cycle or
/// the one before. Two masks, not counts: a change made by an action late in a cycle reaches
/// the actions checked before it in the next cycle.
#[derive(Debug, Clone, Default)]
pub(super) struct Touched {
    /// Changed before this cycle's actions were checked (every action sees these).
    before: u64,
    /// Changed by the actions of this cycle (or from outside since the last cycle checked).
    now: u64,
    /// Changed by the actions of the cycle before (the ones checked before the change have
    /// not seen them yet).
    prev: u64,
}

impl Touched {
    /// The data of `bits` changed.
    #[inline]
    pub(super) fn touch(&mut self, bits: u64) {
        self.now |= bits;
    }

    /// Whether data of `bits` changed in this cycle or the one before.
    #[inline]
    pub(super) fn any(&self, bits: u64) -> bool {
        (self.before | self.now | self.prev) & bits != 0
    }

    /// The actions' checks begin: what changed so far every one of them sees.
    #[inline]
    pub(super) fn begin_checks(&mut self) {
        self.before = std::mem::take(&mut self.now);
    }

    /// Whether an action changed anything in this cycle.
    pub(super) fn in_this_cycle(&self) -> bool {
        self.now != 0
    }

    /// The cycle's checks are over: the actions' changes become the cycle before's.
    pub(super) fn next_cycle(&mut self) {
        self.prev = std::mem::take(&mut self.now);
        self.before = 0;
    }
}

impl Reader for Channel {
    #[inline]
    fn read(&self, slot: Slot, line: u32) -> Result<f64, Fault> {
        let dt = self.cfg.ipo_cycle;
        let s = &self.sync;
        Ok(match slot {
            Slot::AaIm(k) => self.actual_position(k),
            Slot::AaIw(k) => self.workpiece_actual(k),
            Slot::AaIpo(k) => self.machine[k],
            Slot::AaVactm(k) => (self.machine[k] - s.prev_setpoint[k]) / dt * 60.0,
            Slot::AaOvr(k) => s.axis_ovr[k],
            Slot::AcTime => (self.tick - s.block_start) as f64 * dt,
            Slot::AcPath => self.planner.front().map_or(0.0, |m| m.length * self.planner.front_fraction()),
            Slot::AcDteb => self.planner.front().map_or(0.0, |m| m.length * (1.0 - self.planner.front_fraction())),
            Slot::AcVactb => self.planner.velocity() * 60.0,
            Slot::AcOvr => s.ovr,
            Slot::AcDelt => s.deleted,
            Slot::Timer(i) => s.timers[i].unwrap_or(0.0),
            Slot::Marker(i) => s.markers[i],
            Slot::Param(i) => s.params[i],
            Slot::AIn(n) => f64::from(u8::from(self.io.input(n).unwrap_or(false))),
            Slot::AOut(n) => f64::from(u8::from(self.io.output(n).unwrap_or(false))),
            Slot::AIna(i) => s.analog_in[i],
            Slot::AOuta(i) => s.analog_out[i],
            Slot::R(n) => {
                *self.interp.variables().r.get(n).ok_or_else(|| Alarm::index_error(line, "$R", &format!("{n}")))?
            }
        })
    }

    fn read_at(&self, array: Array, v: f64, line: u32) -> Result<f64, Fault> {
        match array {
            Array::R => {
                let r = &self.interp.variables().r;
                Ok(*r
                    .get(v.round().max(0.0) as usize)
                    .filter(|_| v >= 0.0)
                    .ok_or_else(|| Alarm::index_error(line, "$R", &format!("{v}")))?)
            }
            Array::AaS => {
                let n = index(v, "$AA_S", self.spindles.len().max(1), 1, line)?;
                Ok(self.spindles.get(n).map_or(0.0, |s| s.speed))
            }
            a => self.read(element(a, v, &self.cfg.sync_sizes, line)?, line),
        }
    }
}

/// The element `v` of `array` (one with a fixed size), or alarm 17020.
fn element(array: Array, v: f64, z: &SyncSizes, line: u32) -> Result<Slot, Fault> {
    array.slot(v, z).ok_or_else(|| {
        let (name, shape) = array.shape(z);
        let (size, first) = shape.unwrap_or((0, 0));
        Box::new(Alarm::index_outside(line, name, v, size, first))
    })
}

/// Index `v` of a list of `size` numbered from `first`, from 0, or alarm 17020.
fn index(v: f64, name: &str, size: usize, first: usize, line: u32) -> Result<usize, Fault> {
    let n = v.round();
    if v.is_finite() && n >= first as f64 && n < (size + first) as f64 {
        Ok(n as usize - first)
    } else {
        Err(Box::new(Alarm::index_outside(line, name, v, size, first)))
    }
}

impl Channel {
    /// `$AA_IW[k]`: the actual position in workpiece coordinates, as [`Frame::unapply`] maps
    /// it (the same arithmetic), computed once per cycle for the axes read (the geometry axes
    /// together) through the frame's inverse kept while the offsets stay the same.
    ///
    /// [`Frame::unapply`]: crate::interp::frames::frame::Frame::unapply
    fn workpiece_actual(&self, k: usize) -> f64 {
        let (cells, valid) = (&self.sync.wcs, &self.sync.wcs_valid);
        if valid.get() & (1 << k) != 0 {
            return cells[k].get();
        }
        let Some(inv) = self.sync.frame_inverse.as_ref().and_then(|(_, inv)| inv.as_ref()) else { return f64::NAN };
        let frame = &self.offsets.frame;
        let basic = |i: usize| {
            if i < self.cfg.channel_axes.len() { self.actual_position(i) - self.offsets.tool[i] } else { 0.0 }
        };
        let geo = &self.cfg.geo_axes;
        if geo.contains(&Some(k)) {
            let d = geo.map(|a| a.map_or(0.0, |i| basic(i) - frame.trans[i]));
            let mut bits = 0;
            for (g, axis) in geo.iter().enumerate() {
                if let Some(i) = axis {
                    cells[*i].set((0..3).map(|j| inv[g][j] * d[j]).sum());
                    bits |= 1 << i;
                }
            }
            valid.set(valid.get() | bits);
        } else {
            cells[k].set((basic(k) - frame.trans[k]) / frame.factor[k]);
            valid.set(valid.get() | (1 << k));
        }
        cells[k].get()
    }

    /// Keeps the inverse of the active frame for `$AA_IW` (once per change of the offsets):
    /// `None` where [`Frame::unapply`] has no result (a scale factor of zero).
    ///
    /// [`Frame::unapply`]: crate::interp::frames::frame::Frame::unapply
    /// Returns whether the offsets changed.
    pub(super) fn refresh_frame_inverse(&mut self) -> bool {
        let same = self.sync.frame_of(&self.offsets);
        if !same {
            let frame = &self.offsets.frame;
            let inv = frame.linear_inverse().filter(|_| frame.factor.iter().all(|f| *f != 0.0));
            self.sync.frame_inverse = Some((self.offsets.clone(), inv));
        }
        !same
    }

    /// Runs one action of a synchronized action defined at `line`.
    pub(in crate::channel) fn sync_act(&mut self, act: &Act, line: u32) -> Result<(), Fault> {
        match act {
            Act::Set { target, value, index } => {
                let v = flat::eval(value, self, line)?;
                self.sync_set(*target, index, v, line)
            }
            Act::Aux { letter, extension, value } => {
                let value = flat::eval(value, self, line)?;
                if matches!(letter, 'M' | 'S') {
                    self.sync_spindle_word(*letter, *extension, value);
                }
                if *letter != 'S' {
                    let function = AuxFunction { letter: *letter, extension: *extension, value };
                    self.events.push(Event::AuxFunction { function, line });
                }
                Ok(())
            }
            Act::Command { kind, axis, value, mode } => {
                let v = flat::eval(value, self, line)?;
                self.sync_command(*kind, *axis, v, *mode, line)
            }
            Act::DelDtg => {
                self.delete_distance_to_go();
                Ok(())
            }
            act => self.program_sync_act(act, line),
        }
    }

    /// A part program's `$AC_MARKER[i] = v`, `$AC_PARAM[i] = v` or `$AC_TIMER[i] = v` as its
    /// block reaches the main run: as a synchronized action writes it (the index was checked in
    /// preparation).
    pub(in crate::channel) fn write_sync_data(&mut self, target: Target, v: f64, line: u32) {
        if let Err(alarm) = self.sync_set(target, &flat::Code::default(), v, line) {
            self.raise(*alarm);
        }
    }

    /// Writes `v` to `target` (`index` computes the element of [`Target::At`]).
    fn sync_set(&mut self, target: Target, index: &flat::Code, v: f64, line: u32) -> Result<(), Fault> {
        self.sync.dirty |= matches!(
            target,
            Target::Timer(_)
                | Target::Marker(_)
                | Target::Param(_)
                | Target::AOuta(_)
                | Target::At(Array::Timer | Array::Marker | Array::Param | Array::AOuta)
        );
        let s = &mut self.sync;
        match target {
            Target::Ovr => s.ovr = v.clamp(0.0, 200.0),
            Target::AxisOvr(k) => {
                s.axis_ovr[k] = v.clamp(0.0, 200.0);
                s.axis_ovr_written = true;
            }
            Target::At(Array::R) => {
                let n = flat::eval(index, self, line)?;
                if !(n >= 0.0 && self.interp.write_r_param(n.round() as usize, v)) {
                    return Err(Box::new(Alarm::index_error(line, "$R", &format!("{n}"))));
                }
            }
            Target::At(array) => {
                let i = flat::eval(index, self, line)?;
                let t = match element(array, i, &self.cfg.sync_sizes, line)? {
                    Slot::Timer(i) => Target::Timer(i),
                    Slot::Marker(i) => Target::Marker(i),
                    Slot::Param(i) => Target::Param(i),
                    Slot::AOut(n) => Target::AOut(n),
                    Slot::AOuta(i) => Target::AOuta(i),
                    _ => Target::ReadOnly,
                };
                return self.sync_set(t, index, v, line);
            }
            Target::Timer(i) => {
                // A value of 0 or more starts the timer from there, a negative one stops it.
                s.timers[i] = (v >= 0.0).then_some(v);
                s.timing = s.timers.iter().any(Option::is_some);
                s.touch(1 << TIMER_BIT);
            }
            Target::Marker(i) => {
                // Markers are INT: a REAL assigned is rounded.
                set(&mut s.markers[i], v.round(), flat::marker_bit(i), &mut s.touched);
            }
            Target::Param(i) => {
                set(&mut s.params[i], v, flat::param_bit(i), &mut s.touched);
            }
            Target::R(n) => {
                if !self.interp.write_r_param(n, v) {
                    return Err(Box::new(Alarm::index_error(line, "$R", &format!("{n}"))));
                }
            }
            Target::AOut(n) => {
                let on = v != 0.0;
                if self.io.output(n) != Some(on) {
                    self.execute_digital_output(n, on, line);
                    self.note_io();
                }
            }
            Target::AOuta(i) => {
                set(&mut s.analog_out[i], v, flat::analog_out_bit(i), &mut s.touched);
            }
            Target::ReadOnly => return Err(Box::new(Alarm::write_protected(line, "synchronized action variable"))),
        }
        Ok(())
    }

    /// Notes changes of the digital signals (from outside, the program or an action) for the
    /// conditions that read them.
    #[inline]
    pub(super) fn note_io(&mut self) {
        let (io, seen) = (self.io, self.sync.io_seen);
        if io != seen {
            let bits = (u64::from(io.inputs != seen.inputs) << DIGITAL_IN_BIT)
                | (u64::from(io.outputs != seen.outputs) << DIGITAL_OUT_BIT);
            self.sync.touch(bits);
            self.sync.io_seen = io;
        }
    }

    /// Notes that analog inputs were set from outside.
    pub(super) fn note_analog_inputs(&mut self) {
        self.sync.touch(ANALOG_IN_BITS);
    }
}

/// Stores `v` and notes a change (bit for bit) of the data of `bit`.
#[inline]
fn set(to: &mut f64, v: f64, bit: u64, touched: &mut Touched) {
    if to.to_bits() != v.to_bits() {
        *to = v;
        touched.touch(bit);
    }
}

//! The position loop of every axis: the actual value that follows the interpolator's setpoint.
//!
//! Input: the setpoint of each channel axis per IPO cycle (machine coordinates), the block's
//! FFWON/FFWOF (G group 24) and per axis MD32200 `POSCTRL_GAIN` (Kv), MD32620 `FFW_MODE`,
//! MD32630 `FFW_ACTIVATION_MODE`. Output: the actual value (`$AA_IM`) and the following error.
//!
//! The model is the first-order position loop of the Function Manual (G2 velocities, K3
//! feed-forward): the speed controller is ideal, so the axis moves at
//! `ff·v_set + Kv·(x_set − x_act)`, and the following error `e = x_set − x_act` obeys
//! `de/dt = (1 − ff)·v_set − Kv·e`. Without feed-forward (`ff = 0`) it settles at `v/Kv` at
//! constant velocity (Kv = 1 (m/min)/mm: 1 mm at 1 m/min); with the ideal speed feed-forward
//! (`ff = 1`) it stays zero: the drive's own equivalent time constant, which leaves a few µm
//! on a real machine, is not modelled. Each cycle solves the equation exactly for the cycle's
//! constant setpoint velocity: `e ← α·e + (1 − ff)·v·(1 − α)/Kv` with `α = e^(−Kv·dt)`.
//!
//! Spindles and axes without a position loop of their own (a transformation's virtual axes)
//! follow their setpoint. A setpoint jump faster than twice the axis' maximum velocity is not a
//! motion (a reset placing the axes, a restored session): the actual value jumps with it.

use crate::machine_data::MachineConfig;
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::AxisVec;

/// The position loops of a channel's axes.
#[derive(Debug, Clone)]
pub struct Servo {
    /// Following error per channel axis (setpoint − actual).
    error: AxisVec,
    /// The setpoint of the last cycle.
    setpoint: AxisVec,
    /// Feed-forward active per axis (MD32630 = 2 switches only at standstill).
    ffw: [bool; MAX_CHANNEL_AXES],
    /// Per axis: `α = e^(−Kv·dt)`, `(1 − α)/Kv`, the largest setpoint step that is a motion,
    /// whether the axis has a position loop, and its FFW data.
    alpha: AxisVec,
    gain: AxisVec,
    max_step: AxisVec,
    looped: [bool; MAX_CHANNEL_AXES],
    ffw_available: [bool; MAX_CHANNEL_AXES],
    ffw_activation: [u8; MAX_CHANNEL_AXES],
    axes: usize,
    dt: f64,
    /// Every error is exactly zero: the actual value is the setpoint without arithmetic.
    settled: bool,
    /// The errors changed since [`Servo::take_changed`] last handed them out.
    changed: bool,
    /// Every loop is fed forward and settled while the program's FFWON/FFWOF is this value:
    /// a cycle has nothing to compute (the usual case, kept off the IPO cycle's cost).
    idle_while: Option<bool>,
    /// `setpoint` was not kept up to date while idle.
    stale: bool,
}

impl Servo {
    /// The loops of `cfg`'s channel axes at rest at `setpoint`, feed-forward as after reset.
    pub fn new(cfg: &MachineConfig, setpoint: &AxisVec) -> Servo {
        let dt = cfg.ipo_cycle;
        let mut s = Servo {
            error: [0.0; MAX_CHANNEL_AXES],
            setpoint: *setpoint,
            ffw: [false; MAX_CHANNEL_AXES],
            alpha: [0.0; MAX_CHANNEL_AXES],
            gain: [0.0; MAX_CHANNEL_AXES],
            max_step: [f64::INFINITY; MAX_CHANNEL_AXES],
            looped: [false; MAX_CHANNEL_AXES],
            ffw_available: [false; MAX_CHANNEL_AXES],
            ffw_activation: [0; MAX_CHANNEL_AXES],
            axes: cfg.channel_axes.len().min(MAX_CHANNEL_AXES),
            dt,
            settled: true,
            changed: false,
            idle_while: None,
            stale: false,
        };
        for k in 0..s.axes {
            let ax = cfg.axis(k);
            let d = &ax.dynamics;
            s.looped[k] = ax.spindle.is_none() && d.kv.is_finite();
            if s.looped[k] {
                s.alpha[k] = (-d.kv * dt).exp();
                s.gain[k] = (1.0 - s.alpha[k]) / d.kv;
                s.max_step[k] = 2.0 * ax.max_velocity * dt;
            }
            s.ffw_available[k] = d.ffw_available;
            s.ffw_activation[k] = d.ffw_activation;
            s.ffw[k] = s.ffw_wanted(k, cfg.dynamics.reset_ffw);
        }
        s
    }

    /// Feed-forward of axis `k` when the program asks for `program` (FFWON).
    fn ffw_wanted(&self, k: usize, program: bool) -> bool {
        self.ffw_available[k] && (self.ffw_activation[k] == 0 || program)
    }

    /// One IPO cycle: the axes' new setpoints and the executing block's FFWON/FFWOF.
    #[inline]
    pub fn step(&mut self, setpoint: &AxisVec, ffw_program: bool) {
        if self.idle_while == Some(ffw_program) {
            self.stale = true;
            return;
        }
        self.track(setpoint, ffw_program);
    }

    /// [`Servo::step`] with a loop to compute (out of line: the idle cycle stays small).
    #[inline(never)]
    fn track(&mut self, setpoint: &AxisVec, ffw_program: bool) {
        if std::mem::take(&mut self.stale) {
            // Back from idle (FFWOF programmed): this cycle's velocity is not known, the loop
            // starts lagging from the next one.
            self.setpoint = *setpoint;
        }
        let mut settled = true;
        let mut all_fed = true;
        for (k, (&to, &from)) in setpoint.iter().zip(&self.setpoint).enumerate().take(self.axes) {
            let step = to - from;
            let wanted = self.ffw_wanted(k, ffw_program);
            if wanted != self.ffw[k] && (self.ffw_activation[k] != 2 || step == 0.0) {
                self.ffw[k] = wanted;
            }
            if !self.looped[k] || step.abs() > self.max_step[k] {
                self.error[k] = 0.0;
                continue;
            }
            all_fed &= self.ffw[k] && wanted;
            if self.ffw[k] && self.error[k] == 0.0 {
                continue;
            }
            let v = if self.ffw[k] { 0.0 } else { step / self.dt };
            let e = self.alpha[k] * self.error[k] + v * self.gain[k];
            // Below a nanometre the loop has settled (and stays exactly on the setpoint).
            self.error[k] = if e.abs() < 1e-9 && v == 0.0 { 0.0 } else { e };
            settled &= self.error[k] == 0.0;
        }
        self.changed |= !(settled && self.settled);
        self.settled = settled;
        self.setpoint = *setpoint;
        self.idle_while = (settled && all_fed).then_some(ffw_program);
    }

    /// Axis `k`'s setpoint moved by `d` without motion (PRESETON): the loop follows at once.
    pub fn shift(&mut self, k: usize, d: f64) {
        self.setpoint[k] += d;
    }

    /// The axes are put at `setpoint` at rest (reset, restored positions).
    pub fn place(&mut self, setpoint: &AxisVec) {
        self.setpoint = *setpoint;
        self.stale = false;
        self.error = [0.0; MAX_CHANNEL_AXES];
        self.changed |= !self.settled;
        self.settled = true;
    }

    /// The following errors, when they changed since the last call (block preparation reads
    /// `$AA_IM` through them; a settled loop costs it nothing).
    #[inline]
    pub fn take_changed(&mut self) -> Option<&AxisVec> {
        std::mem::take(&mut self.changed).then_some(&self.error)
    }

    /// Following error of channel axis `k` (setpoint − actual).
    pub fn following_error(&self, k: usize) -> f64 {
        self.error[k]
    }

    /// Following errors of every channel axis.
    pub fn errors(&self) -> &AxisVec {
        &self.error
    }

    /// True when every following error is zero.
    pub fn is_settled(&self) -> bool {
        self.settled
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine_data::MachineData;

    fn mill(md: &str) -> MachineConfig {
        let mut data = MachineData::default();
        data.apply_text(crate::machine_data::presets::find("mill-3axis").unwrap().text).unwrap();
        data.apply_text(md).unwrap()
    }

    #[test]
    fn without_feed_forward_the_error_settles_at_velocity_over_kv() {
        // Kv = 2 (m/min)/mm = 33.33 1/s; X at 6 m/min = 100 mm/s: e = v/Kv = 3 mm after a
        // few time constants (30 ms); 0.1 s per 25 cycles, 2 s is 66 time constants.
        let cfg = mill("$MA_POSCTRL_GAIN[X]=2\n$MC_GCODE_RESET_VALUES[23]=1");
        let mut s = Servo::new(&cfg, &[0.0; MAX_CHANNEL_AXES]);
        let mut x = [0.0; MAX_CHANNEL_AXES];
        for _ in 0..500 {
            x[0] += 100.0 * cfg.ipo_cycle;
            s.step(&x, false);
        }
        assert!((s.following_error(0) - 3.0).abs() < 1e-9, "{}", s.following_error(0));
        // With FFWON (activation mode 1: at once) the error decays and stays zero.
        for _ in 0..500 {
            x[0] += 100.0 * cfg.ipo_cycle;
            s.step(&x, true);
        }
        assert_eq!(s.following_error(0), 0.0);
    }

    #[test]
    fn ffw_mode_zero_never_feeds_forward_and_activation_zero_ignores_the_program() {
        let cfg = mill("$MA_FFW_MODE[X]=0\n$MA_FFW_ACTIVATION_MODE[Y]=0");
        let s = Servo::new(&cfg, &[0.0; MAX_CHANNEL_AXES]);
        assert!(!s.ffw_wanted(0, true));
        assert!(s.ffw_wanted(1, false));
        assert!(!s.ffw_wanted(2, false) && s.ffw_wanted(2, true));
    }
}

//! Where an axis reached its velocity or acceleration limit, for a program check (the HMI's
//! 3D view marks these points on the programmed path).
//!
//! Input: the channel after each IPO cycle ([`LimitWatch::observe`]). Output: a bounded list of
//! [`LimitHit`]s and the count of all hits. The axis velocity and acceleration are the
//! interpolator's setpoints differenced over the IPO cycle, compared with `$MA_MAX_AX_VELO`
//! and `$MA_MAX_AX_ACCEL`. A hit is one episode: it begins when the value reaches the limit
//! (within [`REACHED`]) and ends when it falls below [`RELEASED`] of it, so an axis running at
//! its limit for a whole block is one hit, not one per cycle.
//!
//! Decisions where the manuals are silent: rapid traverse (no programmed feed) is not watched,
//! since G0 runs the axes at their limits by design; spindles are not watched; a modulo axis is
//! differenced the short way round its modulo range. Nothing here changes the channel, and a
//! channel that is not observed pays nothing.

use super::Channel;
use super::workpiece_tip::TipProbe;
use crate::machine_data::registry::MAX_CHANNEL_AXES;

/// Share of the limit at which a hit begins (numerical slack of the differenced setpoints).
pub const REACHED: f64 = 0.995;
/// Share of the limit below which a hit has ended.
pub const RELEASED: f64 = 0.9;
/// Hits kept by default; further ones are only counted.
pub const DEFAULT_KEPT: usize = 256;

/// Which limit an axis reached.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LimitKind {
    /// `$MA_MAX_AX_VELO`.
    Velocity,
    /// `$MA_MAX_AX_ACCEL`.
    Acceleration,
}

/// One axis reaching one of its limits.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitHit {
    /// The channel axis by its program name.
    pub axis: String,
    pub kind: LimitKind,
    /// The axis' velocity (mm/s or °/s) or acceleration (mm/s² or °/s²) in that cycle, by
    /// magnitude.
    pub value: f64,
    /// The limit it reached.
    pub limit: f64,
    /// Program line of the block in execution (0 when none).
    pub line: u32,
    /// The tool tip on the workpiece then (`workpiece_tip.rs`: through the kinematics on a
    /// turned table; the unrolled surface under TRACYL), in `geo_names` order, absent ones 0.
    pub basic: [f64; 3],
    /// The TRACYL working diameter when the hit was under TRACYL (`basic` is then unrolled).
    pub tracyl_diameter: Option<f64>,
    /// `false`: a rotary axis the kinematics do not describe had turned the workpiece, so
    /// `basic` is the BCS, not known to be on the workpiece.
    pub exact: bool,
    /// Simulated time of the cycle in seconds.
    pub time: f64,
}

/// Watches a channel cycle by cycle for axes at their limits.
#[derive(Debug, Clone)]
pub struct LimitWatch {
    kept: usize,
    hits: Vec<LimitHit>,
    total: usize,
    prev_pos: Option<[f64; MAX_CHANNEL_AXES]>,
    prev_vel: Option<[f64; MAX_CHANNEL_AXES]>,
    /// Per axis: an episode of (velocity, acceleration) is in progress.
    active: [[bool; 2]; MAX_CHANNEL_AXES],
    /// Where a hit is on the workpiece (asked only when a hit is kept).
    probe: TipProbe,
}

impl Default for LimitWatch {
    fn default() -> Self {
        LimitWatch::new(DEFAULT_KEPT)
    }
}

impl LimitWatch {
    /// A watch that keeps the first `kept` hits and counts the rest.
    pub fn new(kept: usize) -> LimitWatch {
        LimitWatch {
            kept,
            hits: Vec::new(),
            total: 0,
            prev_pos: None,
            prev_vel: None,
            active: [[false; 2]; MAX_CHANNEL_AXES],
            probe: TipProbe::default(),
        }
    }

    /// The hits kept, in the order they happened.
    pub fn hits(&self) -> &[LimitHit] {
        &self.hits
    }

    /// Every hit, the kept ones and those only counted.
    pub fn total(&self) -> usize {
        self.total
    }

    /// Looks at the cycle the channel has just interpolated. Call once after every
    /// `Channel::step`; a gap (cycles not observed) only delays the differences by a cycle.
    pub fn observe(&mut self, ch: &Channel) {
        let cfg = ch.config();
        let pos_now = ch.axis_positions();
        let n = pos_now.len().min(MAX_CHANNEL_AXES);
        let mut pos = [0.0; MAX_CHANNEL_AXES];
        pos[..n].copy_from_slice(&pos_now[..n]);
        let t = cfg.ipo_cycle;
        let Some(prev) = self.prev_pos.replace(pos) else { return };
        let mut vel = [0.0; MAX_CHANNEL_AXES];
        for k in 0..n {
            let mut d = pos[k] - prev[k];
            if let Some((_, size)) = cfg.axis(k).modulo.filter(|&(_, s)| s > 0.0) {
                d -= size * (d / size).round();
            }
            vel[k] = d / t;
        }
        let Some(prev_vel) = self.prev_vel.replace(vel) else { return };
        let mut rapid: Option<bool> = None;
        for k in 0..n {
            let axis = cfg.axis(k);
            if axis.spindle.is_some() {
                continue;
            }
            let values = [vel[k].abs(), ((vel[k] - prev_vel[k]) / t).abs()];
            let limits = [axis.max_velocity, axis.max_accel];
            for (i, kind) in [LimitKind::Velocity, LimitKind::Acceleration].into_iter().enumerate() {
                if limits[i].is_nan() || limits[i] <= 0.0 {
                    continue;
                }
                if self.active[k][i] {
                    self.active[k][i] = values[i] >= RELEASED * limits[i];
                    continue;
                }
                if values[i] < REACHED * limits[i] {
                    continue;
                }
                // Reached: rapid traverse is not watched (looked up once per cycle, and only
                // when some axis reached a limit).
                // The episode begins either way, so a long G0 is looked at once.
                self.active[k][i] = true;
                let snap = ch.snapshot();
                if *rapid.get_or_insert_with(|| snap.programmed_feed.is_none()) {
                    continue;
                }
                self.total += 1;
                if self.hits.len() < self.kept {
                    let at = self.probe.tip(ch);
                    self.hits.push(LimitHit {
                        axis: cfg.program_axis_name(k).to_string(),
                        kind,
                        value: values[i],
                        limit: limits[i],
                        line: snap.block.as_ref().map_or(0, |b| b.line),
                        basic: at.tip,
                        tracyl_diameter: at.tracyl_diameter,
                        exact: at.exact,
                        time: ch.time(),
                    });
                }
            }
        }
    }
}

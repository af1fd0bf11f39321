//! Set WO (Operate's JOG area, "Set WO"): the operator types the position an axis should read in
//! the workpiece coordinate system; the difference to the position it reads now goes into the
//! active settable work offset (`$P_UIFR[n]` of G500/G54.., group 8), so the axis reads the typed
//! value without moving. Like the offsets screen, only in reset state; the change is stored in
//! the frame data and is active at once (MD9440 ACTIVATE_SEL_USER_DATA = 1 behaviour).
//!
//! The translation change is the typed difference mapped through the active frame's rotation,
//! scale and mirror (a rotated G54 shifts along the rotated axis, the other axes keep reading
//! what they read). Basic frames before the settable frame are taken not to rotate.

use super::{Channel, CommandError, Status};

impl Channel {
    /// Sets the active work offset so that `axis` (its name in the WCS display) reads `value`
    /// (a diameter on the transverse axis under DIAMON). Reset state only; not with an active
    /// kinematic transformation (the WCS then is not a frame away from the axes).
    pub fn set_work_offset(&mut self, axis: &str, value: f64) -> Result<(), CommandError> {
        if self.is_active() || self.status == Status::Stopped {
            return Err(CommandError::Busy("Set WO is possible in reset state only"));
        }
        if !value.is_finite() || value.abs() > SET_WO_LIMIT {
            return Err(CommandError::Invalid(format!(
                "Set WO: {} is no position (finite, within ±{SET_WO_LIMIT} mm or degrees)",
                crate::alarm::Alarm::shown(value)
            )));
        }
        if self.trafo.is_some() {
            return Err(CommandError::Invalid(
                "Set WO with an active transformation: switch it off (TRAFOOF) first".into(),
            ));
        }
        let cfg = &self.cfg;
        let n = cfg.channel_axes.len();
        // The WCS display names geometry axes by their geometry name, the others by channel name.
        let display_name = |k: usize| match cfg.geo_axes.iter().position(|g| *g == Some(k)) {
            Some(g) => cfg.geo_names[g].clone(),
            None => cfg.channel_axes[k].name.clone(),
        };
        let k = (0..n)
            .find(|&k| display_name(k).eq_ignore_ascii_case(axis))
            .ok_or_else(|| CommandError::UnknownAxis(axis.to_string()))?;
        let shown = self
            .snapshot()
            .workpiece
            .iter()
            .find(|(name, _)| *name == display_name(k))
            .map(|(_, v)| *v)
            .ok_or_else(|| CommandError::UnknownAxis(axis.to_string()))?;
        let mut delta = shown - value;
        if cfg.transverse_axis == Some(k) && self.offsets.gcodes.diameter_display() {
            delta /= 2.0;
        }
        let frame_n = self.interp.modal().work_offset;
        let mut along = [0.0; crate::machine_data::registry::MAX_CHANNEL_AXES];
        along[k] = delta;
        let shift = self.offsets.frame.apply_vector(&cfg.geo_axes, &along);
        let before = cfg.work_offsets.get(frame_n).map(|f| f.trans.clone()).unwrap_or_default();
        let lines: Vec<String> = (0..n)
            .filter(|&j| shift[j] != 0.0)
            .map(|j| {
                let tr = before.get(j).copied().unwrap_or(0.0) + shift[j];
                format!("$P_UIFR[{frame_n},{},TR]={}", display_name(j), round_nm(tr))
            })
            .collect();
        for line in &lines {
            self.data.stage_text(line)?;
        }
        std::sync::Arc::make_mut(&mut self.cfg)
            .refresh_data(&self.data)
            .map_err(|e| CommandError::Invalid(e.message))?;
        // The active frame is built again from the data, as a reset does (reset state: the
        // modal state is the reset state already).
        let pos = self.machine;
        self.interp.reset(&self.cfg, &pos);
        self.offsets = self.interp.offsets();
        self.adopt_transformation();
        Ok(())
    }
}

/// The largest position Set WO takes, as the swivel screen's fields: an operator's typo of
/// 1e308 would otherwise overflow the offset's translation.
const SET_WO_LIMIT: f64 = 1e6;

/// A translation to 1e-9 mm: what the data text keeps without float noise (0.1 + 0.2).
fn round_nm(v: f64) -> f64 {
    (v * 1e9).round() / 1e9
}

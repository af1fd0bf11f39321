//! The machine and setting data of continuous-path mode, exact stop and the compressor
//! (Function Manual B1), typed once at activation so block preparation reads plain numbers.

use super::MachineData;

/// Tolerances and limits of G641..G645, G601/G602 and COMPON/COMPCAD, per channel axis where
/// the datum is axial.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PathControlData {
    /// MD20480 SMOOTHING_MODE: which tolerances G643 (units digit), G642 and G645 (tens digit)
    /// and G644 (thousands digit) take.
    pub smoothing_mode: i64,
    /// MD20170 COMPRESS_BLOCK_PATH_LIMIT (mm): longer blocks end a compressed section.
    pub block_path_limit: f64,
    /// MD20172 COMPRESS_VELO_TOL (mm/min): the feed change a compressed section tolerates.
    pub velo_tol: f64,
    /// MD33100 COMPRESS_POS_TOL per channel axis (mm or degrees).
    pub axis_tol: Vec<f64>,
    /// MD33120 PATH_TRANS_POS_TOL per channel axis: G645 at tangential transitions.
    pub trans_tol: Vec<f64>,
    /// MD36010 STOP_LIMIT_FINE (G601) and MD36000 STOP_LIMIT_COARSE (G602) per channel axis.
    pub stop_fine: Vec<f64>,
    pub stop_coarse: Vec<f64>,
    /// MD20550 EXACT_POS_MODE: a fixed exact-stop window for G0 (units) and G1.. (tens).
    pub exact_pos_mode: i64,
    /// SD42465 SMOOTH_CONTUR_TOL (mm): setting data, acting at once.
    pub contour_tol: f64,
    /// SD42466 SMOOTH_ORI_TOL (degrees).
    pub ori_tol: f64,
    /// MD20178 ORISON_BLOCK_PATH_LIMIT (mm): longer blocks interrupt ORISON's smoothing.
    pub orison_block_limit: f64,
    /// MD28590 MM_ORISON_BLOCKS: ORISON acts from 4 on; it bounds how many blocks a
    /// smoothing section reaches (`motion::orison`).
    pub orison_blocks: i64,
    /// SD42678 ORISON_TOL (degrees) and SD42680 ORISON_DIST (mm).
    pub orison_tol: f64,
    pub orison_dist: f64,
}

impl PathControlData {
    /// Reads the data; `machine_numbers[k]` is the machine axis number (1-based) of channel
    /// axis `k`.
    pub(super) fn read(md: &MachineData, machine_numbers: &[usize]) -> PathControlData {
        let axial = |name: &str| machine_numbers.iter().map(|&m| md.num(name, m - 1, 0)).collect::<Vec<_>>();
        let mut data = PathControlData {
            smoothing_mode: md.num("$MC_SMOOTHING_MODE", 0, 0) as i64,
            block_path_limit: md.num("$MC_COMPRESS_BLOCK_PATH_LIMIT", 0, 0),
            velo_tol: md.num("$MC_COMPRESS_VELO_TOL", 0, 0),
            axis_tol: axial("$MA_COMPRESS_POS_TOL"),
            trans_tol: axial("$MA_PATH_TRANS_POS_TOL"),
            stop_fine: axial("$MA_STOP_LIMIT_FINE"),
            stop_coarse: axial("$MA_STOP_LIMIT_COARSE"),
            exact_pos_mode: md.num("$MC_EXACT_POS_MODE", 0, 0) as i64,
            contour_tol: 0.0,
            ori_tol: 0.0,
            orison_block_limit: md.num("$MC_ORISON_BLOCK_PATH_LIMIT", 0, 0),
            orison_blocks: md.num("$MC_MM_ORISON_BLOCKS", 0, 0) as i64,
            orison_tol: 0.0,
            orison_dist: 0.0,
        };
        data.refresh_settings(md);
        data
    }

    /// Takes over the setting data, which act without NEWCONF.
    pub(super) fn refresh_settings(&mut self, md: &MachineData) {
        self.contour_tol = md.num("$SC_SMOOTH_CONTUR_TOL", 0, 0);
        self.ori_tol = md.num("$SC_SMOOTH_ORI_TOL", 0, 0);
        self.orison_tol = md.num("$SC_ORISON_TOL", 0, 0);
        self.orison_dist = md.num("$SC_ORISON_DIST", 0, 0);
    }
}

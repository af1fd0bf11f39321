//! Cartesian PTP travel with the generic 5/6-axis transformation: which of the two
//! orientation solutions `STAT=` names, and where the rotary axes go without `TU=`.
//!
//! The Programming Manual (Job planning, "Cartesian PTP travel", generic 5/6-axis
//! transformation) defines STAT bit 0 relative to the start: 0 (the default) approaches the
//! rotary-axis positions at the shorter distance from the start positions, 1 those at the
//! greater distance. The distance is the sum of the orientation axes' travel in degrees (the
//! manual names no weighting); a modulo axis counts its shorter way round, as it travels
//! without TU. On equal distances (a start exactly between the two) bit 0 = 0 keeps the
//! solution with the lower position of the first orientation axis.
//!
//! Other transformations: TRANSMIT uses STAT for its pole ambiguity (`Transmit::ptp_end`:
//! bit 0 turns C through +180° or −180°, bit 1 travels through the pole or rotates in it;
//! Transformations FM, Cartesian PTP travel); the robot transformations (RCTRA, ROBX) use bits
//! 0..2 for shoulder, elbow and hand flip, which this product does not have. TRACYL, TRAANG
//! and TRACON's second member have one solution.

use crate::kinematics::unwrap_near;
use crate::machine_data::MachineConfig;
use crate::motion::AxisVec;

/// Travel in degrees from `start` to `to` of orientation axis `k`: the shorter way round on a
/// modulo axis, the straight difference on one with limits.
fn travel(cfg: &MachineConfig, k: usize, start: &AxisVec, to: f64) -> f64 {
    match cfg.axis(k).modulo {
        Some(_) => (unwrap_near(to, start[k]) - start[k]).abs(),
        None => (to - start[k]).abs(),
    }
}

/// The two solutions (by role, like `slots`), sorted lower first axis first, reordered so the
/// one nearer to the machine position `start` comes first: index 0 is `STAT=0`, 1 is `STAT=1`.
pub fn nearer_first(
    both: [[f64; 3]; 2],
    slots: &[Option<usize>; 3],
    start: &AxisVec,
    cfg: &MachineConfig,
) -> [[f64; 3]; 2] {
    let distance = |s: &[f64; 3]| -> f64 {
        slots.iter().enumerate().filter_map(|(role, k)| k.map(|k| travel(cfg, k, start, s[role]))).sum()
    };
    let [lower, higher] = both;
    if distance(&higher) < distance(&lower) - 1e-9 { [higher, lower] } else { both }
}

/// Without `TU=` a modulo orientation axis takes the shorter way from `start` (whole turns
/// added to its end position in `end`); an axis with limits keeps its solution's position.
pub fn shortest_way(end: &mut AxisVec, slots: &[Option<usize>; 3], start: &AxisVec, cfg: &MachineConfig) {
    for &k in slots.iter().flatten() {
        if cfg.axis(k).modulo.is_some() {
            end[k] = unwrap_near(end[k], start[k]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine_data::{MachineData, presets};

    fn head_ca() -> MachineConfig {
        MachineData::default().apply_text(presets::find("mill5-head-ca").unwrap().text).unwrap()
    }

    #[test]
    fn stat_0_is_the_solution_nearer_to_the_start() {
        let cfg = head_ca();
        let slots = [Some(4), Some(3), None];
        // Orientation (1, 0, 1)/√2 on the C-A head: C90 A45 or C−90 A−45 (by role: C, A).
        let both = [[-90.0, -45.0, 0.0], [90.0, 45.0, 0.0]];
        let mut start = [0.0; crate::machine_data::registry::MAX_CHANNEL_AXES];
        // From A5 C10: |90 − 10| + |45 − 5| = 120 against |−90 − 10| + |−45 − 5| = 150.
        start[3] = 5.0;
        start[4] = 10.0;
        assert_eq!(nearer_first(both, &slots, &start, &cfg), [[90.0, 45.0, 0.0], [-90.0, -45.0, 0.0]]);
        // From A−5 C−10 the lower one is nearer (150 against 120 the other way).
        start[3] = -5.0;
        start[4] = -10.0;
        assert_eq!(nearer_first(both, &slots, &start, &cfg), both);
        // From A0 C0 both are 135 away: the lower first axis stays first.
        start[3] = 0.0;
        start[4] = 0.0;
        assert_eq!(nearer_first(both, &slots, &start, &cfg), both);
        // C at 350: C90 is 100 away the short way round, C−90 (= 270) 80; A0 → 45 either way.
        start[4] = 350.0;
        assert_eq!(nearer_first(both, &slots, &start, &cfg), both);
    }
}

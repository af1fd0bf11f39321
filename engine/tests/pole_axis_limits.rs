//! No machine axis exceeds its velocity (MD32000 `MAX_AX_VELO`) or acceleration (MD32300
//! `MAX_AX_ACCEL`) in any IPO cycle when the tool orientation passes close to the pole of an
//! orientation transformation, where one rotary axis has to turn fast for a small change of
//! the orientation: the look-ahead reduces the path feed there, as it does for linear axes.
//!
//! The check takes the sampled machine setpoints of every IPO cycle and their first and second
//! differences: v_i = (m_i − m_{i−1})/T and a_i = (v_i − v_{i−1})/T. The backward differences
//! are averages over one cycle of the true velocity and acceleration, so they stay within the
//! limits whenever those do; the tolerance (1 % and a rounding floor) covers the planner's
//! per-cycle discretisation only. A velocity jump at a block transition within MD32310
//! `MAX_ACCEL_OVL_FACTOR` is the control's documented allowance and counts against
//! `a_max · factor`.

use nctwin_engine::Channel;
use proptest::prelude::*;

const MAX_TICKS: usize = 400_000;

/// All orientation-transformation presets.
const TRAORI_PRESETS: [&str; 5] =
    ["mill5-head-ca", "mill5-table-ac", "mill5-mixed-bc", "mill6-generic", "mill7-generic"];

/// Runs `program` on `preset` and describes the first IPO cycle in which an axis exceeds a
/// limit, or `None`; also the alarms at the end and the number of cycles.
fn check(preset: &str, program: &str) -> (Option<String>, Vec<u32>, usize) {
    let mut ch = Channel::from_preset(preset, "").unwrap();
    ch.run_program(program).unwrap();
    let cfg = ch.config().clone();
    let t = cfg.ipo_cycle;
    // The tool spindle without axis function is not among the positions.
    let n = cfg.channel_axes.len().min(ch.axis_positions().len());
    let mut prev: Option<Vec<f64>> = None;
    let mut prev_v: Option<Vec<f64>> = None;
    let mut cycles = 0;
    let mut found = None;
    while ch.is_busy() {
        ch.step();
        cycles += 1;
        assert!(cycles < MAX_TICKS, "{preset}: program does not end");
        let m = ch.axis_positions()[..n].to_vec();
        if let Some(p) = &prev {
            let v: Vec<f64> = (0..n)
                .map(|k| {
                    let mut d = m[k] - p[k];
                    if cfg.axis(k).modulo.is_some() {
                        d = (d + 180.0).rem_euclid(360.0) - 180.0;
                    }
                    d / t
                })
                .collect();
            for k in 0..n {
                let ax = cfg.axis(k);
                if ax.spindle.is_some() || found.is_some() {
                    continue;
                }
                let v_lim = ax.max_velocity * 1.01 + 1e-6;
                if v[k].abs() > v_lim {
                    found =
                        Some(format!("{} velocity {} against {} in cycle {cycles}", ax.name, v[k], ax.max_velocity));
                    continue;
                }
                if let Some(pv) = &prev_v {
                    let a_lim = ax.max_accel * ax.accel_overload.max(1.0);
                    // An axis reversing stops between two cycles: each side then comes to or
                    // from rest within its own cycle, so each cycle's mean velocity is bounded
                    // by a·T (the standstill between them is no sample of its own).
                    let a = if v[k] * pv[k] < 0.0 { v[k].abs().max(pv[k].abs()) / t } else { (v[k] - pv[k]) / t };
                    if a.abs() > a_lim * 1.01 + 1e-3 {
                        found = Some(format!("{} acceleration {a} against {a_lim} in cycle {cycles}", ax.name));
                    }
                }
            }
            prev_v = Some(v);
        }
        prev = Some(m);
    }
    let alarms = ch.snapshot().alarms.iter().map(|a| a.number).collect();
    (found, alarms, cycles)
}

/// The first row of the benchmark's mill5 program (gen_program.py --kind mill5 --blocks 60,
/// the blocks after `G1 Z0 F400` and the step to row 1): leaving the pole at X65 and passing
/// about 1° from it, then tilting up to 18° away, 1 mm per block at F1800.
const BENCH_ROW: &str = "\
G71 G17 G90 G94 G40 G54
T1 D1
TRAORI
ORIWKS
ORIVECT
G0 X65 Y5 Z5 A3=0 B3=0 C3=1
G1 Z0 F400
G1 F1800
X65 Y5 Z-2.0957 A3=0.0209 B3=-0.0454 C3=0.9987
X66 Y5 Z-1.9457 A3=0.0195 B3=0.0012 C3=0.9998
X67 Y5 Z-1.7957 A3=0.0211 B3=0.0479 C3=0.9986
X68 Y5 Z-1.649 A3=0.0257 B3=0.0932 C3=0.9953
X69 Y5 Z-1.5083 A3=0.033 B3=0.1361 C3=0.9901
X70 Y5 Z-1.3766 A3=0.043 B3=0.1756 C3=0.9835
X71 Y5 Z-1.2566 A3=0.0553 B3=0.2107 C3=0.976
X72 Y5 Z-1.1507 A3=0.0696 B3=0.2409 C3=0.968
X73 Y5 Z-1.0611 A3=0.0856 B3=0.2658 C3=0.9602
X74 Y5 Z-0.9896 A3=0.103 B3=0.285 C3=0.953
X75 Y5 Z-0.9377 A3=0.1214 B3=0.2984 C3=0.9467
X76 Y5 Z-0.9063 A3=0.1405 B3=0.306 C3=0.9416
X77 Y5 Z-0.8963 A3=0.1601 B3=0.3077 C3=0.9379
X78 Y5 Z-0.9077 A3=0.1797 B3=0.3037 C3=0.9357
X79 Y5 Z-0.9403 A3=0.1992 B3=0.2939 C3=0.9348
X80 Y5 Z-0.9935 A3=0.2181 B3=0.2786 C3=0.9353
X81 Y5 Z-1.0662 A3=0.2361 B3=0.2578 C3=0.9369
X82 Y5 Z-1.1568 A3=0.2528 B3=0.232 C3=0.9393
X83 Y5 Z-1.2636 A3=0.2678 B3=0.2013 C3=0.9422
X84 Y5 Z-1.3844 A3=0.2807 B3=0.1664 C3=0.9452
X85 Y5 Z-1.5168 A3=0.2912 B3=0.1278 C3=0.9481
X86 Y5 Z-1.6579 A3=0.299 B3=0.0864 C3=0.9503
X87 Y5 Z-1.805 A3=0.3037 B3=0.0429 C3=0.9518
X88 Y5 Z-1.955 A3=0.3052 B3=-0.0016 C3=0.9523
X89 Y5 Z-2.1049 A3=0.3035 B3=-0.046 C3=0.9517
X90 Y5 Z-2.2517 A3=0.2985 B3=-0.0894 C3=0.9502
X91 Y5 Z-2.3923 A3=0.2906 B3=-0.1307 C3=0.9479
X92 Y5 Z-2.5239 A3=0.2799 B3=-0.169 C3=0.945
X93 Y5 Z-2.6438 A3=0.2668 B3=-0.2037 C3=0.942
X94 Y5 Z-2.7495 A3=0.2516 B3=-0.234 C3=0.9391
X95 Y5 Z-2.839 A3=0.2348 B3=-0.2595 C3=0.9368
X96 Y5 Z-2.9103 A3=0.2168 B3=-0.2798 C3=0.9353
X97 Y5 Z-2.9621 A3=0.1978 B3=-0.2948 C3=0.9349
X98 Y5 Z-2.9932 A3=0.1783 B3=-0.3042 C3=0.9358
X99 Y5 Z-3.0031 A3=0.1587 B3=-0.3078 C3=0.9381
X100 Y5 Z-2.9915 A3=0.1391 B3=-0.3057 C3=0.9419
X101 Y5 Z-2.9587 A3=0.1201 B3=-0.2977 C3=0.9471
X102 Y5 Z-2.9053 A3=0.1017 B3=-0.2838 C3=0.9535
X103 Y5 Z-2.8325 A3=0.0844 B3=-0.2642 C3=0.9608
X104 Y5 Z-2.7417 A3=0.0686 B3=-0.2389 C3=0.9686
X105 Y5 Z-2.6347 A3=0.0544 B3=-0.2084 C3=0.9765
X105 Y7 Z-2.1652 A3=-0.1959 B3=-0.2377 C3=0.9514
G0 Z25
TRAFOOF
M30
";

/// A line whose tool vector sweeps across +Z at `miss` degrees beside it, from 20° on one
/// side to 20° on the other, under `feed`.
fn sweep_past_the_pole(miss: f64, feed: f64) -> String {
    let (s, m) = (20f64.to_radians().sin(), miss.to_radians().tan());
    format!(
        "G71 G17 G90 G94 G40 G54\nT1 D1\nTRAORI\nORIWKS\nORIVECT\nG0 X0 Y0 Z20 A3={s} B3={m} C3=1\n\
         G1 X20 Y0 Z20 A3={n} B3={m} C3=1 F{feed}\nG0 Z40\nTRAFOOF\nM30\n",
        n = -s
    )
}

#[test]
fn the_benchmark_row_near_the_pole_keeps_every_axis_within_its_limits_on_every_preset() {
    for preset in TRAORI_PRESETS {
        let (excess, alarms, cycles) = check(preset, BENCH_ROW);
        assert!(excess.is_none(), "{preset}: {excess:?} (alarms {alarms:?})");
        assert!(cycles > 100, "{preset}: {cycles} cycles");
    }
}

#[test]
fn a_sweep_across_the_pole_keeps_every_axis_within_its_limits_on_every_preset() {
    for preset in TRAORI_PRESETS {
        for (miss, feed) in [(3.0, 2000.0), (5.0, 5000.0), (0.5, 2000.0)] {
            let (excess, alarms, _) = check(preset, &sweep_past_the_pole(miss, feed));
            assert!(excess.is_none(), "{preset}, {miss}° beside the pole at F{feed}: {excess:?} (alarms {alarms:?})");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 16, failure_persistence: None, ..ProptestConfig::default() })]

    /// Random orientation paths: three blocks of random tip moves and tool vectors within 30°
    /// of +Z (often passing near the pole) on a random TRAORI preset.
    #[test]
    fn random_orientation_paths_keep_every_axis_within_its_limits(
        preset in 0usize..5,
        blocks in proptest::collection::vec(
            (-20.0f64..20.0, -20.0f64..20.0, -0.5f64..0.5, -0.5f64..0.5, 200.0f64..6000.0),
            3,
        ),
    ) {
        let mut program = String::from("G71 G17 G90 G94 G40 G54\nT1 D1\nTRAORI\nORIWKS\nORIVECT\nG0 X0 Y0 Z20 A3=0 B3=0.01 C3=1\n");
        for (x, y, a3, b3, f) in &blocks {
            program.push_str(&format!("G1 X{x:.3} Y{y:.3} Z20 A3={a3:.4} B3={b3:.4} C3=1 F{f:.0}\n"));
        }
        program.push_str("G0 Z40\nTRAFOOF\nM30\n");
        let preset = TRAORI_PRESETS[preset];
        let (excess, alarms, _) = check(preset, &program);
        prop_assert!(excess.is_none(), "{}: {:?} (alarms {:?})\n{}", preset, excess, alarms, program);
    }
}

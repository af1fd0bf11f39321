//! Online tool length offset `$AA_TOFF` / TOFFON / TOFFOF through the CA head of
//! `mill5-head-ca` and on the plain 3-axis mill.
//!
//! Closed form of the head (as in traori_channel.rs): C about Z carries A about X, A pivot 150
//! above the spindle nose, tool 100 long, so `M = P − (0, 0, 150) + (250 + ΔL)·o` with
//! `o = (sin C·sin A, −cos C·sin A, cos A)` and ΔL the online offset along the tool (Z).

use nctwin_engine::{Channel, Snapshot};

fn run(preset: &str, md: &str, program: &str) -> (Channel, Vec<Vec<f64>>) {
    let mut ch = Channel::from_preset(preset, md).unwrap();
    ch.run_program(program).unwrap();
    let mut samples = Vec::new();
    while ch.is_busy() {
        ch.step();
        samples.push(ch.axis_positions().to_vec());
        assert!(samples.len() < 1_000_000, "program does not end");
    }
    (ch, samples)
}

fn machine(s: &Snapshot, name: &str) -> f64 {
    s.machine.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no axis {name}")).1
}

fn head_machine(p: [f64; 3], a: f64, c: f64, dl: f64) -> [f64; 3] {
    let (sa, ca) = a.to_radians().sin_cos();
    let (sc, cc) = c.to_radians().sin_cos();
    let o = [sc * sa, -cc * sa, ca];
    let l = 250.0 + dl;
    [p[0] + l * o[0], p[1] + l * o[1], p[2] - 150.0 + l * o[2]]
}

fn assert_xyz(s: &Snapshot, m: [f64; 3]) {
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    for (name, v) in ["X", "Y", "Z"].iter().zip(m) {
        let got = machine(s, name);
        assert!((got - v).abs() < 1e-6, "{name}: {got} vs {v} ({:?})", s.machine);
    }
}

const HEAD: &str = "T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 A30\n";

#[test]
fn the_offset_lengthens_the_tool_along_its_orientation() {
    let (ch, _) = run("mill5-head-ca", "", &format!("{HEAD}$AA_TOFF[Z]=10\nR1=$AA_TOFF[Z]\nM0\nM30"));
    let s = ch.snapshot();
    assert_xyz(&s, head_machine([0.0, 0.0, 50.0], 30.0, 0.0, 10.0));
    assert_eq!(ch.r_param(1), 10.0);
    // The position display keeps the programmed tool tip (at M0, TRAORI still active).
    let wcs = |n: &str| s.workpiece.iter().find(|(a, _)| a == n).unwrap().1;
    assert!(wcs("X").abs() < 1e-6 && wcs("Y").abs() < 1e-6 && (wcs("Z") - 50.0).abs() < 1e-6, "{:?}", s.workpiece);
}

#[test]
fn the_tip_stays_on_the_path_of_a_move_with_the_offset_in_force() {
    let (ch, samples) = run("mill5-head-ca", "", &format!("{HEAD}$AA_TOFF[Z]=10\nR1=$AA_TOFF[Z]\nX50\nM30"));
    assert_xyz(&ch.snapshot(), head_machine([50.0, 0.0, 50.0], 30.0, 0.0, 10.0));
    // During X50 the machine is the tip on the line (X, 0, 50) moved back by 260·o.
    let o = head_machine([0.0; 3], 30.0, 0.0, 10.0);
    let moving: Vec<_> = samples.iter().filter(|m| m[0] - o[0] > 1.0 && m[0] - o[0] < 49.0).collect();
    assert!(moving.len() > 10);
    for m in moving {
        assert!((m[1] - o[1]).abs() < 1e-6 && (m[2] - (50.0 + o[2])).abs() < 1e-6, "{m:?}");
    }
}

#[test]
fn the_change_is_traversed_with_toff_velo_and_toff_accel() {
    // 600 mm/min = 10 mm/s, 1 m/s²: 12 mm take 12/10 + 10/1000 = 1.21 s (trapezoid); no cycle
    // moves the tool tip's holder more than 10 mm/s · 4 ms = 0.04 mm along the tool.
    let md = "$MC_TOFF_VELO=600.\n$MC_TOFF_ACCEL=1.";
    let (_, without) = run("mill5-head-ca", md, &format!("{HEAD}M30"));
    let (ch, with) = run("mill5-head-ca", md, &format!("{HEAD}$AA_TOFF[Z]=12\nM30"));
    assert_xyz(&ch.snapshot(), head_machine([0.0, 0.0, 50.0], 30.0, 0.0, 12.0));
    let before = without.len();
    let seconds = (with.len() - before) as f64 * 0.004;
    assert!((seconds - 1.21).abs() < 0.03, "{seconds}");
    for w in with[before - 1..].windows(2) {
        let d: f64 = (0..3).map(|i| (w[1][i] - w[0][i]).powi(2)).sum::<f64>().sqrt();
        assert!(d <= 0.04 + 1e-9, "{d}");
    }
}

#[test]
fn integrating_mode_adds_each_write() {
    let (ch, _) = run("mill5-head-ca", "$MC_TOFF_MODE=1", &format!("{HEAD}$AA_TOFF[Z]=3\n$AA_TOFF[Z]=4\nM30"));
    assert_xyz(&ch.snapshot(), head_machine([0.0, 0.0, 50.0], 30.0, 0.0, 7.0));
}

#[test]
fn toffon_sets_and_toffof_takes_the_offset_back() {
    let (ch, _) = run("mill5-head-ca", "", &format!("{HEAD}TOFFON(Z, 4)\nR1=$AA_TOFF[Z]\nM30"));
    assert_xyz(&ch.snapshot(), head_machine([0.0, 0.0, 50.0], 30.0, 0.0, 4.0));
    assert_eq!(ch.r_param(1), 4.0);
    let (ch, _) = run("mill5-head-ca", "", &format!("{HEAD}TOFFON(Z, 4)\nTOFFOF()\nR1=$AA_TOFF[Z]\nM30"));
    assert_xyz(&ch.snapshot(), head_machine([0.0, 0.0, 50.0], 30.0, 0.0, 0.0));
    assert_eq!(ch.r_param(1), 0.0);
}

#[test]
fn without_a_transformation_the_offset_adds_to_the_geometry_axis() {
    let (plain, _) = run("mill-3axis", "", "T1 D1\nG0 X0 Y0 Z10\nM30");
    let (ch, _) = run("mill-3axis", "", "T1 D1\nG0 X0 Y0 Z10\n$AA_TOFF[Z]=5\nM30");
    let (z0, z1) = (machine(&plain.snapshot(), "Z"), machine(&ch.snapshot(), "Z"));
    assert!((z1 - z0 - 5.0).abs() < 1e-9, "{z0} {z1}");
    let s = ch.snapshot();
    let wcs_z = s.workpiece.iter().find(|(a, _)| a == "Z").unwrap().1;
    assert!((wcs_z - 10.0).abs() < 1e-9, "{:?}", s.workpiece);
}

#[test]
fn a_direction_that_is_no_geometry_axis_is_refused_at_its_block() {
    let (ch, _) = run("mill5-head-ca", "", &format!("{HEAD}$AA_TOFF[A]=5\nM30"));
    assert!(ch.snapshot().alarms.iter().any(|a| a.line == Some(5)), "{:?}", ch.snapshot().alarms);
    let (ch, _) = run("mill5-head-ca", "", &format!("{HEAD}TOFFON()\nM30"));
    assert!(ch.snapshot().alarms.iter().any(|a| a.line == Some(5)), "{:?}", ch.snapshot().alarms);
}

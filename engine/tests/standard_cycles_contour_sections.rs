//! CYCLE95 with its contour given as a labelled section of the calling program (NPP
//! "START:END"), on the 2-axis lathe (X a radius): the section is read like the contour
//! subprogram, so the cycle cuts the same path as with the subprogram, and the roughing levels
//! and the finished contour are the ones worked out by hand for the shaft below.

use crate::turning_support;

use turning_support::{Trace, close, run_lathe, shaft_radius};

/// Runs `main` on the 2-axis lathe with a tool without nose radius (the theoretical tip is
/// guided on the contour) and keeps the samples from the arrival at the approach point X30 Z10.
fn run(main: &str, subs: &[(&str, &str)]) -> Trace {
    run_lathe("$TC_DP6[1,1]=0\n", main, subs).after_reaching(30.0, 10.0)
}

/// The shaft: X10 from Z0 to Z-20, a fillet R5 (centre Z-20 X15) to Z-25, the shoulder up to
/// X20, a taper to X25 at Z-40.
const CONTOUR: &str = "G1 X10 Z0\nG1 Z-20\nG2 X15 Z-25 CR=5\nG1 X20\n";
const LAST: &str = "G1 X25 Z-40\n";

const SETUP: &str = "G18 G90 G94\nT1 D1\nS800 M3\nG0 X30 Z10\n";
const CALL_ARGS: &str = "2,0.2,0.1,0,300,0,100,9,0,0,0)";

#[test]
fn cycle95_cuts_a_labelled_section_of_the_caller_as_it_cuts_the_subprogram() {
    // The contour as a subprogram, and as the section CONT_A..CONT_E behind the caller's M30
    // (labels) or N100..N140 (block numbers): the same path, IPO cycle by IPO cycle.
    let sub = format!("G18 G90\n{CONTOUR}{LAST}M17\n");
    let by_sub = run(&format!("{SETUP}CYCLE95(\"SHAFT\",{CALL_ARGS}\nM30\n"), &[("SHAFT", &sub)]);
    assert!(by_sub.alarms.is_empty(), "{:?}", by_sub.alarms);
    let mut lines = CONTOUR.lines();
    let first = lines.next().unwrap();
    let middle: String = lines.map(|l| format!("{l}\n")).collect();
    let labelled =
        format!("{SETUP}CYCLE95(\"CONT_A:CONT_E\",{CALL_ARGS}\nM30\nCONT_A: {first}\n{middle}CONT_E: {LAST}");
    let numbered = format!(
        "{SETUP}CYCLE95(\"N100:N140\",{CALL_ARGS}\nM30\nN100 {first}\n{}N140 {LAST}",
        middle.lines().enumerate().map(|(i, l)| format!("N{} {l}\n", 110 + 10 * i)).collect::<String>()
    );
    for main in [labelled, numbered] {
        let t = run(&main, &[]);
        assert!(t.alarms.is_empty(), "{main}: {:?}", t.alarms);
        assert_eq!(t.samples.len(), by_sub.samples.len(), "{main}");
        assert!(t.samples.iter().zip(&by_sub.samples).all(|(a, b)| a == b), "{main}: another path");
    }
}

#[test]
fn cycle95_section_form_roughs_in_levels_and_finishes_on_the_contour() {
    // VARI 9 (longitudinal outside, complete), MID 2, FALZ 0.2, FALX 0.1: levels from the top
    // X25 down to the boundary's start X10.1: 14.9 / 2 gives 8 cuts of 1.8625 (X23.1375 ..
    // X10.1). Finishing runs on the contour from Z0 to Z-40 X25.
    let main = format!(
        "{SETUP}CYCLE95(\"A1:E1\",{CALL_ARGS}\nM30\nA1: G1 X10 Z0\nG1 Z-20\nG2 X15 Z-25 CR=5\nG1 X20\nE1: G1 X25 Z-40\n"
    );
    let t = run(&main, &[]);
    assert!(t.alarms.is_empty(), "{:?}", t.alarms);
    let mut levels: Vec<f64> = Vec::new();
    for w in t.samples.windows(2) {
        // A roughing cut leaves Z in front of the part (0 < Z <= 1.2) along -Z at one X.
        let cut = close(w[0].x, w[1].x, 1e-12) && w[1].z < w[0].z - 1e-9 && w[0].z > 0.0 && w[0].z < 1.2 + 1e-9;
        if cut && w[0].x > 10.05 && levels.last().is_none_or(|l| !close(*l, w[0].x, 1e-9)) {
            levels.push(w[0].x);
        }
    }
    let want: Vec<f64> = (1..=8).map(|k| 25.0 - k as f64 * 1.8625).collect();
    assert_eq!(levels.len(), want.len(), "{levels:?}");
    assert!(levels.iter().zip(&want).all(|(a, b)| close(*a, *b, 1e-6)), "{levels:?}");
    // The finished contour: every sample at the contour's height or outside it, and the
    // finishing pass reaches the contour's end.
    for s in t.samples.iter().filter(|s| s.z <= 0.0 && s.z >= -40.0) {
        let on_shoulder = close(s.z, -25.0, 1e-6) && s.x >= 15.0 - 1e-6;
        assert!(on_shoulder || s.x >= shaft_radius(s.z) - 1e-6, "inside the part at {s:?}");
    }
    assert!(t.samples.iter().any(|s| close(s.z, -40.0, 1e-9) && close(s.x, 25.0, 1e-9)));
    assert!(t.samples.iter().filter(|s| s.z < -1.0 && close(s.x, shaft_radius(s.z), 1e-6)).count() > 100);
}

#[test]
fn a_section_call_needs_a_caller_and_its_labels() {
    // From the main program "A:B" names no program (14011); a label the caller lacks: 14080 at
    // the calling line.
    let t = run("G18 G90\nCALL \"A:B\"\nM30\n", &[]);
    assert_eq!(t.alarms.iter().map(|a| (a.number, a.line)).collect::<Vec<_>>(), [(14011, Some(2))]);
    let t = run(&format!("{SETUP}CYCLE95(\"A1:NOPE\",{CALL_ARGS}\nM30\nA1: G1 X10 Z0\nG1 X25 Z-40\n"), &[]);
    assert_eq!(t.alarms.iter().map(|a| (a.number, a.line)).collect::<Vec<_>>(), [(14080, Some(5))]);
}

//! TOFFR, the programmable tool radius offset (Programming Manual Fundamentals, "Programmable
//! tool offset"): added to the cutting edge's radius where G41/G42 compensate, without changing
//! the tool data. Expected distances are the radius plus the offset, worked out by hand.

use crate::trc_support;

use trc_support::{alarm_of, run_all};

/// The Y of the tool centre while it runs along the contour Y = 0 between X 10 and X 40 under
/// G41 (left of +X: +Y), with D1 radius 5 and `toffr` programmed before the approach.
fn centre_y(toffr: &str) -> Vec<f64> {
    let program = format!(
        "$TC_DP1[1,1]=120\n$TC_DP6[1,1]=5\nT1 D1\nG17 G90 G0 X-20 Y-20 Z0\n{toffr}\nG41 G1 X0 Y0 F2000\nX50\nG40 G1 X70 Y-20\nM30"
    );
    let (ch, samples) = run_all(&program);
    assert_eq!(alarm_of(&ch), None, "{:?}", ch.alarms());
    samples.iter().filter(|p| (10.0..40.0).contains(&p[0])).map(|p| p[1]).collect()
}

#[test]
fn toffr_adds_to_the_radius_the_compensation_keeps_off_the_contour() {
    for (word, expected) in [("", 5.0), ("TOFFR=1", 6.0), ("TOFFR=-0.5", 4.5)] {
        let ys = centre_y(word);
        assert!(!ys.is_empty(), "{word}: no samples along the contour");
        assert!(ys.iter().all(|y| (y - expected).abs() < 1e-9), "{word}: centre at {ys:?}, expected {expected}");
    }
}

#[test]
fn toffr_leaves_the_tool_data_and_the_lengths_alone() {
    // $TC_DP6 still reads 5 after TOFFR=1; TOFFR takes no index.
    let (ch, _) = run_all("$TC_DP1[1,1]=120\n$TC_DP6[1,1]=5\nT1 D1\nTOFFR=1\nR1=$TC_DP6[1,1]\nM30");
    assert_eq!(alarm_of(&ch), None, "{:?}", ch.alarms());
    assert_eq!(ch.r_param(1), 5.0);
    let (ch, _) = run_all("T1 D1\nTOFFR[1]=1\nM30");
    assert_eq!(alarm_of(&ch), Some(17020), "{:?}", ch.alarms());
}

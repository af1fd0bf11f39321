//! ORICONIO on the CA head of `mill5-head-ca` with MD21104 ORI_IPO_WITH_G_CODE = 1.
//!
//! With `o = (sin C·sin A, −cos C·sin A, cos A)`, every orientation 30° from Z has A = 30 and
//! the azimuth C − 90°; a cone about Z therefore keeps A at 30 and turns only C. Start C = 90
//! (o = (0.5, 0, 0.866)), end (−0.5, 0, 0.866) = C 270; through (0, 0.5, 0.866) = C 180 the cone
//! runs C upwards, through (0, −0.5, 0.866) = C 0 downwards to −90.

use nctwin_engine::Channel;

fn samples(program: &str) -> (Channel, Vec<Vec<f64>>) {
    let mut ch = Channel::from_preset("mill5-head-ca", "$MC_ORI_IPO_WITH_G_CODE=1").unwrap();
    ch.run_program(program).unwrap();
    let mut out = Vec::new();
    while ch.is_busy() {
        ch.step();
        out.push(ch.axis_positions().to_vec());
        assert!(out.len() < 1_000_000);
    }
    (ch, out)
}

fn program(b7: f64) -> String {
    let c = 0.75f64.sqrt();
    format!(
        "T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 ORIAXES A30 C90\nORIWKS ORICONIO\nA3=-0.5 B3=0 C3={c} A7=0 B7={b7} C7={c}\nM30"
    )
}

#[test]
fn the_cone_through_the_intermediate_orientation_keeps_a_and_turns_c_its_way() {
    for (b7, c_mid, c_end) in [(0.5, 180.0, 270.0), (-0.5, 0.0, -90.0)] {
        let (ch, s) = samples(&program(b7));
        assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
        let block: Vec<_> = s.iter().skip_while(|m| (m[4] - 90.0).abs() > 1e-6 || (m[3] - 30.0).abs() > 1e-6).collect();
        assert!(block.len() > 10);
        for m in &block {
            assert!((m[3] - 30.0).abs() < 1e-6, "A {m:?}");
        }
        let end = block.last().unwrap()[4];
        assert!(((end - c_end + 180.0).rem_euclid(360.0) - 180.0).abs() < 1e-6, "C end {end} vs {c_end}");
        // It passes the intermediate orientation and C moves one way only.
        assert!(block.iter().any(|m| ((m[4] - c_mid + 180.0).rem_euclid(360.0) - 180.0).abs() < 2.0));
        let sign = (c_end - 90.0f64).signum();
        assert!(block.windows(2).all(|w| (w[1][4] - w[0][4]) * sign >= -1e-9));
    }
}

#[test]
fn an_intermediate_parallel_to_the_start_gives_the_great_circle_and_a_missing_one_an_alarm() {
    // Intermediate = start: the great circle from (0.5, 0, 0.866) to (−0.5, 0, 0.866) runs
    // through Z, so A passes 0 (the cone would keep it at 30).
    let c = 0.75f64.sqrt();
    let (ch, s) = samples(&format!(
        "T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 ORIAXES A30 C90\nORIWKS ORICONIO\nA3=-0.5 B3=0 C3={c} A7=0.5 B7=0 C7={c}\nM30"
    ));
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
    assert!(s.iter().any(|m| m[3].abs() < 1.0));
    let (ch, _) =
        samples("T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 ORIAXES A30 C90\nORIWKS ORICONIO\nA3=-0.5 B3=0 C3=1\nM30");
    assert!(ch.snapshot().alarms.iter().any(|a| a.line == Some(6)), "{:?}", ch.snapshot().alarms);
}

#[test]
fn oriconto_continues_the_previous_cone_tangentially() {
    // Block 6: ORICONIO about Z from C 90 through C 135 to C 180 (A 30). There the orientation
    // moves along Z × o = (−0.5, 0, 0). ORICONTO to (−0.5, 0, 0.866) continues on the same cone:
    // A stays 30, C goes on upwards from 180 to 270.
    let (h, c) = (0.5f64.sqrt() / 2.0, 0.75f64.sqrt());
    let prog = format!(
        "T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 ORIAXES A30 C90\nORIWKS ORICONIO\nA3=0 B3=0.5 C3={c} A7={h} B7={h} C7={c}\n\
         ORICONTO\nA3=-0.5 B3=0 C3={c}\nM30"
    );
    let (ch, s) = samples(&prog);
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
    let last: Vec<_> = s.iter().skip_while(|m| (m[4] - 180.0).abs() > 1e-6).collect();
    assert!(last.len() > 10);
    for m in &last {
        assert!((m[3] - 30.0).abs() < 1e-6, "{m:?}");
    }
    assert!(last.windows(2).all(|w| w[1][4] >= w[0][4] - 1e-9));
    assert!((last.last().unwrap()[4] - 270.0).abs() < 1e-6);
    // After an ORIAXES block there is no orientation tangent to continue.
    let (ch, _) = samples(&format!(
        "T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 ORIAXES A30 C90\nORIWKS ORICONTO\nA3=-0.5 B3=0 C3={c}\nM30"
    ));
    assert!(ch.snapshot().alarms.iter().any(|a| a.line == Some(6)), "{:?}", ch.snapshot().alarms);
}

//! Orientation polynomials PO[PHI]/PO[PSI]/PO[XH..ZH]/PO[THT] are not modelled: each is refused
//! at its block with the alarm number F2 §3.9 names for it (14136..14139).

use nctwin_engine::Channel;

fn alarms(preset: &str, program: &str) -> Vec<(u32, Option<u32>)> {
    let mut ch = Channel::from_preset(preset, "").unwrap();
    ch.run_program(program).unwrap();
    let mut n = 0;
    while ch.is_busy() {
        ch.step();
        n += 1;
        assert!(n < 1_000_000);
    }
    ch.snapshot().alarms.iter().map(|a| (a.number, a.line)).collect()
}

#[test]
fn each_orientation_polynomial_has_its_alarm_at_its_line() {
    let head = "T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F1000\n";
    for (po, number) in [
        ("PO[PHI]=(10, 20)", 14137),
        ("PO[PSI]=(5)", 14137),
        ("PO[XH]=(1, 2, 3)", 14138),
        ("PO[ZH]=(1, 2)", 14138),
        ("PO[THT]=(10, 4)", 14139),
    ] {
        let got = alarms("mill5-head-ca", &format!("{head}X10 A3=0 B3=0 C3=1 {po}\nM30"));
        assert_eq!(got, [(number, Some(5))], "{po}");
    }
}

#[test]
fn without_an_orientation_transformation_it_is_14136() {
    assert_eq!(alarms("mill-3axis", "G1 F100 X10\nX20 PO[PHI]=(1, 2)\nM30"), [(14136, Some(2))]);
}

#[test]
fn a_coefficient_list_elsewhere_is_an_alarm_not_a_crash() {
    let got = alarms("mill-3axis", "G1 F100 X=(1, 2)\nM30");
    assert_eq!(got.len(), 1);
    assert_eq!(got[0].1, Some(1));
}

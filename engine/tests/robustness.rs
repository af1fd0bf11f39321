//! Property tests: arbitrary input never panics the parser, the NC data reader or a channel.

use nctwin_engine::{Channel, MachineData, lang};
use proptest::prelude::*;

/// Text built from the characters part programs and NC data are made of.
fn nc_text() -> impl Strategy<Value = String> {
    proptest::string::string_regex("[GXYZFIJKNMTDSR0-9=.+\\-*/() ;\\n$\\[\\],\"'ACPHB_]{0,120}").unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, .. ProptestConfig::default() })]

    #[test]
    fn the_parser_accepts_or_reports_any_text(text in nc_text()) {
        let p = lang::parse(&text);
        for d in &p.diagnostics {
            prop_assert!(d.line >= 1 && d.offset <= text.len() + 1);
        }
    }

    #[test]
    fn machine_data_text_is_applied_whole_or_not_at_all(text in nc_text()) {
        let mut md = MachineData::default();
        let before = md.clone();
        if md.apply_text(&text).is_err() {
            prop_assert_eq!(md, before);
        }
    }

    #[test]
    fn any_parsable_program_runs_to_an_end_or_an_alarm(text in nc_text()) {
        let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
        if ch.run_program(&text).is_ok() {
            let mut ticks = 0;
            while ch.is_busy() && ticks < 200_000 {
                ch.step();
                ticks += 1;
            }
            for p in ch.axis_positions() {
                prop_assert!(p.is_finite());
            }
        }
    }
}

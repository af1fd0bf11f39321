//! The active frame chain link by link (`Channel::frame_chain`), worked out by hand.

use nctwin_engine::Channel;

#[test]
fn the_chain_lists_basic_settable_and_programmable_frame_and_their_total() {
    // G54 = X100 Y50 (settable frame, $P_IFRAME); TRANS X5 Y-2 then AROT Z30 (programmable
    // frame, $P_PFRAME). Total: the translations add (the programmable one is in the settable
    // frame's unrotated axes): X105 Y48; rotation Z30.
    let md = "$P_UIFR[1,X,TR]=100\n$P_UIFR[1,Y,TR]=50\n";
    let mut ch = Channel::from_preset("mill-3axis", md).unwrap();
    ch.run_program("G54\nTRANS X5 Y-2\nAROT Z30\nG0 X0 Y0 Z10\nM0\nM30").unwrap();
    for _ in 0..1_000_000 {
        if ch.status() == nctwin_engine::Status::Stopped {
            break;
        }
        ch.step();
    }
    let chain = ch.frame_chain();
    let names: Vec<_> = chain.iter().map(|l| l.name).collect();
    assert_eq!(names.first(), Some(&"$P_PARTFRAME"));
    assert_eq!(names.last(), Some(&"$P_ACTFRAME"));
    assert_eq!(names.len(), 11);
    let get = |name: &str| chain.iter().find(|l| l.name == name).unwrap().data.clone().unwrap();
    let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
    let i = get("$P_IFRAME");
    assert!(close(i.trans[0], 100.0) && close(i.trans[1], 50.0) && i.rot == [0.0; 3], "{i:?}");
    let p = get("$P_PFRAME");
    assert!(close(p.trans[0], 5.0) && close(p.trans[1], -2.0) && close(p.rot[2], 30.0), "{p:?}");
    let total = get("$P_ACTFRAME");
    assert!(close(total.trans[0], 105.0) && close(total.trans[1], 48.0) && close(total.rot[2], 30.0), "{total:?}");
    let basic = get("$P_ACTBFRAME");
    assert!(basic.trans.iter().all(|t| *t == 0.0), "{basic:?}");
}

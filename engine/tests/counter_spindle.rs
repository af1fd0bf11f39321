//! The `lathe-counter-spindle` preset: main spindle SP1 (spindle 1, master after reset),
//! counter spindle SP2 (spindle 2) on its own slide Z2, X in diameters. Worked out by hand.

use nctwin_engine::Channel;

fn run(program: &str) -> Channel {
    let mut ch = Channel::from_preset("lathe-counter-spindle", "").unwrap();
    ch.run_program(program).unwrap();
    ch
}

fn finish(ch: &mut Channel) {
    for _ in 0..2_000_000 {
        if !ch.is_busy() {
            break;
        }
        ch.step();
    }
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
}

fn speed(ch: &Channel, name: &str) -> f64 {
    ch.snapshot().spindles.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no spindle {name}")).1
}

#[test]
fn the_counter_spindle_slide_moves_on_its_own_and_x_is_a_diameter() {
    // Z2=-250 moves only the slide (channel axis 3); X40 is the diameter 40: machine X20.
    let mut ch = run("G0 X40 Z10\nG0 Z2=-250\nM30");
    finish(&mut ch);
    let p = ch.axis_positions();
    assert!((p[0] - 20.0).abs() < 1e-9 && (p[1] - 10.0).abs() < 1e-9 && (p[3] + 250.0).abs() < 1e-9, "{p:?}");
}

#[test]
fn setms_2_makes_s_and_m3_act_on_the_counter_spindle() {
    // After SETMS(2) the plain S1200 M3 is the counter spindle's; the main spindle keeps its
    // S500 from before.
    let mut ch = run("S500 M3\nSETMS(2)\nS1200 M3\nG4 F3\nM0\nM30");
    for _ in 0..2_000_000 {
        if ch.status() == nctwin_engine::Status::Stopped {
            break;
        }
        ch.step();
    }
    assert!((speed(&ch, "SP1") - 500.0).abs() < 1e-6, "SP1 {}", speed(&ch, "SP1"));
    assert!((speed(&ch, "SP2") - 1200.0).abs() < 1e-6, "SP2 {}", speed(&ch, "SP2"));
}

#[test]
fn constant_cutting_speed_follows_the_counter_spindle_after_setms() {
    // SETMS(2) G96 S100 at X40 (diameter 40): n = 100 000 / (π · 40) = 795.77 rev/min on the
    // counter spindle; the main spindle stands.
    let mut ch = run("G0 X40 Z10\nSETMS(2)\nG96 S100 LIMS=3000 M3\nG4 F3\nM0\nM30");
    for _ in 0..2_000_000 {
        if ch.status() == nctwin_engine::Status::Stopped {
            break;
        }
        ch.step();
    }
    let n = 100_000.0 / (std::f64::consts::PI * 40.0);
    assert!((speed(&ch, "SP2") - n).abs() < 1e-6, "SP2 {} vs {n}", speed(&ch, "SP2"));
    assert_eq!(speed(&ch, "SP1"), 0.0);
}

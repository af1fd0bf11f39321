//! Exactness of the horizons (`interp/synchronized/horizon.rs`): random programs with random
//! synchronized actions (thresholds on positions, workpiece positions under frames, speeds,
//! times, distances to go, signals and analog inputs set mid-run, markers written by other
//! actions, overrides that change the motion) run twice side by side, once with horizons and
//! once with every condition evaluated in every IPO cycle. The IPO samples, the data the
//! actions write (one counter per action: the cycles it fired in), the outputs and the end
//! state must be the same bit for bit.

use nctwin_engine::Channel;

use crate::settle;
use settle::channel;

/// xorshift64*: deterministic, no dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        let v = lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64;
        (v * 100.0).round() / 100.0
    }

    fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[self.below(items.len() as u64) as usize]
    }
}

/// A random condition over the variables the main run bounds (and a few it does not).
fn condition(r: &mut Rng) -> String {
    let cmp = r.pick(&[">", "<", ">=", "<="]);
    match r.below(16) {
        0 => format!("$AA_IM[{}]{cmp}{}", r.pick(&["X", "Y"]), r.range(-5.0, 80.0)),
        1 => format!("$AA_IM[Z]{cmp}{}", r.range(-20.0, 5.0)),
        2 => format!("$AA_IW[{}]{cmp}{}", r.pick(&["X", "Y", "Z"]), r.range(-30.0, 80.0)),
        3 => format!("$AA_VACTM[{}]{cmp}{}", r.pick(&["X", "Y", "Z"]), r.range(-6000.0, 6000.0)),
        4 => format!("$AC_VACTB{cmp}{}", r.range(0.0, 8000.0)),
        5 => format!("$AC_TIME{cmp}{}", r.range(0.0, 0.8)),
        6 => format!("$AC_DTEB{cmp}{}", r.range(-1.0, 30.0)),
        7 => format!("$AC_PATH{cmp}{}", r.range(0.0, 30.0)),
        8 => format!("$A_IN[{}]=={}", 1 + r.below(3), r.below(2)),
        9 => format!("$A_INA[1]{cmp}{}", r.range(0.0, 10.0)),
        10 => format!("SQRT(POT($AA_IM[X])+POT($AA_IM[Y])){cmp}{}", r.range(0.0, 100.0)),
        11 => format!("($AA_IM[X]>{}) AND ($AA_IW[Z]<{})", r.range(0.0, 60.0), r.range(-15.0, 5.0)),
        12 if r.below(2) == 0 => format!("$AC_MARKER[7]>{}", r.below(4)),
        // A reader of a deferred action's parameter: that action is run, not deferred.
        12 => format!("$AC_PARAM[31]{cmp}{}", r.range(-60.0, 120.0)),
        13 => format!("ABS($AA_IW[Y]-{}){cmp}{}", r.range(0.0, 60.0), r.range(0.0, 10.0)),
        14 => format!("($AA_IM[Y]*2-$AA_IM[X])/4{cmp}{}", r.range(-20.0, 40.0)),
        _ => format!("$AC_OVR<{} OR $AA_IM[X]>{}", r.range(60.0, 120.0), r.range(0.0, 80.0)),
    }
}

/// A random program: actions `ID=1..n` counting their firings in `$AC_PARAM[id]`, then moves.
fn program(r: &mut Rng) -> String {
    let mut text = String::new();
    for g in ["FFWOF", "G64", "SOFT"] {
        if r.below(3) == 0 {
            text.push_str(g);
            text.push('\n');
        }
    }
    let count = 2 + r.below(7);
    for id in 1..=count {
        if r.below(4) == 0 {
            // Deferred (`channel/sync/lazy.rs`) unless another action reads or writes the element
            // (marker 5 when two of them write it, parameter 31 when a condition reads it).
            let kind = if r.below(3) == 0 { "IDS" } else { "ID" };
            text.push_str(&format!(
                "{kind}={id} DO $AC_PARAM[{}]=$AA_IM[X]*2-$AA_IPO[Y] $AC_MARKER[5]=$AA_IM[Z]*10+{id}\n",
                30 + id
            ));
            continue;
        }
        let trigger = r.pick(&["WHEN", "WHENEVER", "FROM", "EVERY"]);
        let cond = condition(r);
        let mut action = format!("$AC_PARAM[{id}]=$AC_PARAM[{id}]+1");
        match r.below(8) {
            0 if trigger == "WHENEVER" => action.push_str(" $AC_OVR=40"),
            1 => action.push_str(" $AC_MARKER[7]=$AC_MARKER[7]+1"),
            2 => action.push_str(&format!(" $A_OUT[{}]=1", 1 + r.below(4))),
            3 => action.push_str(&format!(" $AC_PARAM[{}]=$AA_IM[X]", 20 + id)),
            _ => {}
        }
        let kind = if r.below(5) == 0 { "IDS" } else { "ID" };
        text.push_str(&format!("{kind}={id} {trigger} {cond} DO {action}\n"));
    }
    for _ in 0..(3 + r.below(6)) {
        match r.below(15) {
            // Block preparation reads what deferred actions wrote (it waits for the main run).
            14 => text.push_str(&format!(
                "G1 X=ABS($AC_PARAM[{}]) MOD 40 Y=ABS($AC_MARKER[5]) MOD 30 F6000\n",
                31 + r.below(count)
            )),
            // A block-modal action on the next motion block, which an input may cut short.
            10 => text.push_str(&format!("WHEN $A_IN[{}]==1 DO DELDTG\n", 1 + r.below(3))),
            11 => text.push_str(&format!("WHENEVER {} DO $AC_MARKER[6]=$AC_MARKER[6]+1\n", condition(r))),
            12 => {
                text.push_str(&format!("{}({})\n", r.pick(&["LOCK", "UNLOCK", "RESET", "CANCEL"]), 1 + r.below(count)))
            }
            13 => text.push_str(&format!(
                "G2 X{} Y{} CR={} F{}\n",
                r.range(0.0, 60.0),
                r.range(0.0, 60.0),
                r.range(45.0, 90.0),
                r.pick(&["2000", "6000"])
            )),
            0 => text.push_str(&format!("TRANS X{} Y{}\n", r.range(-10.0, 10.0), r.range(-10.0, 10.0))),
            1 => text.push_str(&format!("AROT Z{}\n", r.range(-45.0, 45.0))),
            2 => text.push_str(&format!("G4 F{}\n", r.range(0.05, 0.3))),
            3 => {
                text.push_str(&format!("G0 X{} Y{} Z{}\n", r.range(0.0, 60.0), r.range(0.0, 60.0), r.range(-10.0, 5.0)))
            }
            _ => text.push_str(&format!(
                "G1 X{} Y{} Z{} F{}\n",
                r.range(0.0, 60.0),
                r.range(0.0, 60.0),
                r.range(-15.0, 5.0),
                r.pick(&["600", "2000", "6000", "12000"])
            )),
        }
    }
    text.push_str("M30\n");
    text
}

/// What is compared in every cycle.
fn sample(ch: &Channel) -> (Vec<u64>, Vec<u64>, Vec<u64>, u64, Vec<bool>) {
    let s = ch.sync_actions();
    (
        ch.axis_positions().iter().map(|v| v.to_bits()).collect(),
        s.params.iter().map(|v| v.to_bits()).collect(),
        s.markers.iter().map(|v| v.to_bits()).collect(),
        ch.digital_io().outputs,
        s.list().iter().map(|a| a.fired).collect(),
    )
}

#[test]
fn random_actions_fire_in_the_same_cycles_with_and_without_horizons() {
    let mut saved = 0u64;
    let mut total = 0u64;
    // NCTWIN_SYNC_SEEDS=n runs n programs (60 by default).
    let seeds = std::env::var("NCTWIN_SYNC_SEEDS").ok().and_then(|n| n.parse().ok()).unwrap_or(60u64);
    for seed in 1..=seeds {
        let mut r = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
        let text = program(&mut r);
        let mut with = channel("mill-3axis", "");
        let mut without = channel("mill-3axis", "");
        without.set_sync_horizons(false);
        with.run_program(&text).unwrap();
        without.run_program(&text).unwrap();
        // Signals set from outside at random cycles (the same for both).
        let mut inputs: Vec<(usize, usize, f64)> =
            (0..6).map(|_| (r.below(3000) as usize, 1 + r.below(3) as usize, r.range(0.0, 10.0))).collect();
        inputs.sort_by_key(|i| i.0);
        let mut tick = 0;
        while (with.is_busy() || without.is_busy()) && tick < 12_000 {
            for &(_, n, v) in inputs.iter().filter(|i| i.0 == tick) {
                for ch in [&mut with, &mut without] {
                    ch.set_signals(&[(n, v > 5.0)], &[]).unwrap();
                    ch.set_analog_inputs(&[(1, v)]).unwrap();
                }
            }
            with.step();
            without.step();
            tick += 1;
            assert_eq!(sample(&with), sample(&without), "seed {seed}, cycle {tick}:\n{text}");
        }
        // Static actions go on after the end and after a reset.
        for n in 0..300 {
            if n == 150 {
                with.reset();
                without.reset();
            }
            with.step();
            without.step();
            assert_eq!(sample(&with), sample(&without), "seed {seed}, {n} cycles after the end:\n{text}");
        }
        assert_eq!(with.snapshot(), without.snapshot(), "seed {seed}:\n{text}");
        assert_eq!(with.ticks(), without.ticks());
        saved += without.sync_actions().evaluations() - with.sync_actions().evaluations();
        total += without.sync_actions().evaluations();
    }
    // The horizons spare evaluations: over a third of them on these programs, whose
    // thresholds lie where the axes go (with `$AC_DTEB`, `$AC_PATH`, `$AC_OVR` evaluated in
    // every cycle; 121,184 of 279,654 when written).
    assert!(saved * 3 > total, "{saved} of {total} evaluations spared");
}

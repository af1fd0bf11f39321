//! `nctwin simulate`: the real binary, run on program files; its JSON and exit codes.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

/// A fresh folder for one test's files.
fn folder(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("simulate").join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp folder");
    dir
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write file");
    path
}

fn nctwin(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_nctwin")).args(args).output().expect("nctwin runs")
}

fn simulate(args: &[&str]) -> (i32, Value) {
    let mut all = vec!["simulate"];
    all.extend_from_slice(args);
    let out = nctwin(&all);
    let code = out.status.code().expect("exit code");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let json = serde_json::from_str(&stdout).unwrap_or_else(|e| {
        panic!("stdout is not JSON ({e}), exit {code}: {stdout}\nstderr: {}", String::from_utf8_lossy(&out.stderr))
    });
    (code, json)
}

fn approx(v: &Value, expected: f64) {
    let got = v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"));
    assert!((got - expected).abs() < 1e-6, "{got} != {expected}");
}

#[test]
fn a_program_runs_to_its_end_and_reports_state_and_figures() {
    let dir = folder("ends");
    let program = write(&dir, "part.mpf", "G54 T1 D1\nG0 X10 Y20 Z5\nG1 Z-2 F500\nG2 X30 Y20 CR=10 F1200\n\nM30\n");
    let (code, r) = simulate(&["--machine", "mill-3axis", program.to_str().unwrap()]);
    assert_eq!(code, 0, "{r:#}");
    assert_eq!(r["outcome"], "ended");
    assert_eq!(r["machine"], "mill-3axis");
    assert_eq!(r["state"]["status"], "idle");
    assert_eq!(r["state"]["alarms"], serde_json::json!([]));
    let wcs = &r["state"]["positions"]["workpiece"];
    approx(&wcs["X"], 30.0);
    approx(&wcs["Y"], 20.0);
    approx(&wcs["Z"], -2.0);
    assert!(r["state"]["positions"]["machine"]["Z"].is_number());
    assert!(r["state"]["positions"]["basic"]["Z"].is_number());
    assert_eq!(r["blocks"], 5, "non-empty lines");
    assert!(r["block_changes"].as_u64().unwrap() >= 3);
    let cycles = r["ipo_cycles"].as_u64().unwrap();
    assert!(cycles > 100, "{cycles}");
    approx(&r["simulated_time_s"], cycles as f64 * r["ipo_cycle_s"].as_f64().unwrap());
    approx(&r["state"]["time"], r["simulated_time_s"].as_f64().unwrap());
    for key in ["wall_time_s", "load_time_s", "cpu_time_s", "blocks_per_s", "cycles_per_s", "real_time_factor"] {
        assert!(r[key].as_f64().is_some_and(|v| v >= 0.0), "{key}: {}", r[key]);
    }
    assert!(r["peak_rss_kib"].as_u64().is_some_and(|kib| kib > 100), "{}", r["peak_rss_kib"]);
}

#[test]
fn an_alarm_ends_with_exit_code_2() {
    let dir = folder("alarm");
    let program = write(&dir, "limit.mpf", "G0 X10\nG0 X5000\nM30\n");
    let (code, r) = simulate(&["--machine", "mill-3axis", "--compact", program.to_str().unwrap()]);
    assert_eq!(code, 2, "{r:#}");
    assert_eq!(r["outcome"], "alarm");
    assert_eq!(r["state"]["status"], "alarm");
    assert_eq!(r["state"]["alarms"][0]["number"], 10720);
    assert_eq!(r["state"]["alarms"][0]["line"], 2);
    approx(&r["state"]["positions"]["machine"]["X"], 10.0);
}

#[test]
fn syntax_errors_are_reported_before_anything_runs() {
    let dir = folder("syntax");
    let program = write(&dir, "bad.mpf", "G0 X10\nG1 X=\nM30\n");
    let (code, r) = simulate(&["--machine", "mill-3axis", program.to_str().unwrap()]);
    assert_eq!(code, 2, "{r:#}");
    assert_eq!(r["outcome"], "syntax_error");
    assert_eq!(r["syntax_errors"][0]["line"], 2);
    assert_eq!(r["ipo_cycles"], 0);
}

#[test]
fn machine_data_and_stored_subprograms_are_used() {
    let dir = folder("data");
    let md = write(&dir, "machine.nc", "$P_UIFR[1,X,TR]=100\n");
    let subs = dir.join("subs");
    std::fs::create_dir_all(&subs).unwrap();
    write(&subs, "hole.spf", "PROC HOLE(REAL DEPTH)\nG1 Z=-DEPTH F2000\nG0 Z5\nRET\n");
    write(&subs, "notes.txt", "not a program\n");
    let program = write(&dir, "main.mpf", "G54\nG0 X10 Y10 Z5\nHOLE(3)\nG0 X20\nM30\n");
    let (code, r) = simulate(&[
        "--machine",
        "mill-3axis",
        "--machine-data",
        md.to_str().unwrap(),
        "--program-dir",
        subs.to_str().unwrap(),
        program.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{r:#}");
    approx(&r["state"]["positions"]["machine"]["X"], 120.0);
    approx(&r["state"]["positions"]["machine"]["Z"], 5.0);
}

#[test]
fn m0_continues_unless_asked_to_stay() {
    let dir = folder("m0");
    let program = write(&dir, "m0.mpf", "G0 X10\nM0\nG0 X20\nM30\n");
    let (code, r) = simulate(&["--machine", "mill-3axis", program.to_str().unwrap()]);
    assert_eq!((code, &r["outcome"]), (0, &Value::from("ended")), "{r:#}");
    assert_eq!(r["program_stops"], 1);
    approx(&r["state"]["positions"]["machine"]["X"], 20.0);

    let (code, r) = simulate(&["--machine", "mill-3axis", "--stop-at-m0", program.to_str().unwrap()]);
    assert_eq!((code, &r["outcome"]), (0, &Value::from("stopped")), "{r:#}");
    assert_eq!(r["state"]["status"], "stopped");
    approx(&r["state"]["positions"]["machine"]["X"], 10.0);
}

#[test]
fn the_time_limit_stops_with_exit_code_3() {
    let dir = folder("limit");
    let program = write(&dir, "slow.mpf", "G1 X300 F60\nM30\n");
    let (code, r) = simulate(&["--machine", "mill-3axis", "--max-sim-time", "2", program.to_str().unwrap()]);
    assert_eq!(code, 3, "{r:#}");
    assert_eq!(r["outcome"], "limit");
    let t = r["simulated_time_s"].as_f64().unwrap();
    assert!((2.0..3.0).contains(&t), "{t}");
}

#[test]
fn a_thread_with_the_spindle_stopped_ends_as_standstill_with_exit_code_4() {
    let dir = folder("standstill");
    // G33 with M5: the control waits for the spindle for ever (no alarm). The run ends after
    // 60 s of simulated time without any change, at the thread's line 3, with NC stop.
    let program = write(&dir, "thread.mpf", "G0 X20 Z5\nM5\nG33 Z-20 K1.5\nM30\n");
    let (code, r) = simulate(&["--machine", "lathe-2axis", program.to_str().unwrap()]);
    assert_eq!(code, 4, "{r:#}");
    assert_eq!(r["outcome"], "standstill");
    assert_eq!(r["standstill"]["line"], 3);
    assert!(r["standstill"]["message"].as_str().unwrap().contains("line 3"));
    let t = r["simulated_time_s"].as_f64().unwrap();
    // Checked every 4096 IPO cycles: at most two such chunks beyond the 60 s.
    assert!((60.0..100.0).contains(&t), "{t}");
    // A long dwell is no standstill: G4 F100 runs out and the program ends normally.
    let program = write(&dir, "dwell.mpf", "G4 F100\nM30\n");
    let (code, r) = simulate(&["--machine", "lathe-2axis", program.to_str().unwrap()]);
    assert_eq!(code, 0, "{r:#}");
    assert_eq!(r["outcome"], "ended");
}

#[test]
fn usage_and_io_errors_exit_with_1() {
    let dir = folder("usage");
    let missing = dir.join("missing.mpf");
    let out = nctwin(&["simulate", "--machine", "mill-3axis", missing.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot read program"), "{out:?}");

    let program = write(&dir, "ok.mpf", "G0 X1\n");
    let out = nctwin(&["simulate", "--machine", "no-such-machine", program.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no-such-machine"), "{out:?}");

    let md = write(&dir, "bad.nc", "$MA_NO_SUCH_DATUM[X]=1\n");
    let out = nctwin(&["simulate", "--machine", "mill-3axis", "--machine-data", md.to_str().unwrap(), "x.mpf"]);
    assert_eq!(out.status.code(), Some(1), "{out:?}");

    // Usage errors found by the argument parser exit with 1 too (2 means an alarm here).
    let out = nctwin(&["simulate", program.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1), "{out:?}");
    assert!(String::from_utf8_lossy(&out.stderr).contains("--machine"), "{out:?}");
}

#[test]
fn the_server_flags_still_parse_without_a_subcommand() {
    let out = nctwin(&["--help"]);
    assert_eq!(out.status.code(), Some(0));
    let help = String::from_utf8_lossy(&out.stdout);
    assert!(help.contains("simulate") && help.contains("--bind") && help.contains("--data-dir"), "{help}");
}

#[test]
fn interpret_only_prepares_every_block_without_ipo_cycles() {
    let dir = folder("interpret");
    let program = write(&dir, "part.mpf", "G54 T1 D1\nG0 X10 Y20 Z5\nG1 Z-2 F500\nG2 X30 Y20 CR=10 F1200\nM30\n");
    let (code, r) = simulate(&["--machine", "mill-3axis", "--interpret-only", program.to_str().unwrap()]);
    assert_eq!(code, 0, "{r:#}");
    assert_eq!(r["outcome"], "ended");
    assert_eq!(r["moves"], 3);
    assert_eq!(r["ipo_cycles"], 0);
    assert!(r.get("state").is_none());

    let program = write(&dir, "limit.mpf", "G0 X10\nG0 X5000\nM30\n");
    let (code, r) = simulate(&["--machine", "mill-3axis", "--interpret-only", program.to_str().unwrap()]);
    assert_eq!(code, 2, "{r:#}");
    assert_eq!(r["alarm"]["number"], 10720);
}

/// A long program of short moves with `bad` lines put in just before its end.
fn long_program_with(bad: &[&str]) -> String {
    let mut text = String::from("G54 G90 F3000\n");
    for i in 0..20_000 {
        text += &format!("G1 X{} Y{}\n", i % 50, (i / 50) % 50);
    }
    for line in bad {
        text += line;
        text += "\n";
    }
    text + "M30\n"
}

#[test]
fn a_syntax_error_late_in_a_long_program_discards_the_run() {
    // The check runs beside the run; its errors (line 1 is G54, moves on 2..=20001) come in
    // line order and the report is the one of a program that never ran.
    let dir = folder("late_syntax");
    let program = write(&dir, "late.mpf", &long_program_with(&["G1 X=", "G1 Y10", "G1 Y="]));
    for interpret_only in [false, true] {
        let mut args = vec!["--machine", "mill-3axis", program.to_str().unwrap()];
        if interpret_only {
            args.insert(0, "--interpret-only");
        }
        let (code, r) = simulate(&args);
        assert_eq!(code, 2, "{r:#}");
        assert_eq!(r["outcome"], "syntax_error");
        let lines: Vec<u64> =
            r["syntax_errors"].as_array().unwrap().iter().map(|e| e["line"].as_u64().unwrap()).collect();
        assert_eq!(lines, [20_002, 20_004], "{r:#}");
        // 12080 syntax error, at column 6: where the value of `G1 X=` is missing.
        assert_eq!(
            (&r["syntax_errors"][0]["alarm"], &r["syntax_errors"][0]["column"]),
            (&Value::from(12080), &Value::from(6))
        );
        assert_eq!(r["ipo_cycles"], 0);
        assert_eq!(r["blocks"], 20_005);
        if interpret_only {
            assert_eq!(r["moves"], 0, "{r:#}");
        } else {
            assert_eq!(r["block_changes"], 0);
            assert_eq!(r["state"]["status"], "idle", "{r:#}");
            approx(&r["state"]["positions"]["machine"]["X"], 0.0);
            approx(&r["state"]["time"], 0.0);
        }
    }
}

#[test]
fn a_syntax_error_after_an_endless_loop_still_ends_the_run() {
    // Without the check the loop would run forever: the run gives up once the check failed.
    let dir = folder("loop_syntax");
    let program = write(&dir, "loop.mpf", "F3000\nLOOP\nG1 X10\nG1 X0\nENDLOOP\nG1 X=\nM30\n");
    let (code, r) = simulate(&["--machine", "mill-3axis", "--compact", program.to_str().unwrap()]);
    assert_eq!((code, &r["outcome"]), (2, &Value::from("syntax_error")), "{r:#}");
    assert_eq!(r["syntax_errors"][0]["line"], 6);
}

#[test]
fn a_reader_that_went_away_ends_the_run_quietly() {
    // `nctwin simulate ... | head -c 100`: the report's write fails with a broken pipe. The
    // process says nothing more and exits with 1 (I/O error), without a panic. The pipe is
    // closed long before the report is written (20,000 blocks run first).
    let dir = folder("broken_pipe");
    let program = write(&dir, "long.mpf", &long_program_with(&[]));
    let mut child = Command::new(env!("CARGO_BIN_EXE_nctwin"))
        .args(["simulate", "--machine", "mill-3axis", program.to_str().unwrap()])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("nctwin runs");
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("nctwin ends");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

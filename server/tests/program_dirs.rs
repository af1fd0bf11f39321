//! Program folders, archives, encodings and NC data files on the command line: `nctwin simulate
//! --program-dir`, `--machine-data` and `nctwin check`, the real binary on the fixtures of
//! `tests/fixtures` and on files written here in legacy encodings.
//!
//! `fixtures/shop` is laid out like the control's program memory: `MPF/MAIN.MPF` calls
//! `SUB_OK` and `L100` (in `SPF`) and `CYCLE_T` (in `CST`); `SPF` also holds `BROKEN.SPF` (a
//! syntax error, line 2 column 14), `UNDECODABLE.SPF` (binary bytes) and `odd name (1).spf`,
//! none of which MAIN calls; `WKS/SHAFT.WPD` holds `SHAFT.MPF` (archive header, CRLF), which
//! calls its own `SUB_OK` and then `BROKEN`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests").join("fixtures")
}

/// A fresh folder for one test's files.
fn folder(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("program_dirs").join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp folder");
    dir
}

/// Runs `nctwin` in the fixtures folder (so paths print as `shop/...`).
fn nctwin(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_nctwin")).current_dir(fixtures()).args(args).output().expect("nctwin runs")
}

fn simulate(args: &[&str]) -> (i32, Value) {
    let mut all = vec!["simulate", "--machine", "mill-3axis", "--compact"];
    all.extend_from_slice(args);
    let out = nctwin(&all);
    let code = out.status.code().expect("exit code");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let json = serde_json::from_str(&stdout).unwrap_or_else(|e| {
        panic!("stdout is not JSON ({e}), exit {code}: {stdout}\nstderr: {}", String::from_utf8_lossy(&out.stderr))
    });
    (code, json)
}

fn xyz(r: &Value, kind: &str) -> (f64, f64, f64) {
    let p = &r["state"]["positions"][kind];
    (p["X"].as_f64().unwrap(), p["Y"].as_f64().unwrap(), p["Z"].as_f64().unwrap())
}

#[test]
fn a_folder_with_broken_undecodable_and_oddly_named_files_still_runs_the_main_program_to_its_end() {
    let (code, r) = simulate(&["--program-dir", "shop", "shop/MPF/MAIN.MPF"]);
    assert_eq!(code, 0, "{r:#}");
    assert_eq!(r["outcome"], "ended");
    // X1 Y1, SUB_OK: X+10, L100: Y+5, CYCLE_T (from CST): Z+2, then X3.
    assert_eq!(xyz(&r, "workpiece"), (3.0, 6.0, 2.0));
    assert_eq!(r["state"]["alarms"], serde_json::json!([]));
    assert!(r.get("syntax_errors").is_none(), "{r:#}");
    let notes: Vec<&str> = r["notes"].as_array().unwrap().iter().map(|n| n["path"].as_str().unwrap()).collect();
    assert_eq!(notes, ["shop/README.txt", "shop/SPF/odd name (1).spf"]);
}

#[test]
fn a_called_broken_subprogram_raises_its_alarm_at_the_call_naming_it() {
    let (code, r) = simulate(&["--program-dir", "shop", "shop/WKS/SHAFT.WPD/SHAFT.MPF"]);
    assert_eq!(code, 2, "{r:#}");
    assert_eq!(r["outcome"], "alarm");
    let alarm = &r["state"]["alarms"][0];
    assert_eq!(alarm["number"], 12080);
    assert_eq!(alarm["line"], 5, "the call's line in SHAFT");
    assert_eq!(alarm["message"], "Channel 1 block 5 program BROKEN line 2 column 14: missing `)`");
    // X5, then the workpiece's own SUB_OK (X+100), not the one in SPF (X+10).
    assert_eq!(xyz(&r, "workpiece").0, 105.0);
}

#[test]
fn a_called_undecodable_subprogram_is_not_available() {
    let dir = folder("undecodable");
    let main = dir.join("MAIN.MPF");
    std::fs::write(&main, "G0 X1\nUNDECODABLE\nM30\n").unwrap();
    let (code, r) = simulate(&["--program-dir", "shop", main.to_str().unwrap()]);
    assert_eq!(code, 2, "{r:#}");
    let alarm = &r["state"]["alarms"][0];
    assert_eq!((alarm["number"].as_u64(), alarm["line"].as_u64()), (Some(14011), Some(2)));
    let message = alarm["message"].as_str().unwrap();
    assert!(message.contains("program UNDECODABLE not available:"), "{message}");
    assert!(message.ends_with("not a text file: control character U+0003 at byte 2"), "{message}");
}

#[test]
fn check_prints_one_line_per_finding_and_exits_1() {
    let out = nctwin(&["check", "shop"]);
    assert_eq!(out.status.code(), Some(1), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        "shop/README.txt: warning: not a program file (*.MPF, *.SPF or an archive): skipped\n\
         shop/SPF/odd name (1).spf: error: not a program name (letters, digits and _, at most 32): skipped\n\
         shop/SPF/BROKEN.SPF:2:14: alarm 12080: missing `)`\n\
         shop/SPF/UNDECODABLE.SPF: error: not a text file: control character U+0003 at byte 2\n"
    );
}

#[test]
fn check_finds_called_names_nothing_defines_and_passes_a_clean_folder() {
    // MAIN alone: its subprograms are in the folder it was taken from.
    let out = nctwin(&["check", "shop/MPF/MAIN.MPF"]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        "shop/MPF/MAIN.MPF:4:5: alarm 12550: name SUB_OK not defined\n\
         shop/MPF/MAIN.MPF:5:5: alarm 14011: program L100 not available\n\
         shop/MPF/MAIN.MPF:6:5: alarm 12550: name CYCLE_T not defined\n"
    );
    let dir = folder("clean");
    std::fs::write(dir.join("A.MPF"), "G0 X1\nB\nM30\n").unwrap();
    std::fs::write(dir.join("B.SPF"), "G0 X2\nM17\n").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_nctwin")).arg("check").arg(&dir).output().unwrap();
    assert_eq!((out.status.code(), out.stdout.as_slice()), (Some(0), &b""[..]));
}

#[test]
fn an_archive_in_the_folder_and_lines_counted_as_in_the_file() {
    let dir = folder("archive");
    let archive = "%_N_PART_MPF\r\n;$PATH=/_N_MPF_DIR\r\nG0 X1\r\nHELPER\r\nM30\r\n\
                   %_N_HELPER_SPF\r\n;$PATH=/_N_SPF_DIR\r\nG91 G0 Y4\r\nG1 X=\r\nM17\r\n";
    std::fs::write(dir.join("EXPORT.ARC"), archive).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_nctwin")).arg("check").arg(&dir).output().unwrap();
    let expected = format!("{}:9:6: alarm 12080: missing value\n", dir.join("EXPORT.ARC").display());
    assert_eq!((out.status.code(), String::from_utf8_lossy(&out.stdout).into_owned()), (Some(1), expected));
    // The same archive as the main program file: PART runs, HELPER is called from it.
    let main = dir.join("EXPORT.ARC");
    let (code, r) = simulate(&[main.to_str().unwrap()]);
    assert_eq!(code, 2, "{r:#}");
    assert_eq!(r["state"]["alarms"][0]["message"], "Channel 1 block 4 program HELPER line 4 column 6: missing value");
    assert_eq!(xyz(&r, "workpiece").0, 1.0);
}

#[test]
fn legacy_encoded_programs_run_with_their_messages_decoded() {
    let dir = folder("encodings");
    let (cyrillic, _, _) = encoding_rs::WINDOWS_1251.encode(
        "; Программа: фрезерование фланца\r\nG0 X10\r\nMSG(\"Проверьте инструмент и заготовку\")\r\nM0\r\nM30\r\n",
    );
    std::fs::write(dir.join("FLANSCH.MPF"), &cyrillic).unwrap();
    let (chinese, _, _) =
        encoding_rs::GBK.encode("; 子程序 检查刀具长度\nPROC CN_SUB\nG0 Y7\nMSG(\"请检查刀具长度\")\nM17\n");
    std::fs::write(dir.join("CN_SUB.SPF"), &chinese).unwrap();
    std::fs::write(dir.join("MAIN.MPF"), "G0 X1\nCN_SUB\nM0\nM30\n").unwrap();

    let main = dir.join("FLANSCH.MPF");
    let (code, r) = simulate(&["--stop-at-m0", main.to_str().unwrap()]);
    assert_eq!(code, 0, "{r:#}");
    assert_eq!(r["outcome"], "stopped");
    assert_eq!(r["state"]["message"], "Проверьте инструмент и заготовку");

    let main = dir.join("MAIN.MPF");
    let (code, r) = simulate(&["--stop-at-m0", "--program-dir", dir.to_str().unwrap(), main.to_str().unwrap()]);
    assert_eq!(code, 0, "{r:#}");
    assert_eq!(r["state"]["message"], "请检查刀具长度");
    assert_eq!(xyz(&r, "workpiece"), (1.0, 7.0, 0.0));
}

#[test]
fn a_tool_data_ini_file_loads_through_machine_data_with_its_ignored_lines_noted() {
    let dir = folder("tool_data");
    let main = dir.join("T.MPF");
    std::fs::write(&main, "G54 T1 D1\nG0 X0 Y0 Z0\nM30\n").unwrap();
    let (code, r) = simulate(&["--machine-data", "tool_data/INITIAL.INI", main.to_str().unwrap()]);
    assert_eq!(code, 0, "{r:#}");
    // $P_UIFR[1] = CTRANS(X,100,Y,50,Z,-20); tool 1 edge 1: length 80.25 along Z.
    assert_eq!(xyz(&r, "machine"), (100.0, 50.0, 60.25));
    let notes: Vec<&str> = r["notes"].as_array().unwrap().iter().map(|n| n["message"].as_str().unwrap()).collect();
    assert_eq!(
        notes,
        [
            // $TC_TP and $TC_MPP lines are tool management data NCTwin keeps.
            "$SN_ setting data ($SN_JOG_CONT_MODE_LEVELTRIGGRD): 1 line(s) from line 17 not modelled by NCTwin: accepted and ignored",
        ]
    );
}

//! `nctwin simulate --stock-out`: the real binary cuts a program's `WORKPIECE` blank and writes
//! the stock as a binary STL; the report carries the volumes and the checks.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

fn folder(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("simulate_stock").join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp folder");
    dir
}

fn simulate(args: &[&str]) -> (i32, Value, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_nctwin")).arg("simulate").args(args).output().expect("nctwin runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let json = serde_json::from_str(&stdout).unwrap_or(Value::Null);
    (out.status.code().expect("exit code"), json, String::from_utf8_lossy(&out.stderr).into_owned())
}

#[test]
fn a_faced_tube_is_written_as_stl_and_its_removed_ring_reported() {
    let dir = folder("faced");
    // Tube Ø50/Ø30, 60 long; facing 1 mm off the end with the SL3 nose 0.8 down to X14:
    // π (25² − 15²) · 1 = 1256.64 mm³.
    let program = "G18 G90 G94\nT1 D1\nG0 X60 Z50\nWORKPIECE(,\"\",,\"PIPE\",80,0,-60,-80,50,30)\nS1000 M3\nG0 X27 Z-1\nG1 X14 F200\nG0 Z5\nG0 X60 Z50\nM30\n";
    let path = dir.join("face.mpf");
    std::fs::write(&path, program).unwrap();
    let stl = dir.join("part.stl");
    let (code, r, err) = simulate(&[
        "--machine",
        "lathe-2axis",
        "--stock-out",
        stl.to_str().unwrap(),
        "--compact",
        path.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{r} {err}");
    let removed = r["state"]["stock"]["removed"].as_f64().unwrap();
    assert!((removed - std::f64::consts::PI * 400.0).abs() < 1e-6, "{removed}");
    assert_eq!(r["state"]["stock"]["model"], "turning");
    let bytes = std::fs::read(&stl).unwrap();
    let triangles = u32::from_le_bytes(bytes[80..84].try_into().unwrap()) as usize;
    assert_eq!(bytes.len(), 84 + 50 * triangles);
    assert!(triangles > 0);
}

#[test]
fn stock_out_without_a_blank_is_a_usage_error() {
    let dir = folder("no_blank");
    let path = dir.join("p.mpf");
    std::fs::write(&path, "G0 X10\nM30\n").unwrap();
    let stl = dir.join("part.stl");
    let (code, _, err) =
        simulate(&["--machine", "mill-3axis", "--stock-out", stl.to_str().unwrap(), path.to_str().unwrap()]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("WORKPIECE"), "{err}");
}

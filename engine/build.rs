//! Embeds the standard cycle library (`cycles/*.SPF`, NC programs of the control's cycle
//! directory CST) into the engine, so a new cycle needs only its file.

use std::env;
use std::fmt::Write as _;
use std::fs;
use std::path::Path;

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("cycles");
    println!("cargo:rerun-if-changed={}", dir.display());
    let mut files: Vec<_> = fs::read_dir(&dir)
        .expect("engine/cycles exists")
        .map(|entry| entry.expect("readable cycles directory").path())
        .filter(|path| path.extension().is_some_and(|ext| ext.eq_ignore_ascii_case("spf")))
        .collect();
    files.sort();
    for path in &files {
        println!("cargo:rerun-if-changed={}", path.display());
    }
    let mut code = String::from(
        "/// The cycle files: name (the file stem, upper case) and text.\npub static FILES: &[(&str, &str)] = &[\n",
    );
    for path in &files {
        let name = path.file_stem().and_then(|s| s.to_str()).expect("UTF-8 file name").to_ascii_uppercase();
        writeln!(code, "    ({name:?}, include_str!({:?})),", path.display().to_string()).unwrap();
    }
    code.push_str("];\n");
    let out = Path::new(&env::var("OUT_DIR").expect("OUT_DIR")).join("cycle_files.rs");
    fs::write(out, code).expect("write cycle_files.rs");
}

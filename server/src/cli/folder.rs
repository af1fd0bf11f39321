//! Program folders laid out like the control's: `MPF`, `SPF`, `WKS/<NAME>.WPD`, `CUS`, `CMA`,
//! `CST` (also spelled `MPF.DIR`, `_N_MPF_DIR`, `_N_<NAME>_WPD`, any case), a `<NAME>.WPD`
//! folder at the top, and loose files at the top (a flat store, found from anywhere).
//!
//! Opening a folder lists it and reads nothing but archive files: each `*.MPF`/`*.SPF` file
//! becomes a program read, decoded and checked the first time it is called
//! ([`StoredProgram::lazy`]), so a broken, undecodable or oddly named file only ever concerns
//! the run that calls it. A file that is skipped is a [`Note`], never an error of the folder.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use nctwin_engine::programs::{Dir, Kind, StoredProgram, archive, canonical_name};
use nctwin_server::text_decode::decode;

/// A file (or a line of one) that was skipped, and why.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Note {
    pub path: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line: Option<u32>,
    pub message: String,
    /// A finding about a program (it cannot be read, or its name is no program name), not
    /// just a file that is no program.
    #[serde(skip)]
    pub finding: bool,
}

/// Where a stored program's text comes from.
#[derive(Debug, Clone)]
pub struct Origin {
    pub path: PathBuf,
    /// Line of the file where the program's line 1 is (2 and up for the later programs of an
    /// archive).
    pub first_line: u32,
}

/// An opened program folder.
#[derive(Debug, Default)]
pub struct Folder {
    /// The programs with where each one comes from.
    pub programs: Vec<(StoredProgram, Origin)>,
    /// Each folder read (canonical path) with the control directory it stands for.
    pub dirs: Vec<(PathBuf, Option<Dir>)>,
    pub notes: Vec<Note>,
    /// Index in `programs` by (name, directory): a later file of the same program replaces it.
    index: HashMap<(String, Option<Dir>), usize>,
}

impl Folder {
    /// The control directory of the folder holding `file`, if that folder was read.
    pub fn dir_of(&self, file: &Path) -> Option<Option<Dir>> {
        let parent = std::fs::canonicalize(file).ok()?.parent()?.to_path_buf();
        self.dirs.iter().find(|(p, _)| *p == parent).map(|(_, d)| d.clone())
    }
}

/// Opens `root`; only an unreadable `root` itself is an error.
pub fn open(root: &Path) -> Result<Folder, String> {
    let mut folder = Folder::default();
    let entries = list(root).map_err(|e| format!("cannot read program folder {}: {e}", root.display()))?;
    folder.dirs.push((std::fs::canonicalize(root).unwrap_or_else(|_| root.to_path_buf()), None));
    let mut subdirs = Vec::new();
    for (path, is_dir) in entries {
        if is_dir {
            subdirs.push(path);
        } else {
            add_file(&mut folder, &path, None);
        }
    }
    for sub in subdirs {
        let name = file_name(&sub).to_ascii_uppercase();
        let name = name.strip_suffix(".DIR").unwrap_or(&name);
        let name = name.strip_prefix("_N_").and_then(|n| n.strip_suffix("_DIR")).unwrap_or(name);
        let dir = match name {
            "MPF" => Some(Dir::Mpf),
            "SPF" => Some(Dir::Spf),
            "CUS" => Some(Dir::Cus),
            "CMA" => Some(Dir::Cma),
            "CST" => Some(Dir::Cst),
            "WKS" => {
                read_workpieces(&mut folder, &sub);
                continue;
            }
            _ => workpiece_name(&sub).map(Dir::Workpiece),
        };
        match dir {
            Some(dir) => read_dir(&mut folder, &sub, dir),
            None => note(
                &mut folder,
                &sub,
                None,
                "not a program directory of the control (MPF, SPF, WKS, *.WPD, CUS, CMA, CST): skipped",
            ),
        }
    }
    Ok(folder)
}

/// `SHAFT.WPD` or `_N_SHAFT_WPD` → `SHAFT`.
fn workpiece_name(path: &Path) -> Option<String> {
    let upper = file_name(path).to_ascii_uppercase();
    let name = upper.strip_suffix(".WPD").or_else(|| upper.strip_prefix("_N_").and_then(|n| n.strip_suffix("_WPD")))?;
    canonical_name(name)
}

fn read_workpieces(folder: &mut Folder, wks: &Path) {
    let entries = match list(wks) {
        Ok(entries) => entries,
        Err(e) => return finding(folder, wks, None, &format!("cannot read: {e}")),
    };
    for (path, is_dir) in entries {
        match workpiece_name(&path).filter(|_| is_dir) {
            Some(name) => read_dir(folder, &path, Dir::Workpiece(name)),
            None => note(folder, &path, None, "not a workpiece folder (*.WPD): skipped"),
        }
    }
}

fn read_dir(folder: &mut Folder, path: &Path, dir: Dir) {
    let entries = match list(path) {
        Ok(entries) => entries,
        Err(e) => return finding(folder, path, None, &format!("cannot read: {e}")),
    };
    folder.dirs.push((std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf()), Some(dir.clone())));
    for (file, is_dir) in entries {
        if is_dir {
            note(folder, &file, None, "folder inside a program directory: skipped");
        } else {
            add_file(folder, &file, Some(dir.clone()));
        }
    }
}

/// The entries of a folder, sorted so that `*.MPF` comes before `*.SPF` of the same name (the
/// control looks for NAME_SPF before NAME_MPF: the subprogram replaces the main program).
fn list(path: &Path) -> std::io::Result<Vec<(PathBuf, bool)>> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(path)? {
        let entry = entry?;
        let is_dir = entry.file_type().map(|t| t.is_dir()).unwrap_or(false)
            || entry.file_type().is_ok_and(|t| t.is_symlink()) && entry.path().is_dir();
        out.push((entry.path(), is_dir));
    }
    out.sort_by_key(|(p, _)| file_name(p).to_ascii_uppercase());
    Ok(out)
}

fn file_name(path: &Path) -> String {
    path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default()
}

fn note(folder: &mut Folder, path: &Path, line: Option<u32>, message: &str) {
    folder.notes.push(Note { path: path.display().to_string(), line, message: message.to_string(), finding: false });
}

/// A [`Note`] that is a finding.
fn finding(folder: &mut Folder, path: &Path, line: Option<u32>, message: &str) {
    note(folder, path, line, message);
    if let Some(last) = folder.notes.last_mut() {
        last.finding = true;
    }
}

/// Opens one file: a program file or an archive, in no directory of the control.
pub fn open_file(path: &Path) -> Result<Folder, String> {
    if !path.is_file() {
        return Err(format!("cannot read {}: no such file or folder", path.display()));
    }
    let mut folder = Folder::default();
    if let Some(parent) = std::fs::canonicalize(path).ok().and_then(|p| p.parent().map(Path::to_path_buf)) {
        folder.dirs.push((parent, None));
    }
    add_file(&mut folder, path, None);
    Ok(folder)
}

/// The program name and kind of a file name: `SUB1.SPF`, `_N_SUB1_SPF`, `_N_SUB1_SPF.SPF`.
fn program_file(path: &Path) -> Option<(Result<String, String>, Kind)> {
    let upper = file_name(path).to_ascii_uppercase();
    let (stem, kind) = match upper.rsplit_once('.') {
        Some((stem, "MPF")) => (stem, Kind::Main),
        Some((stem, "SPF")) => (stem, Kind::Sub),
        _ if upper.starts_with("_N_") && (upper.ends_with("_MPF") || upper.ends_with("_SPF")) => {
            (&upper[..], Kind::from_suffix(&upper[upper.len() - 3..]))
        }
        _ => return None,
    };
    let stem = match stem.strip_prefix("_N_") {
        Some(inner) => inner.strip_suffix("_MPF").or_else(|| inner.strip_suffix("_SPF")).unwrap_or(inner),
        None => stem,
    };
    Some((canonical_name(stem).ok_or_else(|| stem.to_string()), kind))
}

fn add_file(folder: &mut Folder, path: &Path, dir: Option<Dir>) {
    match program_file(path) {
        Some((Ok(name), kind)) => {
            let file = path.to_path_buf();
            let loader = Arc::new(move || read_program(&file));
            let program = StoredProgram::lazy(name, dir, Some(kind), loader);
            add(folder, program, Origin { path: path.to_path_buf(), first_line: 1 });
        }
        Some((Err(_), _)) => {
            finding(folder, path, None, "not a program name (letters, digits and _, at most 32): skipped")
        }
        None => read_archive(folder, path, dir),
    }
}

fn add(folder: &mut Folder, program: StoredProgram, origin: Origin) {
    let key = (program.name().to_string(), program.dir().cloned());
    match folder.index.get(&key) {
        Some(&i) => {
            let (_, old) = std::mem::replace(&mut folder.programs[i], (program, origin));
            let message = format!("{} in the same directory is called instead", folder.programs[i].1.path.display());
            note(folder, &old.path, None, &message);
        }
        None => {
            folder.index.insert(key, folder.programs.len());
            folder.programs.push((program, origin));
        }
    }
}

/// Any other file: an archive of programs is split into them (each in the directory of its
/// `;$PATH=` line, or this folder's); anything else is skipped.
fn read_archive(folder: &mut Folder, path: &Path, dir: Option<Dir>) {
    let bytes = match std::fs::read(path) {
        Ok(bytes) => bytes,
        Err(e) => return finding(folder, path, None, &format!("cannot read: {e}")),
    };
    let text = match decode(&bytes) {
        Ok(decoded) if archive::is_archive(&decoded.text) => decoded.text,
        Ok(_) => return note(folder, path, None, "not a program file (*.MPF, *.SPF or an archive): skipped"),
        Err(e) => return note(folder, path, None, &format!("{e}: skipped")),
    };
    let split = archive::split(&text);
    for problem in &split.problems {
        finding(folder, path, Some(problem.line), &problem.message);
    }
    for entry in &split.entries {
        if !entry.kind.is_program() {
            let message = format!("{}_{} is NC data: load it with --machine-data", entry.name, entry.kind.suffix());
            note(folder, path, Some(entry.line), &message);
            continue;
        }
        let Some(name) = canonical_name(&entry.name) else {
            finding(folder, path, Some(entry.line), "not a program name: skipped");
            continue;
        };
        let program = StoredProgram::unchecked(
            name,
            entry.dir.clone().or(dir.clone()),
            Some(entry.kind.clone()),
            Arc::from(entry.numbered_text()),
        );
        add(folder, program, Origin { path: path.to_path_buf(), first_line: entry.line });
    }
}

/// Reads a program file for its first call: decoded, and of an archive header only its first
/// program (the header lines become comments, so the lines count as in the file).
pub fn read_program(path: &Path) -> Result<String, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let text = decode(&bytes).map_err(|e| format!("{}: {e}", path.display()))?.text;
    if !archive::is_archive(&text) {
        return Ok(text);
    }
    let split = archive::split(&text);
    split
        .entries
        .first()
        .map(archive::Entry::numbered_text)
        .ok_or_else(|| format!("{}: no program in the archive", path.display()))
}

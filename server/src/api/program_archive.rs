//! `POST/GET /sessions/{id}/program-archive`: the session's programs as one archive file in the
//! control's punch-tape format (`%_N_NAME_MPF`, `;$PATH=/_N_MPF_DIR`, the program, the next
//! header ...), the form machines and Operate export.
//!
//! NC data sections (`%_N_TOA_INI`, `_UFR_INI`, `_SEA_INI` ...) are loaded as the control loads
//! an INI file it reads in: after the programs are stored, all of them together as one
//! `PUT .../machine-data` would (all or nothing, only in reset state, saved before the reply;
//! NC data NCTwin does not model is named in `nctwin-nc-data-ignored` headers). Data that do not
//! load put the programs back: the archive is imported whole or not at all.
//!
//! Import stores every main program and subprogram of the archive under its name through
//! [`AppState::put_program`] (its size limits and its save before the reply), all or nothing:
//! the archive is checked whole first (headers, names, syntax, one program per name), and a
//! store that fails half-way puts the programs already replaced back. A program whose
//! `;$PATH=` line names a directory is stored in it under its name with the directory
//! (`/_N_WKS_DIR/_N_FLANGE_WPD/FLANGE`, [`nctwin_engine::programs::qualified_name`]): the
//! program list, a restart and the export keep it there. A program without a `;$PATH=` line
//! goes into the session's flat store (its name alone); export files such a program in
//! `_N_SPF_DIR` when it is a subprogram (it starts with `PROC` or ends with `M17`/`RET`),
//! else in `_N_MPF_DIR`.

use axum::body::Bytes;
use axum::extract::{Path, State};
use axum::http::HeaderValue;
use axum::http::header::CONTENT_TYPE;
use axum::response::{IntoResponse, Response};
use nctwin_engine::lang;
use nctwin_engine::programs::{Dir, Kind, archive, canonical_name, qualified_name, split_qualified};

use super::machine_data::IGNORED_HEADER;
use super::{command, find_entry, find_session};
use crate::dto::{ArchiveImport, ArchiveNcData, ArchiveProgram, ArchiveSkipped, ErrorBody};
use crate::error::ApiError;
use crate::session::Action;
use crate::state::AppState;
use crate::state::SessionEntry;
use crate::text_decode::decode;

/// Stores the programs of an archive file (the body: the file's bytes, UTF-8 or a legacy code
/// page, LF or CRLF), each in the directory of its `;$PATH=` line, and loads its NC data
/// sections (`_INI`) as the control does; other sections are listed as skipped.
#[utoipa::path(
    post,
    path = "/sessions/{id}/program-archive",
    tag = "programs",
    params(("id" = String, Path, description = "Session id")),
    request_body(content = String, content_type = "text/plain", description = "The archive file: `%_N_NAME_MPF` / `%_N_NAME_SPF` headers, optional `;$PATH=` lines, the programs"),
    responses(
        (status = 200, description = "Every program stored, every NC data section loaded", body = ArchiveImport,
            headers(("nctwin-nc-data-ignored" = String, description = "One per family of NC data lines accepted but not modelled"))),
        (status = 400, description = "Not an archive, an unreadable header, a bad name, a name twice in one directory, a syntax error (program and line named), bad NC data (its archive line) or undecodable bytes; nothing stored", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "The archive has NC data and the channel is not in reset state; nothing stored", body = ErrorBody),
        (status = 413, description = "A program or the session's programs exceed their size limit; nothing stored", body = ErrorBody),
        (status = 503, description = "The storage failed; nothing stored", body = ErrorBody),
    )
)]
pub async fn import_archive(
    State(state): State<AppState>,
    Path(id): Path<String>,
    body: Bytes,
) -> Result<Response, ApiError> {
    let entry = find_entry(&state, &id)?;
    let text = decode(&body).map_err(|e| ApiError::bad_request(format!("archive: {e}")))?.text;
    if !archive::is_archive(&text) {
        return Err(ApiError::bad_request("not an archive: its first line must be a header such as %_N_PART1_MPF"));
    }
    let split = archive::split(&text);
    if let Some(p) = split.problems.first() {
        return Err(ApiError::BadRequest {
            message: format!("archive line {}: {}", p.line, p.message),
            line: Some(p.line),
        });
    }
    let mut programs: Vec<(ArchiveProgram, String)> = Vec::new();
    let mut skipped = Vec::new();
    let mut nc_data = NcData::default();
    for e in &split.entries {
        if e.kind == Kind::Ini {
            nc_data.add(e);
            continue;
        }
        if !e.kind.is_program() {
            let reason = format!("_{} files are not programs", e.kind.suffix());
            skipped.push(ArchiveSkipped { name: format!("{}_{}", e.name, e.kind.suffix()), line: e.line, reason });
            continue;
        }
        let bad = |message: String| ApiError::BadRequest { message, line: Some(e.line) };
        let name = canonical_name(&e.name).ok_or_else(|| {
            bad(format!("archive line {}: `{}` is not a program name (letters, digits, _; at most 32)", e.line, e.name))
        })?;
        // Stored with its directory when the archive names one other than the part-program and
        // subprogram directories: the session's flat store stands for those two (the control
        // finds their programs by name), so `UPMAIN` stays `UPMAIN`.
        let name = qualified_name(e.dir.as_ref().filter(|d| !matches!(d, Dir::Mpf | Dir::Spf)), &name);
        if programs.iter().any(|(p, _)| p.name == name) {
            return Err(bad(format!(
                "archive line {}: a second program {name}: the session keeps one program per name and directory",
                e.line
            )));
        }
        let errors = lang::check(e.body());
        if let Some(first) = errors.first() {
            let line = first.line + e.body_line() - 1;
            let (listed, omitted) = crate::dto::first_diagnostics(&errors);
            return Err(ApiError::Program {
                message: format!(
                    "program {name} line {} (archive line {line}) column {}: {}",
                    first.line, first.column, first.message
                ),
                line,
                errors: listed,
                omitted,
            });
        }
        let info = ArchiveProgram {
            name,
            kind: e.kind.suffix().to_string(),
            directory: e.dir.as_ref().unwrap_or(&Dir::default_for(&e.kind)).path(),
            size: e.body().len(),
        };
        programs.push((info, e.body().to_string()));
    }
    // What each name held before, to put back if a store fails half-way.
    let names: Vec<String> = programs.iter().map(|(p, _)| p.name.clone()).collect();
    let previous: Vec<Option<String>> = find_session(&state, &id)?
        .with_channel(move |ch| names.iter().map(|n| ch.stored_program(n).map(str::to_string)).collect())
        .await
        .map_err(|e| ApiError::from_session(&id, e))?;
    for (i, (info, text)) in programs.iter().enumerate() {
        if let Err(e) = state.put_program(&entry, info.name.clone(), text.clone()).await {
            put_back(&state, &entry, &programs[..i], &previous).await;
            return Err(e);
        }
    }
    let mut warnings = Vec::new();
    if !nc_data.sections.is_empty() {
        warnings = nctwin_engine::machine_data::text::warnings(&nc_data.text);
        let loaded = command(&state, &id, Action::MachineData(nc_data.text.clone()), None).await;
        if let Err(e) = loaded {
            put_back(&state, &entry, &programs, &previous).await;
            return Err(nc_data.archive_error(e));
        }
        state.persist_checkpoint(&entry).await?;
    }
    let import =
        ArchiveImport { programs: programs.into_iter().map(|(p, _)| p).collect(), nc_data: nc_data.sections, skipped };
    let mut response = axum::Json(import).into_response();
    for warning in warnings {
        if let Ok(value) = HeaderValue::from_str(&warning) {
            response.headers_mut().append(IGNORED_HEADER, value);
        }
    }
    Ok(response)
}

/// Puts back what the names of `done` held before the import (`previous`, in order).
async fn put_back(
    state: &AppState,
    entry: &SessionEntry,
    done: &[(ArchiveProgram, String)],
    previous: &[Option<String>],
) {
    for ((program, _), before) in done.iter().zip(previous).rev() {
        let _ = match before {
            Some(text) => state.put_program(entry, program.name.clone(), text.clone()).await.map(drop),
            None => state.delete_program(entry, program.name.clone()).await.map(drop),
        };
    }
}

/// The NC data sections of an archive as one text, loaded together (all or nothing), with the
/// archive line each section's text starts at.
#[derive(Debug, Default)]
struct NcData {
    text: String,
    sections: Vec<ArchiveNcData>,
    /// (first line of the section in `text`, archive line of that line), in order.
    starts: Vec<(u32, u32)>,
}

impl NcData {
    fn add(&mut self, e: &archive::Entry) {
        let first = self.text.matches('\n').count() as u32 + 1;
        self.starts.push((first, e.body_line()));
        self.text.push_str(e.body());
        if !self.text.ends_with('\n') {
            self.text.push('\n');
        }
        self.sections.push(ArchiveNcData { name: format!("{}_{}", e.name, e.kind.suffix()), line: e.line });
    }

    /// A load error with its line counted in the archive.
    fn archive_error(&self, e: ApiError) -> ApiError {
        match e {
            ApiError::BadRequest { message, line: Some(line) } => {
                let (first, archive_line) =
                    self.starts.iter().rev().find(|(first, _)| *first <= line).copied().unwrap_or((1, 1));
                let at = archive_line + line - first;
                ApiError::BadRequest { message: format!("archive line {at}: {message}"), line: Some(at) }
            }
            other => other,
        }
    }
}

/// Every stored program as one archive file (LF line ends), by name.
#[utoipa::path(
    get,
    path = "/sessions/{id}/program-archive",
    tag = "programs",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The archive file", body = String, content_type = "text/plain"),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn export_archive(State(state): State<AppState>, Path(id): Path<String>) -> Result<Response, ApiError> {
    let session = find_session(&state, &id)?;
    let text = session
        .with_channel(|ch| {
            let mut out = String::new();
            for (stored, _) in ch.stored_programs() {
                let Some(text) = ch.stored_program(&stored) else { continue };
                let kind = if is_subprogram(text) { Kind::Sub } else { Kind::Main };
                let (dir, name) = split_qualified(&stored);
                let dir = dir.unwrap_or_else(|| Dir::default_for(&kind));
                archive::write(&mut out, name, &kind, Some(&dir), text);
            }
            out
        })
        .await
        .map_err(|e| ApiError::from_session(&id, e))?;
    Ok(([(CONTENT_TYPE, "text/plain; charset=utf-8")], text).into_response())
}

/// A subprogram starts with `PROC` (after comments and blank lines) or ends with `M17`/`RET`.
fn is_subprogram(text: &str) -> bool {
    let code = |l: &&str| {
        let l = l.split(';').next().unwrap_or("").trim();
        !l.is_empty()
    };
    let first = text.lines().find(code).map(|l| l.trim().to_ascii_uppercase());
    let last = text.lines().rev().find(code).map(|l| l.split(';').next().unwrap_or("").trim().to_ascii_uppercase());
    let ends = |l: &str| l.split_whitespace().any(|w| w == "M17" || w == "RET");
    first.is_some_and(|f| f.starts_with("PROC ") || f == "PROC") || last.is_some_and(|l| ends(&l))
}

#[cfg(test)]
mod tests {
    use super::is_subprogram;

    #[test]
    fn subprograms_are_told_by_proc_or_their_return() {
        assert!(is_subprogram("; cycle\n\nPROC DRILL(REAL DEPTH)\nG1 X=DEPTH\nRET\n"));
        assert!(is_subprogram("G0 X1\nN20 M17 ; back\n"));
        assert!(!is_subprogram("G0 X1\nM30\n"));
        assert!(!is_subprogram("; PROC in a comment\nG0 X1\n"));
    }
}

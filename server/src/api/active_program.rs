//! `GET /sessions/{id}/active-program`: the program the channel runs (or ran last), whoever
//! started it, by line ranges, with its name, version and the call stack of the block in
//! execution. A display pages through a CAM program of millions of blocks with it instead of
//! loading the whole text; the state's `program_serial` tells it when to reload.

use std::sync::Arc;

use axum::Json;
use axum::extract::rejection::QueryRejection;
use axum::extract::{Path, Query, State};
use nctwin_engine::channel::{ActiveProgram, CallLevel};
use nctwin_engine::{Channel, Mode};
use serde::{Deserialize, Serialize};
use utoipa::{IntoParams, ToSchema};

use super::find_session;
use crate::dto::{ErrorBody, OpMode};
use crate::error::ApiError;
use crate::session::active_program::{ActiveCache, IndexedText};
use crate::state::AppState;

/// Most lines one request may ask for.
pub const MAX_LINES: usize = 5000;
/// Lines given when `count` is absent.
pub const DEFAULT_LINES: usize = 200;

/// The line range asked for.
#[derive(Debug, Clone, Deserialize, IntoParams)]
#[into_params(parameter_in = Query)]
pub struct RangeParams {
    /// First line (1-based, default 1). May be one past the last line (an empty answer).
    pub from: Option<usize>,
    /// Number of lines (1..=5000, default 200); fewer at the end of the text.
    pub count: Option<usize>,
    /// The lines of this program of the call stack (a subprogram or cycle by name) instead of
    /// the main program's.
    pub program: Option<String>,
}

/// One level of the call stack.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct CallLevelInfo {
    /// The program of this level by its stored name; null: the main program.
    pub program: Option<String>,
    /// 1-based line in that program: the calling block, on the last level the block in
    /// execution.
    pub line: u32,
}

/// The loaded program and a range of its lines (or of a subprogram's).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ActiveProgramResponse {
    /// Counts the programs the channel loaded; the state's `program_serial`.
    pub serial: u64,
    /// The name it was started under or the stored program with the same text; null for MDA
    /// blocks and unnamed texts.
    pub name: Option<String>,
    /// The directory part of `name` when it names one (`/_N_WKS_DIR/_N_PART_WPD`), else null.
    pub directory: Option<String>,
    /// AUTO or MDA.
    pub mode: OpMode,
    /// SHA-256 of the main program's text (lowercase hex): its version.
    pub sha256: String,
    /// Lines of the main program (a final line end adds none).
    pub line_count: usize,
    /// Bytes of the main program.
    pub bytes: usize,
    /// The program the lines are from: null for the main program, else the `program` asked.
    pub program: Option<String>,
    /// Lines of the program the lines are from.
    pub program_line_count: usize,
    /// Number of the first line given.
    pub from: usize,
    /// The lines, without line ends.
    pub lines: Vec<String>,
    /// The call stack of the block in execution, main program first (empty when none is).
    pub call_stack: Vec<CallLevelInfo>,
}

/// The loaded program of a session by line ranges: its name, version and call stack.
///
/// The program is the one the channel runs or ran last, whoever started it: a `run`, MDA, a
/// block search, a restart that resumed it. It is kept over a reset (as the control keeps the
/// selected program). `program` gives the lines of a subprogram or cycle of the call stack.
#[utoipa::path(
    get,
    path = "/sessions/{id}/active-program",
    tag = "program",
    params(("id" = String, Path, description = "Session id"), RangeParams),
    responses(
        (status = 200, description = "The program and the lines asked for", body = ActiveProgramResponse),
        (status = 400, description = "`from` is 0 or more than one past the last line, or `count` is not 1..=5000", body = ErrorBody),
        (status = 404, description = "No such session, no program loaded yet, or no program of that name", body = ErrorBody),
    )
)]
pub async fn get_active_program(
    State(state): State<AppState>,
    Path(id): Path<String>,
    query: Result<Query<RangeParams>, QueryRejection>,
) -> Result<Json<ActiveProgramResponse>, ApiError> {
    let Query(params) = query.map_err(|e| ApiError::bad_request(e.body_text()))?;
    let count = params.count.unwrap_or(DEFAULT_LINES);
    if !(1..=MAX_LINES).contains(&count) {
        return Err(ApiError::bad_request(format!("count must be 1..={MAX_LINES}, not {count}")));
    }
    let from = params.from.unwrap_or(1);
    if from == 0 {
        return Err(ApiError::bad_request("from is 1-based: the first line is 1"));
    }
    let session = find_session(&state, &id)?;
    let cache = session.active_cache().clone();
    let wanted = params.program.clone();
    let read = session
        .with_channel(move |ch| read_channel(ch, &cache, wanted.as_deref()))
        .await
        .map_err(|e| ApiError::from_session(&id, e))?;
    let Some(read) = read else { return Err(ApiError::NotFound("a loaded program (none has run yet)".into())) };
    let cache = session.active_cache().clone();
    let main = match cache.cached(read.program.serial, &read.program.text) {
        Some(hit) => hit,
        None => {
            let (serial, text) = (read.program.serial, read.program.text.clone());
            let indexed = tokio::task::spawn_blocking(move || Arc::new(IndexedText::new(serial, text)))
                .await
                .map_err(|e| ApiError::Conflict(format!("indexing the program failed: {e}")))?;
            cache.store(indexed.clone());
            indexed
        }
    };
    let sub = match (&params.program, read.sub) {
        (None, _) => None,
        (Some(name), None) => return Err(ApiError::NotFound(format!("program `{name}`"))),
        (Some(_), Some(text)) => {
            let cache = session.active_cache().clone();
            let indexed = tokio::task::spawn_blocking(move || cache.sub_indexed(text))
                .await
                .map_err(|e| ApiError::Conflict(format!("indexing the program failed: {e}")))?;
            Some(indexed)
        }
    };
    let shown = sub.as_ref().unwrap_or(&main);
    let total = shown.line_count();
    if from > total + 1 {
        return Err(ApiError::bad_request(format!("from {from} is past the end: the program has {total} lines")));
    }
    let lines =
        (from..from.saturating_add(count).min(total + 1)).filter_map(|n| shown.line(n)).map(str::to_owned).collect();
    let name = read.name;
    let directory =
        name.as_deref().and_then(|n| n.rsplit_once('/')).map(|(dir, _)| dir.to_owned()).filter(|d| !d.is_empty());
    Ok(Json(ActiveProgramResponse {
        serial: main.serial,
        name,
        directory,
        mode: read.program.mode.into(),
        sha256: main.sha256.clone(),
        line_count: main.line_count(),
        bytes: main.text.len(),
        program: params.program.map(|p| p.trim().to_ascii_uppercase()),
        program_line_count: total,
        from,
        lines,
        call_stack: read.stack.into_iter().map(|l| CallLevelInfo { program: l.program, line: l.line }).collect(),
    }))
}

/// What is read from the channel inside the actor (cheap: shared texts, no scan of the
/// program except to compare it with stored programs of the same size, once per load).
struct ChannelRead {
    program: ActiveProgram,
    name: Option<String>,
    stack: Vec<CallLevel>,
    sub: Option<nctwin_engine::lang::ProgramText>,
}

fn read_channel(ch: &Channel, cache: &ActiveCache, wanted: Option<&str>) -> Option<ChannelRead> {
    let program = ch.active_program()?;
    let name = match cache.label(program.serial) {
        Some(name) => name,
        None => {
            let found = if program.mode == Mode::Mda { None } else { stored_with_text(ch, &program.text) };
            cache.set_label(program.serial, found.clone());
            found
        }
    };
    let sub = wanted.and_then(|n| ch.program_text(n));
    Some(ChannelRead { program, name, stack: ch.call_stack(), sub })
}

/// The stored program whose text is `text` (the first by name), if any: the name of a program
/// run as text, or resumed after a restart.
fn stored_with_text(ch: &Channel, text: &str) -> Option<String> {
    ch.stored_programs()
        .into_iter()
        .filter(|(_, size)| *size == text.len())
        .find(|(name, _)| ch.stored_program(name) == Some(text))
        .map(|(name, _)| name)
}

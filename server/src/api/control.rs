//! Program control of a session's channel: run, start, stop, reset, cancel, MDA and the mode.

use axum::extract::{Path, State};
use nctwin_engine::channel::{PathStep, ReposApproach, ReposMode};
use nctwin_engine::interp::program_control::SkipLevels;

use super::{StateReply, command};
use crate::dto::{
    self, ErrorBody, MdaRequest, ModeRequest, OptionsRequest, OverridesRequest, RunRequest, SearchRequest,
    StartRequest, drive,
};
use crate::error::ApiError;
use crate::extract::{ApiJson, OptionalJson};
use crate::session::{Action, ProgramOptions};
use crate::state::AppState;

/// Loads a part program and starts it in AUTO mode: the text of `program`, or without it the
/// stored program `name` (as Operate's Select and Cycle start; its text is not copied).
///
/// A program with syntax errors is not started (`400` with the line) and nothing moves.
/// `pace: "fast"` computes as fast as possible (simulated time unaffected) for at most 3600 s of
/// simulated time per command; then the channel is stopped (NC stop) and the reply carries
/// the header `nctwin-limit: fast-sim-time` (`fast-wall-time` when it computed for 10 s of wall
/// time first). With `wait: true` the reply comes when the program
/// has ended, stopped (M0, M1 with optional stop, alarm) or a limit was hit; a wait lasts at
/// most 600 s of wall time (then the current state with `nctwin-limit: wait-wall-time`).
#[utoipa::path(
    post,
    path = "/sessions/{id}/run",
    tag = "program",
    params(("id" = String, Path, description = "Session id")),
    request_body = RunRequest,
    responses(
        (status = 200, description = "The state after the start, or at the end of the wait", body = dto::State,
            headers(("nctwin-limit" = String, description = "`fast-sim-time`, `fast-wall-time` or `wait-wall-time` when a server-side limit ended the command or its wait"))),
        (status = 400, description = "Syntax error (with its line), neither `program` nor `name`, no stored program `name`, a skip level outside 0..9, or a malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "A program is active or an alarm needs a reset", body = ErrorBody),
    )
)]
pub async fn run(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<RunRequest>,
) -> Result<StateReply, ApiError> {
    if body.program.is_none() && body.name.is_none() {
        return Err(ApiError::bad_request("give `program` (the text) or `name` (a stored program to run)"));
    }
    let options = ProgramOptions {
        single_block: None,
        optional_stop: body.optional_stop,
        dry_run: body.dry_run,
        skip_levels: body.skip_levels.as_deref().map(skip_levels).transpose()?,
    };
    let action = Action::Run { program: body.program, options, name: body.name };
    command(&state, &id, action, Some(drive(body.pace, body.wait))).await
}

/// NC start: continues a program stopped at M0/M1 or by NC stop (or restarts the loaded
/// program from reset state in AUTO). After JOG in the interrupted program it first returns on
/// a straight line (REPOS) to the point `repos` selects (RMI default, RMB, RME, RMN), or on a
/// quarter circle or semicircle (`approach` `REPOSQ`/`REPOSH` with `disr`). Same
/// `pace`/`wait` options and limits as `run`; the body may be empty.
#[utoipa::path(
    post,
    path = "/sessions/{id}/start",
    tag = "program",
    params(("id" = String, Path, description = "Session id")),
    request_body(content = Option<StartRequest>, description = "Optional; empty means realtime, no wait"),
    responses(
        (status = 200, description = "The state after the start, or at the end of the wait", body = dto::State,
            headers(("nctwin-limit" = String, description = "`fast-sim-time`, `fast-wall-time` or `wait-wall-time` when a server-side limit ended the command or its wait"))),
        (status = 400, description = "No program loaded, REPOSQ/REPOSH without a positive `disr`, or a malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "An alarm needs a reset, or JOG mode", body = ErrorBody),
    )
)]
pub async fn start(
    State(state): State<AppState>,
    Path(id): Path<String>,
    OptionalJson(body): OptionalJson<StartRequest>,
) -> Result<StateReply, ApiError> {
    let approach = body.approach().map_err(ApiError::bad_request)?;
    let action = match (body.repos, approach) {
        (None, ReposApproach::Line) => Action::Start,
        (target, approach) => Action::StartRepos(target.map_or(ReposMode::Interruption, Into::into), approach),
    };
    command(&state, &id, action, Some(drive(body.pace, body.wait))).await
}

/// NC stop: the axes brake on the path; `start` continues. Never refused by the command rate
/// limit.
#[utoipa::path(
    post,
    path = "/sessions/{id}/stop",
    tag = "program",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The state after the stop command (axes may still be braking)", body = dto::State),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn stop(State(state): State<AppState>, Path(id): Path<String>) -> Result<StateReply, ApiError> {
    command(&state, &id, Action::Stop, None).await
}

/// Channel reset: ends the program, stops every axis and spindle at once and clears the alarms
/// a reset clears. Never refused by the command rate limit.
#[utoipa::path(
    post,
    path = "/sessions/{id}/reset",
    tag = "program",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The state after the reset", body = dto::State),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn reset(State(state): State<AppState>, Path(id): Path<String>) -> Result<StateReply, ApiError> {
    command(&state, &id, Action::Reset, None).await
}

/// Cancel key: clears the alarms that cancel clears (e.g. 10621 after a JOG to a limit).
#[utoipa::path(
    post,
    path = "/sessions/{id}/cancel",
    tag = "program",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The state after the cancel", body = dto::State),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn cancel(State(state): State<AppState>, Path(id): Path<String>) -> Result<StateReply, ApiError> {
    command(&state, &id, Action::Cancel, None).await
}

/// Executes blocks in MDA mode (switching to MDA if the channel is in reset state). Same
/// `pace`/`wait` options and limits as `run`.
#[utoipa::path(
    post,
    path = "/sessions/{id}/mda",
    tag = "program",
    params(("id" = String, Path, description = "Session id")),
    request_body = MdaRequest,
    responses(
        (status = 200, description = "The state after the start, or at the end of the wait", body = dto::State,
            headers(("nctwin-limit" = String, description = "`fast-sim-time`, `fast-wall-time` or `wait-wall-time` when a server-side limit ended the command or its wait"))),
        (status = 400, description = "Syntax error (with its line) or a malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "A program is active or an alarm needs a reset", body = ErrorBody),
    )
)]
pub async fn mda(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<MdaRequest>,
) -> Result<StateReply, ApiError> {
    command(&state, &id, Action::Mda { program: body.program }, Some(drive(body.pace, body.wait))).await
}

/// Changes the operating mode; only in reset state.
#[utoipa::path(
    put,
    path = "/sessions/{id}/mode",
    tag = "program",
    params(("id" = String, Path, description = "Session id")),
    request_body = ModeRequest,
    responses(
        (status = 200, description = "The state in the new mode", body = dto::State),
        (status = 400, description = "Malformed body or unknown mode", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "A program or motion is active", body = ErrorBody),
    )
)]
pub async fn set_mode(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<ModeRequest>,
) -> Result<StateReply, ApiError> {
    command(&state, &id, Action::SetMode(body.mode.into()), None).await
}

/// Sets feed, rapid and spindle override (percent); they act at once on a running program.
#[utoipa::path(
    put,
    path = "/sessions/{id}/overrides",
    tag = "program",
    params(("id" = String, Path, description = "Session id")),
    request_body = OverridesRequest,
    responses(
        (status = 200, description = "The state with the new overrides", body = dto::State),
        (status = 400, description = "A value outside its range, or a malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn set_overrides(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<OverridesRequest>,
) -> Result<StateReply, ApiError> {
    let action = Action::SetOverrides { feed: body.feed, rapid: body.rapid, spindle: body.spindle };
    command(&state, &id, action, None).await
}

/// Sets the workpiece counters (`$AC_REQUIRED_PARTS`, `$AC_TOTAL_PARTS`, `$AC_ACTUAL_PARTS`,
/// `$AC_SPECIAL_PARTS`), as the operator does between batches; they act on the next count.
#[utoipa::path(
    put,
    path = "/sessions/{id}/parts",
    tag = "program",
    params(("id" = String, Path, description = "Session id")),
    request_body = dto::PartsRequest,
    responses(
        (status = 200, description = "The state with the new counts", body = dto::State),
        (status = 400, description = "A count above 999,999,999, or a malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn set_parts(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<dto::PartsRequest>,
) -> Result<StateReply, ApiError> {
    let counts = [body.required, body.total, body.actual, body.special];
    command(&state, &id, Action::SetParts(counts), None).await
}

/// The skip levels of a request: 0..=9, else 400 naming the level.
fn skip_levels(levels: &[i64]) -> Result<SkipLevels, ApiError> {
    let max = i64::from(SkipLevels::MAX_LEVEL);
    let bad = |l: i64| ApiError::bad_request(format!("skip level {l} is not one of 0..{max} (/0../9)"));
    let levels = levels.iter().map(|&l| u8::try_from(l).map_err(|_| bad(l))).collect::<Result<Vec<_>, _>>()?;
    SkipLevels::from_levels(&levels).map_err(|l| bad(i64::from(l)))
}

/// Switches single block (SBL1), optional stop (M1), dry-run feed (DRY) and skip levels (SKP).
#[utoipa::path(
    put,
    path = "/sessions/{id}/options",
    tag = "program",
    params(("id" = String, Path, description = "Session id")),
    request_body = OptionsRequest,
    responses(
        (status = 200, description = "The state with the new options", body = dto::State),
        (status = 400, description = "A skip level outside 0..9, or a malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn set_options(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<OptionsRequest>,
) -> Result<StateReply, ApiError> {
    let action = Action::SetOptions(ProgramOptions {
        single_block: body.single_block,
        optional_stop: body.optional_stop,
        dry_run: body.dry_run,
        skip_levels: body.skip_levels.as_deref().map(skip_levels).transpose()?,
    });
    command(&state, &id, action, None).await
}

/// Block search with calculation to a line: the program runs from its start to the target
/// line without motion, collecting the modal state, tool, frames, transformation, spindle
/// commands and the programmed position. The channel then stands stopped at the target; NC
/// start (`start`) outputs the collected spindle commands and offsets, approaches the start of
/// the target block on a straight line (with its feed; rapid for G0) and continues there.
/// AUTO mode in reset state. A line that does not exist or holds no block is `400`; a target
/// the program never reaches (skipped, after M30, not within 50,000,000 blocks) raises alarm
/// 15370. The search follows subprogram calls: `path` names a target inside subprograms, level
/// by level (`{"line": 2, "path": [{"program": "HOLE", "line": 3}]}`: line 3 of HOLE as called
/// by line 2); a target line that calls a subprogram stops before the call.
#[utoipa::path(
    post,
    path = "/sessions/{id}/search",
    tag = "program",
    params(("id" = String, Path, description = "Session id")),
    request_body = SearchRequest,
    responses(
        (status = 200, description = "The state at the search target (or with alarm 15370)", body = dto::State),
        (status = 400, description = "No such line, a line without a block, no program, a syntax error or a malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "Not in AUTO mode, a program is active, or an alarm needs a reset", body = ErrorBody),
    )
)]
pub async fn search(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<SearchRequest>,
) -> Result<StateReply, ApiError> {
    if body.program.is_some() && body.name.is_some() {
        return Err(ApiError::bad_request("give either `program` (text) or `name` (a stored program), not both"));
    }
    let path = body.path.into_iter().map(|s| PathStep { program: s.program, line: s.line }).collect();
    let action = Action::Search { program: body.program, name: body.name, line: body.line, path };
    command(&state, &id, action, None).await
}

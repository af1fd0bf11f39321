//! `POST /sessions/{id}/preview`: the programmed toolpath of a program, for the HMI's 3D view.
//!
//! The program runs on a throwaway copy of the session's channel (its machine data, tools,
//! frames, stored programs and axis positions), reset and in fast pace on a blocking worker, so
//! the session itself is not touched. The tool tip in the WCS is sampled and thinned to a
//! polyline of bounded size; the run is bounded in simulated and in wall time.

use std::time::{Duration, Instant};

use axum::Json;
use axum::extract::{Path, State};
use nctwin_engine::{Channel, Event, Mode, Overrides, Status};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::find_session;
use crate::dto::{AlarmInfo, ErrorBody};
use crate::error::ApiError;
use crate::extract::ApiJson;
use crate::state::AppState;

/// Default and largest number of points in the answer.
pub const DEFAULT_POINTS: usize = 5000;
pub const MAX_POINTS: usize = 20_000;
/// Default and largest simulated program time in seconds.
pub const DEFAULT_TIME_S: f64 = 600.0;
pub const MAX_TIME_S: f64 = 3600.0;
/// Wall time a preview may take on its worker before it is cut short (outcome `limit`).
const WALL_LIMIT: Duration = Duration::from_secs(10);
/// Previews running at once on the whole server (each keeps a blocking worker busy); more
/// wait up to `QUEUE_WAIT`, then get `429`. Any role may ask for a preview, so this bounds
/// what observers can cost.
const CONCURRENT: usize = 2;
const QUEUE_WAIT: Duration = Duration::from_secs(5);
static RUNNING: tokio::sync::Semaphore = tokio::sync::Semaphore::const_new(CONCURRENT);
/// Sampling interval of the tool tip in simulated seconds (at least every IPO cycle).
const SAMPLE_S: f64 = 0.008;
/// A sample closer than this to the straight line between its neighbours is dropped (mm).
const COLLINEAR_TOL: f64 = 0.005;

/// Body of `POST /sessions/{id}/preview`: a program text or a stored program's name.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct PreviewRequest {
    /// The program text. Not together with `name`.
    #[schema(example = "G0 X0 Y0 Z10\nG1 Z-1 F500\nG2 X20 I10\nM30")]
    pub program: Option<String>,
    /// A stored program of the session, by name. Not together with `program`.
    pub name: Option<String>,
    /// `true`: the program the channel runs or ran last (`GET .../active-program`), e.g. a
    /// CAM program of many blocks that the viewer need not download. Not together with
    /// `program` or `name`.
    pub active: Option<bool>,
    /// Most points in the answer (2..=20000, default 5000): the path is thinned to fit.
    pub max_points: Option<usize>,
    /// Simulated seconds after which the preview stops (0 < t <= 3600, default 600).
    pub max_time: Option<f64>,
}

/// How the preview run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum PreviewOutcome {
    /// The program reached its end (M2/M30 or the end of the text).
    Ended,
    /// An NC alarm ended it (see `alarm`); the path up to there is given.
    Alarm,
    /// `max_time` (or the server's wall-time limit) cut it short.
    Limit,
}

/// The programmed toolpath.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct PreviewResponse {
    /// Geometry axis names of the three coordinates of each point (e.g. `["X", "Y", "Z"]`).
    pub axes: [String; 3],
    /// Tool tip in the WCS (mm), in program order; a missing geometry axis reads 0.
    pub points: Vec<[f64; 3]>,
    /// The same points in the BCS (before the work offsets and frames of the moment), where a
    /// 3D view of the machine places them.
    pub basic: Vec<[f64; 3]>,
    /// Program line (1-based) being executed at each point, 0 before the first block.
    pub lines: Vec<u32>,
    /// The program each of `lines` is in: 0 the main program, k the subprogram `programs[k-1]`.
    pub line_program: Vec<u32>,
    /// The subprograms (and cycles) the path passed through, by stored name.
    pub programs: Vec<String>,
    /// At each point: the working diameter (mm) while TRACYL was active, else null. Such points
    /// are on the unrolled surface (X radial, Y the arc length on this diameter, Z axial); a
    /// view wraps them onto the cylinder.
    pub tracyl_diameter: Vec<Option<f64>>,
    /// At each point: the unit tool direction (tip → holder) in the BCS while an orientation
    /// transformation (TRAORI) is active, else null; a 5-axis view draws it along the path.
    pub tool_direction: Vec<Option<[f64; 3]>>,
    /// Where an axis reached its velocity or acceleration limit in feed motion, the first
    /// [`LIMIT_HITS`] in program order (`nctwin_engine::channel::limit_watch`).
    pub limit_hits: Vec<LimitHit>,
    /// Every such hit, also those beyond the list.
    pub limit_hits_total: usize,
    /// The blank the program defined (`WORKPIECE(...)`), as first seen; null without one.
    pub blank: Option<super::preview_blank::PreviewBlank>,
    pub outcome: PreviewOutcome,
    /// The alarm that ended the run, when `outcome` is `alarm`.
    pub alarm: Option<AlarmInfo>,
    /// Simulated program time of the run in seconds.
    pub time: f64,
    /// Samples taken before thinning.
    pub samples: usize,
}

/// Most limit hits listed in a preview.
pub const LIMIT_HITS: usize = 200;

/// Which limit an axis reached.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum LimitKind {
    /// `$MA_MAX_AX_VELO`.
    Velocity,
    /// `$MA_MAX_AX_ACCEL`.
    Acceleration,
}

/// An axis reaching its velocity or acceleration limit in feed motion.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct LimitHit {
    /// The channel axis.
    #[schema(example = "X")]
    pub axis: String,
    pub kind: LimitKind,
    /// Its velocity (mm/s, °/s) or acceleration (mm/s², °/s²) then, by magnitude.
    pub value: f64,
    /// The limit from the machine data, same unit.
    pub limit: f64,
    /// The program line in execution.
    pub line: u32,
    /// The tool tip on the workpiece (geometry axes as `axes`), where a view marks it: the
    /// BCS, or on a table turned without TRAORI the tip through the machine's kinematics (the
    /// frame the table carries); under TRACYL on the unrolled surface (see `tracyl_diameter`).
    pub basic: [f64; 3],
    /// The TRACYL working diameter when the hit was under TRACYL, else null: `basic` is then
    /// radial, arc length on this diameter, axial, and a view wraps it onto the cylinder.
    pub tracyl_diameter: Option<f64>,
    /// `false`: a rotary axis the machine data's kinematics do not describe had turned the
    /// workpiece; `basic` is the BCS and may not be where the tool was on the part.
    pub exact: bool,
    /// Simulated program time in seconds.
    pub time: f64,
}

impl From<&nctwin_engine::channel::limit_watch::LimitHit> for LimitHit {
    fn from(h: &nctwin_engine::channel::limit_watch::LimitHit) -> Self {
        use nctwin_engine::channel::limit_watch::LimitKind as K;
        LimitHit {
            axis: h.axis.clone(),
            kind: match h.kind {
                K::Velocity => LimitKind::Velocity,
                K::Acceleration => LimitKind::Acceleration,
            },
            value: h.value,
            limit: h.limit,
            line: h.line,
            basic: h.basic,
            tracyl_diameter: h.tracyl_diameter,
            exact: h.exact,
            time: h.time,
        }
    }
}

impl PreviewRequest {
    fn limits(&self) -> Result<(usize, f64), ApiError> {
        let points = self.max_points.unwrap_or(DEFAULT_POINTS);
        if !(2..=MAX_POINTS).contains(&points) {
            return Err(ApiError::bad_request(format!("max_points must be 2..={MAX_POINTS}, not {points}")));
        }
        let time = self.max_time.unwrap_or(DEFAULT_TIME_S);
        if !(time.is_finite() && time > 0.0 && time <= MAX_TIME_S) {
            return Err(ApiError::bad_request(format!("max_time must be > 0 and <= {MAX_TIME_S} s, not {time}")));
        }
        Ok((points, time))
    }
}

/// Runs a program on a throwaway copy of the session's channel in fast pace and answers the
/// programmed tool tip path in the WCS as a thinned polyline. The session does not move and
/// may be in any state; the copy starts from the session's axis positions after a reset. The
/// session's skip levels (SKP) and dry-run feed (DRY) act in the copy: the path and time are
/// those the program would run with; single block and M1 do not stop it.
#[utoipa::path(
    post,
    path = "/sessions/{id}/preview",
    tag = "programs",
    params(("id" = String, Path, description = "Session id")),
    request_body = PreviewRequest,
    responses(
        (status = 200, description = "The programmed path", body = PreviewResponse),
        (status = 400, description = "Not exactly one of `program`, `name` and `active`, bad limits, a syntax error (with `line`), or a malformed body", body = ErrorBody),
        (status = 404, description = "No such session, no stored program of that name, or no loaded program", body = ErrorBody),
        (status = 409, description = "The copy cannot start the program (an alarm that a reset does not clear)", body = ErrorBody),
        (status = 429, description = "As many previews run on the server as allowed", body = ErrorBody),
    )
)]
pub async fn preview(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<PreviewRequest>,
) -> Result<Json<PreviewResponse>, ApiError> {
    let (max_points, max_time) = body.limits()?;
    let session = find_session(&state, &id)?;
    let busy = || ApiError::TooManyRequests {
        message: format!("{CONCURRENT} previews have been running for {} s; try again shortly", QUEUE_WAIT.as_secs()),
        retry_after: Some(Duration::from_secs(1)),
    };
    let _permit = tokio::time::timeout(QUEUE_WAIT, RUNNING.acquire()).await.map_err(|_| busy())?.map_err(|_| busy())?;
    let copy = session.with_channel(|ch| Box::new(ch.clone())).await.map_err(|e| ApiError::from_session(&id, e))?;
    let text = match (body.program, body.name, body.active.unwrap_or(false)) {
        (Some(text), None, false) => text,
        (None, Some(name), false) => copy
            .stored_program(&name)
            .map(str::to_owned)
            .ok_or_else(|| ApiError::NotFound(format!("program `{name}`")))?,
        (None, None, true) => copy
            .active_program()
            .map(|p| p.text.to_string())
            .ok_or_else(|| ApiError::NotFound("a loaded program (none has run yet)".into()))?,
        _ => {
            return Err(ApiError::bad_request(
                "give either `program` (the text), `name` (a stored program) or `active: true` (the loaded program)",
            ));
        }
    };
    let run = tokio::task::spawn_blocking(move || trace(copy, &text, max_time, max_points));
    let response = run.await.map_err(|e| ApiError::Conflict(format!("the preview failed: {e}")))??;
    Ok(Json(response))
}

/// Runs `text` on `channel` (fast, no operator stops) and samples the tool tip in the WCS.
pub fn trace(
    mut channel: Box<Channel>,
    text: &str,
    max_time: f64,
    max_points: usize,
) -> Result<PreviewResponse, ApiError> {
    channel.reset();
    // Operate's simulation: programs read `$P_SIM` TRUE and skip probing and PLC handshakes.
    channel.set_simulation(true);
    // The preview traces the path; the session's stock is not cut by it, and its NC start is
    // not locked by axes the session has not referenced yet.
    channel.clear_stock();
    channel.reference_all_for_simulation();
    // Operator stops would end the trace; SKP and DRY stay as the session has them.
    channel.single_block = false;
    channel.optional_stop = false;
    channel.set_overrides(Overrides { feed: 100.0, rapid: 100.0, spindle: 100.0 })?;
    if channel.mode() != Mode::Auto {
        channel.set_mode(Mode::Auto)?;
    }
    channel.run_program(text)?;
    let cfg = channel.config();
    let axes = cfg.geo_names.clone();
    let every = ((SAMPLE_S / cfg.ipo_cycle).round() as u64).max(1);
    let end_tick = channel.ticks() + (max_time / cfg.ipo_cycle).ceil() as u64;
    let started = Instant::now();
    let mut programs = Vec::new();
    let mut samples = vec![tip(&channel, &axes, &mut programs)];
    let mut limited = false;
    let mut watch = nctwin_engine::channel::limit_watch::LimitWatch::new(LIMIT_HITS);
    let mut blank = None;
    loop {
        while channel.is_busy() {
            channel.step();
            watch.observe(&channel);
            if !channel.is_busy() {
                break;
            }
            // Also at every block change, so that corners are not cut by the sampling.
            let changed = channel.take_events().iter().any(|e| matches!(e, Event::BlockChanged(_)));
            if changed && blank.is_none() {
                blank = super::preview_blank::blank_of(&mut channel);
            }
            if changed || channel.ticks().is_multiple_of(every) {
                samples.push(tip(&channel, &axes, &mut programs));
            }
            if channel.ticks() >= end_tick || (channel.ticks().is_multiple_of(4096) && started.elapsed() > WALL_LIMIT) {
                limited = true;
                break;
            }
        }
        // M0/M1: carry on as an operator's NC start would.
        if !limited && channel.status() == Status::Stopped && channel.start().is_ok() {
            continue;
        }
        break;
    }
    // The end position. A program end resets the frames (the WCS display falls back to G500):
    // the end point keeps the work offset of the last sample taken while the program ran.
    let mut end = tip(&channel, &axes, &mut programs);
    if let Some(last) = samples.last() {
        end.wcs = std::array::from_fn(|i| end.bcs[i] - (last.bcs[i] - last.wcs[i]));
    }
    samples.push(end);
    let alarm = channel.alarms().first().map(AlarmInfo::from);
    let outcome = if alarm.is_some() {
        PreviewOutcome::Alarm
    } else if limited {
        PreviewOutcome::Limit
    } else {
        PreviewOutcome::Ended
    };
    let count = samples.len();
    let kept = thin(samples, max_points);
    Ok(PreviewResponse {
        axes,
        points: kept.iter().map(|s| s.wcs).collect(),
        basic: kept.iter().map(|s| s.bcs).collect(),
        lines: kept.iter().map(|s| s.line).collect(),
        line_program: kept.iter().map(|s| s.program).collect(),
        programs,
        tracyl_diameter: kept.iter().map(|s| s.tracyl_diameter).collect(),
        tool_direction: kept.iter().map(|s| s.tool_direction).collect(),
        limit_hits: watch.hits().iter().map(LimitHit::from).collect(),
        limit_hits_total: watch.total(),
        blank: blank.or_else(|| super::preview_blank::blank_of(&mut channel)),
        outcome,
        alarm,
        time: channel.time(),
        samples: count,
    })
}

/// One sample of the tool tip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub wcs: [f64; 3],
    pub bcs: [f64; 3],
    pub line: u32,
    /// The program `line` is in: 0 the main program, k the k-th subprogram met.
    pub program: u32,
    /// The TRACYL working diameter while TRACYL is active.
    pub tracyl_diameter: Option<f64>,
    /// The unit tool direction in the BCS while an orientation transformation is active.
    pub tool_direction: Option<[f64; 3]>,
}

/// The tool tip in the WCS and the BCS (geometry axes by name) and the current line; a
/// subprogram met for the first time is added to `programs`.
fn tip(channel: &Channel, axes: &[String; 3], programs: &mut Vec<String>) -> Sample {
    let snap = channel.snapshot();
    let pick = |values: &[(String, f64)]| {
        let mut p = [0.0; 3];
        for (slot, name) in axes.iter().enumerate() {
            if let Some((_, v)) = values.iter().find(|(n, _)| n == name) {
                p[slot] = *v;
            }
        }
        p
    };
    Sample {
        wcs: pick(&snap.workpiece),
        bcs: pick(&snap.basic),
        line: snap.block.as_ref().map_or(0, |b| b.line),
        program: match snap.block.as_ref().and_then(|b| b.program.as_deref()) {
            None => 0,
            Some(name) => match programs.iter().position(|p| p == name) {
                Some(k) => k as u32 + 1,
                None => {
                    programs.push(name.to_string());
                    programs.len() as u32
                }
            },
        },
        tracyl_diameter: snap.transformation.and_then(|t| t.diameter),
        tool_direction: channel.tool_direction_bcs(),
    }
}

/// Drops repeated and collinear samples, then keeps every n-th so that at most `max` remain
/// (the first and the last always stay).
pub fn thin(samples: Vec<Sample>, max: usize) -> Vec<Sample> {
    let mut kept: Vec<Sample> = Vec::with_capacity(samples.len().min(max * 2));
    for s in samples {
        if kept.last().is_some_and(|last| dist(&last.wcs, &s.wcs) < 1e-9) {
            continue;
        }
        // The previous point lies on the line from the one before it to this one: not needed.
        if kept.len() >= 2 {
            let (a, b) = (&kept[kept.len() - 2].wcs, &kept[kept.len() - 1].wcs);
            let same =
                |k: &Sample| k.line == s.line && k.program == s.program && k.tracyl_diameter == s.tracyl_diameter;
            // A turning tool keeps a point wherever it has turned 0.5° since the point before
            // (a 5-axis view draws the tool axis there): compared with that point, not the
            // middle one, so that a slow turn adds up.
            let turned = !same_direction(kept[kept.len() - 2].tool_direction, s.tool_direction);
            if same(&kept[kept.len() - 1]) && !turned && off_line(a, &s.wcs, b) < COLLINEAR_TOL {
                kept.pop();
            }
        }
        kept.push(s);
    }
    if kept.len() <= max {
        return kept;
    }
    let stride = kept.len().div_ceil(max - 1);
    let last = kept.len() - 1;
    kept.into_iter().enumerate().filter(|(i, _)| i % stride == 0 || *i == last).map(|(_, s)| s).collect()
}

/// Tool directions within 0.5° of each other (or both absent).
fn same_direction(a: Option<[f64; 3]>, b: Option<[f64; 3]>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2] >= 0.5f64.to_radians().cos(),
        _ => false,
    }
}

/// Distance of two points.
pub(crate) fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Distance of `p` from the segment `a`–`b`.
pub(crate) fn off_line(a: &[f64; 3], b: &[f64; 3], p: &[f64; 3]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ap = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
    let len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    let t = if len2 > 0.0 { ((ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / len2).clamp(0.0, 1.0) } else { 0.0 };
    dist(p, &[a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn collinear_samples_collapse_to_the_corners() {
        // A straight line in 11 samples, then a right-angle turn: only the ends and the corner stay.
        let at =
            |p: [f64; 3]| Sample { wcs: p, bcs: p, line: 1, program: 0, tracyl_diameter: None, tool_direction: None };
        let mut s: Vec<Sample> = (0..=10).map(|i| at([f64::from(i), 0.0, 0.0])).collect();
        s.extend((1..=5).map(|i| at([10.0, f64::from(i), 0.0])));
        let kept: Vec<[f64; 3]> = thin(s, 100).into_iter().map(|k| k.wcs).collect();
        assert_eq!(kept, vec![[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [10.0, 5.0, 0.0]]);
    }

    #[test]
    fn thinning_keeps_at_most_max_points_with_both_ends() {
        // A zigzag: no sample is collinear, so only the stride thins it.
        let s: Vec<Sample> = (0..1000)
            .map(|i| {
                let p = [f64::from(i), f64::from(i % 2), 0.0];
                Sample { wcs: p, bcs: p, line: 1, program: 0, tracyl_diameter: None, tool_direction: None }
            })
            .collect();
        let kept = thin(s, 100);
        assert!(kept.len() <= 100, "{}", kept.len());
        assert_eq!(kept.first().map(|k| k.wcs), Some([0.0, 0.0, 0.0]));
        assert_eq!(kept.last().map(|k| k.wcs), Some([999.0, 1.0, 0.0]));
    }
}

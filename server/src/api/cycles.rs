//! The standard cycle library shipped with NCTwin (the control's CST directory): read-only, the
//! same for every session, so users can read what `CYCLE81(...)` does before they call it.

use axum::Json;
use axum::extract::Path;
use nctwin_engine::programs::cycles;

use crate::dto::{ErrorBody, ProgramInfo, ProgramText};
use crate::error::ApiError;

/// Lists the cycles of the standard cycle library by name.
#[utoipa::path(
    get,
    path = "/cycles",
    tag = "programs",
    responses((status = 200, description = "The library's cycles by name", body = [ProgramInfo]))
)]
pub async fn list_cycles() -> Json<Vec<ProgramInfo>> {
    Json(
        cycles::library()
            .iter()
            .map(|c| ProgramInfo { name: c.name().to_string(), size: c.text().map_or(0, |t| t.len()) })
            .collect(),
    )
}

/// One cycle's NC program text.
#[utoipa::path(
    get,
    path = "/cycles/{name}",
    tag = "programs",
    params(("name" = String, Path, description = "Cycle name, e.g. CYCLE81")),
    responses(
        (status = 200, description = "The cycle's program", body = ProgramText),
        (status = 404, description = "No such cycle", body = ErrorBody),
    )
)]
pub async fn get_cycle(Path(name): Path<String>) -> Result<Json<ProgramText>, ApiError> {
    let wanted = name.to_ascii_uppercase();
    let cycle = cycles::find(&wanted).ok_or_else(|| ApiError::NotFound(format!("cycle `{name}`")))?;
    Ok(Json(ProgramText { name: wanted, text: cycle.text().map(|t| t.to_string()).unwrap_or_default() }))
}

//! Technology cycles (Function Manual "Synchronized actions", technology cycles): a program
//! whose blocks are actions of synchronized actions, called from an action by its name
//! (`ID=1 WHEN $A_IN[1]==1 DO LOADER`). The main run runs it as its own sequence, one block
//! per IPO cycle; a block that moves axes (`POS`, `SPOS`) is done when they have arrived
//! (`channel/program_sync.rs`).
//!
//! Read when the calling block is prepared: every block compiled like the actions after `DO`,
//! so a bad block is an alarm at the calling line before the run.
//!
//! Modelled as follows where the manuals leave room:
//! - A block holds actions only (no `WHEN`...`DO` of its own), optionally with a block number;
//!   `PROC NAME` and comment lines are passed over; `M17`, `RET` or the end of the text end
//!   the cycle.
//! - A technology cycle may call another one (as an action); at most 8 levels, 12571 beyond.

use std::sync::Arc;

use super::compile;
use super::flat::Act;
use crate::alarm::Alarm;
use crate::lang::sync_action;
use crate::machine_data::MachineConfig;
use crate::programs::Programs;

/// A technology cycle ready for the main run.
#[derive(Debug, Clone, PartialEq)]
pub struct TechCycle {
    pub name: String,
    pub blocks: Vec<TechBlock>,
}

/// One block of a technology cycle: its actions, run in one IPO cycle.
#[derive(Debug, Clone, PartialEq)]
pub struct TechBlock {
    /// The line in the cycle's program (1-based).
    pub line: u32,
    pub actions: Vec<Act>,
}

/// Resolves the technology cycles named among `acts` (called at `line`).
pub fn resolve(acts: &mut [Act], cfg: &MachineConfig, programs: &Programs, line: u32) -> Result<(), Alarm> {
    resolve_level(acts, cfg, programs, line, 0)
}

fn resolve_level(
    acts: &mut [Act],
    cfg: &MachineConfig,
    programs: &Programs,
    line: u32,
    depth: u32,
) -> Result<(), Alarm> {
    for act in acts.iter_mut() {
        if let Act::CycleName(name) = act {
            if depth >= 8 {
                return Err(compile::not_admissible(line, &format!("{name} (technology cycles nested deeper than 8)")));
            }
            let cycle = load(name, cfg, programs, line, depth)?;
            *act = Act::Cycle(Arc::new(cycle));
        }
    }
    Ok(())
}

/// Reads and compiles the technology cycle `name`.
fn load(name: &str, cfg: &MachineConfig, programs: &Programs, line: u32, depth: u32) -> Result<TechCycle, Alarm> {
    let text =
        programs.find(name, None).and_then(|p| p.raw_text().ok()).ok_or_else(|| Alarm::unknown_name(line, name))?;
    let mut blocks = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let code = raw.split(';').next().unwrap_or("").trim();
        let code = strip_block_number(code);
        let upper = code.to_ascii_uppercase();
        if code.is_empty() || upper.starts_with("PROC ") || upper.starts_with('%') {
            continue;
        }
        if matches!(upper.as_str(), "M17" | "RET" | "M2" | "M02" | "M30") {
            break;
        }
        let bad = |message: &str| Alarm::syntax(line, &format!("technology cycle {name} line {}: {message}", i + 1));
        if sync_action::opens(code) {
            return Err(bad("a block of a technology cycle holds actions only"));
        }
        let parsed = sync_action::parse(&format!("DO {code}")).map_err(|e| bad(&e.message))?;
        let def = compile::compile(&parsed, cfg, line)?;
        if def.deletes_distance() || def.ends_preprocessing_stop() {
            return Err(compile::not_admissible(line, &format!("DELDTG/STOPREOF in technology cycle {name}")));
        }
        let mut actions = def.flat_actions;
        resolve_level(&mut actions, cfg, programs, line, depth + 1)?;
        blocks.push(TechBlock { line: i as u32 + 1, actions });
    }
    Ok(TechCycle { name: name.to_string(), blocks })
}

/// `N10 POS[X]=1` → `POS[X]=1`.
fn strip_block_number(code: &str) -> &str {
    let b = code.as_bytes();
    if b.first().is_some_and(|c| c.eq_ignore_ascii_case(&b'N')) && b.get(1).is_some_and(u8::is_ascii_digit) {
        let end = b.iter().skip(1).position(|c| !c.is_ascii_digit()).map_or(b.len(), |p| p + 1);
        return code[end..].trim_start();
    }
    code
}

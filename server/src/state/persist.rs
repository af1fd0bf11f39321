//! Between a `Channel` and the storage records: what a checkpoint holds and how a saved
//! session becomes a channel again.
//!
//! A restored session has its machine data, stored programs, axis positions and operating
//! mode as saved, and the channel state a reset keeps: tool and cutting edge, toolholder,
//! system frames, R parameters, the online tool offset `$AA_TOFF`, a transformation kept over reset
//! ([`nctwin_engine::channel::ResumeState`], stored as JSON). A program that was running or
//! stopped in AUTO when the checkpoint was taken comes back stopped at its block (block search
//! with calculation to it: NC start approaches the block and continues); one only loaded comes
//! back loaded. Alarms, spindle speeds and simulated time start afresh.
//!
//! What a restart does not bring back, as a real control's power on would not: a turning
//! spindle (spindles never start by themselves; a resumed program's block search outputs its
//! S/M3/M4 at NC start, an idle channel's spindles stand with their power-on speed and the
//! master spindle of MD20090), alarms (power on clears every alarm; a cause that persists
//! raises its alarm again when it is met) and simulated time.
//!
//! The AUTO program's text is not part of the channel state's JSON: it travels beside it as the
//! checkpoint's [`ActiveProgram`], which storage rewrites only when its hash changed. Reading a
//! checkpoint shares the channel's text (no copy); hashing happens off the session's actor, once
//! per loaded program ([`ProgramHashCache`]).

use std::sync::Mutex;

use nctwin_engine::channel::ResumeState;
use nctwin_engine::lang::ProgramText;
use nctwin_engine::{Channel, MachineData, Mode};

use crate::storage::{ActiveProgram, Checkpoint, SavedSession, Storage, StorageError};

/// Files a program wrote or deleted with the file functions (WRITE, DELETE), each once with its
/// text when taken (`None`: deleted), as [`Channel::take_program_changes`] gives them.
pub type ProgramChanges = Vec<(String, Option<String>)>;

/// Saves the files a program wrote or deleted: one program row each, the text as it is when the
/// checkpoint is taken. The engine collects the changes by name, so a log written line by line
/// is one row write per checkpoint, not one per line.
pub fn save_program_changes(storage: &dyn Storage, id: &str, changes: &ProgramChanges) -> Result<(), StorageError> {
    for (name, text) in changes {
        match text {
            Some(text) => storage.put_program(id, name, text)?,
            None => storage.delete_program(id, name)?,
        }
    }
    Ok(())
}

/// The current checkpoint of a channel, with its AUTO program hashed.
pub fn checkpoint(channel: &Channel) -> Checkpoint {
    let (mut checkpoint, text) = checkpoint_unhashed(channel);
    checkpoint.active_program = text.map(ActiveProgram::hashed);
    checkpoint
}

/// The current checkpoint without its active program, and the AUTO program's shared text (for
/// [`ProgramHashCache::active_program`]): cheap enough for the session's actor.
pub fn checkpoint_unhashed(channel: &Channel) -> (Checkpoint, Option<ProgramText>) {
    let (state, text) = channel.resume_state_shared();
    let checkpoint = Checkpoint {
        machine_data: channel.machine_data().to_text(),
        positions: channel.axis_positions().to_vec(),
        mode: mode_name(channel.mode()).into(),
        channel_state: serde_json::to_string(&state).ok(),
        active_program: None,
    };
    (checkpoint, text)
}

/// A session's last hashed AUTO program: checkpoints of the same loaded program (the same
/// shared text) reuse its hash instead of reading up to 16 MiB again.
#[derive(Debug, Default)]
pub struct ProgramHashCache(Mutex<Option<ActiveProgram>>);

impl ProgramHashCache {
    /// The active program of a checkpoint whose AUTO program is `text`; without one the cache
    /// lets the old text go.
    pub fn checkpointed(&self, text: Option<ProgramText>) -> Option<ActiveProgram> {
        match text {
            Some(text) => Some(self.active_program(text)),
            None => {
                *self.0.lock().unwrap_or_else(|e| e.into_inner()) = None;
                None
            }
        }
    }

    /// `text` with its hash, from the cache when it is the text hashed last.
    pub fn active_program(&self, text: ProgramText) -> ActiveProgram {
        let mut cached = self.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(hit) = cached.as_ref().filter(|c| c.text.shares_text_with(&text)) {
            return hit.clone();
        }
        let hashed = ActiveProgram::hashed(text);
        *cached = Some(hashed.clone());
        hashed
    }
}

/// Puts the stored program text into a channel state that refers to it (written since schema
/// version 3); a state of an older row carries its text inline and is taken as it is.
fn with_program_text(mut state: ResumeState, active: Option<&ActiveProgram>) -> Result<ResumeState, String> {
    if let Some(program) = state.program.as_mut().filter(|p| p.text.is_empty()) {
        let text = active.ok_or("the active program's text is missing from storage")?;
        program.text = text.text.to_string();
    }
    Ok(state)
}

pub fn mode_name(mode: Mode) -> &'static str {
    match mode {
        Mode::Jog => "JOG",
        Mode::Mda => "MDA",
        Mode::Auto => "AUTO",
    }
}

fn mode_from(name: &str) -> Option<Mode> {
    match name {
        "JOG" => Some(Mode::Jog),
        "MDA" => Some(Mode::Mda),
        "AUTO" => Some(Mode::Auto),
        _ => None,
    }
}

/// Rebuilds the channel of a saved session. Machine data that no longer applies (after an
/// engine change) is an error: the caller keeps the record and skips the session rather than
/// restore it wrongly. Positions, mode and programs that no longer fit are logged and left out;
/// their rows stay in storage.
pub fn rebuild(saved: &SavedSession) -> Result<Channel, String> {
    let record = &saved.record;
    let mut data = MachineData::default();
    data.apply_text(&record.checkpoint.machine_data).map_err(|e| format!("machine data: {e}"))?;
    let mut channel = Channel::new(data).map_err(|e| format!("machine data: {e}"))?;
    crate::session::start_clock(&mut channel);
    if let Err(e) = channel.restore_positions(&record.checkpoint.positions) {
        tracing::warn!(session = %record.id, error = %e, "saved positions not restored");
    }
    for (name, text) in &saved.programs {
        // A file a program wrote (a log) need not be a program: kept unchecked, as it was.
        if let Err(e) = channel.store_program(name, text).or_else(|_| channel.store_file(name, text)) {
            tracing::warn!(session = %record.id, program = %name, error = %e, "saved program not restored");
        }
    }
    // After the stored programs: the block search of an active program may call them.
    if let Some(json) = &record.checkpoint.channel_state {
        let restored = serde_json::from_str::<ResumeState>(json)
            .map_err(|e| e.to_string())
            .and_then(|state| with_program_text(state, record.checkpoint.active_program.as_ref()))
            .and_then(|state| channel.restore_resume_state(&state).map_err(|e| e.to_string()));
        if let Err(e) = restored {
            tracing::warn!(session = %record.id, error = %e, "saved channel state not restored");
        }
    }
    match mode_from(&record.checkpoint.mode).map(|m| channel.set_mode(m)) {
        Some(Ok(())) => {}
        _ => tracing::warn!(session = %record.id, mode = %record.checkpoint.mode, "saved mode not restored"),
    }
    // Restoring is not news to anyone: no mode-change event for the first stream client.
    channel.take_events();
    Ok(channel)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::storage::{SessionRecord, TokenHashes};

    fn saved(channel: &Channel, programs: Vec<(String, String)>) -> SavedSession {
        SavedSession {
            record: SessionRecord {
                id: "s1".into(),
                number: 1,
                machine: "lathe-2axis".into(),
                client_ip: None,
                tokens: TokenHashes { owner: "a".into(), operator: "b".into(), observer: "c".into() },
                checkpoint: checkpoint(channel),
                persistent: false,
                last_active_ms: None,
            },
            programs,
        }
    }

    #[test]
    fn a_checkpoint_rebuilds_the_same_machine_data_positions_and_mode() {
        let mut channel =
            Channel::from_preset("mill-3axis", "$MA_POS_LIMIT_PLUS[X]=400.\n$TC_DP1[1,1]=120\n$TC_DP3[1,1]=42.5")
                .expect("preset");
        channel.mda("G0 X12.345 Y-7 Z0.1").expect("mda");
        for _ in 0..100_000 {
            if !channel.is_busy() {
                break;
            }
            channel.step();
        }
        channel.set_mode(Mode::Jog).expect("jog");
        channel.store_program("SUB1", "G1 X1 F100\nM17").expect("program");
        let programs = vec![("SUB1".to_string(), "G1 X1 F100\nM17".to_string())];

        let restored = rebuild(&saved(&channel, programs)).expect("rebuild");
        assert_eq!(restored.machine_data().to_text(), channel.machine_data().to_text());
        assert_eq!(restored.axis_positions(), channel.axis_positions(), "bit for bit");
        assert_eq!(restored.mode(), Mode::Jog);
        assert_eq!(restored.stored_program("SUB1"), Some("G1 X1 F100\nM17"));
        assert_eq!(restored.snapshot().machine, channel.snapshot().machine);
    }

    /// Stops a program at its M0 (line 2) and returns the channel.
    fn stopped_at_m0() -> Channel {
        let mut channel = Channel::from_preset("mill-3axis", "").expect("preset");
        channel.run_program("G0 X1\nM0\nG0 X2\nM30").expect("run");
        for _ in 0..100_000 {
            if !channel.is_busy() {
                break;
            }
            channel.step();
        }
        channel
    }

    #[test]
    fn the_program_text_travels_beside_the_state_and_old_inline_states_still_restore() {
        let channel = stopped_at_m0();
        let checkpoint = checkpoint(&channel);
        let json = checkpoint.channel_state.as_deref().expect("state");
        assert!(!json.contains("G0 X2"), "the text is not in the state: {json}");
        let active = checkpoint.active_program.as_ref().expect("active program");
        assert_eq!(&*active.text, "G0 X1\nM0\nG0 X2\nM30");
        // Restored from the text beside the state.
        let restored = rebuild(&saved(&channel, vec![])).expect("rebuild");
        assert_eq!((restored.status(), restored.snapshot().block.map(|b| b.line)), (channel.status(), Some(2)));
        // A row of schema version 2: the text inline, no active program row.
        let mut old = saved(&channel, vec![]);
        old.record.checkpoint.channel_state = serde_json::to_string(&channel.resume_state()).ok();
        old.record.checkpoint.active_program = None;
        let restored = rebuild(&old).expect("rebuild");
        assert_eq!(restored.snapshot().block.map(|b| b.line), Some(2));
        // A state that refers to a text storage lost: restored without the program, not wrongly.
        let mut lost = saved(&channel, vec![]);
        lost.record.checkpoint.active_program = None;
        let restored = rebuild(&lost).expect("rebuild");
        assert_eq!((restored.status(), restored.snapshot().block), (nctwin_engine::Status::Idle, None));
    }

    #[test]
    fn the_hash_cache_hashes_a_shared_text_once_and_a_new_text_again() {
        let cache = ProgramHashCache::default();
        let text = ProgramText::from("G0 X1\nM30");
        let first = cache.active_program(text.clone());
        let again = cache.active_program(text.clone());
        assert!(first.text.shares_text_with(&again.text), "the cached entry is reused");
        // The hash of a second allocation of the same text: equal, though computed anew.
        let other = cache.active_program(ProgramText::from("G0 X1\nM30"));
        assert!(!other.text.shares_text_with(&text));
        assert_eq!(other.sha256, first.sha256);
        // SHA-256 of "abc" (FIPS 180-2, appendix B.1).
        assert_eq!(
            ActiveProgram::hashed(ProgramText::from("abc")).sha256,
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }

    #[test]
    fn a_restart_is_a_power_on_for_spindles_and_alarms() {
        // Before: the lathe's main spindle turning at 1000 rev/min (M3 in MDA), then alarm 10860
        // (a feed motion without a feedrate) waiting for a reset.
        let settle = |c: &mut Channel| {
            for _ in 0..100_000 {
                if !c.is_busy() {
                    break;
                }
                c.step();
            }
        };
        let mut channel = Channel::from_preset("lathe-2axis", "").expect("preset");
        channel.mda("M3 S1000").expect("mda");
        settle(&mut channel);
        let _ = channel.mda("G1 X10");
        settle(&mut channel);
        assert_eq!(channel.alarms().iter().map(|a| a.number).collect::<Vec<_>>(), [10860]);
        let turning = |c: &Channel| c.snapshot().spindles.iter().any(|(_, speed)| *speed != 0.0);
        assert!(turning(&channel), "{:?}", channel.snapshot().spindles);
        let restored = rebuild(&saved(&channel, vec![])).expect("rebuild");
        assert!(!turning(&restored), "no spindle starts by itself: {:?}", restored.snapshot().spindles);
        assert!(restored.alarms().is_empty());
    }

    #[test]
    fn a_restart_mid_posa_takes_the_axis_on_to_its_end_and_older_states_have_none() {
        // FA[Z]=300 (5 mm/s): after 100 cycles of 4 ms Z is about 2 mm on its way to −5.
        let mut channel = Channel::from_preset("mill-3axis", "").expect("preset");
        channel.run_program("POSA[Z]=-5 FA[Z]=300\nG4 F3\nM30").expect("run");
        for _ in 0..100 {
            channel.step();
        }
        let checkpoint = checkpoint(&channel);
        let json = checkpoint.channel_state.as_deref().expect("state");
        assert!(json.contains(r#""positioning":[{"axis":"Z","end":-5.0,"feed":5.0,"kind":"POSA"}]"#), "{json}");
        let mut restored = rebuild(&saved(&channel, vec![])).expect("rebuild");
        let p = restored.snapshot().positioning;
        assert_eq!(p.iter().map(|p| (p.kind, p.target)).collect::<Vec<_>>(), [("POSA", Some(-5.0))]);
        restored.start().expect("NC start");
        for _ in 0..100_000 {
            if !restored.is_busy() {
                break;
            }
            restored.step();
        }
        assert!(restored.alarms().is_empty(), "{:?}", restored.alarms());
        assert_eq!(restored.axis_positions()[2], -5.0);
        // A checkpoint written before the field: the program comes back, no axis travels.
        let mut old = saved(&channel, vec![]);
        let without = json.replace(r#","positioning":[{"axis":"Z","end":-5.0,"feed":5.0,"kind":"POSA"}]"#, "");
        old.record.checkpoint.channel_state = Some(without);
        let restored = rebuild(&old).expect("rebuild");
        assert_eq!(restored.snapshot().block.map(|b| b.line), Some(2));
        assert!(restored.snapshot().positioning.is_empty());
    }

    #[test]
    fn machine_data_that_no_longer_applies_is_an_error_not_a_wrong_session() {
        let channel = Channel::from_preset("mill-3axis", "").expect("preset");
        let mut bad = saved(&channel, vec![]);
        bad.record.checkpoint.machine_data = "$MN_NO_SUCH_DATUM=1".into();
        assert!(rebuild(&bad).is_err());
    }
}

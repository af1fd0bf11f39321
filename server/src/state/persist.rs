//! Between a `Channel` and the storage records: what a checkpoint holds and how a saved
//! session becomes a channel again.
//!
//! A restored session has its machine data, stored programs, axis positions and operating
//! mode as saved, and the channel state a reset keeps: tool and cutting edge, toolholder,
//! system frames, R parameters, a transformation kept over reset
//! ([`nctwin_engine::channel::ResumeState`], stored as JSON). A program that was running or
//! stopped in AUTO when the checkpoint was taken comes back stopped at its block (block search
//! with calculation to it: NC start approaches the block and continues); one only loaded comes
//! back loaded. Alarms, spindle speeds and simulated time start afresh.

use nctwin_engine::channel::ResumeState;
use nctwin_engine::{Channel, MachineData, Mode};

use crate::storage::{Checkpoint, SavedSession};

/// The current checkpoint of a channel.
pub fn checkpoint(channel: &Channel) -> Checkpoint {
    Checkpoint {
        machine_data: channel.machine_data().to_text(),
        positions: channel.axis_positions().to_vec(),
        mode: mode_name(channel.mode()).into(),
        channel_state: serde_json::to_string(&channel.resume_state()).ok(),
    }
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
    if let Err(e) = channel.restore_positions(&record.checkpoint.positions) {
        tracing::warn!(session = %record.id, error = %e, "saved positions not restored");
    }
    for (name, text) in &saved.programs {
        if let Err(e) = channel.store_program(name, text) {
            tracing::warn!(session = %record.id, program = %name, error = %e, "saved program not restored");
        }
    }
    // After the stored programs: the block search of an active program may call them.
    if let Some(json) = &record.checkpoint.channel_state {
        let restored = serde_json::from_str::<ResumeState>(json)
            .map_err(|e| e.to_string())
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

    #[test]
    fn machine_data_that_no_longer_applies_is_an_error_not_a_wrong_session() {
        let channel = Channel::from_preset("mill-3axis", "").expect("preset");
        let mut bad = saved(&channel, vec![]);
        bad.record.checkpoint.machine_data = "$MN_NO_SUCH_DATUM=1".into();
        assert!(rebuild(&bad).is_err());
    }
}

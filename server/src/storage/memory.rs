//! [`MemoryStorage`]: keeps everything in memory and loses it with the process. For tests and
//! for embedding the server where nothing must survive (`AppState::new`).

use std::collections::BTreeMap;
use std::sync::Mutex;

use super::{Checkpoint, SavedSession, SessionRecord, Storage, StorageError};

/// Sessions and their programs in maps; "durable" for the life of the process only.
#[derive(Debug, Default)]
pub struct MemoryStorage {
    /// Held only for one map operation, never across an await.
    sessions: Mutex<BTreeMap<String, SavedSession>>,
}

impl MemoryStorage {
    fn with<R>(&self, f: impl FnOnce(&mut BTreeMap<String, SavedSession>) -> R) -> R {
        // Every critical section is one complete map update, so a poisoned lock is consistent.
        f(&mut self.sessions.lock().unwrap_or_else(|e| e.into_inner()))
    }
}

impl Storage for MemoryStorage {
    fn describe(&self) -> String {
        "memory (nothing survives a restart)".into()
    }

    fn backend(&self) -> &'static str {
        "memory"
    }

    fn check(&self) -> Result<(), StorageError> {
        Ok(())
    }

    fn load(&self) -> Result<Vec<SavedSession>, StorageError> {
        let mut all: Vec<SavedSession> = self.with(|m| m.values().cloned().collect());
        all.sort_by_key(|s| s.record.number);
        Ok(all)
    }

    fn create_session(&self, record: &SessionRecord) -> Result<(), StorageError> {
        let saved = SavedSession { record: record.clone(), programs: Vec::new() };
        self.with(|m| m.insert(record.id.clone(), saved));
        Ok(())
    }

    fn save_checkpoint(&self, id: &str, checkpoint: &Checkpoint) -> Result<(), StorageError> {
        self.with(|m| {
            if let Some(s) = m.get_mut(id) {
                s.record.checkpoint = checkpoint.clone();
            }
        });
        Ok(())
    }

    fn delete_session(&self, id: &str) -> Result<(), StorageError> {
        self.with(|m| m.remove(id));
        Ok(())
    }

    fn put_program(&self, id: &str, name: &str, text: &str) -> Result<(), StorageError> {
        self.with(|m| {
            let s = m.get_mut(id).ok_or_else(|| StorageError::new(format!("session `{id}` is not stored")))?;
            match s.programs.binary_search_by(|(n, _)| n.as_str().cmp(name)) {
                Ok(i) => s.programs[i].1 = text.to_string(),
                Err(i) => s.programs.insert(i, (name.to_string(), text.to_string())),
            }
            Ok(())
        })
    }

    fn set_persistent(&self, id: &str, persistent: bool) -> Result<(), StorageError> {
        self.with(|m| {
            if let Some(s) = m.get_mut(id) {
                s.record.persistent = persistent;
            }
        });
        Ok(())
    }

    fn save_activity(&self, activity: &[(String, u64)]) -> Result<(), StorageError> {
        self.with(|m| {
            for (id, ms) in activity {
                if let Some(s) = m.get_mut(id) {
                    s.record.last_active_ms = Some(*ms);
                }
            }
        });
        Ok(())
    }

    fn delete_program(&self, id: &str, name: &str) -> Result<(), StorageError> {
        self.with(|m| {
            if let Some(s) = m.get_mut(id) {
                s.programs.retain(|(n, _)| n != name);
            }
        });
        Ok(())
    }
}

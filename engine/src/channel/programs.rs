//! The session's stored programs (main programs and subprograms called by name).

use std::sync::Arc;

use super::{Channel, CommandError};
use crate::interp::Programs;
use crate::programs::{Dir, Kind, StoredProgram, qualified_name, split_qualified};

impl Channel {
    /// Stores a program under `name` (upper-cased; a `.MPF`/`.SPF` ending is dropped) for
    /// calls by name; a name with a directory (`/_N_WKS_DIR/_N_SHAFT_WPD/SHAFT`, see
    /// [`crate::programs::qualified_name`]) files it there. The text is checked first: a
    /// program with syntax errors is refused. Returns the stored name.
    pub fn store_program(&mut self, name: &str, text: &str) -> Result<String, CommandError> {
        let (dir, base) = split_qualified(name);
        let name = program_name(base)?;
        CommandError::check(text)?;
        self.interp.files_mut().discard(&name);
        match dir {
            None => self.programs.insert(name.clone(), Arc::from(text)),
            Some(d) => {
                let stored = qualified_name(Some(&d), &name);
                self.programs.add(StoredProgram::checked(name, Some(d), None, Arc::from(text)));
                return Ok(stored);
            }
        }
        Ok(name)
    }

    /// Stores every program of an archive text (`%_N_NAME_MPF` / `_SPF` / `_INI` headers, each
    /// program up to the next header) under the name of its header, header line included;
    /// returns the names in order. All or nothing: a text without a header, a bad header or a
    /// program with syntax errors stores none of them.
    pub fn store_archive(&mut self, text: &str) -> Result<Vec<String>, CommandError> {
        let archive = crate::programs::archive::split(text);
        if let Some(problem) = archive.problems.first() {
            return Err(CommandError::Invalid(format!("line {}: {}", problem.line, problem.message)));
        }
        if archive.entries.is_empty() {
            return Err(CommandError::Invalid("no archive header (%_N_NAME_MPF) in the text".into()));
        }
        let mut checked = Vec::with_capacity(archive.entries.len());
        for entry in &archive.entries {
            if let Kind::Other(suffix) = &entry.kind {
                return Err(CommandError::Invalid(format!(
                    "line {}: a _{suffix} file is no program (_MPF, _SPF or _INI)",
                    entry.line
                )));
            }
            let name = program_name(&entry.name)?;
            CommandError::check(entry.text)?;
            checked.push((name, entry.text));
        }
        Ok(checked
            .into_iter()
            .map(|(name, body)| {
                self.interp.files_mut().discard(&name);
                self.programs.insert(name.clone(), Arc::from(body));
                name
            })
            .collect())
    }

    /// A stored program's text (a file a running program wrote or deleted as it is now): by
    /// its stored name with a directory exactly that one, by its name alone the one the main
    /// program would call, else the first directory's.
    pub fn stored_program(&self, name: &str) -> Option<&str> {
        if let (Some(dir), base) = split_qualified(name) {
            let base = program_name(base).ok()?;
            return self.programs.in_dir(&base, Some(&dir)).and_then(|p| p.text()).map(|t| &**t);
        }
        let name = program_name(name).ok()?;
        match self.interp.files().pending(&name) {
            Some(p) => p.text.as_deref(),
            // As the main program would find it, else in whichever directory holds it.
            None => self.programs.file(&name, None).and_then(|p| p.text()).map(|t| &**t),
        }
    }

    /// Stores `text` under `name` without checking it: a file that need not be a program (a
    /// log a program wrote with WRITE), checked only if it is ever called.
    pub fn store_file(&mut self, name: &str, text: &str) -> Result<String, CommandError> {
        let (dir, base) = split_qualified(name);
        let name = program_name(base)?;
        self.interp.files_mut().discard(&name);
        let stored = qualified_name(dir.as_ref(), &name);
        self.programs.add(StoredProgram::unchecked(name, dir, None, Arc::from(text)));
        Ok(stored)
    }

    /// Takes the file functions' changes into the store (when the program no longer runs, so
    /// a log written line by line is copied once) and sets the files' clock; called every
    /// cycle, it costs a comparison when no file changed.
    #[inline]
    pub(super) fn sync_files(&mut self) {
        let files = self.interp.files_mut();
        files.set_tick(self.tick);
        if files.has_pending() && self.status != super::Status::Running {
            self.store_pending_files();
        }
    }

    #[cold]
    fn store_pending_files(&mut self) {
        for (name, change) in self.interp.files_mut().take_pending() {
            match change.text {
                Some(text) => {
                    // Replaces the program of that name in the directory it was found in.
                    let kind = Some(change.kind);
                    self.changed_files.insert(qualified_name(change.dir.as_ref(), &name));
                    self.programs.add(StoredProgram::unchecked(name.clone(), change.dir, kind, Arc::from(text)));
                }
                None => {
                    // Deleted from every directory: each stored name is gone.
                    let dirs: Vec<Option<Dir>> =
                        self.programs.iter().filter(|p| p.name() == name).map(|p| p.dir().cloned()).collect();
                    for dir in dirs {
                        self.changed_files.insert(qualified_name(dir.as_ref(), &name));
                    }
                    self.programs.remove(&name);
                }
            }
        }
    }

    /// Runs an NC data file as the control runs a selected `_INI` file at NC start: its data
    /// (tool offsets, frames, setting data, `CHANDATA`, `METRIC`/`INCH`) are loaded and
    /// activated as [`Channel::apply_machine_data`] does, and the run is over at once.
    pub fn run_data_file(&mut self, text: &str) -> Result<(), CommandError> {
        self.apply_machine_data(text)
    }

    /// Sets the quota of the program store in bytes (`None`: none) that the file functions keep
    /// to: a WRITE that would make the store larger answers error 12 (no free resources).
    pub fn set_program_budget(&mut self, bytes: Option<usize>) {
        self.interp.files_mut().set_budget(bytes);
    }

    /// Takes pending file changes into the store; the names changed since the shell last asked.
    pub(super) fn take_changed_file_names(&mut self) -> std::collections::BTreeSet<String> {
        if self.interp.files().has_pending() {
            let status = std::mem::replace(&mut self.status, super::Status::Idle);
            self.sync_files();
            self.status = status;
        }
        std::mem::take(&mut self.changed_files)
    }

    /// The programs the file functions wrote or deleted since the last call, each once, with
    /// their text now (`None`: deleted): what the shell persists. Pending changes of a program
    /// that still runs are taken into the store first.
    pub fn take_program_changes(&mut self) -> Vec<(String, Option<String>)> {
        self.take_changed_file_names()
            .into_iter()
            .map(|name| {
                let text = match split_qualified(&name) {
                    (Some(dir), base) => self.programs.in_dir(base, Some(&dir)).and_then(|p| p.text()),
                    (None, base) => self.programs.in_dir(base, None).and_then(|p| p.text()),
                };
                (name.clone(), text.map(|t| t.to_string()))
            })
            .collect()
    }

    /// Removes a stored program; false if there was none.
    pub fn delete_program(&mut self, name: &str) -> bool {
        if let (Some(dir), base) = split_qualified(name) {
            return program_name(base).is_ok_and(|n| self.programs.remove_in(&n, Some(&dir)));
        }
        program_name(name).is_ok_and(|n| {
            // A file the running program wrote and not yet stored counts as there.
            let pending = self.interp.files().pending(&n).is_some_and(|p| p.text.is_some());
            self.interp.files_mut().discard(&n);
            self.programs.remove(&n) || pending
        })
    }

    /// The program store (directories, programs read when first called).
    pub fn program_store(&self) -> &Programs {
        &self.programs
    }

    /// The program store to add to: [`crate::programs::StoredProgram`]s in directories, read
    /// and checked when first called (a program run from a folder of the control's layout).
    pub fn program_store_mut(&mut self) -> &mut Programs {
        &mut self.programs
    }

    /// What the static name check of a program ([`crate::check`]) needs of this channel: its
    /// machine (axis names), the names of its stored programs and its global user variables.
    /// Cheap (names only), so a caller can take it and check a large program elsewhere.
    pub fn name_context(&self) -> crate::check::NameContext {
        crate::check::NameContext::new(
            self.cfg.clone(),
            self.programs.iter().map(|p| p.name().to_string()),
            self.interp
                .variables()
                .global_names()
                .chain(crate::programs::cycles::GLOBALS.iter().copied())
                .map(str::to_string),
        )
    }

    /// Names and sizes (bytes) of the stored programs, by name (0 for one not read yet), with
    /// the files a running program wrote or deleted as they are now.
    pub fn stored_programs(&self) -> Vec<(String, usize)> {
        let stored = self.programs.iter().map(|p| (qualified_name(p.dir(), p.name()), p.text().map_or(0, |t| t.len())));
        let files = self.interp.files();
        if !files.has_pending() {
            return stored.collect();
        }
        let mut all: std::collections::BTreeMap<String, usize> = stored.collect();
        for (name, p) in files.pending_all() {
            match &p.text {
                Some(text) => all.insert(name.clone(), text.len()),
                None => all.remove(name),
            };
        }
        all.into_iter().collect()
    }
}

/// The canonical name of a stored program (see [`crate::programs::canonical_name`]).
pub(super) fn program_name(name: &str) -> Result<String, CommandError> {
    crate::programs::canonical_name(name)
        .ok_or_else(|| CommandError::Invalid(format!("bad program name `{name}`: letters, digits and _, at most 32")))
}

#[cfg(test)]
mod tests {
    use super::Channel;

    #[test]
    fn stored_programs_survive_new_machine_data_and_new_chain_data() {
        let mut ch = Channel::from_preset("mill-3axis", "").expect("preset");
        ch.store_program("SUB", "G0 X1\nM17").expect("store");
        ch.apply_machine_data("$MA_POS_LIMIT_PLUS[AX1]=50.").expect("machine data");
        assert_eq!(ch.stored_programs(), [("SUB".to_string(), 9)]);
        let chains = ch.export_kinematic_chains();
        ch.import_kinematic_chains(&chains).expect("chain data");
        assert_eq!(ch.stored_program("SUB"), Some("G0 X1\nM17"));
    }
}

//! The tool list as the operator edits it: replaced as a whole (tool data text), tools loaded
//! into a magazine place and unloaded to the loading magazine 9999. The data act at once, as a
//! program's `$TC_` writes do, and only in reset state (like machine data).

use std::sync::Arc;

use crate::channel::{Channel, CommandError, Status};
use crate::machine_data::text::{self, Line};
use crate::machine_data::tools_list::KIND_MAGAZINE_PLACE;
use crate::machine_data::tools_mgmt::{BUFFER_MAGAZINE, MAX_PLACE, ToolMgmtData};

/// The loading magazine: unloaded tools wait at its places (outside the machine).
pub const LOADING_MAGAZINE: u32 = 9999;

impl Channel {
    /// Replaces every cutting edge and tool-management datum by `text` (lines of `$TC_DP`,
    /// `$TC_TP`, `$TC_MAP`, `$TC_MPP`, `$TC_MOP` only), all-or-nothing; only in reset state.
    pub fn replace_tool_data(&mut self, text: &str) -> Result<(), CommandError> {
        self.require_reset("tool data can only be replaced in reset state")?;
        for line in text::parse(text)? {
            if let Line::Assign { line, name, .. } = line
                && !name.starts_with("$TC_DP")
                && !ToolMgmtData::handles(&name)
            {
                return Err(CommandError::Invalid(format!("line {line}: {name} is no tool datum")));
            }
        }
        let mut data = self.data.clone();
        data.clear_tool_data();
        data.stage_text(text)?;
        self.take_tool_data(data)
    }

    /// Loads tool `t` into `place` of `magazine` (an ordinary place of a real magazine, free or
    /// already holding the tool).
    pub fn load_tool(&mut self, t: u32, magazine: u32, place: u32) -> Result<(), CommandError> {
        self.require_reset("tools can only be loaded in reset state")?;
        let list = &self.cfg.tool_list;
        if !list.tools.contains_key(&t) {
            return Err(CommandError::Invalid(format!("tool {t} is not defined")));
        }
        let mag = list
            .magazines
            .iter()
            .find(|g| g.number == magazine && g.number < BUFFER_MAGAZINE)
            .ok_or_else(|| CommandError::Invalid(format!("magazine {magazine} is not defined")))?;
        let p = mag
            .places
            .get((place as usize).wrapping_sub(1))
            .ok_or_else(|| CommandError::Invalid(format!("magazine {magazine} has no place {place}")))?;
        if p.kind != KIND_MAGAZINE_PLACE || p.state & 1 != 0 {
            return Err(CommandError::Invalid(format!(
                "magazine {magazine} place {place} is disabled or no tool place"
            )));
        }
        if let Some(other) = p.tool.filter(|o| *o != t) {
            return Err(CommandError::Invalid(format!("magazine {magazine} place {place} holds tool {other}")));
        }
        let mut data = self.data.clone();
        data.move_tool(t, magazine, place);
        self.take_tool_data(data)
    }

    /// Unloads tool `t` from its place to the first free place of the loading magazine 9999;
    /// not the tool in the spindle.
    pub fn unload_tool(&mut self, t: u32) -> Result<(), CommandError> {
        self.require_reset("tools can only be unloaded in reset state")?;
        let list = &self.cfg.tool_list;
        let entry = list.tools.get(&t).ok_or_else(|| CommandError::Invalid(format!("tool {t} is not defined")))?;
        if self.offsets.t == t {
            return Err(CommandError::Invalid(format!("tool {t} is in the spindle")));
        }
        if entry.place.is_none_or(|(m, _)| m == LOADING_MAGAZINE) {
            return Err(CommandError::Invalid(format!("tool {t} is not loaded")));
        }
        let taken: Vec<u32> = list
            .magazines
            .iter()
            .filter(|g| g.number == LOADING_MAGAZINE)
            .flat_map(|g| g.places.iter().filter(|p| p.tool.is_some()).map(|p| p.number))
            .collect();
        let free = (1..=MAX_PLACE as u32)
            .find(|p| !taken.contains(p))
            .ok_or_else(|| CommandError::Invalid("the loading magazine 9999 is full".into()))?;
        let mut data = self.data.clone();
        data.move_tool(t, LOADING_MAGAZINE, free);
        self.take_tool_data(data)
    }

    /// The number of the tool named `name` (with `duplo`, or the only tool of that name); a
    /// name of digits that no tool has is taken as a tool number.
    pub fn find_tool(&self, name: &str, duplo: Option<i64>) -> Result<u32, CommandError> {
        let list = &self.cfg.tool_list;
        let named: Vec<_> =
            list.tools.values().filter(|e| e.name == name && duplo.is_none_or(|d| e.duplo == d)).collect();
        match named.as_slice() {
            [one] => Ok(one.number),
            [] => match name.parse::<u32>() {
                Ok(t) if list.tools.contains_key(&t) && duplo.is_none() => Ok(t),
                _ => Err(CommandError::Invalid(format!(
                    "no tool named {name}{}",
                    match duplo {
                        Some(d) => format!(" with duplo number {d}"),
                        None => String::new(),
                    }
                ))),
            },
            _ => Err(CommandError::Invalid(format!("{} tools are named {name}: give the duplo number", named.len()))),
        }
    }

    /// Refuses an edit unless in reset state; the tool life counted so far goes into the data
    /// first, so the edit does not lose it.
    fn require_reset(&mut self, why: &'static str) -> Result<(), CommandError> {
        if self.is_active() || self.status == Status::Stopped {
            return Err(CommandError::Busy(why));
        }
        self.flush_tool_monitor();
        Ok(())
    }

    /// Activates changed tool data at once (as a program's `$TC_` write does).
    fn take_tool_data(&mut self, data: crate::machine_data::MachineData) -> Result<(), CommandError> {
        let mut cfg = (*self.cfg).clone();
        cfg.refresh_data(&data).map_err(|e| CommandError::Invalid(e.message))?;
        self.data = data;
        self.cfg = Arc::new(cfg);
        Ok(())
    }
}

//! The tool list as activated: every tool with its name, duplo number, state and place, and
//! every magazine with its places, built from the raw data of [`super::tools_mgmt`] and the
//! cutting edges `$TC_DP`.
//!
//! A tool that has a name (`$TC_TP2`) but no place (`$TC_MPP6`) is put into the first free
//! place of a real magazine (lowest magazine number below the buffer magazine 9998, place kind
//! 1, not disabled, empty) when the data are activated, so a tool list typed or imported by
//! hand can be used at once; the entry says so (`auto_placed`). Where no place is free the
//! tool stays without a place and can still be selected (this product's choice: the control
//! would need an operator to load it).

use std::collections::BTreeMap;

use super::config::ActivationError;
use super::tools_mgmt::{BUFFER_MAGAZINE, Family, ToolMgmtData};
use super::{EdgeParams, Value};

/// `$TC_TP8` bit 2: the tool is disabled and is not selected by name.
pub const STATE_DISABLED: i64 = 1 << 2;
/// `$TC_TP8` bit 4: a cutting edge reached its prewarning limit.
pub const STATE_PREWARNING: i64 = 1 << 4;
/// `$TC_TP9` bit 0: time monitoring; bit 1: count monitoring.
pub const MONITOR_TIME: i64 = 1;
pub const MONITOR_COUNT: i64 = 2;
/// `$TC_MPP4` bit 0: the place is disabled.
const PLACE_DISABLED: i64 = 1;
/// `$TC_MPP1` place kind 1: an ordinary magazine place; 2: a spindle (toolholder) place.
pub const KIND_MAGAZINE_PLACE: i64 = 1;
pub const KIND_SPINDLE: i64 = 2;

/// One tool of the list.
#[derive(Debug, Clone, PartialEq)]
pub struct ToolEntry {
    pub number: u32,
    /// `$TC_TP2`; empty for a tool known only by its number.
    pub name: String,
    /// `$TC_TP1`.
    pub duplo: i64,
    /// `$TC_TP8` (bit 0 active, 1 enabled, 2 disabled, 3 measured, 4 prewarning, ...).
    pub state: i64,
    /// `$TC_TP9`: 0 none, 1 time, 2 count, 4 wear.
    pub monitoring: i64,
    /// Magazine and place (`$TC_MPP6`), if the tool has one.
    pub place: Option<(u32, u32)>,
    /// The place was given at activation because the data named none.
    pub auto_placed: bool,
    /// The cutting edge numbers, ascending.
    pub edges: Vec<u32>,
}

/// One place of a magazine.
#[derive(Debug, Clone, PartialEq)]
pub struct Place {
    pub number: u32,
    /// `$TC_MPP1`: 1 magazine place, 2 spindle, 3 gripper, 4 loader, ...
    pub kind: i64,
    /// `$TC_MPP4`.
    pub state: i64,
    pub tool: Option<u32>,
}

/// One magazine (`$TC_MAP..`).
#[derive(Debug, Clone, PartialEq)]
pub struct Magazine {
    pub number: u32,
    /// `$TC_MAP1`: 1 chain, 3 turret, 5 box, 7 buffer, 9 loading.
    pub kind: i64,
    pub name: String,
    pub places: Vec<Place>,
}

/// Why a tool name selects no tool.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NameError {
    /// No tool has this name.
    Unknown,
    /// Every duplo of the name is disabled.
    Disabled,
}

/// The activated tool list.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ToolList {
    pub tools: BTreeMap<u32, ToolEntry>,
    pub magazines: Vec<Magazine>,
    /// The data as written, for reads of the values the list does not type.
    pub raw: ToolMgmtData,
    /// Some tool has time or count monitoring (`$TC_TP9` bit 0 or 1): only then does the main
    /// run count (the per-IPO-cycle guard).
    pub monitored: bool,
}

impl ToolList {
    /// Builds the list; fails on a place holding an unknown tool, a tool in two places, or two
    /// tools with the same name and duplo number.
    pub fn build(tm: &ToolMgmtData, edges: &BTreeMap<(u32, u32), EdgeParams>) -> Result<ToolList, ActivationError> {
        let fail = |message: String| Err(ActivationError { datum: None, message });
        let mut tools: BTreeMap<u32, ToolEntry> = BTreeMap::new();
        let entry = |t: u32| ToolEntry {
            number: t,
            name: String::new(),
            duplo: 0,
            state: 0,
            monitoring: 0,
            place: None,
            auto_placed: false,
            edges: Vec::new(),
        };
        for (t, d) in edges.keys() {
            tools.entry(*t).or_insert_with(|| entry(*t)).edges.push(*d);
        }
        for ((t, _), n, v) in tm.of_family(Family::Tool) {
            let e = tools.entry(t).or_insert_with(|| entry(t));
            match (n, v) {
                (2, Value::Str(s)) => e.name = s.clone(),
                (1, v) => e.duplo = v.as_f64().unwrap_or(0.0) as i64,
                (8, v) => e.state = v.as_f64().unwrap_or(0.0) as i64,
                (9, v) => e.monitoring = v.as_f64().unwrap_or(0.0) as i64,
                _ => {}
            }
        }
        let mut seen: BTreeMap<(&str, i64), u32> = BTreeMap::new();
        for e in tools.values().filter(|e| !e.name.is_empty()) {
            if let Some(other) = seen.insert((&e.name, e.duplo), e.number) {
                return fail(format!(
                    "$TC_TP2[{}]: tools {other} and {} are both \"{}\" with duplo number {} ($TC_TP1)",
                    e.number, e.number, e.name, e.duplo
                ));
            }
        }

        // Magazines: every number with magazine or place data; places 1..max($TC_MAP7, highest place).
        let mut sizes: BTreeMap<u32, (i64, String, u32)> = BTreeMap::new();
        for ((m, _), n, v) in tm.of_family(Family::Magazine) {
            let s = sizes.entry(m).or_insert((0, String::new(), 0));
            match (n, v) {
                (1, v) => s.0 = v.as_f64().unwrap_or(0.0) as i64,
                (2, Value::Str(name)) => s.1 = name.clone(),
                (7, v) => s.2 = s.2.max(v.as_f64().unwrap_or(0.0).clamp(0.0, 999.0) as u32),
                _ => {}
            }
        }
        for ((m, p), _, _) in tm.of_family(Family::Place) {
            let s = sizes.entry(m).or_insert((0, String::new(), 0));
            s.2 = s.2.max(p);
        }
        let mut magazines = Vec::new();
        for (m, (kind, name, count)) in sizes {
            // Internal magazines: 9998 the buffer (type 7), 9999 the loading magazine (type 9).
            let kind = match (kind, m) {
                (0, BUFFER_MAGAZINE) => 7,
                (0, 9999) => 9,
                _ => kind,
            };
            let default_kind = if m == BUFFER_MAGAZINE { KIND_SPINDLE } else { KIND_MAGAZINE_PLACE };
            let places = (1..=count)
                .map(|p| Place {
                    number: p,
                    kind: match tm.int(Family::Place, m, p, 1) {
                        0 => default_kind,
                        k => k,
                    },
                    state: tm.int(Family::Place, m, p, 4),
                    tool: None,
                })
                .collect();
            magazines.push(Magazine { number: m, kind, name, places });
        }
        for ((m, p), n, v) in tm.of_family(Family::Place) {
            if n != 6 {
                continue;
            }
            let t = v.as_f64().unwrap_or(0.0) as u32;
            let Some(e) = tools.get_mut(&t) else {
                return fail(format!("$TC_MPP6[{m},{p}]={t}: tool {t} is not defined ($TC_TP or $TC_DP data)"));
            };
            if let Some((m0, p0)) = e.place {
                return fail(format!("$TC_MPP6[{m},{p}]={t}: tool {t} is already in magazine {m0} place {p0}"));
            }
            e.place = Some((m, p));
            let place = magazines
                .iter_mut()
                .find(|g| g.number == m)
                .and_then(|g| g.places.get_mut(p as usize - 1))
                .expect("places cover every $TC_MPP index");
            place.tool = Some(t);
        }
        // Named tools without a place go into the first free magazine place.
        let unplaced: Vec<u32> =
            tools.values().filter(|e| !e.name.is_empty() && e.place.is_none()).map(|e| e.number).collect();
        for t in unplaced {
            let free = magazines.iter_mut().filter(|g| g.number < BUFFER_MAGAZINE).find_map(|g| {
                let m = g.number;
                g.places
                    .iter_mut()
                    .find(|p| p.kind == KIND_MAGAZINE_PLACE && p.state & PLACE_DISABLED == 0 && p.tool.is_none())
                    .map(|p| (m, p))
            });
            if let Some((m, place)) = free {
                place.tool = Some(t);
                let e = tools.get_mut(&t).expect("listed above");
                e.place = Some((m, place.number));
                e.auto_placed = true;
            }
        }
        let monitored = tools.values().any(|e| e.monitoring & (MONITOR_TIME | MONITOR_COUNT) != 0);
        Ok(ToolList { tools, magazines, raw: tm.clone(), monitored })
    }

    /// The tool `T="name"` selects: among the tools of that name the enabled one with the
    /// lowest duplo number (the control's replacement-tool choice with the default strategy).
    pub fn by_name(&self, name: &str) -> Result<u32, NameError> {
        let mut named = self.tools.values().filter(|e| e.name == name).peekable();
        if named.peek().is_none() {
            return Err(NameError::Unknown);
        }
        named
            .filter(|e| e.state & STATE_DISABLED == 0)
            .min_by_key(|e| (e.duplo, e.number))
            .map(|e| e.number)
            .ok_or(NameError::Disabled)
    }

    /// The spindle place: the first place of kind 2 in the buffer magazine.
    pub fn spindle_place(&self) -> Option<(u32, u32)> {
        let buffer = self.magazines.iter().find(|g| g.number == BUFFER_MAGAZINE)?;
        buffer.places.iter().find(|p| p.kind == KIND_SPINDLE).map(|p| (BUFFER_MAGAZINE, p.number))
    }

    /// A program's read of `$TC_TPn[t]`, `$TC_MAPn[m]`, `$TC_MPPn[m,p]`, `$TC_MOPn[t,d]`
    /// (`b` = 0 for the one-index families): the activated value (places given at activation
    /// included), the default 0 or "" where nothing is stored. `None` for another name.
    pub fn read(&self, name: &str, a: u32, b: u32) -> Option<Value> {
        let (family, n) = Family::of(name)?;
        let place =
            || self.magazines.iter().find(|g| g.number == a).and_then(|g| g.places.get((b as usize).wrapping_sub(1)));
        Some(match (family, n) {
            (Family::Tool, 2) => Value::Str(self.tools.get(&a).map(|e| e.name.clone()).unwrap_or_default()),
            (Family::Magazine, 2) => Value::Str(match self.raw.get(family, a, 0, 2) {
                Some(Value::Str(s)) => s.clone(),
                _ => String::new(),
            }),
            (Family::Place, 1) => Value::Int(place().map_or(0, |p| p.kind)),
            (Family::Place, 6) => Value::Int(place().and_then(|p| p.tool).map_or(0, i64::from)),
            (Family::Monitoring, _) => {
                Value::Real(self.raw.get(family, a, b, n).and_then(Value::as_f64).unwrap_or(0.0))
            }
            _ => Value::Int(self.raw.int(family, a, b, n)),
        })
    }

    /// Whether the data use tool management at all (a name or a magazine).
    pub fn is_managed(&self) -> bool {
        !self.magazines.is_empty() || self.tools.values().any(|e| !e.name.is_empty())
    }
}

#[cfg(test)]
mod tests {
    use crate::machine_data::MachineData;

    fn list(text: &str) -> super::ToolList {
        let mut md = MachineData::default();
        (*md.apply_text(text).unwrap().tool_list).clone()
    }

    #[test]
    fn a_named_tool_without_a_place_goes_into_the_first_free_place() {
        // Places 1 and 2 of the chain magazine: 1 holds tool 1, 2 is disabled ($TC_MPP4 bit 0),
        // so tool 7 lands in place 3.
        let l = list(
            "$TC_MAP1[1]=1\n$TC_MAP7[1]=4\n$TC_TP2[1]=\"A\"\n$TC_MPP6[1,1]=1\n$TC_MPP4[1,2]=1\n\
             $TC_TP2[7]=\"DRILL_8\"\n$TC_DP1[7,1]=200\n",
        );
        let t7 = &l.tools[&7];
        assert_eq!((t7.place, t7.auto_placed), (Some((1, 3)), true));
        assert!(!l.tools[&1].auto_placed);
        assert_eq!(l.magazines[0].places[2].tool, Some(7));
        assert_eq!(t7.edges, vec![1]);
    }

    #[test]
    fn the_enabled_duplo_with_the_lowest_number_is_selected_by_name() {
        let l = list(
            "$TC_TP2[1]=\"M\"\n$TC_TP1[1]=1\n$TC_TP8[1]=4\n$TC_TP2[2]=\"M\"\n$TC_TP1[2]=3\n\
             $TC_TP2[3]=\"M\"\n$TC_TP1[3]=2\n$TC_TP2[4]=\"X\"\n$TC_TP8[4]=4\n",
        );
        assert_eq!(l.by_name("M"), Ok(3), "duplo 1 is disabled, duplo 2 is tool 3");
        assert_eq!(l.by_name("X"), Err(super::NameError::Disabled));
        assert_eq!(l.by_name("Q"), Err(super::NameError::Unknown));
    }

    #[test]
    fn inconsistent_places_and_names_are_refused() {
        let mut md = MachineData::default();
        for (text, needle) in [
            ("$TC_MAP1[1]=1\n$TC_MPP6[1,1]=5", "tool 5 is not defined"),
            ("$TC_TP2[5]=\"A\"\n$TC_MPP6[1,1]=5\n$TC_MPP6[1,2]=5", "already in magazine 1 place 1"),
            ("$TC_TP2[5]=\"A\"\n$TC_TP2[6]=\"A\"", "both \"A\" with duplo number 0"),
        ] {
            let e = md.apply_text(text).unwrap_err();
            assert!(e.message.contains(needle), "{text}: {}", e.message);
        }
    }
}

//! Machine data, tool data and settable frames: the control's configuration.
//!
//! Input: NC data text in the control's assignment syntax ([`text`]), checked against the
//! table of known data ([`registry`]). Output: a validated, typed [`MachineConfig`] that the
//! rest of the engine reads. Text is applied all-or-nothing: an unknown name, a bad index, a
//! bad value or an inconsistent result rejects the whole text with the offending line.

pub mod carrier;
pub mod chains;
mod config;
pub mod dynamics;
pub mod flat_d;
pub mod gears;
pub mod inch;
pub mod path_control;
pub mod presets;
pub mod process_counting;
pub mod registry;
pub mod sync_sizes;
pub mod text;
pub mod tool_orient;
pub mod tools_list;
pub mod tools_mgmt;
pub mod trafo;
pub mod traori;

use std::collections::BTreeMap;

pub use carrier::{Carrier, CarrierKind};
pub use config::{ChannelAxis, FrameAngles, FrameData, MachineAxis, MachineConfig, ResetTrafo};
use registry::{Def, Kind, Scope};
use text::{IndexTok, Line, Literal};
pub use trafo::{ChainDef, TrafoDataSet, TrafoKind, TrafoParams};
pub use traori::{OriMachine, OriSettings, TraoriParams};

/// A value of a machine datum.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    Bool(bool),
    Int(i64),
    Real(f64),
    Str(String),
}

impl Value {
    /// Numeric view (booleans as 0/1); `None` for strings.
    pub fn as_f64(&self) -> Option<f64> {
        match *self {
            Value::Bool(b) => Some(if b { 1.0 } else { 0.0 }),
            Value::Int(i) => Some(i as f64),
            Value::Real(r) => Some(r),
            Value::Str(_) => None,
        }
    }
}

/// Rejected NC data: what is wrong and, where it comes from one line, that line (1-based).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}{message}", line.map(|l| format!("line {l}: ")).unwrap_or_default())]
pub struct MdError {
    pub line: Option<u32>,
    pub message: String,
}

impl MdError {
    pub(crate) fn at(line: u32, message: impl Into<String>) -> Self {
        MdError { line: Some(line), message: message.into() }
    }
    pub(crate) fn general(message: impl Into<String>) -> Self {
        MdError { line: None, message: message.into() }
    }
}

/// Where one machine datum element is stored: the datum, the machine axis (axial data) and the
/// array index.
type Key = (&'static str, Scope, usize, usize);

/// Number of tool parameters `$TC_DP1..$TC_DP25` per cutting edge.
pub const TOOL_PARAMS: usize = 25;
/// Highest tool number and cutting-edge number accepted.
pub const MAX_TOOL_NUMBER: i64 = 32000;
pub const MAX_EDGE_NUMBER: i64 = 12;

/// The offsets of one cutting edge: `$TC_DP1..$TC_DP25` (index 0 = DP1), then the
/// orientation data `$TC_DPV3..5`, `$TC_DPVN3..5` (see `tool_orient.rs`).
pub type EdgeParams = [f64; tool_orient::EDGE_SLOTS];

/// One component of a stored frame `$P_UIFR[n, axis, TR|FI|RT|SC|MI]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum FrameComponent {
    /// Coarse translation.
    Translation,
    /// Fine translation.
    Fine,
    /// Rotation about a geometry axis, degrees (RPY: Z, then Y', then X'').
    Rotation,
    /// Scale factor.
    Scale,
    /// Mirroring (1) of the axis.
    Mirror,
}

impl FrameComponent {
    /// The component's keyword in NC data text.
    pub fn code(self) -> &'static str {
        match self {
            FrameComponent::Translation => "TR",
            FrameComponent::Fine => "FI",
            FrameComponent::Rotation => "RT",
            FrameComponent::Scale => "SC",
            FrameComponent::Mirror => "MI",
        }
    }

    fn parse(code: &str) -> Option<FrameComponent> {
        [Self::Translation, Self::Fine, Self::Rotation, Self::Scale, Self::Mirror]
            .into_iter()
            .find(|c| c.code() == code)
    }
}

/// The stored frames of the data management.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum FrameFamily {
    /// NCU-global basic frames `$P_NCBFR[n]` (MD18602), chained before the channel basic frames.
    NcuBase,
    /// Channel basic frames `$P_CHBFR[n]` (`$P_UBFR` is `$P_CHBFR[0]`), chained into `$P_ACTBFRAME`.
    Base,
    /// Settable frames `$P_UIFR[n]`, selected by G500/G54.../G505...
    Settable,
}

impl FrameFamily {
    /// The system variable and the machine datum that sizes it.
    fn names(self) -> (&'static str, &'static str) {
        match self {
            FrameFamily::NcuBase => ("$P_NCBFR", "$MN_MM_NUM_GLOBAL_BASE_FRAMES"),
            FrameFamily::Base => ("$P_CHBFR", "$MC_MM_NUM_BASE_FRAMES"),
            FrameFamily::Settable => ("$P_UIFR", "$MC_MM_NUM_USER_FRAMES"),
        }
    }
}

/// Where a stored frame value lives: family, frame number, axis name, component.
pub type FrameKey = (FrameFamily, usize, String, FrameComponent);

/// The stored configuration of a channel: only values that differ from the defaults are kept,
/// so a session costs memory in proportion to what was configured.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MachineData {
    values: BTreeMap<Key, Value>,
    tools: BTreeMap<(u32, u32), EdgeParams>,
    frames: BTreeMap<FrameKey, f64>,
    /// Toolholder data `$TC_CARRn[m]` by (m, n), values that differ from the default.
    carriers: BTreeMap<(u32, u32), Value>,
    /// Kinematic chain elements and transformation records (`$NK_`, `$NT_`).
    kin: chains::KinData,
    /// Tool-management data `$TC_TP`, `$TC_MAP`, `$TC_MPP`, `$TC_MOP`.
    tm: tools_mgmt::ToolMgmtData,
}

impl MachineData {
    /// The value of element `index` of `def` for machine axis `axis` (0 for non-axial data),
    /// or its default.
    pub fn get(&self, def: &'static Def, axis: usize, index: usize) -> Value {
        let key = (def.name, def.scope, axis, index);
        match self.values.get(&key) {
            Some(v) => v.clone(),
            None => {
                let rotary = def.scope == Scope::Axis && self.is_rotary(axis);
                def.default_value(index, rotary)
            }
        }
    }

    fn is_rotary(&self, axis: usize) -> bool {
        self.values.get(&("IS_ROT_AX", Scope::Axis, axis, 0)).is_some_and(|v| *v == Value::Bool(true))
    }

    /// Numeric value by full name; panics only on a programming error (unknown name).
    pub(crate) fn num(&self, full_name: &str, axis: usize, index: usize) -> f64 {
        let def = registry::lookup(full_name).unwrap_or_else(|| panic!("{full_name} is not in the registry"));
        self.get(def, axis, index).as_f64().unwrap_or(0.0)
    }

    pub(crate) fn string(&self, full_name: &str, index: usize) -> String {
        let def = registry::lookup(full_name).unwrap_or_else(|| panic!("{full_name} is not in the registry"));
        match self.get(def, 0, index) {
            Value::Str(s) => s,
            other => format!("{other:?}"),
        }
    }

    /// Applies NC data text all-or-nothing and returns the activated configuration.
    pub fn apply_text(&mut self, text: &str) -> Result<MachineConfig, MdError> {
        let lines = text::parse(text)?;
        let mut staged = self.clone();
        let mut origin: BTreeMap<&'static str, u32> = BTreeMap::new();
        for line in &lines {
            match line {
                Line::ChanData { line, channel } if *channel != 1 => {
                    return Err(MdError::at(*line, format!("CHANDATA({channel}): this control has one channel")));
                }
                Line::ChanData { .. } => {}
                Line::Assign { line, name, indices, value } => {
                    if let Some(datum) = staged.assign(*line, name, indices, value)? {
                        origin.insert(datum, *line);
                    }
                }
            }
        }
        let config = staged.activate().map_err(|e| match e.datum.and_then(|d| origin.get(d)) {
            Some(&line) => MdError::at(line, e.message),
            None => MdError::general(e.message),
        })?;
        *self = staged;
        Ok(config)
    }

    /// Assigns NC data text all-or-nothing without activating it (as a part program writes
    /// machine data: it becomes active with NEWCONF or a reset).
    pub fn stage_text(&mut self, text: &str) -> Result<(), MdError> {
        let mut staged = self.clone();
        for line in text::parse(text)? {
            if let Line::Assign { line, name, indices, value } = line {
                staged.assign(line, &name, &indices, &value)?;
            }
        }
        *self = staged;
        Ok(())
    }

    /// Builds the typed configuration; fails on inconsistent data.
    pub fn activate(&self) -> Result<MachineConfig, config::ActivationError> {
        MachineConfig::build(self)
    }

    /// Assigns one line; returns the datum name for error attribution.
    fn assign(
        &mut self,
        line: u32,
        name: &str,
        indices: &[IndexTok],
        value: &Literal,
    ) -> Result<Option<&'static str>, MdError> {
        let err = |m: String| MdError::at(line, m);
        // Tool management and setting data NCTwin does not model: accepted, ignored, warned
        // about (`text::warnings`).
        if text::unmodelled(name).is_some() {
            return Ok(None);
        }
        if chains::is_chain_name(name) {
            let counts = (
                self.num("$MN_MM_MAXNUM_KIN_CHAIN_ELEM", 0, 0) as usize,
                self.num("$MN_MM_NUM_KIN_TRAFOS", 0, 0) as usize,
            );
            self.kin.assign(line, name, indices, value, counts)?;
            return Ok(None);
        }
        if let Some(n) = name.strip_prefix("$TC_DP") {
            self.assign_tool(line, name, n, indices, value)?;
            return Ok(None);
        }
        if tools_mgmt::ToolMgmtData::handles(name) {
            self.tm.assign(line, name, indices, value)?;
            return Ok(None);
        }
        if let Some(n) = name.strip_prefix("$TC_CARR") {
            self.assign_carrier(line, name, n, indices, value)?;
            return Ok(None);
        }
        let family = match name {
            "$P_UIFR" => Some((FrameFamily::Settable, indices.to_vec())),
            "$P_CHBFR" => Some((FrameFamily::Base, indices.to_vec())),
            "$P_NCBFR" => Some((FrameFamily::NcuBase, indices.to_vec())),
            // The user basic frame is channel basic frame 0.
            "$P_UBFR" => Some((FrameFamily::Base, [&[IndexTok::Number(0)], indices].concat())),
            _ => None,
        };
        if let Some((family, indices)) = family {
            self.assign_frame(line, family, &indices, value)?;
            return Ok(None);
        }
        let def = registry::lookup(name).ok_or_else(|| err(format!("unknown name {name}")))?;
        let (axis, index) = self.resolve_indices(line, def, indices)?;
        let value = convert(def, value).map_err(|m| err(format!("{name}: {m}")))?;
        self.values.insert((def.name, def.scope, axis, index), value);
        Ok(Some(def.name))
    }

    fn resolve_indices(&self, line: u32, def: &'static Def, indices: &[IndexTok]) -> Result<(usize, usize), MdError> {
        let name = def.full_name();
        let err = |m: String| MdError::at(line, m);
        let array_index = |tok: Option<&IndexTok>| -> Result<usize, MdError> {
            match tok {
                None if def.len == 1 => Ok(0),
                None => Err(err(format!("{name} is an array of {}: an index is needed", def.len))),
                Some(IndexTok::Number(n)) if *n >= 0 && (*n as usize) < def.len => Ok(*n as usize),
                Some(t) => Err(err(format!("bad index {} for {name} (valid: 0..{})", show(t), def.len - 1))),
            }
        };
        match def.scope {
            Scope::Axis => {
                let (arr, ax) = match indices {
                    // An axial array named without its element is element 0, as on the control
                    // (`$MA_MAX_AX_ACCEL[X]` is `$MA_MAX_AX_ACCEL[0,X]`, the DYNNORM value).
                    [ax] => (Some(&IndexTok::Number(0)), ax),
                    [i, ax] => (Some(i), ax),
                    _ => return Err(err(format!("{name} is axial data: index it by AXn or a machine axis name"))),
                };
                Ok((self.resolve_axis(line, &name, ax)?, array_index(arr)?))
            }
            Scope::Nck | Scope::Channel => match indices {
                [] | [_] => Ok((0, array_index(indices.first())?)),
                _ => Err(err(format!("{name} takes at most one index"))),
            },
        }
    }

    /// `AXn` (1-based) or a machine axis name from `$MN_AXCONF_MACHAX_NAME_TAB`.
    fn resolve_axis(&self, line: u32, name: &str, tok: &IndexTok) -> Result<usize, MdError> {
        let bad = || {
            MdError::at(
                line,
                format!(
                    "bad axis index {} for {name}: use AXn (n = 1..{}) or a machine axis name",
                    show(tok),
                    registry::MAX_MACHINE_AXES
                ),
            )
        };
        let IndexTok::Name(id) = tok else { return Err(bad()) };
        if let Some(n) = id.strip_prefix("AX").and_then(|n| n.parse::<usize>().ok()) {
            return (1..=registry::MAX_MACHINE_AXES).contains(&n).then_some(n - 1).ok_or_else(bad);
        }
        (0..registry::MAX_MACHINE_AXES)
            .find(|&i| self.string("$MN_AXCONF_MACHAX_NAME_TAB", i).eq_ignore_ascii_case(id))
            .ok_or_else(bad)
    }

    fn assign_tool(
        &mut self,
        line: u32,
        name: &str,
        param: &str,
        indices: &[IndexTok],
        value: &Literal,
    ) -> Result<(), MdError> {
        let err = |m: String| MdError::at(line, m);
        let p = tool_orient::slot(param).ok_or_else(|| {
            err(format!("unknown name {name} (tool data is $TC_DP1..$TC_DP{TOOL_PARAMS}, $TC_DPV3..5, $TC_DPVN3..5)"))
        })?;
        let (t, d) = match indices {
            [IndexTok::Number(t), IndexTok::Number(d)] => (*t, *d),
            // A flat D number (MD18102 = 1): the data set without a tool (`flat_d.rs`).
            [IndexTok::Number(d)] if (1..=flat_d::MAX_FLAT_D).contains(d) => {
                let Literal::Number(v) = value else {
                    return Err(err(format!("{name}: expected a number")));
                };
                self.tools.entry((0, *d as u32)).or_insert([0.0; tool_orient::EDGE_SLOTS])[p] = *v;
                return Ok(());
            }
            _ => return Err(err(format!("{name} needs [tool number, cutting edge], e.g. {name}[1,1]"))),
        };
        if !(1..=MAX_TOOL_NUMBER).contains(&t) {
            return Err(err(format!("{name}: tool number {t} out of range 1..{MAX_TOOL_NUMBER}")));
        }
        if !(1..=MAX_EDGE_NUMBER).contains(&d) {
            return Err(err(format!("{name}: cutting edge {d} out of range 1..{MAX_EDGE_NUMBER}")));
        }
        let Literal::Number(v) = value else {
            return Err(err(format!("{name}: expected a number")));
        };
        self.tools.entry((t as u32, d as u32)).or_insert([0.0; tool_orient::EDGE_SLOTS])[p] = *v;
        Ok(())
    }

    /// `$TC_CARRn[m]=value`: toolholder m (1..MD18088 MM_NUM_TOOL_CARRIER), parameter n.
    fn assign_carrier(
        &mut self,
        line: u32,
        name: &str,
        param: &str,
        indices: &[IndexTok],
        value: &Literal,
    ) -> Result<(), MdError> {
        let err = |m: String| MdError::at(line, m);
        let n: u32 =
            param.parse().ok().filter(|n| carrier::param_kind(*n).is_some()).ok_or_else(|| {
                err(format!("unknown name {name} (toolholder data is $TC_CARR1..46, 55..60, 64, 65)"))
            })?;
        let [IndexTok::Number(m)] = indices else {
            return Err(err(format!("{name} needs [toolholder number], e.g. {name}[1]")));
        };
        let count = self.num("$MN_MM_NUM_TOOL_CARRIER", 0, 0) as i64;
        if !(1..=count).contains(m) {
            return Err(err(format!("{name}[{m}]: toolholder out of range 1..{count} ($MN_MM_NUM_TOOL_CARRIER)")));
        }
        let v = carrier::convert(n, value).map_err(|e| err(format!("{name}[{m}]: {e}")))?;
        let key = (*m as u32, n);
        if v == carrier::default_value(n) {
            self.carriers.remove(&key);
        } else {
            self.carriers.insert(key, v);
        }
        Ok(())
    }

    fn assign_frame(
        &mut self,
        line: u32,
        family: FrameFamily,
        indices: &[IndexTok],
        value: &Literal,
    ) -> Result<(), MdError> {
        let err = |m: String| MdError::at(line, m);
        let (var, count_datum) = family.names();
        let [IndexTok::Number(n), IndexTok::Name(axis), IndexTok::Name(comp)] = indices else {
            return Err(err(format!("{var} needs [frame, axis, TR|FI|RT|SC|MI], e.g. {var}[1,X,TR]=10")));
        };
        let component = FrameComponent::parse(comp)
            .ok_or_else(|| err(format!("{var}: unknown frame component {comp} (TR, FI, RT, SC, MI)")))?;
        let frames = self.num(count_datum, 0, 0) as i64;
        if !(0..frames).contains(n) {
            return Err(err(format!("{var}[{n}]: frame out of range 0..{} ({count_datum})", frames - 1)));
        }
        let Literal::Number(v) = value else {
            return Err(err(format!("{var}: expected a number")));
        };
        if component == FrameComponent::Scale && *v == 0.0 {
            return Err(err(format!("{var}[{n},{axis},SC]: a scale factor of 0 is not allowed")));
        }
        // Neutral values are not stored (the frame then reads as neutral there).
        let key = (family, *n as usize, axis.clone(), component);
        let neutral = if component == FrameComponent::Scale { 1.0 } else { 0.0 };
        if *v == neutral {
            self.frames.remove(&key);
        } else {
            self.frames.insert(key, *v);
        }
        Ok(())
    }

    /// The stored data as NC data text (only what differs from the defaults), in a stable
    /// order. Applying it to default data gives this data back.
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        for ((name, scope, axis, index), value) in &self.values {
            let def = registry::DEFS
                .iter()
                .find(|d| d.name == *name && d.scope == *scope)
                .expect("stored data is registered");
            let value = match value {
                Value::Bool(b) => if *b { "TRUE" } else { "FALSE" }.to_string(),
                Value::Int(i) => i.to_string(),
                Value::Real(r) => format!("{r:?}"),
                Value::Str(s) => format!("\"{s}\""),
            };
            let index = match (def.scope, def.len) {
                (Scope::Axis, 1) => format!("[AX{}]", axis + 1),
                (Scope::Axis, _) => format!("[{index},AX{}]", axis + 1),
                (_, 1) => String::new(),
                _ => format!("[{index}]"),
            };
            out += &format!("{}{index}={value}\n", def.full_name());
        }
        for ((t, d), params) in &self.tools {
            for (p, v) in params.iter().enumerate().filter(|(_, v)| **v != 0.0) {
                match t {
                    0 => out += &format!("$TC_DP{}[{d}]={v:?}\n", tool_orient::name(p)),
                    _ => out += &format!("$TC_DP{}[{t},{d}]={v:?}\n", tool_orient::name(p)),
                }
            }
        }
        out += &self.tm.to_text();
        for ((m, n), v) in &self.carriers {
            out += &format!("$TC_CARR{n}[{m}]={}\n", carrier::show(*n, v));
        }
        for ((family, frame, axis, component), v) in &self.frames {
            out += &format!("{}[{frame},{axis},{}]={v:?}\n", family.names().0, component.code());
        }
        out += &self.kin.to_text();
        out
    }

    /// Cutting edges with their parameters, ordered by (tool, edge).
    pub fn tools(&self) -> &BTreeMap<(u32, u32), EdgeParams> {
        &self.tools
    }

    /// The raw tool-management data (`$TC_TP`, `$TC_MAP`, `$TC_MPP`, `$TC_MOP`).
    pub fn tool_mgmt(&self) -> &tools_mgmt::ToolMgmtData {
        &self.tm
    }

    /// Deletes every cutting edge and every tool-management datum (a tool list replaced as a
    /// whole).
    pub fn clear_tool_data(&mut self) {
        self.tools.clear();
        self.tm = Default::default();
    }

    /// Deletes tool `t` (DELT): its cutting edges, tool and monitoring data and its place.
    pub fn delete_tool(&mut self, t: u32) {
        self.tools.retain(|(tool, _), _| *tool != t);
        self.tm.delete_tool(t);
    }

    /// Moves tool `t` into place (m, p): its old place entry is removed.
    pub fn move_tool(&mut self, t: u32, m: u32, p: u32) {
        self.tm.clear_places_of(t);
        self.tm.set_place_tool(m, p, Some(t));
    }

    /// Every toolholder 1..MD18088 MM_NUM_TOOL_CARRIER, typed (defaults where nothing is stored).
    pub fn carriers(&self) -> BTreeMap<u32, Carrier> {
        let fine = self.num("$SC_TOCARR_FINE_CORRECTION", 0, 0) != 0.0;
        let count = self.num("$MN_MM_NUM_TOOL_CARRIER", 0, 0) as u32;
        let mut by_holder: BTreeMap<u32, BTreeMap<u32, Value>> = (1..=count).map(|m| (m, BTreeMap::new())).collect();
        for ((m, n), v) in &self.carriers {
            by_holder.entry(*m).or_default().insert(*n, v.clone());
        }
        by_holder.into_iter().map(|(m, p)| (m, Carrier::build(m, &p, fine))).collect()
    }

    /// The kinematic chain data (`$NK_`, `$NT_`).
    pub fn kin(&self) -> &chains::KinData {
        &self.kin
    }

    /// `DELOBJ("KIN_CHAIN_ELEM")` / `DELOBJ("TRAFO_DATA")`: deletes every chain element or
    /// every transformation record (effective at the next activation).
    pub fn delete_kin(&mut self, elements: bool, trafos: bool) {
        if elements {
            self.kin.clear_elements();
        }
        if trafos {
            self.kin.clear_trafos();
        }
    }

    /// `DELOBJ("TOOLCARRIER", start, end)`: the data of the toolholders numbered `range` back
    /// to the defaults (acting at once, like a `$TC_CARR` write).
    pub fn delete_carriers(&mut self, range: std::ops::RangeInclusive<u32>) {
        self.carriers.retain(|(m, _), _| !range.contains(m));
    }

    /// Stored frame components by (family, frame, axis name, component).
    pub fn frames(&self) -> &BTreeMap<FrameKey, f64> {
        &self.frames
    }
}

fn show(tok: &IndexTok) -> String {
    match tok {
        IndexTok::Number(n) => n.to_string(),
        IndexTok::Name(s) => s.clone(),
    }
}

fn convert(def: &Def, lit: &Literal) -> Result<Value, String> {
    let in_range = |v: f64| -> Result<f64, String> {
        if v < def.min || v > def.max { Err(format!("value {v} out of range {}..{}", def.min, def.max)) } else { Ok(v) }
    };
    match (def.kind, lit) {
        (Kind::Bool, Literal::Bool(b)) => Ok(Value::Bool(*b)),
        (Kind::Bool, Literal::Number(n)) if *n == 0.0 || *n == 1.0 => Ok(Value::Bool(*n == 1.0)),
        (Kind::Int, Literal::Number(n)) if n.fract() == 0.0 => Ok(Value::Int(in_range(*n)? as i64)),
        (Kind::Int, Literal::Number(n)) => Err(format!("expected an integer, found {n}")),
        (Kind::Real, Literal::Number(n)) => Ok(Value::Real(in_range(*n)?)),
        (Kind::Str, Literal::Str(s)) if s.len() <= 32 => Ok(Value::Str(s.clone())),
        (Kind::Str, Literal::Str(_)) => Err("string longer than 32 characters".into()),
        (kind, lit) => Err(format!("expected {}, found {lit:?}", kind_name(kind))),
    }
}

fn kind_name(kind: Kind) -> &'static str {
    match kind {
        Kind::Bool => "TRUE or FALSE",
        Kind::Int => "an integer",
        Kind::Real => "a number",
        Kind::Str => "a string in double quotes",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axial_data_is_indexed_by_axn_or_by_machine_axis_name() {
        let mut md = MachineData::default();
        md.apply_text("$MA_POS_LIMIT_PLUS[AX1]=500\n$MA_POS_LIMIT_PLUS[Y1]=400").unwrap();
        assert_eq!(md.num("$MA_POS_LIMIT_PLUS", 0, 0), 500.0);
        assert_eq!(md.num("$MA_POS_LIMIT_PLUS", 1, 0), 400.0);
    }

    #[test]
    fn an_error_on_any_line_applies_nothing() {
        let mut md = MachineData::default();
        let before = md.clone();
        let e = md.apply_text("$MA_POS_LIMIT_PLUS[AX1]=500\n$MA_NO_SUCH=1\n").unwrap_err();
        assert_eq!(e.line, Some(2));
        assert!(e.message.contains("$MA_NO_SUCH"));
        assert_eq!(md, before);
    }

    #[test]
    fn ncu_basic_frames_are_sized_by_md18602_and_round_trip() {
        let mut md = MachineData::default();
        let e = md.apply_text("$P_NCBFR[0,X,TR]=1").unwrap_err();
        assert!(e.message.contains("MM_NUM_GLOBAL_BASE_FRAMES"), "{}", e.message);
        md.apply_text("$MN_MM_NUM_GLOBAL_BASE_FRAMES=2\n$P_NCBFR[1,Y,TR]=4.5\n$MN_FRAME_ANGLE_INPUT_MODE=2").unwrap();
        let cfg = md.activate().unwrap();
        assert_eq!(cfg.ncu_base_frames.len(), 2);
        assert_eq!(cfg.ncu_base_frames[1].trans[1], 4.5);
        assert_eq!(cfg.frame_angles, FrameAngles::Euler);
        let mut again = MachineData::default();
        again.apply_text(&md.to_text()).unwrap();
        assert_eq!(again, md);
    }

    #[test]
    fn stored_frames_keep_every_component_and_round_trip_as_text() {
        let mut md = MachineData::default();
        let text = "$P_UIFR[1,X,TR]=10.0\n$P_UIFR[1,Z,RT]=30.0\n$P_UIFR[2,Y,SC]=2.0\n$P_UIFR[2,X,MI]=1.0\n$P_UBFR[Z,TR]=-5.0\n$P_CHBFR[0,X,FI]=0.25";
        md.apply_text(text).unwrap();
        let cfg = md.activate().unwrap();
        assert_eq!(cfg.work_offsets[1].trans[0], 10.0);
        assert_eq!(cfg.work_offsets[1].rot, [0.0, 0.0, 30.0]);
        assert_eq!((cfg.work_offsets[2].scale[1], cfg.work_offsets[2].mirror[0]), (2.0, true));
        assert_eq!((cfg.base_frames[0].trans[2], cfg.base_frames[0].trans[0]), (-5.0, 0.25));
        let mut again = MachineData::default();
        again.apply_text(&md.to_text()).unwrap();
        assert_eq!(again, md);
        // A neutral value deletes the component again.
        md.apply_text("$P_UIFR[1,Z,RT]=0").unwrap();
        assert_eq!(md.activate().unwrap().work_offsets[1].rot, [0.0; 3]);
        for (text, needle) in [
            ("$P_UIFR[1,X,XX]=1", "unknown frame component XX"),
            ("$P_UIFR[1,X,SC]=0", "scale factor of 0"),
            ("$P_CHBFR[1,X,TR]=1", "out of range 0..0"),
        ] {
            let e = md.apply_text(text).unwrap_err();
            assert!(e.message.contains(needle), "{text}: {}", e.message);
        }
    }

    #[test]
    fn bad_indices_and_values_are_rejected_with_their_line() {
        let mut md = MachineData::default();
        for (text, needle) in [
            ("$MC_AXCONF_GEOAX_NAME_TAB[3]=\"Q\"", "bad index 3"),
            ("$MA_IS_ROT_AX[AX32]=TRUE", "bad axis index AX32"),
            ("$MA_IS_ROT_AX[AX1]=\"yes\"", "expected TRUE or FALSE"),
            ("$MN_IPO_SYSCLOCK_TIME_RATIO=2.5", "expected an integer"),
            ("$MN_SYSCLOCK_CYCLE_TIME=5", "out of range"),
            ("$TC_DP6[0,1]=3", "tool number 0"),
            ("$TC_DP26[1,1]=3", "unknown name"),
        ] {
            let e = md.apply_text(&format!("; first\n{text}")).unwrap_err();
            assert_eq!(e.line, Some(2), "{text}");
            assert!(e.message.contains(needle), "{text}: {}", e.message);
        }
    }

    #[test]
    fn inconsistent_data_names_the_line_that_caused_it() {
        let mut md = MachineData::default();
        let e = md.apply_text("$MA_POS_LIMIT_PLUS[AX1]=500\n$MA_POS_LIMIT_MINUS[AX1]=600\n").unwrap_err();
        assert!(e.line.is_some(), "{e}");
        assert!(e.message.contains("POS_LIMIT"), "{e}");
    }

    #[test]
    fn text_export_round_trips_every_preset() {
        for preset in presets::PRESETS {
            let mut md = MachineData::default();
            md.apply_text(preset.text).unwrap();
            md.apply_text("$TC_DP3[9,2]=1.25\n$P_UIFR[1,X,FI]=0.5").unwrap_or_else(|e| panic!("{}: {e}", preset.id));
            let mut again = MachineData::default();
            again.apply_text(&md.to_text()).unwrap_or_else(|e| panic!("{}: {e}\n{}", preset.id, md.to_text()));
            assert_eq!(again, md, "{}", preset.id);
        }
    }

    #[test]
    fn tool_data_is_stored_per_edge() {
        let mut md = MachineData::default();
        md.apply_text("$TC_DP1[3,2]=120\n$TC_DP3[3,2]=55.5").unwrap();
        let edge = md.tools()[&(3, 2)];
        assert_eq!((edge[0], edge[2]), (120.0, 55.5));
    }
}

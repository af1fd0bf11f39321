//! Wire types of the tool list (`GET/PUT /sessions/{id}/tools`) and their translation from the
//! engine's activated tool list and into tool data text (`$TC_TP`, `$TC_DP`, `$TC_MAP`,
//! `$TC_MPP`, `$TC_MOP` lines), with the JSON field each line came from, so a refused line is
//! answered naming the field.

use std::collections::BTreeMap;

use nctwin_engine::machine_data::{MAX_EDGE_NUMBER, MAX_TOOL_NUMBER, MachineConfig};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// The session's tool list: tools with their cutting edges and places, and the magazines.
/// `PUT` takes the same document back (the fields marked read-only are ignored).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ToolList {
    /// Read-only: the tool in the spindle (T number, 0 = none).
    #[serde(default)]
    pub spindle: u32,
    /// Read-only: the programmed tool `$P_TOOLP` (under MD22550 = 1 the one M6 changes to).
    #[serde(default)]
    pub prepared: u32,
    pub tools: Vec<ToolEntry>,
    #[serde(default)]
    pub magazines: Vec<Magazine>,
}

/// One tool (`$TC_TP..[number]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ToolEntry {
    /// Tool number T (1..32000).
    pub number: u32,
    /// `$TC_TP2`, the name `T="name"` selects (empty: selected by number only).
    #[serde(default)]
    pub name: String,
    /// `$TC_TP1` duplo number.
    #[serde(default)]
    pub duplo: i64,
    /// `$TC_TP8` state bits (1 active, 2 enabled, 4 disabled, 8 measured, ...).
    #[serde(default)]
    pub state: i64,
    /// `$TC_TP9` monitoring type (0 none, 1 time, 2 count, 4 wear).
    #[serde(default)]
    pub monitoring: i64,
    /// Magazine place (`$TC_MPP6`); without one a named tool is put into the first free place.
    #[serde(default)]
    pub place: Option<PlaceRef>,
    /// Read-only: the place was given when the data were activated (the data named none).
    #[serde(default)]
    pub auto_placed: bool,
    /// Read-only: the tool is in the spindle.
    #[serde(default)]
    pub in_spindle: bool,
    #[serde(default)]
    pub edges: Vec<Edge>,
}

/// A magazine place.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct PlaceRef {
    /// Magazine number (1..9999; 9998 buffer, 9999 loading magazine).
    pub magazine: u32,
    /// Place number (1..999).
    pub place: u32,
}

/// One cutting edge D of a tool (`$TC_DPn[t,d]`, `$TC_MOPn[t,d]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Edge {
    /// D number (1..12).
    pub d: u32,
    /// `$TC_DP1` tool type (120 end mill, 200 twist drill, 500 roughing tool, ...).
    #[serde(rename = "type", default)]
    pub tool_type: f64,
    /// `$TC_DP2` cutting edge position (turning tools, 1..9).
    #[serde(default)]
    pub position: f64,
    /// `$TC_DP3..5` geometry lengths 1..3, mm.
    #[serde(default)]
    pub lengths: [f64; 3],
    /// `$TC_DP6` geometry radius, mm.
    #[serde(default)]
    pub radius: f64,
    /// `$TC_DP12..14` wear of the lengths, mm.
    #[serde(default)]
    pub wear_lengths: [f64; 3],
    /// `$TC_DP15` wear of the radius, mm.
    #[serde(default)]
    pub wear_radius: f64,
    /// The other non-zero parameters `$TC_DPn` (7..11, 16..25) by n.
    #[serde(default)]
    pub more: BTreeMap<u32, f64>,
    /// The non-zero monitoring data `$TC_MOPn` by n (1 time prewarning, 2 remaining time, 3
    /// count prewarning, 4 remaining count, 11 time setpoint, 13 count setpoint, ...).
    #[serde(default)]
    pub monitoring: BTreeMap<u32, f64>,
}

/// One magazine (`$TC_MAP..[number]`) with its places.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Magazine {
    pub number: u32,
    /// `$TC_MAP1`: 1 chain, 3 turret, 5 box, 7 buffer, 9 loading.
    pub kind: i64,
    /// `$TC_MAP2`.
    #[serde(default)]
    pub name: String,
    /// The places 1..n in order.
    pub places: Vec<Place>,
}

/// One place of a magazine.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Place {
    pub number: u32,
    /// `$TC_MPP1`: 1 magazine place, 2 spindle, 3 gripper, ...
    pub kind: i64,
    /// `$TC_MPP4` state bits (1 disabled).
    #[serde(default)]
    pub state: i64,
    /// Read-only: the tool in the place (tools name their places).
    #[serde(default)]
    pub tool: Option<u32>,
}

/// Body of `POST .../tools/{name}/load`.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct LoadRequest {
    pub magazine: u32,
    pub place: u32,
    /// The duplo number, where several tools share the name.
    #[serde(default)]
    pub duplo: Option<i64>,
}

/// Query of `POST .../tools/{name}/unload`.
#[derive(Debug, Clone, Copy, Deserialize, utoipa::IntoParams)]
#[into_params(parameter_in = Query)]
pub struct UnloadQuery {
    /// The duplo number, where several tools share the name.
    pub duplo: Option<i64>,
}

/// DP slots with a field of their own (0-based: DP1..6, DP12..15).
const NAMED_DP: [usize; 10] = [0, 1, 2, 3, 4, 5, 11, 12, 13, 14];

impl ToolList {
    /// Shows the live remaining life (`$TC_MOP2`, minutes) of the edge whose cutting time the
    /// main run is counting: the tool data get the count only at thresholds, edge changes and
    /// the end of the program.
    pub fn with_remaining_time(mut self, t: u32, d: u32, minutes: f64) -> ToolList {
        let edge = self.tools.iter_mut().filter(|e| e.number == t).flat_map(|e| e.edges.iter_mut()).find(|e| e.d == d);
        if let Some(edge) = edge {
            edge.monitoring.insert(2, minutes);
        }
        self
    }

    /// The list as the engine activated it, with the spindle and prepared tools.
    pub fn from_config(cfg: &MachineConfig, spindle: u32, prepared: u32) -> ToolList {
        let list = &cfg.tool_list;
        let tools = list
            .tools
            .values()
            .map(|e| ToolEntry {
                number: e.number,
                name: e.name.clone(),
                duplo: e.duplo,
                state: e.state,
                monitoring: e.monitoring,
                place: e.place.map(|(magazine, place)| PlaceRef { magazine, place }),
                auto_placed: e.auto_placed,
                in_spindle: spindle != 0 && e.number == spindle,
                edges: e
                    .edges
                    .iter()
                    .map(|&d| {
                        let p = &cfg.tools[&(e.number, d)];
                        let more = (0..25)
                            .filter(|i| !NAMED_DP.contains(i) && p[*i] != 0.0)
                            .map(|i| (i as u32 + 1, p[i]))
                            .collect();
                        let monitoring = (1..=15)
                            .filter_map(|n| {
                                let v = list.read(&format!("$TC_MOP{n}"), e.number, d)?.as_f64()?;
                                (v != 0.0).then_some((n, v))
                            })
                            .collect();
                        Edge {
                            d,
                            tool_type: p[0],
                            position: p[1],
                            lengths: [p[2], p[3], p[4]],
                            radius: p[5],
                            wear_lengths: [p[11], p[12], p[13]],
                            wear_radius: p[14],
                            more,
                            monitoring,
                        }
                    })
                    .collect(),
            })
            .collect();
        let magazines = list
            .magazines
            .iter()
            .map(|g| Magazine {
                number: g.number,
                kind: g.kind,
                name: g.name.clone(),
                places: g
                    .places
                    .iter()
                    .map(|p| Place { number: p.number, kind: p.kind, state: p.state, tool: p.tool })
                    .collect(),
            })
            .collect();
        ToolList { spindle, prepared, tools, magazines }
    }

    /// The list as tool data text, and for each line (1-based, index + 1) the field it came
    /// from. A value no line can carry is refused here, naming its field.
    pub fn to_text(&self) -> Result<(String, Vec<String>), String> {
        let mut out = Text::default();
        let mut numbers = BTreeMap::new();
        let mut places = BTreeMap::new();
        for (i, t) in self.tools.iter().enumerate() {
            let at = format!("tools[{i}]");
            if !(1..=MAX_TOOL_NUMBER as u32).contains(&t.number) {
                return Err(format!("{at}.number: {} is out of range 1..{MAX_TOOL_NUMBER}", t.number));
            }
            if let Some(j) = numbers.insert(t.number, i) {
                return Err(format!("{at}.number: tool {} is also tools[{j}]", t.number));
            }
            let n = t.number;
            if t.name.len() > 32 || t.name.contains(['"', '\n', '\r', ';']) {
                return Err(format!("{at}.name: at most 32 characters, no quotes, semicolons or line breaks"));
            }
            if !t.name.is_empty() {
                out.line(format!("$TC_TP2[{n}]=\"{}\"", t.name), format!("{at}.name"));
            }
            for (field, p, v) in [("duplo", 1, t.duplo), ("state", 8, t.state), ("monitoring", 9, t.monitoring)] {
                if v != 0 {
                    out.line(format!("$TC_TP{p}[{n}]={v}"), format!("{at}.{field}"));
                }
            }
            if let Some(PlaceRef { magazine, place }) = t.place {
                if let Some(j) = places.insert((magazine, place), i) {
                    return Err(format!(
                        "{at}.place: magazine {magazine} place {place} already holds tool {} (tools[{j}])",
                        self.tools[j].number
                    ));
                }
                out.line(format!("$TC_MPP6[{magazine},{place}]={n}"), format!("{at}.place"));
            }
            let mut ds = BTreeMap::new();
            for (k, e) in t.edges.iter().enumerate() {
                let at = format!("{at}.edges[{k}]");
                if !(1..=MAX_EDGE_NUMBER as u32).contains(&e.d) {
                    return Err(format!("{at}.d: {} is out of range 1..{MAX_EDGE_NUMBER}", e.d));
                }
                if let Some(j) = ds.insert(e.d, k) {
                    return Err(format!("{at}.d: D{} is also edges[{j}]", e.d));
                }
                let named = [
                    ("type", 1, e.tool_type),
                    ("position", 2, e.position),
                    ("lengths[0]", 3, e.lengths[0]),
                    ("lengths[1]", 4, e.lengths[1]),
                    ("lengths[2]", 5, e.lengths[2]),
                    ("radius", 6, e.radius),
                    ("wear_lengths[0]", 12, e.wear_lengths[0]),
                    ("wear_lengths[1]", 13, e.wear_lengths[1]),
                    ("wear_lengths[2]", 14, e.wear_lengths[2]),
                    ("wear_radius", 15, e.wear_radius),
                ];
                // An edge is written even where every value is 0 (DP1 carries it).
                out.line(format!("$TC_DP1[{n},{}]={:?}", e.d, e.tool_type), format!("{at}.type"));
                for (field, p, v) in named.into_iter().skip(1).chain(e.more.iter().map(|(p, v)| ("more", *p, *v))) {
                    let field = if field == "more" { format!("more.{p}") } else { field.to_string() };
                    if !v.is_finite() {
                        return Err(format!("{at}.{field}: {v} is not a finite number"));
                    }
                    if field.starts_with("more")
                        && (NAMED_DP.contains(&(p as usize).wrapping_sub(1)) || !(1..=25).contains(&p))
                    {
                        return Err(format!("{at}.{field}: more holds $TC_DP7..11 and 16..25 only"));
                    }
                    if v != 0.0 {
                        out.line(format!("$TC_DP{p}[{n},{}]={v:?}", e.d), format!("{at}.{field}"));
                    }
                }
                for (p, v) in &e.monitoring {
                    if !v.is_finite() {
                        return Err(format!("{at}.monitoring.{p}: {v} is not a finite number"));
                    }
                    out.line(format!("$TC_MOP{p}[{n},{}]={v:?}", e.d), format!("{at}.monitoring.{p}"));
                }
            }
        }
        for (i, g) in self.magazines.iter().enumerate() {
            let at = format!("magazines[{i}]");
            let m = g.number;
            if g.name.len() > 32 || g.name.contains(['"', '\n', '\r', ';']) {
                return Err(format!("{at}.name: at most 32 characters, no quotes, semicolons or line breaks"));
            }
            out.line(format!("$TC_MAP1[{m}]={}", g.kind), format!("{at}.kind"));
            if !g.name.is_empty() {
                out.line(format!("$TC_MAP2[{m}]=\"{}\"", g.name), format!("{at}.name"));
            }
            out.line(format!("$TC_MAP7[{m}]={}", g.places.len()), format!("{at}.places"));
            for (k, p) in g.places.iter().enumerate() {
                if p.number as usize != k + 1 {
                    return Err(format!(
                        "{at}.places[{k}].number: places are numbered 1..n in order, expected {}",
                        k + 1
                    ));
                }
                out.line(format!("$TC_MPP1[{m},{}]={}", p.number, p.kind), format!("{at}.places[{k}].kind"));
                if p.state != 0 {
                    out.line(format!("$TC_MPP4[{m},{}]={}", p.number, p.state), format!("{at}.places[{k}].state"));
                }
            }
        }
        Ok((out.text, out.fields))
    }
}

/// Text under construction with the field of each line.
#[derive(Default)]
struct Text {
    text: String,
    fields: Vec<String>,
}

impl Text {
    fn line(&mut self, line: String, field: String) {
        self.text += &line;
        self.text.push('\n');
        self.fields.push(field);
    }
}

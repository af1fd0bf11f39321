//! Transformations defined by kinematic chains (Transformations FM chapter K12, REFERENCE §9.5):
//! the chain elements `$NK_…[i]` and the transformation records `$NT_…[n]`, stored beside the
//! machine data as NC data text (assigned all-or-nothing, exported by `to_text`), and turned at
//! activation (NEWCONF, reset) into typed [`TrafoDataSet`]s.
//!
//! Element model (this product's reading of the manual where it is silent):
//! * Every element has an input frame and an output frame. The root (`$MN_ROOT_KIN_ELEM_NAME`,
//!   default "ROOT") starts in the world frame. `$NK_NEXT` starts its element in the output
//!   frame of this one, `$NK_PARALLEL` in the input frame of this one (a branch beside it).
//! * `$NK_TYPE`: "OFFSET" translates by `$NK_OFF_DIR`; "AXIS_LIN" translates by
//!   `(position + $NK_A_OFF)` along the unit direction `$NK_OFF_DIR`; "AXIS_ROT" turns about
//!   `$NK_OFF_DIR` through the frame origin by the effective angle
//!   `position − $NT_ROT_AX_OFFSET + $NK_A_OFF`; "ROT_CONST" turns about `$NK_OFF_DIR` by the
//!   constant angle `$NK_A_OFF` (degrees).
//! * `$NK_AXIS` names the machine axis (`$MN_AXCONF_MACHAX_NAME_TAB`) or the channel axis an
//!   axis element follows.
//! * A subchain `FIRST_ELEM .. LAST_ELEM` is the way from the root to `LAST_ELEM`, which must
//!   pass `FIRST_ELEM` (empty = the root); no axis may lie between the root and `FIRST_ELEM`.
//!   The tool subchain ends at the tool reference point, the workpiece subchain at the
//!   workpiece reference point (the BCS origin); an empty workpiece subchain is the world frame.
//!
//! TRAORI_DYN becomes the generic orientation transformation of the machine data (types 24, 40
//! or 56: head, table or mixed) through the product-of-exponentials form of the chains: at the
//! kinematic zero (all axes 0) each rotary axis has a point and a direction in the world frame,
//! and the offsets `l1..l4` of the vector chain are differences of those points. The chains
//! must therefore have the shape TRAORI models: linear axes along +X/+Y/+Z before the rotary
//! axes of the tool chain (or along −X/−Y/−Z before those of the workpiece chain: an axis that
//! moves the workpiece moves the tool relative to it the other way), at most two rotary axes
//! on the workpiece side, three on the tool side, one on each for mixed kinematics, and
//! constant rotations that cancel by the end of each subchain (the BCS and the tool are not
//! rotated against the world frame at the kinematic zero).
//!
//! TRANSMIT_K, TRACYL_K and TRAANG_K become the machine data's TRANSMIT/TRACYL/TRAANG data sets
//! ([`classic`]). TRAORI_STAT and TRACON_K records are checked and stored, not built (TRAFOON of
//! one raises 14401 saying why: TRACON_K chains an Open Architecture transformation, which the
//! consulted sources do not describe and this product does not model). Of the
//! further `$NT_` fields, `$NT_POLE_LIMIT`/`$NT_POLE_TOL` reach TRAORI and `$NT_POLE_SIDE_FIX`
//! TRANSMIT; `$NT_ROT_OFFSET_FROM_FRAME` is carried like `TRANSMIT/TRACYL_ROT_AX_FRAME` (which
//! the kinematics do not evaluate either); `$NT_CLOSE_CHAIN_P/T` and `$NT_CORR_ELEM_P/T` are
//! checked to name elements of their subchain (OFFSET elements for the latter); the work offset
//! of a closed chain is not modelled, the correction elements are what CORRTRAFO writes
//! ([`correct`]); `$NT_AUX_POS` and
//! `$NT_IDENT` are not evaluated by the control (manual); `$NT_BASE_TOOL_COMP` ($P_TRAFRAME),
//! `$NT_ROT_AX_POS` (constant rotations as orientation axes) and `$NT_IGNORE_TOOL_ORIENT` (the
//! tool's own orientation is not modelled) are stored and range-checked only.

mod classic;
pub mod correct;
mod program;

pub use program::export_program;

use std::collections::{BTreeMap, BTreeSet};

use super::config::{ActivationError, ChannelAxis, MachineAxis};
use super::text::{IndexTok, Literal};
use super::trafo::{ChainDef, TrafoDataSet, TrafoKind, TrafoParams};
use super::traori::{OriMachine, TraoriParams};
use super::{MachineData, MdError, Value};

/// Data-set number of `$NT_…[n]` in `MachineConfig::trafos` is this plus n (the machine-data
/// sets are 1..10).
pub const KIN_TRAFO_NUMBER_BASE: usize = 100;

/// Longest element or transformation name (the manual: 31 characters).
const MAX_NAME: usize = 31;

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Family {
    /// `$NK_`: chain elements, indexed 0 .. MD18880 − 1.
    Element,
    /// `$NT_`: transformation records, indexed 0 .. MD18866 − 1.
    Trafo,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum VKind {
    Str,
    Real,
    Int,
}

/// One `$NK_`/`$NT_` variable: name, family, type, number of components (1 = no 2nd index).
struct Var {
    name: &'static str,
    family: Family,
    kind: VKind,
    len: usize,
}

const fn var(name: &'static str, family: Family, kind: VKind, len: usize) -> Var {
    Var { name, family, kind, len }
}

use Family::{Element as E, Trafo as T};
use VKind::{Int, Real, Str};

/// Every stored variable, in export order within a record.
const VARS: &[Var] = &[
    var("$NK_NAME", E, Str, 1),
    var("$NK_TYPE", E, Str, 1),
    var("$NK_NEXT", E, Str, 1),
    var("$NK_PARALLEL", E, Str, 1),
    var("$NK_OFF_DIR", E, Real, 3),
    var("$NK_AXIS", E, Str, 1),
    var("$NK_A_OFF", E, Real, 1),
    var("$NT_NAME", T, Str, 1),
    var("$NT_TRAFO_TYPE", T, Str, 1),
    var("$NT_TRAFO_INDEX", T, Int, 1),
    var("$NT_T_CHAIN_FIRST_ELEM", T, Str, 1),
    var("$NT_T_CHAIN_LAST_ELEM", T, Str, 1),
    var("$NT_P_CHAIN_FIRST_ELEM", T, Str, 1),
    var("$NT_P_CHAIN_LAST_ELEM", T, Str, 1),
    var("$NT_T_REF_ELEM", T, Str, 1),
    var("$NT_GEO_AX_NAME", T, Str, 3),
    var("$NT_ROT_AX_NAME", T, Str, 3),
    var("$NT_ROT_AX_OFFSET", T, Real, 3),
    var("$NT_TRAFO_INCLUDES_TOOL", T, Int, 1),
    var("$NT_BASE_ORIENT", T, Real, 3),
    var("$NT_BASE_ORIENT_NORMAL", T, Real, 3),
    var("$NT_CNTRL", T, Int, 1),
    var("$NT_ROT_OFFSET_FROM_FRAME", T, Int, 1),
    var("$NT_CLOSE_CHAIN_P", T, Str, 1),
    var("$NT_CLOSE_CHAIN_T", T, Str, 1),
    var("$NT_AUX_POS", T, Real, 3),
    var("$NT_IDENT", T, Int, 3),
    var("$NT_BASE_TOOL_COMP", T, Int, 1),
    var("$NT_ROT_AX_POS", T, Real, 3),
    var("$NT_POLE_LIMIT", T, Real, 1),
    var("$NT_POLE_TOL", T, Real, 1),
    var("$NT_IGNORE_TOOL_ORIENT", T, Int, 1),
    var("$NT_CORR_ELEM_T", T, Str, 4),
    var("$NT_CORR_ELEM_P", T, Str, 4),
    var("$NT_POLE_SIDE_FIX", T, Int, 1),
    // TRACON_K: the member transformations in BCS → MCS order (stored only; four entries like
    // MD24995 TRACON_CHAIN is this product's choice, the seed gives no count).
    var("$NT_TRACON_CHAIN", T, Str, 4),
];

fn default(var: &Var, k: usize) -> Value {
    match (var.name, var.kind) {
        ("$NT_BASE_ORIENT", _) => Value::Real(if k == 2 { 1.0 } else { 0.0 }),
        ("$NT_BASE_ORIENT_NORMAL", _) => Value::Real(if k == 1 { 1.0 } else { 0.0 }),
        // As MD24130 TRAFO_INCLUDES_TOOL_n in this product (the manual gives no default).
        ("$NT_TRAFO_INCLUDES_TOOL", _) => Value::Int(1),
        (_, Str) => Value::Str(String::new()),
        (_, Real) => Value::Real(0.0),
        (_, Int) => Value::Int(0),
    }
}

/// True for a name this module stores.
pub fn is_chain_name(name: &str) -> bool {
    name.starts_with("$NK_") || name.starts_with("$NT_")
}

/// The stored `$NK_`/`$NT_` data: only values that differ from the defaults, keyed by family,
/// record index, variable (position in the table) and component.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct KinData {
    values: BTreeMap<(Family, usize, usize, usize), Value>,
}

impl KinData {
    /// Assigns one line of NC data text; `counts` are MD18880 and MD18866.
    pub(super) fn assign(
        &mut self,
        line: u32,
        name: &str,
        indices: &[IndexTok],
        value: &Literal,
        counts: (usize, usize),
    ) -> Result<(), MdError> {
        let err = |m: String| MdError::at(line, m);
        let Some(pos) = VARS.iter().position(|v| v.name == name) else {
            let known: Vec<&str> = VARS.iter().map(|v| v.name).collect();
            return Err(err(format!("unknown name {name} (kinematic chain data: {})", known.join(", "))));
        };
        let v = &VARS[pos];
        let (count, datum) = match v.family {
            Family::Element => (counts.0, "$MN_MM_MAXNUM_KIN_CHAIN_ELEM"),
            Family::Trafo => (counts.1, "$MN_MM_NUM_KIN_TRAFOS"),
        };
        let (i, k) = match (indices, v.len) {
            ([IndexTok::Number(i)], 1) => (*i, 0),
            ([IndexTok::Number(i), IndexTok::Number(k)], len) if len > 1 => {
                if !(0..len as i64).contains(k) {
                    return Err(err(format!("{name}[{i},{k}]: component {k} out of range 0..{}", len - 1)));
                }
                (*i, *k as usize)
            }
            (_, 1) => return Err(err(format!("{name} needs one index, e.g. {name}[0]"))),
            _ => return Err(err(format!("{name} needs two indices, e.g. {name}[0,0]"))),
        };
        if !(0..count as i64).contains(&i) {
            return Err(err(format!("{name}[{i}]: index out of range 0..{} ({datum})", count as i64 - 1)));
        }
        let value = match (v.kind, value) {
            (Str, Literal::Str(s) | Literal::Ident(s)) if s.chars().count() <= MAX_NAME => Value::Str(s.clone()),
            (Str, Literal::Str(_) | Literal::Ident(_)) => {
                return Err(err(format!("{name}: string longer than {MAX_NAME} characters")));
            }
            (Real, Literal::Number(n)) => Value::Real(*n),
            (Int, Literal::Number(n)) if n.fract() == 0.0 => Value::Int(*n as i64),
            (Int, Literal::Bool(b)) => Value::Int(i64::from(*b)),
            (Str, _) => return Err(err(format!("{name}: expected a string in double quotes"))),
            (Real, _) => return Err(err(format!("{name}: expected a number"))),
            (Int, _) => return Err(err(format!("{name}: expected an integer"))),
        };
        let key = (v.family, i as usize, pos, k);
        if value == default(v, k) {
            self.values.remove(&key);
        } else {
            self.values.insert(key, value);
        }
        Ok(())
    }

    /// The value of `name[indices]` as a program reads it (`R1=$NK_OFF_DIR[3,2]`): the stored
    /// value or the default. `counts` are MD18880 and MD18866, which bound the first index.
    pub fn read(&self, name: &str, indices: &[i64], counts: (usize, usize)) -> Result<Value, String> {
        let pos =
            VARS.iter().position(|v| v.name == name).ok_or_else(|| format!("{name} is no kinematic chain datum"))?;
        let v = &VARS[pos];
        let count = match v.family {
            Family::Element => counts.0,
            Family::Trafo => counts.1,
        };
        let (i, k) = match (indices, v.len) {
            ([i], 1) => (*i, 0),
            ([i, k], len) if len > 1 && (0..len as i64).contains(k) => (*i, *k as usize),
            ([_, k], len) if len > 1 => return Err(format!("{name}: component {k} out of range 0..{}", len - 1)),
            (_, 1) => return Err(format!("{name} needs one index")),
            _ => return Err(format!("{name} needs two indices")),
        };
        if !(0..count as i64).contains(&i) {
            return Err(format!("{name}[{i}]: index out of range 0..{}", count as i64 - 1));
        }
        Ok(self.values.get(&(v.family, i as usize, pos, k)).cloned().unwrap_or_else(|| default(v, k)))
    }

    /// The stored data as NC data text, record by record.
    pub(super) fn to_text(&self) -> String {
        let mut out = String::new();
        for ((_, i, pos, k), value) in &self.values {
            let v = &VARS[*pos];
            let index = if v.len == 1 { format!("[{i}]") } else { format!("[{i},{k}]") };
            let value = match value {
                Value::Str(s) => format!("\"{s}\""),
                Value::Real(r) => format!("{r:?}"),
                Value::Int(n) => n.to_string(),
                Value::Bool(b) => u8::from(*b).to_string(),
            };
            out += &format!("{}{index}={value}\n", v.name);
        }
        out
    }

    /// Deletes every record of a family (`DELOBJ("KIN_CHAIN_ELEM")` / `DELOBJ("TRAFO_DATA")`).
    pub fn clear_elements(&mut self) {
        self.values.retain(|k, _| k.0 != Family::Element);
    }

    pub fn clear_trafos(&mut self) {
        self.values.retain(|k, _| k.0 != Family::Trafo);
    }

    /// Sets `$NK_OFF_DIR[record, 0..2]` (what CORRTRAFO writes).
    pub fn set_off_dir(&mut self, record: usize, v: [f64; 3]) {
        let pos = VARS.iter().position(|v| v.name == "$NK_OFF_DIR").expect("a known variable");
        for (k, x) in v.iter().enumerate() {
            let key = (Family::Element, record, pos, k);
            if *x == 0.0 {
                self.values.remove(&key);
            } else {
                self.values.insert(key, Value::Real(*x));
            }
        }
    }

    fn get(&self, family: Family, i: usize, name: &str, k: usize) -> Value {
        let pos = VARS.iter().position(|v| v.name == name).expect("a known variable");
        self.values.get(&(family, i, pos, k)).cloned().unwrap_or_else(|| default(&VARS[pos], k))
    }

    fn str(&self, family: Family, i: usize, name: &str, k: usize) -> String {
        match self.get(family, i, name, k) {
            Value::Str(s) => s,
            _ => String::new(),
        }
    }

    fn num(&self, family: Family, i: usize, name: &str, k: usize) -> f64 {
        self.get(family, i, name, k).as_f64().unwrap_or(0.0)
    }

    fn vec3(&self, family: Family, i: usize, name: &str) -> Vec3 {
        std::array::from_fn(|k| self.num(family, i, name, k))
    }

    /// Record indices of a family that hold any data.
    fn records(&self, family: Family) -> BTreeSet<usize> {
        self.values.keys().filter(|k| k.0 == family).map(|k| k.1).collect()
    }
}

type Vec3 = [f64; 3];
type Mat = [[f64; 3]; 3];

const IDENTITY: Mat = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

fn mat_vec(m: &Mat, v: &Vec3) -> Vec3 {
    std::array::from_fn(|r| m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2])
}

fn mat_mul(a: &Mat, b: &Mat) -> Mat {
    std::array::from_fn(|r| std::array::from_fn(|c| (0..3).map(|j| a[r][j] * b[j][c]).sum()))
}

/// Rotation by `deg` degrees about unit axis `u` (right-handed).
fn rotation(u: &Vec3, deg: f64) -> Mat {
    let (s, c) = deg.to_radians().sin_cos();
    let t = 1.0 - c;
    let [x, y, z] = *u;
    [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
    ]
}

fn unit(v: &Vec3) -> Option<Vec3> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (n > 1e-9).then(|| v.map(|x| x / n))
}

fn sub(a: &Vec3, b: &Vec3) -> Vec3 {
    std::array::from_fn(|i| a[i] - b[i])
}

/// The element types of `$NK_TYPE`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElemType {
    Offset,
    AxisLin,
    AxisRot,
    RotConst,
}

impl ElemType {
    fn parse(s: &str) -> Option<ElemType> {
        match s.to_ascii_uppercase().as_str() {
            "OFFSET" => Some(ElemType::Offset),
            "AXIS_LIN" => Some(ElemType::AxisLin),
            "AXIS_ROT" => Some(ElemType::AxisRot),
            "ROT_CONST" => Some(ElemType::RotConst),
            _ => None,
        }
    }
}

/// One checked chain element.
#[derive(Debug, Clone)]
struct Elem {
    /// The `$NK_…[i]` record index.
    record: usize,
    name: String,
    ty: ElemType,
    /// Offset vector (OFFSET) or unit direction (axes, constant rotations).
    dir: Vec3,
    /// Channel axis of an axis element.
    axis: Option<usize>,
    a_off: f64,
    /// Parent element and whether this one is its `$NK_NEXT` (else its `$NK_PARALLEL`).
    parent: Option<(usize, bool)>,
}

fn general(message: String) -> ActivationError {
    ActivationError { datum: None, message }
}

/// The checked element graph: a tree below the root.
struct Graph {
    elems: Vec<Elem>,
    root: Option<usize>,
}

impl Graph {
    fn find(&self, name: &str) -> Option<usize> {
        self.elems.iter().position(|e| e.name == name)
    }

    /// The way from the root to `last`, root first.
    fn path_to(&self, last: usize) -> Result<Vec<usize>, ActivationError> {
        let mut path = vec![last];
        let mut at = last;
        while let Some((p, _)) = self.elems[at].parent {
            path.push(p);
            at = p;
        }
        if Some(at) != self.root {
            return Err(general(format!(
                "kinematic chain: element \"{}\" is not connected to the root element",
                self.elems[last].name
            )));
        }
        path.reverse();
        Ok(path)
    }
}

fn build_graph(
    kin: &KinData,
    root_name: &str,
    channel_axes: &[ChannelAxis],
    machine_axes: &[MachineAxis],
) -> Result<Graph, ActivationError> {
    let f = Family::Element;
    let mut elems = Vec::new();
    for i in kin.records(f) {
        let name = kin.str(f, i, "$NK_NAME", 0);
        let at = |m: String| general(format!("$NK_…[{i}] \"{name}\": {m}"));
        if name.is_empty() {
            return Err(general(format!("$NK_…[{i}]: element {i} has data but no $NK_NAME")));
        }
        if elems.iter().any(|(_, e): &(usize, Elem)| e.name == name) {
            return Err(at("two elements have this name".into()));
        }
        let ty_text = kin.str(f, i, "$NK_TYPE", 0);
        let ty = ElemType::parse(&ty_text).ok_or_else(|| {
            at(format!("$NK_TYPE \"{ty_text}\" is not an element type (OFFSET, AXIS_LIN, AXIS_ROT, ROT_CONST)"))
        })?;
        let raw = kin.vec3(f, i, "$NK_OFF_DIR");
        let dir = match ty {
            ElemType::Offset => raw,
            _ => {
                unit(&raw).ok_or_else(|| at("$NK_OFF_DIR, the direction of the element, is the zero vector".into()))?
            }
        };
        let axis_name = kin.str(f, i, "$NK_AXIS", 0);
        let axis = match ty {
            ElemType::AxisLin | ElemType::AxisRot => {
                if axis_name.is_empty() {
                    return Err(at("an axis element needs $NK_AXIS".into()));
                }
                let k = channel_axes
                    .iter()
                    .position(|c| machine_axes[c.machine_axis].name.eq_ignore_ascii_case(&axis_name))
                    .or_else(|| channel_axes.iter().position(|c| c.name.eq_ignore_ascii_case(&axis_name)))
                    .ok_or_else(|| {
                        at(format!("$NK_AXIS \"{axis_name}\" is no machine or channel axis of this channel"))
                    })?;
                let rotary = machine_axes[channel_axes[k].machine_axis].rotary;
                if rotary != (ty == ElemType::AxisRot) {
                    return Err(at(format!(
                        "$NK_AXIS \"{axis_name}\" is a {} axis, the element type {ty_text}",
                        if rotary { "rotary" } else { "linear" }
                    )));
                }
                Some(k)
            }
            _ => None,
        };
        elems.push((i, Elem { record: i, name, ty, dir, axis, a_off: kin.num(f, i, "$NK_A_OFF", 0), parent: None }));
    }
    // Links: every element follows at most one other (the chains form a tree).
    let names: Vec<String> = elems.iter().map(|(_, e)| e.name.clone()).collect();
    let mut links = Vec::new();
    for (pos, (i, e)) in elems.iter().enumerate() {
        for (var, next) in [("$NK_NEXT", true), ("$NK_PARALLEL", false)] {
            let target = kin.str(f, *i, var, 0);
            if target.is_empty() {
                continue;
            }
            let t = names.iter().position(|n| *n == target).ok_or_else(|| {
                general(format!("$NK_…[{i}] \"{}\": {var} names \"{target}\", which is no element", e.name))
            })?;
            links.push((pos, t, next));
        }
    }
    let mut elems: Vec<Elem> = elems.into_iter().map(|(_, e)| e).collect();
    for (from, to, next) in links {
        if let Some((other, _)) = elems[to].parent {
            return Err(general(format!(
                "kinematic chain: element \"{}\" follows both \"{}\" and \"{}\" (each element has one predecessor)",
                elems[to].name, elems[other].name, elems[from].name
            )));
        }
        elems[to].parent = Some((from, next));
    }
    let root = elems.iter().position(|e| e.name == root_name);
    if let Some(r) = root
        && let Some((p, _)) = elems[r].parent
    {
        return Err(general(format!(
            "kinematic chain: the root element \"{root_name}\" cannot follow \"{}\"",
            elems[p].name
        )));
    }
    // Cycles: with one parent each, a walk up that takes more steps than there are elements
    // runs round a cycle.
    for start in 0..elems.len() {
        let mut at = start;
        let mut steps = 0;
        while let Some((p, _)) = elems[at].parent {
            at = p;
            steps += 1;
            if at == start || steps > elems.len() {
                return Err(general(format!(
                    "kinematic chain: element \"{}\" lies on a cycle of $NK_NEXT/$NK_PARALLEL",
                    elems[start].name
                )));
            }
        }
    }
    if root.is_none() && !elems.is_empty() {
        return Err(general(format!(
            "kinematic chain: no element is named \"{root_name}\" (the root element, $MN_ROOT_KIN_ELEM_NAME)"
        )));
    }
    Ok(Graph { elems, root })
}

/// An axis on a subchain at the kinematic zero, in the world frame.
#[derive(Debug, Clone, Copy)]
struct AxisAt {
    elem: usize,
    rotary: bool,
    /// Frame origin where the axis acts (rotary: a point of the axis).
    point: Vec3,
    dir: Vec3,
}

/// A subchain walked at the kinematic zero: its axes in order from the root and its end frame.
struct Walk {
    axes: Vec<AxisAt>,
    end: Vec3,
    rot: Mat,
}

fn walk(g: &Graph, what: &str, first: &str, last: &str) -> Result<Walk, ActivationError> {
    if last.is_empty() {
        return Ok(Walk { axes: Vec::new(), end: [0.0; 3], rot: IDENTITY });
    }
    let find = |var: &str, name: &str| {
        g.find(name).ok_or_else(|| general(format!("{what}: {var} \"{name}\" is no element of the kinematic chain")))
    };
    let last_i = find("LAST_ELEM", last)?;
    let path = g.path_to(last_i)?;
    let first_i = if first.is_empty() { path[0] } else { find("FIRST_ELEM", first)? };
    let start = path.iter().position(|&e| e == first_i).ok_or_else(|| {
        general(format!("{what}: FIRST_ELEM \"{first}\" does not lie on the way from the root to \"{last}\""))
    })?;
    let (mut rot, mut origin) = (IDENTITY, [0.0; 3]);
    let mut axes = Vec::new();
    for (n, &e) in path.iter().enumerate() {
        // An element acts on the way unless the way leaves it to its parallel branch.
        let applies = n + 1 == path.len() || g.elems[path[n + 1]].parent == Some((e, true));
        if !applies {
            continue;
        }
        let el = &g.elems[e];
        if n < start && matches!(el.ty, ElemType::AxisLin | ElemType::AxisRot) {
            return Err(general(format!(
                "{what}: axis element \"{}\" lies between the root and FIRST_ELEM \"{first}\"",
                el.name
            )));
        }
        let d = mat_vec(&rot, &el.dir);
        match el.ty {
            ElemType::Offset => origin = std::array::from_fn(|i| origin[i] + d[i]),
            ElemType::AxisLin => {
                axes.push(AxisAt { elem: e, rotary: false, point: origin, dir: d });
                origin = std::array::from_fn(|i| origin[i] + d[i] * el.a_off);
            }
            ElemType::AxisRot => axes.push(AxisAt { elem: e, rotary: true, point: origin, dir: d }),
            ElemType::RotConst => rot = mat_mul(&rot, &rotation(&el.dir, el.a_off)),
        }
    }
    Ok(Walk { axes, end: origin, rot })
}

fn is_identity(m: &Mat) -> bool {
    (0..3).all(|r| (0..3).all(|c| (m[r][c] - IDENTITY[r][c]).abs() < 1e-9))
}

/// The geometry axis (0..2) of a linear axis along `sign`·e_g, if it is one.
fn along(dir: &Vec3, sign: f64) -> Option<usize> {
    (0..3).find(|&g| (0..3).all(|i| (dir[i] - if i == g { sign } else { 0.0 }).abs() < 1e-9))
}

/// The transformation types of `$NT_TRAFO_TYPE` the manual lists; TRAORI_DYN, TRANSMIT_K,
/// TRACYL_K and TRAANG_K are built.
const KNOWN_TYPES: &[&str] = &["TRAORI_DYN", "TRAORI_STAT", "TRANSMIT_K", "TRACYL_K", "TRAANG_K", "TRACON_K", "TRAANG"];

/// Checks the element graph and builds every TRAORI_DYN, TRANSMIT_K, TRACYL_K and TRAANG_K
/// record into a data set numbered [`KIN_TRAFO_NUMBER_BASE`] + n. Records of the other listed
/// types are checked and stay stored but are not built (not modelled); `pole` are the pole
/// limits the orientation sets use unless `$NT_POLE_TOL` / `$NT_POLE_LIMIT` give them.
pub(super) fn build(
    md: &MachineData,
    channel_axes: &[ChannelAxis],
    machine_axes: &[MachineAxis],
    pole: (f64, f64),
) -> Result<Vec<TrafoDataSet>, ActivationError> {
    let kin = &md.kin;
    let root_name = md.string("$MN_ROOT_KIN_ELEM_NAME", 0);
    let g = build_graph(kin, &root_name, channel_axes, machine_axes)?;
    let f = Family::Trafo;
    let mut sets: Vec<TrafoDataSet> = Vec::new();
    let mut names: Vec<String> = Vec::new();
    for n in kin.records(f) {
        let name = kin.str(f, n, "$NT_NAME", 0);
        if name.is_empty() {
            return Err(general(format!("$NT_…[{n}]: transformation {n} has data but no $NT_NAME")));
        }
        let what = format!("$NT_…[{n}] \"{name}\"");
        if names.contains(&name) {
            return Err(general(format!("{what}: two transformations have this name")));
        }
        names.push(name.clone());
        let ty = kin.str(f, n, "$NT_TRAFO_TYPE", 0).to_ascii_uppercase();
        if !KNOWN_TYPES.contains(&ty.as_str()) {
            return Err(general(format!(
                "{what}: $NT_TRAFO_TYPE \"{ty}\" is not a transformation type ({})",
                KNOWN_TYPES.join(", ")
            )));
        }
        check_common(kin, &g, n, &what)?;
        let set = match ty.as_str() {
            "TRAORI_DYN" => traori_dyn(kin, &g, n, &what, name, pole)?,
            "TRANSMIT_K" => classic::rotary(kin, &g, n, &what, name, TrafoKind::Transmit)?,
            "TRACYL_K" => classic::rotary(kin, &g, n, &what, name, TrafoKind::Tracyl)?,
            "TRAANG_K" => classic::inclined(kin, &g, n, &what, name)?,
            // TRAORI_STAT: its subchains and axis names are checked, the static transformation
            // itself is not modelled. TRACON_K and the OA type TRAANG stay stored, not built.
            "TRAORI_STAT" => {
                check_static(kin, &g, n, &what)?;
                continue;
            }
            _ => continue,
        };
        sets.push(set);
    }
    Ok(sets)
}

/// What building a chain record needs besides the chain data: the root element's name
/// (MD16800) and the pole limits of MD24530/MD24540 that apply unless the record sets its own.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BuildContext {
    pub root: String,
    pub pole: (f64, f64),
}

/// Builds TRAORI_DYN record `n` of `kin` alone (the data set CORRTRAFO corrects), exactly as
/// activation builds it.
pub fn rebuild_traori(
    kin: &KinData,
    ctx: &BuildContext,
    channel_axes: &[ChannelAxis],
    machine_axes: &[MachineAxis],
    n: usize,
) -> Result<TrafoDataSet, ActivationError> {
    let g = build_graph(kin, &ctx.root, channel_axes, machine_axes)?;
    let name = kin.str(Family::Trafo, n, "$NT_NAME", 0);
    let what = format!("$NT_…[{n}] \"{name}\"");
    if !kin.str(Family::Trafo, n, "$NT_TRAFO_TYPE", 0).eq_ignore_ascii_case("TRAORI_DYN") {
        return Err(general(format!("{what}: not a TRAORI_DYN record")));
    }
    check_common(kin, &g, n, &what)?;
    traori_dyn(kin, &g, n, &what, name, ctx.pole)
}

/// `$NT_ROT_AX_CNT[n, k]` (read only): the rotary axis elements on the workpiece (k = 0) or the
/// tool (k = 1) subchain of record `n`; 0 where the chain cannot be walked.
pub fn rot_ax_cnt(
    kin: &KinData,
    ctx: &BuildContext,
    channel_axes: &[ChannelAxis],
    machine_axes: &[MachineAxis],
    n: usize,
    k: usize,
) -> usize {
    let Ok(g) = build_graph(kin, &ctx.root, channel_axes, machine_axes) else { return 0 };
    let f = Family::Trafo;
    let (first, last) = if k == 0 {
        ("$NT_P_CHAIN_FIRST_ELEM", "$NT_P_CHAIN_LAST_ELEM")
    } else {
        ("$NT_T_CHAIN_FIRST_ELEM", "$NT_T_CHAIN_LAST_ELEM")
    };
    walk(&g, "", &kin.str(f, n, first, 0), &kin.str(f, n, last, 0))
        .map_or(0, |w| w.axes.iter().filter(|a| a.rotary).count())
}

/// The `$NT_TRAFO_TYPE` of the record named `name`, if one is.
pub fn type_of(kin: &KinData, name: &str) -> Option<String> {
    let f = Family::Trafo;
    kin.records(f)
        .into_iter()
        .find(|&n| kin.str(f, n, "$NT_NAME", 0) == name)
        .map(|n| kin.str(f, n, "$NT_TRAFO_TYPE", 0).to_ascii_uppercase())
}

fn traori_dyn(
    kin: &KinData,
    g: &Graph,
    n: usize,
    what: &str,
    name: String,
    pole: (f64, f64),
) -> Result<TrafoDataSet, ActivationError> {
    let f = Family::Trafo;
    let s = |var: &str| kin.str(f, n, var, 0);
    let fail = |m: String| Err(general(format!("{what}: {m}")));
    let tool_last = s("$NT_T_CHAIN_LAST_ELEM");
    if tool_last.is_empty() {
        return fail("$NT_T_CHAIN_LAST_ELEM must name the end of the tool chain".into());
    }
    let tool = walk(g, &format!("{what} tool chain"), &s("$NT_T_CHAIN_FIRST_ELEM"), &tool_last)?;
    let part = walk(g, &format!("{what} workpiece chain"), &s("$NT_P_CHAIN_FIRST_ELEM"), &s("$NT_P_CHAIN_LAST_ELEM"))?;
    let t_ref = s("$NT_T_REF_ELEM");
    if !t_ref.is_empty() && t_ref != tool_last {
        return fail(format!(
            "$NT_T_REF_ELEM \"{t_ref}\": a tool reference position other than the end of the tool chain is not modelled"
        ));
    }
    if !is_identity(&tool.rot) || !is_identity(&part.rot) {
        return fail(
            "the constant rotations (ROT_CONST) of a subchain must cancel by its end: the tool and the workpiece \
             frames are not rotated against the world frame at the kinematic zero"
                .into(),
        );
    }
    let elem_name = |e: usize| g.elems[e].name.as_str();
    if let Some(a) = tool.axes.iter().find(|a| part.axes.iter().any(|b| b.elem == a.elem)) {
        return fail(format!("axis element \"{}\" lies on both the tool and the workpiece chain", elem_name(a.elem)));
    }
    // Linear axes before the rotary axes of their subchain, along ±X/±Y/±Z.
    let mut lin: [Option<usize>; 3] = [None; 3];
    let mut lin_elem: [Option<usize>; 3] = [None; 3];
    for (chain, sign) in [(&tool, 1.0), (&part, -1.0)] {
        let mut seen_rotary = None;
        for a in &chain.axes {
            if a.rotary {
                seen_rotary = Some(a.elem);
                continue;
            }
            if let Some(r) = seen_rotary {
                return fail(format!(
                    "linear axis element \"{}\" follows rotary axis element \"{}\": TRAORI_DYN needs the linear axes nearer the root",
                    elem_name(a.elem),
                    elem_name(r)
                ));
            }
            let Some(gx) = along(&a.dir, sign) else {
                return fail(format!(
                    "linear axis element \"{}\" must point along {}X, {}Y or {}Z in the world frame",
                    elem_name(a.elem),
                    if sign > 0.0 { "+" } else { "−" },
                    if sign > 0.0 { "+" } else { "−" },
                    if sign > 0.0 { "+" } else { "−" }
                ));
            };
            if let Some(other) = lin_elem[gx] {
                return fail(format!(
                    "linear axis elements \"{}\" and \"{}\" both move along geometry axis {gx}",
                    elem_name(other),
                    elem_name(a.elem)
                ));
            }
            lin[gx] = g.elems[a.elem].axis;
            lin_elem[gx] = Some(a.elem);
        }
    }
    for (gx, e) in lin_elem.iter().enumerate() {
        let named = kin.str(f, n, "$NT_GEO_AX_NAME", gx);
        match e {
            Some(e) if named != g.elems[*e].name => {
                return fail(format!(
                    "$NT_GEO_AX_NAME[{n},{gx}] must name the linear axis element \"{}\" (found \"{named}\")",
                    g.elems[*e].name
                ));
            }
            None if !named.is_empty() => {
                return fail(format!(
                    "$NT_GEO_AX_NAME[{n},{gx}] \"{named}\" is no linear axis along geometry axis {gx} on the chains"
                ));
            }
            _ => {}
        }
    }
    if lin.iter().flatten().count() < 2 {
        return fail("TRAORI_DYN needs at least two linear axis elements on the chains".into());
    }
    let t_rot: Vec<AxisAt> = tool.axes.iter().filter(|a| a.rotary).copied().collect();
    let p_rot: Vec<AxisAt> = part.axes.iter().filter(|a| a.rotary).copied().collect();
    let (machine, order): (OriMachine, Vec<AxisAt>) = match (t_rot.len(), p_rot.len()) {
        (1..=3, 0) => (OriMachine::Tool, t_rot.clone()),
        (0, 1..=2) => (OriMachine::Part, p_rot.clone()),
        (1, 1) => (OriMachine::Mixed, vec![t_rot[0], p_rot[0]]),
        (t, p) => {
            return fail(format!(
                "{t} rotary axis element(s) on the tool chain and {p} on the workpiece chain: TRAORI_DYN models 1..3 on the tool, 1..2 on the workpiece or one on each"
            ));
        }
    };
    // $NT_ROT_AX_NAME lists the orientation axes without gaps, in the order of the kinematics.
    for (k, a) in order.iter().enumerate() {
        let named = kin.str(f, n, "$NT_ROT_AX_NAME", k);
        if named != g.elems[a.elem].name {
            return fail(format!(
                "$NT_ROT_AX_NAME[{n},{k}] must name rotary axis element \"{}\" (found \"{named}\"): the axes are listed from the root of the tool chain, then of the workpiece chain",
                g.elems[a.elem].name
            ));
        }
    }
    for k in order.len()..3 {
        let named = kin.str(f, n, "$NT_ROT_AX_NAME", k);
        if !named.is_empty() {
            return fail(format!(
                "$NT_ROT_AX_NAME[{n},{k}] \"{named}\" is no further rotary axis element on the chains"
            ));
        }
    }
    let zero = [0.0; 3];
    let (x_t, x_p) = (tool.end, part.end);
    let p = |i: usize| order[i].point;
    // Offsets of the vector chain (see the module documentation and `traori`'s mapping).
    let (part_offset, joint_offset, base_tool, joint_offset_part, joint_offset_2_3) = match machine {
        OriMachine::Tool => match order.len() {
            1 => (sub(&p(0), &x_p), sub(&x_t, &p(0)), zero, zero, zero),
            2 => (sub(&p(0), &x_p), sub(&p(1), &p(0)), sub(&x_t, &p(1)), zero, zero),
            _ => (sub(&p(0), &x_p), sub(&p(1), &p(0)), sub(&x_t, &p(2)), zero, sub(&p(2), &p(1))),
        },
        OriMachine::Part => match order.len() {
            1 => (sub(&x_p, &p(0)), zero, sub(&p(0), &x_t), zero, zero),
            _ => (sub(&x_p, &p(1)), sub(&p(1), &p(0)), sub(&p(0), &x_t), zero, zero),
        },
        OriMachine::Mixed => (sub(&x_p, &p(1)), p(0), sub(&x_t, &p(0)), p(1), zero),
    };
    let mut axis = [[0.0; 3]; 3];
    let mut rot_offset = [0.0; 3];
    let mut axes_in = [lin[0], lin[1], lin[2], None, None, None, None];
    for (k, a) in order.iter().enumerate() {
        axis[k] = a.dir;
        rot_offset[k] = kin.num(f, n, "$NT_ROT_AX_OFFSET", k) - g.elems[a.elem].a_off;
        axes_in[3 + k] = g.elems[a.elem].axis;
    }
    let used: Vec<usize> = axes_in.iter().flatten().copied().collect();
    if (1..used.len()).any(|i| used[..i].contains(&used[i])) {
        return fail("two axis elements follow the same channel axis".into());
    }
    let base_orient = unit(&kin.vec3(f, n, "$NT_BASE_ORIENT"))
        .ok_or_else(|| general(format!("{what}: $NT_BASE_ORIENT is the zero vector")))?;
    let trafo_type = match machine {
        OriMachine::Tool => 24,
        OriMachine::Part => 40,
        OriMachine::Mixed => 56,
    };
    let index = kin.num(f, n, "$NT_TRAFO_INDEX", 0) as i64;
    let conventional = usize::try_from(index / 10 % 100).ok().filter(|c| *c > 0);
    Ok(TrafoDataSet {
        number: KIN_TRAFO_NUMBER_BASE + n,
        trafo_type,
        kind: TrafoKind::Traori,
        kind_index: 0,
        axes_in,
        geo_axes: lin,
        includes_tool: kin.num(f, n, "$NT_TRAFO_INCLUDES_TOOL", 0) != 0.0,
        params: TrafoParams::Traori(Box::new(TraoriParams {
            machine,
            generic: true,
            axis,
            base_orient,
            base_orient_normal: unit(&kin.vec3(f, n, "$NT_BASE_ORIENT_NORMAL")).unwrap_or([0.0, 1.0, 0.0]),
            part_offset,
            base_tool,
            joint_offset,
            joint_offset_part,
            joint_offset_2_3,
            tool_rot_ax_offset: zero,
            rot_offset,
            sign_plus: [true; 3],
            non_pole_limit: positive_or(kin.num(f, n, "$NT_POLE_TOL", 0), pole.0),
            pole_limit: positive_or(kin.num(f, n, "$NT_POLE_LIMIT", 0), pole.1),
            nutator_angle: 0.0,
            oriax_assign: [None; 3],
            ext_axis: [0.0, 0.0, 1.0],
            ext_offset: 0.0,
        })),
        chain: Some(ChainDef { name, conventional }),
    })
}

/// `value` if set (> 0), else the machine-data default.
fn positive_or(value: f64, default: f64) -> f64 {
    if value > 0.0 { value } else { default }
}

/// Checks the `$NT_` data every type shares: value ranges and element names that must lie on
/// the subchains (`$NT_CLOSE_CHAIN_P/T`, `$NT_CORR_ELEM_P/T`).
fn check_common(kin: &KinData, g: &Graph, n: usize, what: &str) -> Result<(), ActivationError> {
    let f = Family::Trafo;
    let fail = |m: String| Err(general(format!("{what}: {m}")));
    for (var, max) in [("$NT_ROT_OFFSET_FROM_FRAME", 2), ("$NT_POLE_SIDE_FIX", 2), ("$NT_BASE_TOOL_COMP", 7)] {
        let v = kin.num(f, n, var, 0);
        if !(0.0..=f64::from(max)).contains(&v) {
            return fail(format!("{var}[{n}]={v}: allowed are 0..{max}"));
        }
    }
    let v = kin.num(f, n, "$NT_IGNORE_TOOL_ORIENT", 0);
    if v != 0.0 && v != 1.0 {
        return fail(format!("$NT_IGNORE_TOOL_ORIENT[{n}]={v}: FALSE or TRUE"));
    }
    for var in ["$NT_POLE_LIMIT", "$NT_POLE_TOL"] {
        let v = kin.num(f, n, var, 0);
        if !(0.0..=180.0).contains(&v) {
            return fail(format!("{var}[{n}]={v}: an angle 0..180 degrees"));
        }
    }
    // The subchain a name must lie on: the way from the root to the chain's last element.
    let on_chain = |last_var: &str, name: &str| -> bool {
        let last = kin.str(f, n, last_var, 0);
        match (g.find(&last), g.find(name)) {
            (Some(l), Some(e)) => g.path_to(l).is_ok_and(|p| p.contains(&e)),
            _ => false,
        }
    };
    for (var, last, k) in
        [("$NT_CLOSE_CHAIN_P", "$NT_P_CHAIN_LAST_ELEM", 1), ("$NT_CLOSE_CHAIN_T", "$NT_T_CHAIN_LAST_ELEM", 1)]
            .into_iter()
            .chain([("$NT_CORR_ELEM_P", "$NT_P_CHAIN_LAST_ELEM", 4), ("$NT_CORR_ELEM_T", "$NT_T_CHAIN_LAST_ELEM", 4)])
    {
        for c in 0..k {
            let name = kin.str(f, n, var, c);
            if name.is_empty() {
                continue;
            }
            let at = if k == 1 { format!("{var}[{n}]") } else { format!("{var}[{n},{c}]") };
            if !on_chain(last, &name) {
                return fail(format!("{at} \"{name}\" is no element of the subchain ending at {last}"));
            }
            let corr = k == 4;
            if corr && g.find(&name).is_some_and(|e| g.elems[e].ty != ElemType::Offset) {
                return fail(format!("{at} \"{name}\": a correction element must be of type OFFSET"));
            }
        }
    }
    Ok(())
}

/// TRAORI_STAT (K12 §4.1.7): the subchains must exist and every name in `$NT_GEO_AX_NAME` /
/// `$NT_ROT_AX_NAME` must be an axis element on them, so a record that would fail on a real
/// control fails here too, although the transformation is not built.
fn check_static(kin: &KinData, g: &Graph, n: usize, what: &str) -> Result<(), ActivationError> {
    let f = Family::Trafo;
    let s = |var: &str| kin.str(f, n, var, 0);
    let tool = walk(g, &format!("{what} tool chain"), &s("$NT_T_CHAIN_FIRST_ELEM"), &s("$NT_T_CHAIN_LAST_ELEM"))?;
    let part = walk(g, &format!("{what} workpiece chain"), &s("$NT_P_CHAIN_FIRST_ELEM"), &s("$NT_P_CHAIN_LAST_ELEM"))?;
    for (var, rotary) in [("$NT_GEO_AX_NAME", false), ("$NT_ROT_AX_NAME", true)] {
        for k in 0..3 {
            let named = kin.str(f, n, var, k);
            if named.is_empty() {
                continue;
            }
            let found = tool.axes.iter().chain(&part.axes).find(|a| g.elems[a.elem].name == named);
            if found.is_none_or(|a| a.rotary != rotary) {
                return Err(general(format!(
                    "{what}: {var}[{n},{k}] \"{named}\" is no {} axis element on the tool or the workpiece chain",
                    if rotary { "rotary" } else { "linear" }
                )));
            }
        }
    }
    Ok(())
}

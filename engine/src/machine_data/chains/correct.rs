//! CORRTRAFO (Transformations FM K12 §4.3.2, REFERENCE §9.6): the correction of one offset
//! vector (`$NT_CORR_ELEM_T/P`) or of one orientation axis' direction (`$NT_ROT_AX_NAME`) of a
//! TRAORI_DYN record after a machine measurement, worked out on the chain data alone. The
//! caller writes the result into `$NK_OFF_DIR` and rebuilds the active transformation.
//!
//! Readings of this product where the manual summary is silent:
//! * `Corr_Elem` is the position k of the correction element (`$NT_CORR_ELEM_T/P[n, k]`,
//!   0..3), which is also the section it lies in; for a direction (units digit 1) it is the
//!   orientation axis (`$NT_ROT_AX_NAME[n, k]`, 0..2).
//! * "World coordinates" (tens digit 1) are the world frame at the kinematic zero: the vector is
//!   turned back through the constant rotations (`ROT_CONST`) before the element.
//! * Section k of a subchain runs from its start (section 0) or orientation axis k − 1 to
//!   orientation axis k or the subchain's end (the last section); its vector is the sum of
//!   everything between, at the kinematic zero, in world coordinates.
//! * The limit of an offset correction is the length of the change of the element's vector.

use super::{ActivationError, ChannelAxis, ElemType, Family, Graph, KinData, MachineAxis, Mat, Vec3};
use super::{BuildContext, IDENTITY, build_graph, mat_mul, mat_vec, rotation, sub, unit};

/// The subchain a correction element is taken from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Chain {
    /// `$NT_CORR_ELEM_T`, the tool chain.
    Tool,
    /// `$NT_CORR_ELEM_P`, the workpiece chain.
    Part,
}

/// CORRTRAFO's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Request {
    /// `Corr_Elem`.
    pub elem: i64,
    /// `Corr_Mode`, decimal coded.
    pub mode: i64,
    /// `Corr_Vect`.
    pub vect: Vec3,
    pub chain: Chain,
}

/// SD41610 CORR_TRAFO_LIN_MAX (mm) and SD41611 CORR_TRAFO_DIR_MAX (degrees).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Limits {
    pub lin_max: f64,
    pub dir_max: f64,
}

/// The new `$NK_OFF_DIR` of element record `record`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Correction {
    pub record: usize,
    pub off_dir: Vec3,
}

/// CORRTRAFO's status codes (0 is success). 1..3 and 42/43 are the manual's; the others are
/// this product's numbers for errors the consulted sources name no code for.
pub mod status {
    /// 1: no transformation is active.
    pub const NO_TRAFO: i64 = 1;
    /// 2: the active transformation is no orientation transformation.
    pub const NOT_ORIENTATION: i64 = 2;
    /// 3: the active orientation transformation is not defined by kinematic chains.
    pub const NOT_CHAIN: i64 = 3;
    /// 4: a digit of `Corr_Mode` has no meaning (this product's number).
    pub const BAD_MODE: i64 = 4;
    /// 5: `Corr_Elem` names no correction element / orientation axis (this product's number).
    pub const BAD_ELEM: i64 = 5;
    /// 6: the correction element does not lie in section `Corr_Elem` (this product's number).
    pub const NOT_IN_SECTION: i64 = 6;
    /// 7: the corrected direction is the zero vector or the corrected chain does not build
    /// (this product's number).
    pub const NOT_BUILDABLE: i64 = 7;
    /// 41: an offset changes by more than SD41610 CORR_TRAFO_LIN_MAX (this product's number).
    pub const LIN_LIMIT: i64 = 41;
    /// 42: a direction turns by more than SD41611 CORR_TRAFO_DIR_MAX.
    pub const DIR_LIMIT: i64 = 42;
}

/// The decimal digits of `Corr_Mode`.
#[derive(Debug, Clone, Copy)]
struct Mode {
    direction: bool,
    /// 0 direct, 1 world coordinates, 2 whole section.
    reference: i64,
    incremental: bool,
    monitored: bool,
}

fn decode(mode: i64) -> Option<Mode> {
    let digit = |p: u32| mode / 10i64.pow(p) % 10;
    let valid = (0..10_000).contains(&mode)
        && digit(0) <= 1
        && digit(1) <= 2
        && digit(2) <= 1
        && digit(3) <= 1
        && !(digit(0) == 1 && digit(1) == 2);
    valid.then(|| Mode {
        direction: digit(0) == 1,
        reference: digit(1),
        incremental: digit(2) == 1,
        monitored: digit(3) == 0,
    })
}

/// One element acting on a subchain at the kinematic zero: how its input frame is turned
/// against the world, and the section it lies in.
struct Step {
    elem: usize,
    rot: Mat,
    section: usize,
}

/// A subchain walked at the kinematic zero (like `walk`, keeping every element).
struct Sub {
    steps: Vec<Step>,
    /// Start, orientation axes, end: section k runs from `bounds[k]` to `bounds[k + 1]`.
    bounds: Vec<Vec3>,
}

fn subchain(g: &Graph, first: &str, last: &str) -> Option<Sub> {
    let path = g.path_to(g.find(last)?).ok()?;
    let start = if first.is_empty() { 0 } else { path.iter().position(|&e| g.elems[e].name == first)? };
    let (mut rot, mut origin) = (IDENTITY, [0.0; 3]);
    let (mut steps, mut bounds) = (Vec::new(), Vec::new());
    for (n, &e) in path.iter().enumerate() {
        let applies = n + 1 == path.len() || g.elems[path[n + 1]].parent == Some((e, true));
        if !applies {
            continue;
        }
        if n >= start && bounds.is_empty() {
            bounds.push(origin);
        }
        let el = &g.elems[e];
        if n >= start {
            steps.push(Step { elem: e, rot, section: bounds.len().saturating_sub(1) });
        }
        let d = mat_vec(&rot, &el.dir);
        match el.ty {
            ElemType::Offset => origin = std::array::from_fn(|i| origin[i] + d[i]),
            ElemType::AxisLin => origin = std::array::from_fn(|i| origin[i] + d[i] * el.a_off),
            ElemType::AxisRot if n >= start => bounds.push(origin),
            ElemType::AxisRot => {}
            ElemType::RotConst => rot = mat_mul(&rot, &rotation(&el.dir, el.a_off)),
        }
    }
    if bounds.is_empty() {
        bounds.push(origin);
    }
    bounds.push(origin);
    Some(Sub { steps, bounds })
}

fn transpose(m: &Mat) -> Mat {
    std::array::from_fn(|r| std::array::from_fn(|c| m[c][r]))
}

fn add(a: &Vec3, b: &Vec3) -> Vec3 {
    std::array::from_fn(|i| a[i] + b[i])
}

fn norm(v: &Vec3) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Works out CORRTRAFO `req` on TRAORI_DYN record `n`; `Err` is the status code.
pub fn correct(
    kin: &KinData,
    ctx: &BuildContext,
    channel_axes: &[ChannelAxis],
    machine_axes: &[MachineAxis],
    n: usize,
    req: &Request,
    limits: Limits,
) -> Result<Correction, i64> {
    let mode = decode(req.mode).ok_or(status::BAD_MODE)?;
    let g =
        build_graph(kin, &ctx.root, channel_axes, machine_axes).map_err(|_: ActivationError| status::NOT_BUILDABLE)?;
    let f = Family::Trafo;
    let s = |var: &str, k: usize| kin.str(f, n, var, k);
    let chain_of = |chain: Chain| match chain {
        Chain::Tool => subchain(&g, &s("$NT_T_CHAIN_FIRST_ELEM", 0), &s("$NT_T_CHAIN_LAST_ELEM", 0)),
        Chain::Part => subchain(&g, &s("$NT_P_CHAIN_FIRST_ELEM", 0), &s("$NT_P_CHAIN_LAST_ELEM", 0)),
    };
    let k = usize::try_from(req.elem).map_err(|_| status::BAD_ELEM)?;
    let (name, chains) = if mode.direction {
        (if k < 3 { s("$NT_ROT_AX_NAME", k) } else { String::new() }, vec![Chain::Tool, Chain::Part])
    } else {
        let var = if req.chain == Chain::Tool { "$NT_CORR_ELEM_T" } else { "$NT_CORR_ELEM_P" };
        (if k < 4 { s(var, k) } else { String::new() }, vec![req.chain])
    };
    let e = g.find(&name).filter(|_| !name.is_empty()).ok_or(status::BAD_ELEM)?;
    let wanted = if mode.direction { ElemType::AxisRot } else { ElemType::Offset };
    if g.elems[e].ty != wanted {
        return Err(status::BAD_ELEM);
    }
    let (walked, rot, section) = chains
        .into_iter()
        .filter_map(chain_of)
        .find_map(|c| c.steps.iter().find(|st| st.elem == e).map(|st| (st.rot, st.section)).map(|(r, s)| (c, r, s)))
        .ok_or(status::BAD_ELEM)?;
    let old = if mode.direction {
        unit(&kin.vec3(Family::Element, g.elems[e].record, "$NK_OFF_DIR")).ok_or(status::NOT_BUILDABLE)?
    } else {
        g.elems[e].dir
    };
    let to_world = |v: &Vec3| mat_vec(&rot, v);
    let to_local = |v: &Vec3| mat_vec(&transpose(&rot), v);
    let new = match mode.reference {
        0 if mode.incremental => add(&old, &req.vect),
        0 => req.vect,
        1 if mode.incremental => to_local(&add(&to_world(&old), &req.vect)),
        1 => to_local(&req.vect),
        _ => {
            if section != k || k + 1 >= walked.bounds.len() {
                return Err(status::NOT_IN_SECTION);
            }
            let world_old = to_world(&old);
            let target = if mode.incremental {
                add(&world_old, &req.vect)
            } else {
                // The rest of the section stays: the element takes what the section lacks.
                let section_vec = sub(&walked.bounds[k + 1], &walked.bounds[k]);
                add(&world_old, &sub(&req.vect, &section_vec))
            };
            to_local(&target)
        }
    };
    if mode.direction {
        let u = unit(&new).ok_or(status::NOT_BUILDABLE)?;
        let angle = (u[0] * old[0] + u[1] * old[1] + u[2] * old[2]).clamp(-1.0, 1.0).acos().to_degrees();
        if mode.monitored && angle > limits.dir_max {
            return Err(status::DIR_LIMIT);
        }
    } else if mode.monitored && norm(&sub(&new, &old)) > limits.lin_max {
        return Err(status::LIN_LIMIT);
    }
    Ok(Correction { record: g.elems[e].record, off_dir: new })
}

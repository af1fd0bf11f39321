//! TRANSMIT_K, TRACYL_K and TRAANG_K: the face-end, cylinder-surface and inclined-axis
//! transformations defined by kinematic chains (Transformations FM, K12 §4.1.4–4.1.6), built
//! into the same typed data sets as their machine-data counterparts, so that one implementation
//! in `kinematics` serves both.
//!
//! Axis roles ($NT_…[n, k], the indices of `TRAFO_AXES_IN_n`):
//! * TRANSMIT_K / TRACYL_K: `$NT_GEO_AX_NAME[n,0]` the linear axis perpendicular to the rotary
//!   axis, `[n,1]` the supplementary axis across it (257, 513, 514), `[n,2]` the longitudinal
//!   axis parallel to it; `$NT_ROT_AX_NAME[n,1]` the rotary axis, on the workpiece chain.
//! * TRAANG_K: `$NT_GEO_AX_NAME[n,0]` the inclined infeed axis, `[n,2]` the longitudinal axis,
//!   `[n,1]` an optional axis that passes through.
//!
//! The BCS is not the world frame of the chains (K12 §4.1.4): its Z axis is the longitudinal
//! direction — the effective direction of the longitudinal axis if there is one, else the
//! direction in which the tool turns positively relative to the workpiece (the rotary
//! element's direction reversed: a workpiece axis turns the tool the other way round) — its X
//! axis the effective direction of the radial (TRAANG: inclined axis projected normal to Z),
//! Y = Z × X. An axis element on the workpiece chain moves the tool relative to the workpiece
//! against its direction, so its effective direction is the element's reversed. The BCS origin
//! lies on the rotary axis, level with the workpiece reference point (TRAANG: at it). At the
//! kinematic zero the tool reference point in this frame is the data set's base tool, and the
//! rotary element's zero (`$NK_A_OFF`, `$NT_ROT_AX_OFFSET[n,1]`) is the rotary axis offset.

use super::{ActivationError, AxisAt, Family, Graph, KinData, Vec3, Walk, general, unit, walk};
use crate::machine_data::trafo::{ChainDef, TrafoDataSet, TrafoKind, TrafoParams};

const EPS: f64 = 1e-9;

fn dot(a: &Vec3, b: &Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: &Vec3, b: &Vec3) -> Vec3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn parallel(a: &Vec3, b: &Vec3) -> bool {
    cross(a, b).iter().all(|c| c.abs() < EPS)
}

fn same(a: &Vec3, b: &Vec3) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() < EPS)
}

/// `$NT_CNTRL` bits 16–18: the geometry axis (0..2) of roles 0, 1, 2 for codes 0..5
/// (X Y Z, Z X Y, Y Z X, Z Y X, X Z Y, Y X Z).
fn geo_order(code: i64) -> Option<[usize; 3]> {
    Some(match code {
        0 => [0, 1, 2],
        1 => [2, 0, 1],
        2 => [1, 2, 0],
        3 => [2, 1, 0],
        4 => [0, 2, 1],
        5 => [1, 0, 2],
        _ => return None,
    })
}

/// One axis element of a subchain with its effective direction (tool relative to workpiece).
#[derive(Debug, Clone, Copy)]
struct Eff {
    at: AxisAt,
    dir: Vec3,
    on_part: bool,
}

/// What the three builders share: the walked subchains and the record's accessors.
struct Record<'a> {
    kin: &'a KinData,
    g: &'a Graph,
    n: usize,
    what: &'a str,
    tool: Walk,
    part: Walk,
    axes: Vec<Eff>,
}

impl<'a> Record<'a> {
    fn new(kin: &'a KinData, g: &'a Graph, n: usize, what: &'a str) -> Result<Record<'a>, ActivationError> {
        let s = |var: &str| kin.str(Family::Trafo, n, var, 0);
        let tool_last = s("$NT_T_CHAIN_LAST_ELEM");
        if tool_last.is_empty() {
            return Err(general(format!("{what}: $NT_T_CHAIN_LAST_ELEM must name the end of the tool chain")));
        }
        let tool = walk(g, &format!("{what} tool chain"), &s("$NT_T_CHAIN_FIRST_ELEM"), &tool_last)?;
        let part =
            walk(g, &format!("{what} workpiece chain"), &s("$NT_P_CHAIN_FIRST_ELEM"), &s("$NT_P_CHAIN_LAST_ELEM"))?;
        let t_ref = s("$NT_T_REF_ELEM");
        if !t_ref.is_empty() && t_ref != tool_last {
            return Err(general(format!(
                "{what}: $NT_T_REF_ELEM \"{t_ref}\": a tool reference position other than the end of the tool chain is not modelled"
            )));
        }
        let mut axes: Vec<Eff> = tool.axes.iter().map(|a| Eff { at: *a, dir: a.dir, on_part: false }).collect();
        for a in &part.axes {
            if axes.iter().any(|b| b.at.elem == a.elem) {
                return Err(general(format!(
                    "{what}: axis element \"{}\" lies on both the tool and the workpiece chain",
                    g.elems[a.elem].name
                )));
            }
            axes.push(Eff { at: *a, dir: a.dir.map(|c| -c), on_part: true });
        }
        Ok(Record { kin, g, n, what, tool, part, axes })
    }

    fn fail<T>(&self, m: String) -> Result<T, ActivationError> {
        Err(general(format!("{}: {m}", self.what)))
    }

    fn name(&self, e: &Eff) -> &str {
        &self.g.elems[e.at.elem].name
    }

    /// The linear axis element `$NT_GEO_AX_NAME[n,k]` names, if any.
    fn geo(&self, k: usize) -> Result<Option<Eff>, ActivationError> {
        let named = self.kin.str(Family::Trafo, self.n, "$NT_GEO_AX_NAME", k);
        if named.is_empty() {
            return Ok(None);
        }
        match self.axes.iter().find(|a| self.name(a) == named) {
            Some(a) if !a.at.rotary => Ok(Some(*a)),
            Some(_) => self.fail(format!("$NT_GEO_AX_NAME[{},{k}] \"{named}\" is a rotary axis element", self.n)),
            None => self.fail(format!(
                "$NT_GEO_AX_NAME[{},{k}] \"{named}\" is no axis element on the tool or the workpiece chain",
                self.n
            )),
        }
    }

    /// Every rotary axis element on the subchains must be one the record names: an unnamed one
    /// would turn the tool or the workpiece without the transformation knowing. Unnamed linear
    /// axes stay outside the transformation (as a machine's Y axis beside TRANSMIT 256), taken
    /// at position 0 for the base tool.
    fn all_named(&self, named: &[Option<Eff>]) -> Result<(), ActivationError> {
        for a in self.axes.iter().filter(|a| a.at.rotary) {
            if !named.iter().flatten().any(|b| b.at.elem == a.at.elem) {
                return self.fail(format!(
                    "rotary axis element \"{}\" lies on a subchain but is no axis of the transformation ($NT_ROT_AX_NAME)",
                    self.name(a)
                ));
            }
        }
        Ok(())
    }

    fn int(&self, var: &str) -> i64 {
        self.kin.num(Family::Trafo, self.n, var, 0) as i64
    }

    fn cntrl(&self) -> i64 {
        self.int("$NT_CNTRL")
    }

    fn channel(&self, e: &Eff) -> usize {
        self.g.elems[e.at.elem].axis.expect("axis elements have a channel axis")
    }

    fn order(&self) -> Result<[usize; 3], ActivationError> {
        let code = (self.cntrl() >> 16) & 7;
        geo_order(code).map_or_else(
            || self.fail(format!("$NT_CNTRL bits 16..18 = {code}: the order of the geometry axes is 0..5")),
            Ok,
        )
    }

    fn set(
        &self,
        name: String,
        kind: TrafoKind,
        trafo_type: u32,
        axes_in: [Option<usize>; 7],
        geo_axes: [Option<usize>; 3],
        params: TrafoParams,
    ) -> TrafoDataSet {
        let index = self.int("$NT_TRAFO_INDEX");
        let conventional = usize::try_from(index / 10 % 100).ok().filter(|c| *c > 0);
        TrafoDataSet {
            number: super::KIN_TRAFO_NUMBER_BASE + self.n,
            trafo_type,
            kind,
            kind_index: 0,
            axes_in,
            geo_axes,
            includes_tool: self.kin.num(Family::Trafo, self.n, "$NT_TRAFO_INCLUDES_TOOL", 0) != 0.0,
            params,
            chain: Some(ChainDef { name, conventional }),
        }
    }
}

/// Builds a TRANSMIT_K or TRACYL_K record.
pub(super) fn rotary(
    kin: &KinData,
    g: &Graph,
    n: usize,
    what: &str,
    name: String,
    kind: TrafoKind,
) -> Result<TrafoDataSet, ActivationError> {
    let r = Record::new(kin, g, n, what)?;
    let f = Family::Trafo;
    let cntrl = r.cntrl();
    let (bit9, bit10) = (cntrl >> 9 & 1 == 1, cntrl >> 10 & 1 == 1);
    let (trafo_type, supplementary) = match kind {
        TrafoKind::Transmit => (if bit9 { 257 } else { 256 }, bit9),
        _ if bit10 => (514, true),
        _ => (if bit9 { 513 } else { 512 }, bit9),
    };
    for k in [0, 2] {
        let named = kin.str(f, n, "$NT_ROT_AX_NAME", k);
        if !named.is_empty() {
            return r.fail(format!(
                "$NT_ROT_AX_NAME[{n},{k}] \"{named}\": {} has one rotary axis, in $NT_ROT_AX_NAME[{n},1]",
                kind.name()
            ));
        }
    }
    let rot_name = kin.str(f, n, "$NT_ROT_AX_NAME", 1);
    let Some(rot) = r.axes.iter().find(|a| r.name(a) == rot_name && !rot_name.is_empty()).copied() else {
        return r.fail(format!(
            "$NT_ROT_AX_NAME[{n},1] must name the rotary axis element of the workpiece chain (found \"{rot_name}\")"
        ));
    };
    if !rot.at.rotary || !rot.on_part {
        return r.fail(format!("\"{rot_name}\" must be a rotary axis element on the workpiece chain"));
    }
    // Linear axes of the workpiece chain after the rotary axis would turn with it.
    let rot_pos = r.part.axes.iter().position(|a| a.elem == rot.at.elem).expect("on the workpiece chain");
    if let Some(a) = r.part.axes[rot_pos + 1..].first() {
        return r.fail(format!(
            "axis element \"{}\" follows the rotary axis \"{rot_name}\" on the workpiece chain",
            g.elems[a.elem].name
        ));
    }
    let Some(radial) = r.geo(0)? else {
        return r.fail(format!("$NT_GEO_AX_NAME[{n},0] must name the linear axis perpendicular to the rotary axis"));
    };
    let extra = r.geo(1)?;
    let axial = r.geo(2)?;
    if supplementary && extra.is_none() {
        return r.fail(format!(
            "type {trafo_type} ($NT_CNTRL bits 9/10) needs $NT_GEO_AX_NAME[{n},1], the supplementary linear axis"
        ));
    }
    r.all_named(&[Some(radial), extra, axial, Some(rot)])?;
    let d = rot.at.dir;
    let e_z = match axial {
        Some(a) if parallel(&a.dir, &d) => a.dir,
        Some(a) => return r.fail(format!("longitudinal axis \"{}\" is not parallel to the rotary axis", r.name(&a))),
        None => d.map(|c| -c),
    };
    if dot(&radial.dir, &e_z).abs() > EPS {
        return r.fail(format!("linear axis \"{}\" is not perpendicular to the rotary axis", r.name(&radial)));
    }
    let e_x = radial.dir;
    let e_y = cross(&e_z, &e_x);
    if let Some(y) = extra.filter(|_| supplementary)
        && !same(&y.dir, &e_y)
    {
        return r.fail(format!(
            "supplementary axis \"{}\" must move the tool along Z × X of the transformation, {e_y:?}",
            r.name(&y)
        ));
    }
    // The tool turns positively about e_z relative to the workpiece when e_z opposes the
    // rotary element's direction; $NT_CNTRL bit 11 inverts the sense.
    let mut sign_plus = dot(&e_z, &d) < 0.0;
    if cntrl >> 11 & 1 == 1 {
        sign_plus = !sign_plus;
    }
    let x_p = r.part.end;
    let p_c = rot.at.point;
    let along = dot(&std::array::from_fn(|i| x_p[i] - p_c[i]), &d);
    let origin: Vec3 = std::array::from_fn(|i| p_c[i] + along * d[i]);
    let v: Vec3 = std::array::from_fn(|i| r.tool.end[i] - origin[i]);
    let order = r.order()?;
    let mut base_tool = [0.0; 3];
    for (role, e) in [e_x, e_y, e_z].iter().enumerate() {
        base_tool[order[role]] = dot(&v, e);
    }
    let rot_offset = kin.num(f, n, "$NT_ROT_AX_OFFSET", 1) - g.elems[rot.at.elem].a_off;
    let axes_in = [
        Some(r.channel(&radial)),
        Some(r.channel(&rot)),
        axial.map(|a| r.channel(&a)),
        extra.filter(|_| supplementary).map(|a| r.channel(&a)),
        None,
        None,
        None,
    ];
    let mut geo_axes = [None; 3];
    for role in 0..3 {
        geo_axes[order[role]] = axes_in[role];
    }
    let rot_frame = r.int("$NT_ROT_OFFSET_FROM_FRAME") as u8;
    let params = match kind {
        TrafoKind::Transmit => TrafoParams::Transmit {
            rot_offset,
            rot_frame,
            sign_plus,
            pole_side_fix: r.int("$NT_POLE_SIDE_FIX") as u8,
            base_tool,
        },
        _ => TrafoParams::Tracyl { rot_offset, rot_frame, default_mode: u8::from(bit9), sign_plus, base_tool },
    };
    Ok(r.set(name, kind, trafo_type, axes_in, geo_axes, params))
}

/// Builds a TRAANG_K record: the angle is that of the inclined axis against the plane normal
/// to the longitudinal axis, measured towards the longitudinal axis.
pub(super) fn inclined(
    kin: &KinData,
    g: &Graph,
    n: usize,
    what: &str,
    name: String,
) -> Result<TrafoDataSet, ActivationError> {
    let r = Record::new(kin, g, n, what)?;
    for k in 0..3 {
        let named = kin.str(Family::Trafo, n, "$NT_ROT_AX_NAME", k);
        if !named.is_empty() {
            return r.fail(format!("$NT_ROT_AX_NAME[{n},{k}] \"{named}\": TRAANG_K has no rotary axis"));
        }
    }
    let Some(infeed) = r.geo(0)? else {
        return r.fail(format!("$NT_GEO_AX_NAME[{n},0] must name the inclined axis"));
    };
    let Some(longitudinal) = r.geo(2)? else {
        return r.fail(format!("$NT_GEO_AX_NAME[{n},2] must name the longitudinal axis"));
    };
    let other = r.geo(1)?;
    r.all_named(&[Some(infeed), other, Some(longitudinal)])?;
    let e_z = longitudinal.dir;
    let sin = dot(&infeed.dir, &e_z);
    let Some(e_x) = unit(&std::array::from_fn(|i| infeed.dir[i] - sin * e_z[i])) else {
        return r.fail(format!("inclined axis \"{}\" is parallel to the longitudinal axis", r.name(&infeed)));
    };
    let cos = dot(&infeed.dir, &e_x);
    let angle = sin.atan2(cos).to_degrees();
    if angle.abs() < EPS {
        return r.fail(format!(
            "axis \"{}\" is perpendicular to the longitudinal axis: TRAANG needs an angle other than 0",
            r.name(&infeed)
        ));
    }
    let e_y = cross(&e_z, &e_x);
    if let Some(y) = other
        && !same(&y.dir, &e_y)
    {
        return r
            .fail(format!("axis \"{}\" must move the tool along Z × X of the transformation, {e_y:?}", r.name(&y)));
    }
    let v: Vec3 = std::array::from_fn(|i| r.tool.end[i] - r.part.end[i]);
    if dot(&v, &e_y).abs() > EPS {
        return r.fail(format!(
            "the tool reference point lies {} off the plane of the inclined and the longitudinal axis (TRAANG passes Y through)",
            dot(&v, &e_y)
        ));
    }
    let order = r.order()?;
    let mut base_tool = [0.0; 3];
    base_tool[order[0]] = dot(&v, &e_x);
    base_tool[order[2]] = dot(&v, &e_z);
    let axes_in = [
        Some(r.channel(&infeed)),
        Some(r.channel(&longitudinal)),
        other.map(|a| r.channel(&a)),
        None,
        None,
        None,
        None,
    ];
    let mut geo_axes = [None; 3];
    geo_axes[order[0]] = axes_in[0];
    geo_axes[order[1]] = axes_in[2];
    geo_axes[order[2]] = axes_in[1];
    let params = TrafoParams::Traang { angle, base_tool, velo_reserve: 0.0, accel_reserve: 0.0 };
    Ok(r.set(name, TrafoKind::Traang, 1024, axes_in, geo_axes, params))
}

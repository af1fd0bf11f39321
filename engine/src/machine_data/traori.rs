//! The orientation transformation data (TRAORI): `$MC_TRAFO_TYPE_n` codes 16..255 decoded into
//! which side the rotary axes move and their directions, plus the `$MC_TRAFO5_*` / `$MC_TRAFO6_*`
//! data of set 1 or 2 (REFERENCE §6.1, §6.2), checked once at activation.
//!
//! Conventions of this product where the manual is silent:
//! * Fixed types (16..53) and the cardan head (128..255) get their axis directions from the type
//!   code; an axis that turns the workpiece gets the reversed direction (DIN: a positive axis
//!   motion turns the tool relative to the workpiece right-handedly, REFERENCE §6.4.1), so a
//!   table AC (33) has the same orientation formula as a head CA (20).
//! * Generic types (24, 40, 56) take `TRAFO5_AXISn` as entered (reverse them for DIN tables).
//! * Cardan head: the primed 2nd axis lies in the plane of the two named axes, at the nutator
//!   angle φ from its own axis towards the 1st axis (CA′: `A′ = cos φ·x + sin φ·z`); bits 3–4
//!   give the tool direction in the zero position (0 = x, 1 = y, 2 = z), bits 5–6 the moving
//!   component (0 tool, 1 workpiece, 2 both). Only 148 is verified (S3 p.239).
//! * The offset vectors map onto the chain as in the TCARR table of §6.4.1: tool kinematics
//!   l1 = PART_OFFSET, l2 = JOINT_OFFSET, l3 = BASE_TOOL; part kinematics l2 = BASE_TOOL,
//!   l3 = JOINT_OFFSET (offset between the table axes), l4 = PART_OFFSET; mixed l1 = JOINT_OFFSET,
//!   l2 = BASE_TOOL, l3 = JOINT_OFFSET_PART, l4 = PART_OFFSET.

use super::MachineData;
use super::config::ActivationError;

/// Which part of the machine the rotary axes move (machine types 1, 2, 3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OriMachine {
    /// Swivel head: the rotary axes turn the tool.
    Tool,
    /// Tilting rotary table: the rotary axes turn the workpiece.
    Part,
    /// Axis 1 turns the tool (one-axis head), axis 2 the workpiece (rotary table).
    Mixed,
}

/// The decoded, checked data of one orientation transformation data set. Arrays indexed by
/// rotary axis are by role: [0] = `TRAFO_AXES_IN_n[3]`, [1] = `[4]`, [2] = `[5]`.
#[derive(Debug, Clone, PartialEq)]
pub struct TraoriParams {
    pub machine: OriMachine,
    /// Generic type (24, 40, 56): directions and basic orientation come from the machine data.
    pub generic: bool,
    /// Unit direction of rotary axis 1..3.
    pub axis: [[f64; 3]; 3],
    /// Unit basic tool orientation (tip → holder) in the zero position.
    pub base_orient: [f64; 3],
    /// `TRAFO6_BASE_ORIENT_NORMAL_t` (unit; 6-axis tool normal, for THETA).
    pub base_orient_normal: [f64; 3],
    /// `TRAFO5_PART_OFFSET_t`.
    pub part_offset: [f64; 3],
    /// `TRAFO5_BASE_TOOL_t`.
    pub base_tool: [f64; 3],
    /// `TRAFO5_JOINT_OFFSET_t`.
    pub joint_offset: [f64; 3],
    /// `TRAFO5_JOINT_OFFSET_PART_t`.
    pub joint_offset_part: [f64; 3],
    /// `TRAFO6_JOINT_OFFSET_2_3_t`.
    pub joint_offset_2_3: [f64; 3],
    /// `TRAFO5_TOOL_ROT_AX_OFFSET_t` (swivelled linear axis; kept, not used by these types).
    pub tool_rot_ax_offset: [f64; 3],
    /// `TRAFO5_ROT_AX_OFFSET_t`: axis positions of the kinematic zero position (degrees).
    pub rot_offset: [f64; 3],
    /// `TRAFO5_ROT_SIGN_IS_PLUS_t`.
    pub sign_plus: [bool; 3],
    /// `TRAFO5_NON_POLE_LIMIT_t`, `TRAFO5_POLE_LIMIT_t` (degrees).
    pub non_pole_limit: f64,
    pub pole_limit: f64,
    /// `TRAFO5_NUTATOR_AX_ANGLE_t` (degrees).
    pub nutator_angle: f64,
    /// `TRAFO5_ORIAX_ASSIGN_TAB_t`: channel axes of the (virtual) orientation axes.
    pub oriax_assign: [Option<usize>; 3],
    /// `TRAFO7_EXT_AXIS1_t` (unit): direction of the 7th axis (`TRAFO_AXES_IN_n[6]`), which
    /// turns the workpiece right-handedly about it when it moves positive.
    pub ext_axis: [f64; 3],
    /// `TRAFO7_EXT_ROT_AX_OFFSET_t`: position of the 7th axis at which the workpiece
    /// coordinates coincide with the BCS (degrees).
    pub ext_offset: f64,
}

/// Channel data of orientation programming (MD21090..21130), read at activation.
#[derive(Debug, Clone, PartialEq)]
pub struct OriSettings {
    /// MD21090 `MAX_LEAD_ANGLE`, MD21092 `MAX_TILT_ANGLE` (degrees).
    pub max_lead_angle: f64,
    pub max_tilt_angle: f64,
    /// MD21094 `ORIPATH_MODE`.
    pub oripath_mode: u32,
    /// MD21100 `ORIENTATION_IS_EULER`: A2/B2/C2 are Euler angles (else RPY) unless MD21102.
    pub orientation_is_euler: bool,
    /// MD21102 `ORI_DEF_WITH_G_CODE`: G group 50 decides the angle convention.
    pub ori_def_with_g_code: bool,
    /// MD21104 `ORI_IPO_WITH_G_CODE`: G group 51 decides the interpolation.
    pub ori_ipo_with_g_code: bool,
    /// MD21108 `POLE_ORI_MODE`.
    pub pole_ori_mode: u32,
    /// MD21110 `X_AXIS_IN_OLD_X_Z_PLANE`.
    pub x_axis_in_old_x_z_plane: bool,
    /// MD21120 / MD21130 `ORIAX_TURN_TAB_1/2` (1 = X, 2 = Y, 3 = Z) for ORIVIRT1/2.
    pub turn_tab: [[u8; 3]; 2],
    /// MD21190 `TOFF_MODE`: `$AA_TOFF` writes are integrated (added) instead of absolute.
    pub toff_integrating: bool,
    /// MD21194 `TOFF_VELO` (mm/s) and MD21196 `TOFF_ACCEL` (mm/s²) of the online tool offset.
    pub toff_velocity: f64,
    pub toff_accel: f64,
}

impl OriSettings {
    pub(super) fn read(md: &MachineData) -> OriSettings {
        let n = |name: &str, i: usize| md.num(&format!("$MC_{name}"), 0, i);
        OriSettings {
            max_lead_angle: n("MAX_LEAD_ANGLE", 0),
            max_tilt_angle: n("MAX_TILT_ANGLE", 0),
            oripath_mode: n("ORIPATH_MODE", 0) as u32,
            orientation_is_euler: n("ORIENTATION_IS_EULER", 0) != 0.0,
            ori_def_with_g_code: n("ORI_DEF_WITH_G_CODE", 0) != 0.0,
            ori_ipo_with_g_code: n("ORI_IPO_WITH_G_CODE", 0) != 0.0,
            pole_ori_mode: n("POLE_ORI_MODE", 0) as u32,
            x_axis_in_old_x_z_plane: n("X_AXIS_IN_OLD_X_Z_PLANE", 0) != 0.0,
            turn_tab: [
                std::array::from_fn(|i| n("ORIAX_TURN_TAB_1", i) as u8),
                std::array::from_fn(|i| n("ORIAX_TURN_TAB_2", i) as u8),
            ],
            toff_integrating: n("TOFF_MODE", 0) != 0.0,
            toff_velocity: n("TOFF_VELO", 0) / 60.0,
            toff_accel: n("TOFF_ACCEL", 0) * 1000.0,
        }
    }
}

/// What a type code says about the kinematics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Decoded {
    pub machine: OriMachine,
    pub generic: bool,
    /// Cardan head: the 2nd axis is inclined by the nutator angle.
    pub cardan: bool,
    /// Cartesian axis (0 = X, 1 = Y, 2 = Z) of the 1st and 2nd rotary axis (fixed types).
    pub letters: [usize; 2],
    /// Cartesian axis of the tool in the zero position (fixed types).
    pub tool_dir: usize,
}

/// Axis sequences of the low bits: AB, AC, BA, BC, CA, CB.
const SEQUENCES: [[usize; 2]; 6] = [[0, 1], [0, 2], [1, 0], [1, 2], [2, 0], [2, 1]];
const SEQ_NAMES: [&str; 6] = ["AB", "AC", "BA", "BC", "CA", "CB"];

/// Decodes a `TRAFO_TYPE` of the orientation range, or says why it is not supported.
pub fn decode(t: u32) -> Result<Decoded, String> {
    let fixed = |machine, seq: u32| Decoded {
        machine,
        generic: false,
        cardan: false,
        letters: SEQUENCES[seq as usize],
        tool_dir: 2,
    };
    let generic = |machine| Decoded { machine, generic: true, cardan: false, letters: [2, 0], tool_dir: 2 };
    let useless = |seq: u32| {
        Err(format!(
            "type {t} ({} sequence) is not a practical combination: the axis would only spin the tool about its own axis",
            SEQ_NAMES[seq as usize]
        ))
    };
    match t {
        16..=21 => match t - 16 {
            s @ (1 | 3) => useless(s),
            s => Ok(fixed(OriMachine::Tool, s)),
        },
        32..=37 => match t - 32 {
            s @ (4 | 5) => useless(s),
            s => Ok(fixed(OriMachine::Part, s)),
        },
        48..=53 => match t - 48 {
            s @ (4 | 5) => useless(s),
            s => Ok(fixed(OriMachine::Mixed, s)),
        },
        24 => Ok(generic(OriMachine::Tool)),
        40 => Ok(generic(OriMachine::Part)),
        56 => Ok(generic(OriMachine::Mixed)),
        72 => Err("type 72 (generic 5-axis transformation from orientable toolholder $MC_TRAFO5_TCARR_NO) is not modelled yet".into()),
        68 | 69 => Err(format!("type {t} (5-axis transformation with swivelled linear axis) is not modelled")),
        128..=255 => {
            let (seq, dir, moving) = (t & 7, (t >> 3) & 3, (t >> 5) & 3);
            if seq > 5 || dir > 2 || moving > 2 {
                return Err(format!(
                    "type {t} is not a valid cardan-head code (bits 0-2 sequence 0..5, bits 3-4 tool direction 0..2, bits 5-6 moving component 0..2)"
                ));
            }
            let machine = [OriMachine::Tool, OriMachine::Part, OriMachine::Mixed][moving as usize];
            Ok(Decoded { machine, generic: false, cardan: true, letters: SEQUENCES[seq as usize], tool_dir: dir as usize })
        }
        _ => Err(format!(
            "type {t} is not an orientation transformation (16, 18, 20, 21, 24, 32..35, 40, 48..51, 56, cardan 128..245)"
        )),
    }
}

/// Static names of the data that activation errors blame, for sets 1 and 2.
fn datum(name: &str, k: usize) -> &'static str {
    match (name, k) {
        ("AXIS1", 1) => "TRAFO5_AXIS1_1",
        ("AXIS1", _) => "TRAFO5_AXIS1_2",
        ("AXIS2", 1) => "TRAFO5_AXIS2_1",
        ("AXIS2", _) => "TRAFO5_AXIS2_2",
        ("AXIS3", 1) => "TRAFO5_AXIS3_1",
        ("AXIS3", _) => "TRAFO5_AXIS3_2",
        ("BASE_ORIENT", 1) => "TRAFO5_BASE_ORIENT_1",
        ("BASE_ORIENT", _) => "TRAFO5_BASE_ORIENT_2",
        ("NORMAL", 1) => "TRAFO6_BASE_ORIENT_NORMAL_1",
        ("NORMAL", _) => "TRAFO6_BASE_ORIENT_NORMAL_2",
        ("ORIAX", 1) => "TRAFO5_ORIAX_ASSIGN_TAB_1",
        ("ORIAX", _) => "TRAFO5_ORIAX_ASSIGN_TAB_2",
        ("EXT_AXIS", 1) => "TRAFO7_EXT_AXIS1_1",
        _ => "TRAFO7_EXT_AXIS1_2",
    }
}

fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (n > 1e-9).then(|| [v[0] / n, v[1] / n, v[2] / n])
}

/// Sine of the angle below which two directions count as (anti)parallel for alarm 4342.
const PARALLEL_SIN: f64 = 1e-4;

fn parallel(a: &[f64; 3], b: &[f64; 3]) -> bool {
    let c = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt() < PARALLEL_SIN
}

/// Reads and checks the data of the `k`-th orientation data set (`k` = 1 or 2) of type `t`
/// with the roles `axes_in` already resolved to channel axes.
pub(super) fn params(
    md: &MachineData,
    t: u32,
    k: usize,
    axes_in: &[Option<usize>; 7],
    type_datum: &'static str,
    axes_datum: &'static str,
    resolve: &dyn Fn(usize) -> Option<usize>,
) -> Result<TraoriParams, ActivationError> {
    let fail = |datum: &'static str, message: String| Err(ActivationError { datum: Some(datum), message });
    let d = match decode(t) {
        Ok(d) => d,
        Err(why) => return fail(type_datum, format!("$MC_{type_datum}={t}: {why}")),
    };
    let v3 = |name: &str| -> [f64; 3] { std::array::from_fn(|i| md.num(&format!("$MC_{name}_{k}"), 0, i)) };
    let s = |name: &str| md.num(&format!("$MC_{name}_{k}"), 0, 0);
    let alarm = |datum: &'static str, code: u32, what: &str| {
        fail(
            datum,
            format!(
                "alarm 4342: invalid machine data for generic orientation transformation {k}, error {code}: {what}"
            ),
        )
    };
    let linear = axes_in[..3].iter().flatten().count();
    let rotary = [axes_in[3].is_some(), axes_in[4].is_some(), axes_in[5].is_some()];
    if linear < 2 {
        return fail(axes_datum, format!("$MC_{axes_datum}[0..2] must name at least two linear axes for TRAORI ({t})"));
    }
    if !rotary[0] && !rotary[1] {
        return fail(
            axes_datum,
            format!(
                "$MC_{type_datum}={t}: TRAFO_AXES_IN[3] or [4] must name a rotary axis of the orientation transformation"
            ),
        );
    }
    if d.machine == OriMachine::Mixed && !(rotary[0] && rotary[1]) {
        if d.generic {
            return alarm(axes_datum, 5, "type 56 needs two rotary axes (TRAFO_AXES_IN[3] and [4])");
        }
        return fail(
            axes_datum,
            format!("$MC_{axes_datum}[3] and [4] must both name rotary axes for mixed kinematics ({t})"),
        );
    }
    if rotary[2] && !(d.generic && d.machine == OriMachine::Tool && rotary[0] && rotary[1]) {
        return fail(
            axes_datum,
            format!(
                "$MC_{type_datum}={t}: a 3rd rotary axis (TRAFO_AXES_IN[5]) needs the generic 6-axis type 24 with two other rotary axes"
            ),
        );
    }
    // The 7th axis (F2 §3.7.6) extends only the generic tool kinematics (type 24).
    let ext_axis = if axes_in[6].is_some() {
        if !(d.generic && d.machine == OriMachine::Tool) {
            return fail(
                axes_datum,
                format!("$MC_{type_datum}={t}: a 7th axis (TRAFO_AXES_IN[6]) needs the generic type 24"),
            );
        }
        match unit(v3("TRAFO7_EXT_AXIS1")) {
            Some(u) => u,
            None => {
                return alarm(datum("EXT_AXIS", k), 9, &format!("$MC_TRAFO7_EXT_AXIS1_{k} is the zero vector"));
            }
        }
    } else {
        [0.0, 0.0, 1.0]
    };
    let nutator_angle = s("TRAFO5_NUTATOR_AX_ANGLE");
    let base_orient_normal_raw = v3("TRAFO6_BASE_ORIENT_NORMAL");
    let (axis, base_orient) = if d.generic {
        let raw = [v3("TRAFO5_AXIS1"), v3("TRAFO5_AXIS2"), v3("TRAFO5_AXIS3")];
        let mut axis = [[0.0; 3]; 3];
        for (i, (code, name)) in [(1, "AXIS1"), (2, "AXIS2"), (6, "AXIS3")].into_iter().enumerate() {
            if rotary[i] {
                axis[i] = match unit(raw[i]) {
                    Some(u) => u,
                    None => return alarm(datum(name, k), code, &format!("$MC_TRAFO5_{name}_{k} is the zero vector")),
                };
            }
        }
        let Some(base) = unit(v3("TRAFO5_BASE_ORIENT")) else {
            return alarm(datum("BASE_ORIENT", k), 3, &format!("$MC_TRAFO5_BASE_ORIENT_{k} is the zero vector"));
        };
        if rotary[0] && rotary[1] && parallel(&axis[0], &axis[1]) {
            return alarm(datum("AXIS2", k), 4, "rotary axes 1 and 2 are (nearly) parallel");
        }
        if rotary[2] {
            let Some(normal) = unit(base_orient_normal_raw) else {
                return alarm(datum("NORMAL", k), 7, &format!("$MC_TRAFO6_BASE_ORIENT_NORMAL_{k} is the zero vector"));
            };
            if parallel(&normal, &base) {
                return alarm(datum("NORMAL", k), 8, "tool normal vector parallel to the basic orientation");
            }
        }
        (axis, base)
    } else {
        let e = |i: usize| {
            let mut v = [0.0; 3];
            v[i] = 1.0;
            v
        };
        let [a1, a2] = d.letters;
        let mut axis = [e(a1), e(a2), [0.0; 3]];
        if d.cardan {
            let (s, c) = nutator_angle.to_radians().sin_cos();
            axis[1] = std::array::from_fn(|i| c * e(a2)[i] + s * e(a1)[i]);
        }
        // DIN: axes on the workpiece side describe the relative motion of the tool.
        let reversed = match d.machine {
            OriMachine::Tool => [false, false],
            OriMachine::Part => [true, true],
            OriMachine::Mixed => [false, true],
        };
        for i in 0..2 {
            if reversed[i] {
                axis[i] = axis[i].map(|x| -x);
            }
        }
        (axis, e(d.tool_dir))
    };
    let mut oriax_assign = [None; 3];
    for (i, slot) in oriax_assign.iter_mut().enumerate() {
        let n = md.num(&format!("$MC_TRAFO5_ORIAX_ASSIGN_TAB_{k}"), 0, i) as usize;
        if n != 0 {
            *slot = Some(resolve(n).ok_or_else(|| ActivationError {
                datum: Some(datum("ORIAX", k)),
                message: format!("$MC_TRAFO5_ORIAX_ASSIGN_TAB_{k}[{i}]={n}: channel axis {n} does not exist"),
            })?);
        }
    }
    Ok(TraoriParams {
        machine: d.machine,
        generic: d.generic,
        axis,
        base_orient,
        base_orient_normal: unit(base_orient_normal_raw).unwrap_or([1.0, 0.0, 0.0]),
        part_offset: v3("TRAFO5_PART_OFFSET"),
        base_tool: v3("TRAFO5_BASE_TOOL"),
        joint_offset: v3("TRAFO5_JOINT_OFFSET"),
        joint_offset_part: v3("TRAFO5_JOINT_OFFSET_PART"),
        joint_offset_2_3: v3("TRAFO6_JOINT_OFFSET_2_3"),
        tool_rot_ax_offset: v3("TRAFO5_TOOL_ROT_AX_OFFSET"),
        rot_offset: v3("TRAFO5_ROT_AX_OFFSET"),
        sign_plus: v3("TRAFO5_ROT_SIGN_IS_PLUS").map(|b| b != 0.0),
        non_pole_limit: s("TRAFO5_NON_POLE_LIMIT"),
        pole_limit: s("TRAFO5_POLE_LIMIT"),
        nutator_angle,
        oriax_assign,
        ext_axis,
        ext_offset: s("TRAFO7_EXT_ROT_AX_OFFSET"),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_code_table_of_the_manual_decodes() {
        for (t, machine, letters) in [
            (16, OriMachine::Tool, [0, 1]),
            (18, OriMachine::Tool, [1, 0]),
            (20, OriMachine::Tool, [2, 0]),
            (21, OriMachine::Tool, [2, 1]),
            (32, OriMachine::Part, [0, 1]),
            (33, OriMachine::Part, [0, 2]),
            (34, OriMachine::Part, [1, 0]),
            (35, OriMachine::Part, [1, 2]),
            (48, OriMachine::Mixed, [0, 1]),
            (49, OriMachine::Mixed, [0, 2]),
            (50, OriMachine::Mixed, [1, 0]),
            (51, OriMachine::Mixed, [1, 2]),
        ] {
            let d = decode(t).unwrap();
            assert_eq!((d.machine, d.letters, d.generic), (machine, letters, false), "type {t}");
        }
        assert!(decode(24).unwrap().generic && decode(40).unwrap().machine == OriMachine::Part);
        assert_eq!(decode(56).unwrap().machine, OriMachine::Mixed);
    }

    #[test]
    fn impractical_and_unmodelled_codes_are_refused_with_a_reason() {
        for t in [17, 19, 36, 37, 52, 53] {
            assert!(decode(t).unwrap_err().contains("not a practical combination"), "{t}");
        }
        assert!(decode(72).unwrap_err().contains("toolholder"));
        assert!(decode(68).unwrap_err().contains("swivelled linear axis"));
        assert!(decode(22).is_err() && decode(134).is_err() && decode(248).is_err());
    }

    #[test]
    fn type_148_is_a_cardan_ca_head_with_the_tool_along_z() {
        let d = decode(148).unwrap();
        assert_eq!((d.machine, d.cardan, d.letters, d.tool_dir), (OriMachine::Tool, true, [2, 0], 2));
    }
}

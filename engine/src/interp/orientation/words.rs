//! Tool orientation programming under an orientation transformation (TRAORI): the words
//! A3/B3/C3 (direction vector), A2/B2/C2 (angles), A6/B6/C6 (cone axis), the G groups 25
//! (ORIWKS/ORIMKS), 50 (ORIEULER/ORIRPY/ORIRPY2/ORIVIRT1/ORIVIRT2) and 51 (ORIVECT/ORIAXES/
//! ORIPLANE/ORICONCW/ORICONCCW/...), and how a block's end orientation becomes rotary-axis
//! positions and an orientation path.
//!
//! Conventions: an orientation vector points from the tool tip to the holder (a G17 milling
//! tool in its zero position is +Z). Under ORIWKS the programmed vector refers to the workpiece
//! coordinate system and turns with the active frame; under ORIMKS it refers to the basic
//! coordinate system. The interpolation is decided by G group 51 when MD21104
//! ORI_IPO_WITH_G_CODE is set, otherwise ORIWKS interpolates the vector on a great circle and
//! ORIMKS the rotary axes linearly (Transformations Function Manual, F2).

use crate::alarm::{Alarm, Clear};
use crate::interp::Interpreter;
use crate::interp::frames::frame::Frame;
use crate::interp::modal::MotionMode;
pub use crate::interp::orientation::rotation::RotReference;
use crate::kinematics::orient::ChainKind;
use crate::kinematics::orient::vec3::{cross, dot, neg, norm, normalize, scale, sub};
use crate::kinematics::orient::{angles, cone_sweep, cone_tangent, cone_through};
use crate::kinematics::{AnyTrafo, Transformation, Traori, Vec3};
use crate::machine_data::MachineConfig;
use crate::motion::{AxisVec, OriPath};

/// G group 25: what a programmed orientation refers to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OriReference {
    /// ORIWKS: the workpiece coordinate system.
    Workpiece,
    /// ORIMKS: the machine (basic) coordinate system.
    Machine,
}

/// G group 50: how A2/B2/C2 define the orientation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AngleDefinition {
    Euler,
    Rpy,
    Rpy2,
    Virtual1,
    Virtual2,
}

/// G group 51: how the orientation is interpolated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OriInterpolation {
    /// ORIVECT and ORIPLANE: great circle.
    Vector,
    /// ORIAXES: the rotary axes linearly.
    Axes,
    /// ORICONCW / ORICONCCW: on a cone about A6/B6/C6.
    Cone { clockwise: bool },
    /// ORIPATH: every motion block ends with the orientation LEAD/TILT give relative to its
    /// path tangent and the surface normal; in between a great circle.
    Path,
    /// ORICONIO: on the cone through the start, the intermediate orientation A7/B7/C7 and the
    /// end.
    ConeIntermediate,
    /// ORICONTO: on the cone tangential to the previous block's orientation motion.
    ConeTangential,
    /// ORICURVE: from the tool tip towards a second curve through XH/YH/ZH.
    Curve,
    /// ORIPATHS: not modelled (alarm when used).
    Unmodelled(&'static str),
}

/// The modal orientation state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OriModal {
    pub reference: OriReference,
    pub angles: AngleDefinition,
    pub interpolation: OriInterpolation,
    /// LEAD and TILT (degrees), modal.
    pub lead: f64,
    pub tilt: f64,
    /// The last surface normal (A5/B5/C5 of the last block that gave one; +Z at reset).
    pub normal: Vec3,
    /// Direction in which the orientation moved at the end of the last motion block (BCS), if
    /// it was interpolated as a vector: the tangent ORICONTO continues.
    pub last_change: Option<Vec3>,
    /// G group 54: the reference of the tool rotation THETA (6-axis).
    pub rotation: RotReference,
    /// The last THETA in force (degrees).
    pub theta: f64,
    /// ORICURVE: where the upper curve of the previous block ended (BCS), when the previous
    /// motion block was an ORICURVE block with XH/YH/ZH.
    pub upper: Option<Vec3>,
}

impl OriModal {
    /// Reset values: ORIMKS, ORIEULER, ORIVECT.
    pub fn reset() -> OriModal {
        OriModal {
            reference: OriReference::Machine,
            angles: AngleDefinition::Euler,
            interpolation: OriInterpolation::Vector,
            lead: 0.0,
            tilt: 0.0,
            normal: [0.0, 0.0, 1.0],
            last_change: None,
            rotation: RotReference::Absolute,
            theta: 0.0,
            upper: None,
        }
    }

    /// Applies the orientation G functions of a block.
    pub(in crate::interp) fn apply(&mut self, w: &OriWords) {
        if let Some(r) = w.reference {
            self.reference = r;
        }
        if let Some(a) = w.angles_def {
            self.angles = a;
        }
        if let Some(i) = w.interpolation {
            self.interpolation = i;
        }
        if let Some(r) = w.rotation {
            self.rotation = r;
        }
        if let Some(l) = w.lead {
            self.lead = l;
        }
        if let Some(t) = w.tilt {
            self.tilt = t;
        }
        if let Some(n) =
            normalize(&w.normal_end.map(|c| c.unwrap_or(0.0))).filter(|_| w.normal_end.iter().any(Option::is_some))
        {
            self.normal = n;
        }
    }
}

/// The orientation words of one block.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct OriWords {
    /// A3, B3, C3.
    pub vector: [Option<f64>; 3],
    /// A2, B2, C2 (degrees).
    pub angles: [Option<f64>; 3],
    /// A6, B6, C6: cone axis.
    pub cone_axis: [Option<f64>; 3],
    /// A7, B7, C7: intermediate orientation of ORICONIO.
    pub intermediate: [Option<f64>; 3],
    /// ORIRESET(a, b, c): the orientation axes to these positions (omitted: the rest position).
    pub reset: Option<[Option<f64>; 3]>,
    /// LEAD=, TILT= (degrees).
    pub lead: Option<f64>,
    pub tilt: Option<f64>,
    /// A4/B4/C4 and A5/B5/C5: surface normal at the block start and end.
    pub normal_start: [Option<f64>; 3],
    pub normal_end: [Option<f64>; 3],
    pub reference: Option<OriReference>,
    pub angles_def: Option<AngleDefinition>,
    pub interpolation: Option<OriInterpolation>,
    /// G group 54 (ORIROTA, ORIROTR, ORIROTT, ORIROTC).
    pub rotation: Option<RotReference>,
    /// THETA= (degrees) and whether it was given incrementally (`THETA=IC(..)`).
    pub theta: Option<(f64, bool)>,
    /// XH=, YH=, ZH=: end point of the upper curve of ORICURVE (WCS).
    pub upper: [Option<f64>; 3],
}

impl OriWords {
    /// True if the block programs an orientation directly (vector or angles).
    pub fn programmed(&self) -> bool {
        self.vector.iter().chain(&self.angles).any(Option::is_some)
    }

    /// True if the block programs an orientation relative to the path (LEAD, TILT).
    pub fn path_relative(&self) -> bool {
        self.lead.is_some() || self.tilt.is_some()
    }

    /// True if the block moves the orientation (programmed, path-relative, ORIRESET, or the
    /// tool rotation THETA).
    pub fn moves(&self) -> bool {
        self.programmed()
            || self.path_relative()
            || self.reset.is_some()
            || self.theta.is_some()
            || self.upper.iter().any(Option::is_some)
    }

    /// Takes an orientation G function (`ORIWKS`, ...); false if `name` is none.
    pub fn keyword(&mut self, name: &str) -> bool {
        use OriInterpolation as I;
        if let Some(r) = RotReference::keyword(name) {
            self.rotation = Some(r);
            return true;
        }
        match name {
            "ORIWKS" => self.reference = Some(OriReference::Workpiece),
            "ORIMKS" => self.reference = Some(OriReference::Machine),
            "ORIEULER" => self.angles_def = Some(AngleDefinition::Euler),
            "ORIRPY" => self.angles_def = Some(AngleDefinition::Rpy),
            "ORIRPY2" => self.angles_def = Some(AngleDefinition::Rpy2),
            "ORIVIRT1" => self.angles_def = Some(AngleDefinition::Virtual1),
            "ORIVIRT2" => self.angles_def = Some(AngleDefinition::Virtual2),
            "ORIVECT" | "ORIPLANE" => self.interpolation = Some(I::Vector),
            "ORIAXES" => self.interpolation = Some(I::Axes),
            "ORICONCW" => self.interpolation = Some(I::Cone { clockwise: true }),
            "ORICONCCW" => self.interpolation = Some(I::Cone { clockwise: false }),
            "ORIPATH" => self.interpolation = Some(I::Path),
            "ORIPATHS" => self.interpolation = Some(I::Unmodelled("ORIPATHS")),
            "ORICONIO" => self.interpolation = Some(I::ConeIntermediate),
            "ORICONTO" => self.interpolation = Some(I::ConeTangential),
            "ORICURVE" => self.interpolation = Some(I::Curve),
            _ => return false,
        }
        true
    }

    /// Takes an orientation address (`A3=`, ...); false if `name` is none.
    pub fn address(&mut self, name: &str, value: f64) -> bool {
        match name {
            "LEAD" => self.lead = Some(value),
            "TILT" => self.tilt = Some(value),
            _ => {}
        }
        if matches!(name, "LEAD" | "TILT") {
            return true;
        }
        if let Some(g) = ["XH", "YH", "ZH"].iter().position(|n| *n == name) {
            self.upper[g] = Some(value);
            return true;
        }
        let slot = match name {
            "A3" | "B3" | "C3" => &mut self.vector,
            "A2" | "B2" | "C2" => &mut self.angles,
            "A4" | "B4" | "C4" => &mut self.normal_start,
            "A5" | "B5" | "C5" => &mut self.normal_end,
            "A6" | "B6" | "C6" => &mut self.cone_axis,
            "A7" | "B7" | "C7" => &mut self.intermediate,
            _ => return false,
        };
        slot[(name.as_bytes()[0] - b'A') as usize] = Some(value);
        true
    }
}

/// True for the addresses [`OriWords::address`] takes.
pub fn is_address(name: &str) -> bool {
    matches!(
        name,
        "A2" | "B2"
            | "C2"
            | "A3"
            | "B3"
            | "C3"
            | "A4"
            | "B4"
            | "C4"
            | "A5"
            | "B5"
            | "C5"
            | "A6"
            | "B6"
            | "C6"
            | "A7"
            | "B7"
            | "C7"
            | "LEAD"
            | "TILT"
            | "XH"
            | "YH"
            | "ZH"
    )
}

/// 14110: orientation programmed without an orientation transformation (number and wording
/// after the control's alarm list, from memory).
fn without_transformation(line: u32) -> Alarm {
    Alarm {
        number: 14110,
        message: format!(
            "Channel 1 block {line} Euler angles or orientation vector programmed without orientation transformation"
        ),
        line: Some(line),
        clear: Clear::Reset,
    }
}

/// 14113 / 14114: LEAD or TILT beyond MD21090 MAX_LEAD_ANGLE / MD21092 MAX_TILT_ANGLE
/// (numbers from the control's alarm list, from memory).
fn angle_too_large(line: u32, lead: bool, value: f64, max: f64) -> Alarm {
    Alarm {
        number: if lead { 14113 } else { 14114 },
        message: format!(
            "Channel 1 block {line} programmed {} angle {value} too large (maximum {max})",
            if lead { "lead" } else { "tilt" }
        ),
        line: Some(line),
        clear: Clear::Reset,
    }
}

/// The orientation LEAD and TILT (degrees) give with the path tangent `t` and the surface
/// normal `n` (both unit, same system): `o = R(T, TILT)·R(S, LEAD)·N` with N the normal made
/// perpendicular to T and S = N × T. A positive LEAD leans the tool (tip → holder) forward in
/// the direction of travel, a positive TILT turns it right-handed about the tangent (this
/// product's sign conventions; the manual leaves them open). `None` when T ∥ N.
fn lead_and_tilt(t: Vec3, n: Vec3, lead: f64, tilt: f64) -> Option<Vec3> {
    let np = normalize(&sub(&n, &scale(&t, dot(&n, &t))))?;
    let leaned = crate::motion::rotate(np, cross(&np, &t), lead.to_radians());
    Some(crate::motion::rotate(leaned, t, tilt.to_radians()))
}

/// Pole handling of the great circle (TRAFO5_NON_POLE_LIMIT, TRAFO5_POLE_LIMIT): when the
/// great circle from `start` to `end` passes the pole direction of the kinematics closer than
/// NON_POLE_LIMIT without meeting it, and moving `end` onto the plane through the pole and
/// `start` changes it by at most POLE_LIMIT, the orientation is interpolated exactly through the
/// pole instead: the returned end orientation lies on that plane, so the great circle to it
/// crosses the pole and the pole axis need not swing round. `None`: keep the programmed end.
fn through_pole(t: &Traori, start: Vec3, end: Vec3) -> Option<Vec3> {
    let chain = t.chain();
    if chain.axes < 2 {
        return None;
    }
    let pole = match chain.kind {
        ChainKind::Tool => chain.v[0],
        ChainKind::Part | ChainKind::Mixed => chain.v[1],
    };
    let (non_pole_limit, pole_limit) = t.pole_limits();
    // `v` without its component along the unit vector `k`, normalised.
    let off = |v: &Vec3, k: &Vec3| normalize(&sub(v, &scale(k, dot(v, k))));
    // Closest approach of the great circle's arc to ±pole.
    let normal = normalize(&cross(&start, &end))?;
    let p = if dot(&pole, &start) + dot(&pole, &end) >= 0.0 { pole } else { neg(&pole) };
    let off_plane = dot(&p, &normal).abs().clamp(0.0, 1.0).asin().to_degrees();
    let foot = off(&p, &normal)?;
    let within = dot(&cross(&start, &foot), &normal) > 0.0 && dot(&cross(&foot, &end), &normal) > 0.0;
    if !within || off_plane >= non_pole_limit || off_plane < 1e-9 || t.pole_angle(&start) < 1e-6 {
        return None;
    }
    let meridian = normalize(&cross(&p, &start))?;
    let moved = off(&end, &meridian)?;
    let change = dot(&moved, &end).clamp(-1.0, 1.0).acos().to_degrees();
    (change <= pole_limit).then_some(moved)
}

/// MD21108 `POLE_ORI_MODE` for a great circle starting at `start`: the units digit applies
/// when the start orientation is the pole, the tens digit when it lies within
/// `TRAFO5_NON_POLE_LIMIT` of it (F2 §3.2 "Behavior at pole"). This product's reading of the
/// digit values (the manual excerpt names only the digits' roles): 0 = the great circle as
/// programmed (the pole axis turns to its end position at the start of the block, the path
/// slowing down as the axis limits demand); 1 = the block is interpolated with the rotary axes
/// linearly (ORIAXES), like the pole tolerance of kinematic chains ($NT_POLE_LIMIT), so the
/// pole axis turns together with the tilt axis. Other values act like 0.
fn pole_start_as_axes(t: &Traori, cfg: &MachineConfig, start: &Vec3) -> bool {
    let angle = t.pole_angle(start);
    let digit = if angle < 1e-6 {
        cfg.ori.pole_ori_mode % 10
    } else if angle < t.pole_limits().0 {
        cfg.ori.pole_ori_mode / 10 % 10
    } else {
        return false;
    };
    digit == 1
}

/// 14120: great-circle interpolation between antiparallel orientations.
fn antiparallel(line: u32) -> Alarm {
    Alarm {
        number: 14120,
        message: format!("Channel 1 block {line} plane of the orientation interpolation is undefined"),
        line: Some(line),
        clear: Clear::Reset,
    }
}

/// The unit vector of the programmed angles (degrees) under `def`; `None` for a virtual-axis
/// table (MD21120/21130) that names no reference axis.
fn from_angles(def: AngleDefinition, [a, b, c]: [f64; 3], cfg: &MachineConfig) -> Option<Vec3> {
    match def {
        AngleDefinition::Euler => Some(angles::euler_to_vector(a, b, c)),
        AngleDefinition::Rpy => Some(angles::rpy_to_vector(a, b, c)),
        AngleDefinition::Rpy2 => Some(angles::rpy2_to_vector(a, b, c)),
        AngleDefinition::Virtual1 => angles::virt_to_vector(cfg.ori.turn_tab[0], [a, b, c]),
        AngleDefinition::Virtual2 => angles::virt_to_vector(cfg.ori.turn_tab[1], [a, b, c]),
    }
}

impl Interpreter {
    /// Sets the orientation axes of `end` for a block with orientation words and returns the
    /// orientation path when the orientation is interpolated as a vector. `end` holds the
    /// block's BCS end point with any directly programmed rotary axes; `tangent` is the unit
    /// path direction at the block end in the WCS (for LEAD/TILT), if the tool tip moves.
    #[allow(clippy::too_many_arguments)]
    pub(in crate::interp) fn orientation_block_unchecked(
        &self,
        words: &crate::interp::modal::Words,
        cfg: &MachineConfig,
        frame: &Frame,
        start: &AxisVec,
        end: &mut AxisVec,
        tangent: Option<Vec3>,
        line: u32,
    ) -> Result<Option<OriPath>, Alarm> {
        let ori = &words.ori;
        let Some((active, machine)) = self.orientation_transformation() else {
            return if ori.moves() { Err(without_transformation(line)) } else { Ok(None) };
        };
        let slots = active.trafo.orientation_slots();
        let rotary_words = words.axes.iter().any(|(k, ..)| slots.contains(&Some(*k)));
        // The 7th axis of a generic 7-axis transformation turns the workpiece: orientations are
        // relative to it, at its block-end position for the end orientation.
        let seventh = match &active.trafo {
            AnyTrafo::Traori(t) => t.seventh_slot(),
            _ => None,
        };
        let seventh_moves = seventh.is_some_and(|k| (end[k] - start[k]).abs() > 1e-9);
        let modal_interpolation = if cfg.ori.ori_ipo_with_g_code {
            self.modal.ori.interpolation
        } else if self.modal.ori.reference == OriReference::Workpiece {
            OriInterpolation::Vector
        } else {
            OriInterpolation::Axes
        };
        if (ori.moves() && rotary_words) || (ori.programmed() && ori.reset.is_some()) {
            return Err(Alarm::conflicting_functions(line, "orientation axes, A2..C3 and ORIRESET together"));
        }
        if let Some(values) = ori.reset {
            // ORIRESET: the orientation axes linearly to the given or the rest positions.
            let rest = self.orientation_rest().unwrap_or_default();
            for (role, slot) in slots.iter().enumerate() {
                if let Some(k) = slot {
                    end[*k] = values[role].unwrap_or(rest[role]);
                }
            }
            return Ok(None);
        }
        let modal = self.modal.ori;
        let path_relative = ori.path_relative() || (modal.interpolation == OriInterpolation::Path && tangent.is_some());
        if ori.programmed() && path_relative && ori.path_relative() {
            return Err(Alarm::conflicting_functions(line, "LEAD/TILT together with A2..C3"));
        }
        if ori.upper.iter().any(Option::is_some) {
            if modal_interpolation != OriInterpolation::Curve {
                return Err(Alarm::value_out_of_range(line, "XH/YH/ZH need ORICURVE (and MD21104 = 1)"));
            }
            if ori.programmed() || ori.path_relative() || rotary_words {
                return Err(Alarm::conflicting_functions(line, "XH/YH/ZH together with another orientation"));
            }
            let circle = matches!(words.motion.unwrap_or(self.modal.motion), MotionMode::Cw | MotionMode::Ccw);
            return self.curve_orientation(ori, cfg, frame, start, end, active, machine, circle, line);
        }
        let target = if path_relative && !ori.programmed() && !rotary_words {
            if modal.lead.abs() > cfg.ori.max_lead_angle {
                return Err(angle_too_large(line, true, modal.lead, cfg.ori.max_lead_angle));
            }
            if modal.tilt.abs() > cfg.ori.max_tilt_angle {
                return Err(angle_too_large(line, false, modal.tilt, cfg.ori.max_tilt_angle));
            }
            let Some(t) = tangent else {
                return Err(Alarm::value_out_of_range(line, "LEAD/TILT need a motion of the tool tip"));
            };
            let (t, n) = match modal.reference {
                OriReference::Workpiece => (frame.rotate_direction(t), frame.rotate_direction(modal.normal)),
                OriReference::Machine => (frame.rotate_direction(t), modal.normal),
            };
            let bcs = lead_and_tilt(t, n, modal.lead, modal.tilt)
                .ok_or_else(|| Alarm::value_out_of_range(line, "LEAD/TILT: the path runs along the surface normal"))?;
            active.trafo.orientation_axes(&bcs, machine, end).map_err(|_| {
                Alarm::value_out_of_range(line, "orientation not reachable by the rotary axes of the transformation")
            })?;
            Some(bcs)
        } else if ori.programmed() {
            let wcs = if ori.vector.iter().any(Option::is_some) {
                normalize(&ori.vector.map(|c| c.unwrap_or(0.0)))
                    .ok_or_else(|| Alarm::value_out_of_range(line, "orientation vector A3/B3/C3 of length 0"))?
            } else {
                let def = if cfg.ori.ori_def_with_g_code {
                    modal.angles
                } else if cfg.ori.orientation_is_euler {
                    AngleDefinition::Euler
                } else {
                    AngleDefinition::Rpy
                };
                from_angles(def, ori.angles.map(|a| a.unwrap_or(0.0)), cfg).ok_or_else(|| {
                    Alarm::value_out_of_range(line, "ORIAX_TURN_TAB names no reference axis for ORIVIRT")
                })?
            };
            let bcs = match modal.reference {
                OriReference::Workpiece => frame.rotate_direction(wcs),
                OriReference::Machine => wcs,
            };
            active.trafo.orientation_axes(&bcs, machine, end).map_err(|_| {
                Alarm::value_out_of_range(line, "orientation not reachable by the rotary axes of the transformation")
            })?;
            Some(bcs)
        } else if rotary_words {
            let mut m = *machine;
            for k in slots.iter().flatten().chain(&seventh) {
                m[*k] = end[*k];
            }
            active.trafo.orientation(&m)
        } else if seventh_moves && modal_interpolation != OriInterpolation::Axes {
            // Vector interpolation keeps the orientation relative to the workpiece while the
            // 7th axis turns it (F2 §3.7.6: only ORIMKS/ORIAXES leave the tool axes alone).
            // Whatever the interpolation type, a constant orientation is the path.
            let Some(o) = active.trafo.orientation(machine) else { return Ok(None) };
            active.trafo.orientation_axes(&o, machine, end).map_err(|_| {
                Alarm::value_out_of_range(line, "orientation not reachable by the rotary axes of the transformation")
            })?;
            return Ok(OriPath::cone(o, o, 0.0));
        } else {
            return Ok(None);
        };
        let Some(o_end) = target else { return Ok(None) };
        let interpolation = if path_relative { OriInterpolation::Vector } else { modal_interpolation };
        let mut m_start = *machine;
        for k in slots.iter().flatten() {
            m_start[*k] = start[*k];
        }
        let Some(o_start) = active.trafo.orientation(&m_start) else { return Ok(None) };
        let interpolation = match &active.trafo {
            AnyTrafo::Traori(t)
                if interpolation == OriInterpolation::Vector
                    && pole_start_as_axes(t, cfg, &t.in_chain_frame(&o_start, machine)) =>
            {
                OriInterpolation::Axes
            }
            _ => interpolation,
        };
        let vector =
            matches!(interpolation, OriInterpolation::Vector | OriInterpolation::Path | OriInterpolation::Curve);
        let o_end = match (&active.trafo, vector) {
            // The pole is a direction of the tool kinematics: tested in its frame (7-axis: with
            // the table where the block starts).
            (AnyTrafo::Traori(t), true) => {
                match through_pole(t, t.in_chain_frame(&o_start, machine), t.in_chain_frame(&o_end, machine))
                    .map(|o| t.in_workpiece_frame(&o, machine))
                {
                    Some(o) => {
                        // Through the pole: the end moves onto the start's meridian, which the
                        // rotary axes reach with the pole axis where it stands.
                        active.trafo.orientation_axes(&o, machine, end).map_err(|_| {
                            Alarm::value_out_of_range(
                                line,
                                "orientation not reachable by the rotary axes of the transformation",
                            )
                        })?;
                        o
                    }
                    None => o_end,
                }
            }
            _ => o_end,
        };
        match interpolation {
            OriInterpolation::Axes => Ok(None),
            // ORICURVE without XH/YH/ZH: the end orientation by a great circle.
            OriInterpolation::Vector | OriInterpolation::Path | OriInterpolation::Curve => {
                match OriPath::great_circle(o_start, o_end).map_err(|_| antiparallel(line))? {
                    // A constant orientation on a turning workpiece still needs the tool axes
                    // solved at every point.
                    None if seventh_moves => Ok(OriPath::cone(o_start, o_start, 0.0)),
                    p => Ok(p),
                }
            }
            OriInterpolation::Cone { clockwise } => {
                let given = ori.cone_axis.map(|c| c.unwrap_or(0.0));
                let k = normalize(&given).ok_or_else(|| {
                    Alarm::value_out_of_range(line, "cone interpolation needs the cone axis A6/B6/C6")
                })?;
                let k = if modal.reference == OriReference::Workpiece { frame.rotate_direction(k) } else { k };
                let sweep = cone_sweep(&k, &o_start, &o_end, !clockwise).ok_or_else(|| {
                    Alarm::value_out_of_range(line, "cone interpolation: an orientation lies on the cone axis")
                })?;
                Ok(OriPath::cone(o_start, k, sweep))
            }
            OriInterpolation::ConeIntermediate => {
                // All three must differ; an intermediate parallel to the start or the end
                // orientation makes it a great circle (F2 §3.11.3).
                let given = ori.intermediate.map(|c| c.unwrap_or(0.0));
                let oi = normalize(&given).ok_or_else(|| {
                    Alarm::value_out_of_range(line, "ORICONIO needs the intermediate orientation A7/B7/C7")
                })?;
                let oi = if modal.reference == OriReference::Workpiece { frame.rotate_direction(oi) } else { oi };
                let parallel = |a: &Vec3, b: &Vec3| norm(&cross(a, b)) < 1e-9;
                if parallel(&oi, &o_start) || parallel(&oi, &o_end) {
                    return OriPath::great_circle(o_start, o_end).map_err(|_| antiparallel(line));
                }
                let (k, sweep) = cone_through(&o_start, &oi, &o_end).ok_or_else(|| {
                    Alarm::value_out_of_range(line, "ORICONIO: start and end orientation must differ")
                })?;
                Ok(OriPath::cone(o_start, k, sweep))
            }
            OriInterpolation::ConeTangential => {
                let t = modal.last_change.ok_or_else(|| {
                    Alarm::value_out_of_range(
                        line,
                        "ORICONTO needs a preceding block whose orientation moved as a vector (the tangent)",
                    )
                })?;
                match cone_tangent(&o_start, &t, &o_end) {
                    Some((k, sweep)) => Ok(OriPath::cone(o_start, k, sweep)),
                    // The end lies on the great circle the motion is heading along.
                    None => OriPath::great_circle(o_start, o_end).map_err(|_| antiparallel(line)),
                }
            }
            OriInterpolation::Unmodelled(name) => Err(Alarm::unknown_name(line, name)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-9)
    }

    #[test]
    fn euler_and_rpy_give_the_reference_vectors() {
        let preset = crate::machine_data::presets::find("mill-3axis").unwrap();
        let cfg = crate::machine_data::MachineData::default().apply_text(preset.text).unwrap();
        let h = std::f64::consts::FRAC_1_SQRT_2;
        // Euler: A2 about Z turns the tilt plane, B2 tilts away from Z; C2 has no effect.
        assert!(close(from_angles(AngleDefinition::Euler, [90.0, 45.0, 33.0], &cfg).unwrap(), [h, 0.0, h]));
        // RPY: B2 = 90 tilts Z onto X; then C2 = 90 about Z carries it onto Y.
        assert!(close(from_angles(AngleDefinition::Rpy, [0.0, 90.0, 0.0], &cfg).unwrap(), [1.0, 0.0, 0.0]));
        assert!(close(from_angles(AngleDefinition::Rpy, [0.0, 90.0, 90.0], &cfg).unwrap(), [0.0, 1.0, 0.0]));
        // RPY: A2 = 90 about X turns Z onto −Y.
        assert!(close(from_angles(AngleDefinition::Rpy, [90.0, 0.0, 0.0], &cfg).unwrap(), [0.0, -1.0, 0.0]));
    }
}

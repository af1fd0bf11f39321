//! The interpreter's toolholder words and the swivel cycle CYCLE800 as a predefined procedure
//! (REFERENCE §7.2, §8). The math lives in [`crate::interp::tools::toolholder`] and the orientation chain.
//!
//! What is written where (this product's assignment; REFERENCE §8.2 leaves it open):
//! * `$P_PARTFRAME`: the table offset of a P/M holder, with PAROT its rotation.
//! * `$P_TOOLFRAME`: TOROT/TOFRAME and the swivelled plane of CYCLE800,
//!   `TRANS(X0,Y0,Z0) : ROT(R) : TRANS(X1,Y1,Z1)`. CYCLE800 computes its frame through TOROT
//!   (SD42980 TOFRAME_MODE, "frame definition for TOROT, PAROT = 2000 swivel", IM9 12/2017
//!   p.566), and this frame lies below the programmable frame, so TRANS/ROT programmed after a
//!   swivel act on the swivelled plane.
//! * `$P_CYCFRAME` stays for other cycles.
//!
//! CYCLE800 parameters (`_FR, _TC, _ST, _MODE, _X0, _Y0, _Z0, _A, _B, _C, _X1, _Y1, _Z1, _DIR,
//! _FR_I, _DMODE`): see [`SwivelArgs`]. Decisions where the sources are silent:
//! * Axis by axis: `_A`, `_B`, `_C` are the angles of the 1st, 2nd and 3rd rotation of the
//!   sequence, each about the already rotated axes: `R = R_1(A)·R_2(B)·R_3(C)`.
//! * Solid angle: `R = Rz(A)·Ry(B)`, then `C` about the new Z.
//! * Projection angle: `_MODE` bits 1–0 and 3–2 name the two projection axes (angles `_A`,
//!   `_B`), bits 5–4 the axis of the rotation in the plane (`_C`), which turns about the new
//!   axis of that name. The construction is ROTS' (REFERENCE §8.2).
//! * Direct: `_A`, `_B` are the positions of rotary axes 1 and 2.
//! * `_DIR` −1 minus (lower value of the direction-reference axis), +1 plus, 0 compute and set
//!   the frame without moving the rotary axes. If only one solution is reachable it is taken.
//! * `_ST` units digit 0 new, 1 additive; the tens digit 1 (`_ST` = 10, 11) asks for tool
//!   tracking, which needs an active TRAORI: with TRAORI the rotary axes always move with the
//!   tool tip held (the transformation tracks), without it only the rotary axes move.
//! * Retraction `_FR`: 1 machine Z to `$TC_CARR40`, 2 Z then X/Y to `$TC_CARR38/39` (machine
//!   coordinates), 4 along the tool away from the workpiece until the first linear axis reaches
//!   its software limit, 5 by `_FR_I` along the tool; all in rapid traverse before swivelling.
//! * Deselection (`CYCLE800()` or `_TC="0"`): TCARR=0, PAROTOF, TOROTOF; nothing moves.

use crate::alarm::Alarm;
use crate::interp::eval::value::Value;
use crate::interp::frames::frame::{self, Frame};
use crate::interp::modal::Words;
use crate::interp::tools::toolholder::{self, Holder, TcoMode};
use crate::interp::{Interpreter, Item, check_software_limits, compensation::trc};
use crate::kinematics::Vec3;
use crate::kinematics::orient::vec3::{cross, dot, normalize, unit};
use crate::kinematics::{AnyTrafo, Transformation};
use crate::machine_data::{Carrier, MachineConfig};
use crate::motion::{AxisLimit, Feed, Move, Path};

/// CYCLE800 alarms. 61186/61187 are the sourced ones (IM9 06/2019 p.581, shown only with
/// MD55410 bits 0/1); 61184 "no solution possible" is recalled from the cycle's alarm list
/// (I-recall); 61181 (swivel data set unknown), 61183 (retraction mode) and 61182 (bad
/// parameter) are this product's choices in the cycle alarm range.
pub mod alarms {
    pub const UNKNOWN_DATA_SET: u32 = 61181;
    pub const BAD_PARAMETER: u32 = 61182;
    pub const RETRACTION: u32 = 61183;
    pub const NO_SOLUTION: u32 = 61184;
    pub const ROTATION_IN_WORK_OFFSET: u32 = 61186;
    pub const ROTATION_IN_BASE: u32 = 61187;
}

/// 14150 (toolholder number not defined or larger than MD18088) and 14152 (toolholder:
/// invalid orientation) are recalled from the NCK alarm list (I-recall); 14153 is sourced.
pub const ALARM_HOLDER_NUMBER: u32 = 14150;
pub const ALARM_HOLDER_ORIENTATION: u32 = 14152;

fn cycle_alarm(line: u32, number: u32, text: &str) -> Alarm {
    Alarm::user(line, number, &format!("Channel 1 block {line} CYCLE800: {text}"))
}

/// The swivel modes of `_MODE` bits 7–6.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SwivelMode {
    /// Rotations about these geometry axes (0 = X), in order.
    AxisByAxis([usize; 3]),
    Solid,
    /// Projection axes (1st, 2nd) and the in-plane rotation axis.
    Projection([usize; 3]),
    Direct,
}

/// The evaluated parameters of one CYCLE800 call.
#[derive(Debug, Clone, PartialEq)]
pub struct SwivelArgs {
    /// `_FR` retraction mode 0, 1, 2, 4, 5.
    pub retract: i64,
    /// `_TC` swivel data set name or number ("" = the active one).
    pub data_set: String,
    /// `_ST`: units digit additive, tens digit tracking.
    pub additive: bool,
    pub tracking: bool,
    pub mode: SwivelMode,
    pub p0: Vec3,
    pub angles: [f64; 3],
    pub p1: Vec3,
    /// `_DIR`: −1, 0, +1.
    pub dir: i64,
    /// `_FR_I` incremental retraction path.
    pub retract_by: f64,
}

/// Decodes the `_MODE` value.
pub fn decode_mode(mode: i64) -> Option<SwivelMode> {
    if !(0..256).contains(&mode) {
        return None;
    }
    let axis = |shift: i64| match (mode >> shift) & 3 {
        0 => None,
        a => Some(a as usize - 1),
    };
    let seq = [axis(0), axis(2), axis(4)];
    let three = || {
        let [Some(a), Some(b), Some(c)] = seq else { return None };
        (a != b && b != c && a != c).then_some([a, b, c])
    };
    match mode >> 6 {
        0 => three().map(SwivelMode::AxisByAxis),
        1 => Some(SwivelMode::Solid),
        2 => three().map(SwivelMode::Projection),
        _ => Some(SwivelMode::Direct),
    }
}

/// `None` for a deselection (`CYCLE800()`, `_TC="0"`).
pub fn parse(values: &[Option<Value>], line: u32) -> Result<Option<SwivelArgs>, Alarm> {
    if values.len() > 16 {
        return Err(Alarm::syntax(line, "CYCLE800 takes at most 16 parameters"));
    }
    if values.iter().all(Option::is_none) {
        return Ok(None);
    }
    let bad = |what: &str| cycle_alarm(line, alarms::BAD_PARAMETER, what);
    let num = |i: usize| -> Result<f64, Alarm> {
        match values.get(i).cloned().flatten() {
            None => Ok(0.0),
            Some(v) => v.as_f64().map_err(|_| bad(&format!("parameter {} must be a number", i + 1))),
        }
    };
    let int = |i: usize| -> Result<i64, Alarm> {
        let v = num(i)?;
        if v.fract() != 0.0 || v.abs() > 1e9 {
            return Err(bad(&format!("parameter {} must be a whole number, not {v}", i + 1)));
        }
        Ok(v as i64)
    };
    let data_set = match values.get(1).cloned().flatten() {
        None => String::new(),
        Some(Value::Str(s)) | Some(Value::Axis(s)) => s,
        Some(v) => {
            let n = v.as_f64().map_err(|_| bad("_TC must be a name or a number"))?;
            format!("{n}")
        }
    };
    if data_set.trim() == "0" {
        return Ok(None);
    }
    let retract = int(0)?;
    if ![0, 1, 2, 4, 5].contains(&retract) {
        return Err(cycle_alarm(line, alarms::RETRACTION, &format!("_FR={retract} (0, 1, 2, 4 or 5)")));
    }
    let retract_by = num(14)?;
    if retract == 5 && retract_by < 0.0 {
        return Err(cycle_alarm(line, alarms::RETRACTION, &format!("negative retraction path _FR_I={retract_by}")));
    }
    let st = int(2)?;
    if st < 0 || st % 10 > 1 {
        return Err(bad(&format!("_ST={st}: units digit 0 (new) or 1 (additive)")));
    }
    let raw_mode = int(3)?;
    let mode = decode_mode(raw_mode).ok_or_else(|| bad(&format!("_MODE={raw_mode}")))?;
    let dir = int(13)?;
    if !(-1..=1).contains(&dir) {
        return Err(bad(&format!("_DIR={dir} (-1, 0, +1)")));
    }
    let v3 = |i: usize| -> Result<Vec3, Alarm> { Ok([num(i)?, num(i + 1)?, num(i + 2)?]) };
    Ok(Some(SwivelArgs {
        retract,
        data_set,
        additive: st % 10 == 1,
        tracking: (st / 10) % 10 == 1,
        mode,
        p0: v3(4)?,
        angles: v3(7)?,
        p1: v3(10)?,
        dir,
        retract_by,
    }))
}

fn mul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn transpose(a: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

fn from_columns(c: [Vec3; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|r| std::array::from_fn(|k| c[k][r]))
}

/// The rotation of the swivelled plane (columns: its axes in the old system) for the modes
/// that define it by angles; `None` for direct swivelling (the kinematics decides).
pub fn rotation(mode: SwivelMode, a: [f64; 3]) -> Option<[[f64; 3]; 3]> {
    Some(match mode {
        SwivelMode::AxisByAxis(seq) => {
            (0..3).fold(frame::rpy(0.0, 0.0, 0.0), |r, i| mul(&r, &frame::about_axis(seq[i], a[i])))
        }
        SwivelMode::Solid => {
            mul(&mul(&frame::about_axis(2, a[0]), &frame::about_axis(1, a[1])), &frame::about_axis(2, a[2]))
        }
        SwivelMode::Projection([i, j, k]) => {
            // The cyclic pair (p, q = p + 1): new p = R_q(angle_q)·e_p stays in the old p-r
            // plane; q' = R_p(angle_p)·e_q lies in the old q-r plane; the normal r = p × q.
            let angle = |axis: usize| {
                if axis == i {
                    a[0]
                } else if axis == j {
                    a[1]
                } else {
                    0.0
                }
            };
            let p = if (i + 1) % 3 == j { i } else { j };
            let q = (p + 1) % 3;
            let r = (p + 2) % 3;
            let rot = |axis: usize, v: Vec3| {
                let m = frame::about_axis(axis, angle(axis));
                std::array::from_fn::<f64, 3, _>(|row| dot(&m[row], &v))
            };
            let new_p = rot(q, unit(p));
            let q_dir = rot(p, unit(q));
            let new_r = normalize(&cross(&new_p, &q_dir))?;
            let new_q = cross(&new_r, &new_p);
            let mut cols = [[0.0; 3]; 3];
            cols[p] = new_p;
            cols[q] = new_q;
            cols[r] = new_r;
            mul(&from_columns(cols), &frame::about_axis(k, a[2]))
        }
        SwivelMode::Direct => return None,
    })
}

fn holder_alarm(line: u32, number: u32, text: &str) -> Alarm {
    Alarm::user(line, number, &format!("Channel 1 block {line} toolholder: {text}"))
}

/// Alarm 14153: invalid kinematic type `$TC_CARR23` (PGA 04.00 system-variable list).
pub fn invalid_kind(line: u32, value: &str) -> Alarm {
    holder_alarm(line, crate::machine_data::carrier::ALARM_INVALID_KIND, &format!("invalid kinematic type {value}"))
}

impl Interpreter {
    /// The active toolholder's data.
    pub(in crate::interp) fn carrier<'a>(&self, cfg: &'a MachineConfig) -> Option<&'a Carrier> {
        (self.holder.number != 0).then(|| cfg.carriers.get(&self.holder.number)).flatten()
    }

    /// The angles TCOABS uses: `$TC_CARR13/14`, or the position of the axis 21/22 names.
    fn stored_angles(&self, c: &Carrier, cfg: &MachineConfig) -> [f64; 2] {
        std::array::from_fn(|i| match c.axes[i].as_deref().and_then(|a| cfg.program_axis(a)) {
            Some(k) => self.pos[k],
            None => c.angles[i],
        })
    }

    /// G groups 22, 42, 52, 53, TCARR and CYCLE800 of a block.
    pub(in crate::interp) fn holder_block(
        &mut self,
        words: &Words,
        cfg: &MachineConfig,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        if let Some(c) = words.cut {
            self.holder.cut = c;
        }
        let mut changed = false;
        if let Some(t) = &words.tcarr {
            let number = match t {
                Value::Str(name) => cfg
                    .carriers
                    .values()
                    .find(|c| !c.name.is_empty() && c.name.eq_ignore_ascii_case(name))
                    .map(|c| c.number),
                v => {
                    let n = v.as_f64().map_err(|e| Alarm::type_error(line, &e.0))?;
                    (n.fract() == 0.0 && (0.0..=99.0).contains(&n)).then_some(n as u32)
                }
            };
            let number = number
                .filter(|n| *n == 0 || cfg.carriers.contains_key(n))
                .ok_or_else(|| holder_alarm(line, ALARM_HOLDER_NUMBER, &format!("TCARR={t:?} is not defined")))?;
            self.holder.number = number;
            changed = true;
        }
        if let Some(t) = words.tco {
            self.holder.tco = t;
            changed = true;
        }
        if let Some(p) = words.parot {
            self.holder.parot = p;
            changed = true;
        }
        // A plane change only swaps the tool's own length components (every block recomputes
        // the tool vector); the holder's angles stay.
        if changed {
            self.update_holder(cfg, line)?;
        }
        if let Some(code) = words.g53_group {
            self.tool_frame(code, cfg);
        }
        if let Some(values) = &words.swivel {
            self.cycle800(values, cfg, line, out)?;
        }
        Ok(())
    }

    /// Recomputes the holder's angles (TCOABS or TCOFR) and `$P_PARTFRAME`.
    fn update_holder(&mut self, cfg: &MachineConfig, line: u32) -> Result<(), Alarm> {
        let Some(c) = self.carrier(cfg).cloned() else {
            self.holder.second = None;
            self.holder.solutions = 0;
            self.system.part = Frame::identity();
            return Ok(());
        };
        let stored = self.stored_angles(&c, cfg);
        match self.holder.tco {
            TcoMode::Abs => {
                self.holder.angles = stored;
                self.holder.second = None;
                self.holder.solutions = 1;
            }
            TcoMode::Frame(axis) => {
                let geo = &cfg.geo_axes;
                let s = &self.system;
                let (base, settable) =
                    (crate::interp::basic_frame(cfg), crate::interp::work_offset(cfg, self.modal.work_offset));
                let above = frame::chain(&[&base, &settable, &s.tool, &self.pframe, &s.cycle], geo);
                let target = above.rotate_direction(unit(axis));
                let b = toolholder::base_orientation(self.modal.plane);
                let mut sols = toolholder::solve(&c, target, b, stored);
                let dist = |p: &[f64; 2]| (p[0] - stored[0]).abs() + (p[1] - stored[1]).abs();
                sols.sort_by(|x, y| dist(x).total_cmp(&dist(y)));
                let first = *sols.first().ok_or_else(|| {
                    holder_alarm(line, ALARM_HOLDER_ORIENTATION, "TCOFR: the frame's direction cannot be reached")
                })?;
                self.holder.angles = first;
                self.holder.second = sols.get(1).copied();
                self.holder.solutions = sols.len() as u8;
            }
        }
        self.system.part = toolholder::part_frame(&c, self.holder.angles, self.holder.parot, &cfg.geo_axes);
        Ok(())
    }

    /// The tool length vector through the active holder.
    pub(in crate::interp) fn holder_tool(
        &self,
        cfg: &MachineConfig,
        mut plain: crate::motion::AxisVec,
    ) -> crate::motion::AxisVec {
        let Some(c) = self.carrier(cfg) else { return plain };
        let geo = &cfg.geo_axes;
        let l: Vec3 = std::array::from_fn(|g| geo[g].map_or(0.0, |k| plain[k]));
        let eff = toolholder::tool_length(c, self.holder.angles, l);
        for (g, k) in geo.iter().enumerate() {
            if let Some(k) = k {
                plain[*k] = eff[g];
            }
        }
        plain
    }

    /// The tool direction in the parent system of `$P_TOOLFRAME` (after $P_PARTFRAME, the
    /// basic and the settable frame): from TRAORI, else from the holder, else the plane's.
    fn tool_direction(&self, cfg: &MachineConfig) -> Vec3 {
        let b = toolholder::base_orientation(self.modal.plane);
        let bcs = match self.orientation_transformation() {
            Some((active, machine)) => active.trafo.orientation(machine).unwrap_or(b),
            None => match self.carrier(cfg) {
                Some(c) => toolholder::machine_orientation(c, self.holder.angles, b),
                None => b,
            },
        };
        self.below_tool_frame(cfg).unrotate_direction(bcs)
    }

    /// $P_PARTFRAME : $P_SETFRAME : $P_EXTFRAME : $P_ACTBFRAME : $P_IFRAME.
    fn below_tool_frame(&self, cfg: &MachineConfig) -> Frame {
        let (base, settable) = (crate::interp::basic_frame(cfg), self.iframe(cfg));
        let s = &self.system;
        frame::chain(&[&s.part, &s.set, &s.ext, &base, &settable], &cfg.geo_axes)
    }

    /// G group 53: TOROT/TOFRAME (codes 2..9) write `$P_TOOLFRAME`, TOROTOF (1) deletes it.
    fn tool_frame(&mut self, code: i64, cfg: &MachineConfig) {
        self.holder.g53 = code;
        if code == 1 {
            self.system.tool = Frame::identity();
            return;
        }
        // Tool along Z (TOROT, TOROTZ, TOFRAME, TOFRAMEZ), Y or X.
        let axis = match code {
            4 | 8 => 1,
            5 | 9 => 0,
            _ => 2,
        };
        let r = align(self.tool_direction(cfg), axis, cfg.toframe_mode);
        if code >= 6 {
            self.system.tool = Frame::rotation(r);
        } else {
            self.system.tool.lin = r;
        }
    }
}

/// The rotation whose axis `a` (0 = X) is the unit direction `t` and whose free rotation about
/// it follows SD42980 TOFRAME_MODE: 2001 the new abscissa stays in the old abscissa-tool plane,
/// 2002 the new ordinate in the old ordinate-tool plane, otherwise (2000, and 0/1 where
/// MD21110 is not modelled separately) the smallest rotation that takes the old axis onto `t`
/// (this product's reading of "X/Y compromise").
pub fn align(t: Vec3, a: usize, mode: i64) -> [[f64; 3]; 3] {
    let (abs, ord) = ((a + 1) % 3, (a + 2) % 3);
    let from_abscissa = |x: Vec3| {
        let mut cols = [[0.0; 3]; 3];
        cols[a] = t;
        cols[abs] = x;
        cols[ord] = cross(&t, &x);
        from_columns(cols)
    };
    match mode {
        2001 => {
            if let Some(x) = normalize(&cross(&unit(ord), &t)) {
                return from_abscissa(x);
            }
        }
        2002 => {
            if let Some(y) = normalize(&cross(&t, &unit(abs))) {
                return from_abscissa(cross(&y, &t));
            }
        }
        _ => {}
    }
    let e = unit(a);
    let axis = cross(&e, &t);
    let (s, c) = (crate::kinematics::orient::vec3::norm(&axis), dot(&e, &t));
    let r = match normalize(&axis) {
        Some(k) => crate::kinematics::orient::vec3::Rot::about(&k, s.atan2(c)),
        // Parallel: identity; antiparallel: half a turn about the abscissa.
        None if c > 0.0 => crate::kinematics::orient::vec3::Rot::IDENTITY,
        None => crate::kinematics::orient::vec3::Rot::about(&unit(abs), std::f64::consts::PI),
    };
    r.0
}

impl Interpreter {
    /// CYCLE800: swivel the plane (and the rotary axes), or deselect.
    fn cycle800(
        &mut self,
        values: &[Option<Value>],
        cfg: &MachineConfig,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let Some(args) = parse(values, line)? else {
            self.holder = Holder { cut: self.holder.cut, ..Holder::default() };
            self.system.part = Frame::identity();
            self.system.tool = Frame::identity();
            return Ok(());
        };
        let traori = self.orientation_transformation().and_then(|(a, _)| match &a.trafo {
            AnyTrafo::Traori(t) => Some(t.clone()),
            _ => None,
        });
        // The swivel data set: by name or number, or the active one.
        let carrier = if args.data_set.is_empty() {
            self.carrier(cfg).cloned()
        } else {
            let by_name = cfg.carriers.values().find(|c| c.name.eq_ignore_ascii_case(&args.data_set));
            let by_number = args.data_set.parse::<f64>().ok().and_then(|n| cfg.carriers.get(&(n as u32)));
            by_name.or(by_number).cloned()
        };
        if carrier.is_none() && traori.is_none() {
            return Err(cycle_alarm(
                line,
                alarms::UNKNOWN_DATA_SET,
                &format!("swivel data set \"{}\" is not defined", args.data_set),
            ));
        }
        self.check_frame_rotations(cfg, line)?;

        let geo = cfg.geo_axes;
        let below = self.below_tool_frame_without_part(cfg);
        let plane_tool = toolholder::base_orientation(self.modal.plane);
        let old = if args.additive { self.system.tool.clone() } else { Frame::identity() };
        let limits = AxisLimit::for_channel(cfg);

        // Rotary axis positions and the frame's rotation.
        let mut rotary: Vec<(usize, f64)> = Vec::new();
        let (rot, chosen) = match (&carrier, &traori, rotation(args.mode, args.angles)) {
            (_, Some(t), r) => {
                let r = r.ok_or_else(|| {
                    cycle_alarm(line, alarms::BAD_PARAMETER, "direct swivelling needs a swivel data set, not TRAORI")
                })?;
                let target = below.then(&old, &geo).rotate_direction(mul_vec(&r, &plane_tool));
                let target = self.system.part.rotate_direction(target);
                let sols = t.solutions(&target).map_err(|_| no_solution(line))?;
                let slots = t.orientation_slots();
                // The data set's direction reference, else the first rotary axis.
                let i = carrier.as_ref().map_or(0, Carrier::direction_reference);
                let s = match args.dir {
                    1 => {
                        if sols[1][i] >= sols[0][i] {
                            sols[1]
                        } else {
                            sols[0]
                        }
                    }
                    _ => {
                        if sols[1][i] < sols[0][i] {
                            sols[1]
                        } else {
                            sols[0]
                        }
                    }
                };
                for (role, slot) in slots.iter().enumerate() {
                    if let Some(k) = slot {
                        rotary.push((*k, s[role]));
                    }
                }
                (r, None)
            }
            (Some(c), None, Some(r)) => {
                let target = below.then(&old, &geo).rotate_direction(mul_vec(&r, &plane_tool));
                let near = self.stored_angles(c, cfg);
                let sols = toolholder::solve(c, target, plane_tool, near);
                let i = c.direction_reference();
                let pick = match args.dir {
                    1 => sols.iter().max_by(|a, b| a[i].total_cmp(&b[i])),
                    _ => sols.iter().min_by(|a, b| a[i].total_cmp(&b[i])),
                };
                let pos = *pick.ok_or_else(|| no_solution(line))?;
                let second = sols.iter().find(|s| **s != pos).copied();
                self.holder.second = second;
                self.holder.solutions = sols.len() as u8;
                (r, Some(pos))
            }
            (Some(c), None, None) => {
                let pos = [args.angles[0], args.angles[1]];
                for (i, p) in pos.iter().enumerate() {
                    if let Some((lo, hi)) = c.limits[i].filter(|_| c.has_axis(i))
                        && !(lo - 1e-9..=hi + 1e-9).contains(p)
                    {
                        return Err(no_solution(line));
                    }
                }
                // The tool system as seen from the workpiece, without the frames below.
                let rel = toolholder::relative_rotation(c, pos);
                let r = mul(&transpose(&below.then(&old, &geo).lin), &rel);
                self.holder.second = None;
                self.holder.solutions = 1;
                (r, Some(pos))
            }
            (None, None, _) => unreachable!("checked above"),
        };

        // Retraction, then the rotary axes, in rapid traverse; nothing moves when _DIR = 0.
        let moves = args.dir != 0 || matches!(args.mode, SwivelMode::Direct);
        if moves {
            self.trc.flush(&limits, out)?;
            self.retract(&args, carrier.as_ref(), cfg, line, out)?;
        }
        if let (Some(c), Some(pos), None) = (&carrier, chosen, &traori) {
            for (i, p) in pos.iter().enumerate() {
                if let Some(k) = c.axes[i].as_deref().and_then(|a| cfg.program_axis(a)).filter(|_| c.has_axis(i)) {
                    rotary.push((k, *p));
                }
            }
            self.holder.number = c.number;
            self.holder.angles = pos;
            self.holder.tco = TcoMode::Abs;
            self.holder.parot = c.kind != crate::machine_data::CarrierKind::Tool;
        }

        // The swivelled plane.
        let mut t0 = [0.0; crate::machine_data::registry::MAX_CHANNEL_AXES];
        let mut t1 = t0;
        for (g, k) in geo.iter().enumerate() {
            if let Some(k) = k {
                t0[*k] = args.p0[g];
                t1[*k] = args.p1[g];
            }
        }
        let s = Frame::translation(t0).then(&Frame::rotation(rot), &geo).then(&Frame::translation(t1), &geo);
        self.system.tool = old.then(&s, &geo);
        self.holder.g53 = 2;
        if let Some(c) = self.carrier(cfg).cloned() {
            self.system.part = toolholder::part_frame(&c, self.holder.angles, self.holder.parot, &geo);
        }
        self.note_offsets_before_change();
        self.offsets.frame = self.active_frame(cfg);
        let plain = crate::interp::tool_vector(cfg, &self.modal, self.offsets.t, self.offsets.d);
        self.offsets.tool = self.holder_tool(cfg, plain);

        if moves && !rotary.is_empty() {
            let start = self.pos;
            let mut end = start;
            for (k, v) in &rotary {
                end[*k] = *v;
            }
            self.rapid(start, end, cfg, line, out)?;
        }
        Ok(())
    }

    /// 61186/61187 when MD55410 asks for them: rotations in the active settable frame or in
    /// the basic frame.
    fn check_frame_rotations(&self, cfg: &MachineConfig, line: u32) -> Result<(), Alarm> {
        let mask = cfg.swivel_alarm_mask;
        let rotated = |f: &Frame| f.couples_axes();
        let settable = crate::interp::work_offset(cfg, self.modal.work_offset);
        let base = crate::interp::basic_frame(cfg);
        if mask & 1 != 0 && rotated(&settable) {
            return Err(cycle_alarm(
                line,
                alarms::ROTATION_IN_WORK_OFFSET,
                "active work offset and base contain rotations",
            ));
        }
        if mask & 2 != 0 && rotated(&base) {
            return Err(cycle_alarm(
                line,
                alarms::ROTATION_IN_BASE,
                "active base and base reference contain rotations",
            ));
        }
        Ok(())
    }

    /// $P_SETFRAME : $P_EXTFRAME : $P_ACTBFRAME : $P_IFRAME (the frames between the part frame
    /// and the tool frame).
    fn below_tool_frame_without_part(&self, cfg: &MachineConfig) -> Frame {
        let (base, settable) = (crate::interp::basic_frame(cfg), self.iframe(cfg));
        let s = &self.system;
        frame::chain(&[&s.set, &s.ext, &base, &settable], &cfg.geo_axes)
    }

    /// The retraction of `_FR` as rapid moves in machine (channel axis) coordinates.
    fn retract(
        &mut self,
        args: &SwivelArgs,
        c: Option<&Carrier>,
        cfg: &MachineConfig,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let geo = cfg.geo_axes;
        let retract_pos = c.map_or([0.0; 3], |c| c.retract);
        match args.retract {
            1 | 2 => {
                let Some(z) = geo[2] else { return Ok(()) };
                let start = self.pos;
                let mut end = start;
                end[z] = retract_pos[2];
                self.rapid(start, end, cfg, line, out)?;
                if args.retract == 2 {
                    let start = self.pos;
                    let mut end = start;
                    for g in 0..2 {
                        if let Some(k) = geo[g] {
                            end[k] = retract_pos[g];
                        }
                    }
                    self.rapid(start, end, cfg, line, out)?;
                }
            }
            4 | 5 => {
                let b = toolholder::base_orientation(self.modal.plane);
                let o = c.map_or(b, |c| toolholder::machine_orientation(c, self.holder.angles, b));
                let distance = if args.retract == 5 {
                    args.retract_by
                } else {
                    // Up to the first software limit of a linear axis along the tool.
                    let mut d = f64::INFINITY;
                    for g in 0..3 {
                        let Some(k) = geo[g] else { continue };
                        let ax = cfg.axis(k);
                        if o[g] > 1e-12 {
                            d = d.min((ax.limit_plus - self.pos[k]) / o[g]);
                        } else if o[g] < -1e-12 {
                            d = d.min((ax.limit_minus - self.pos[k]) / o[g]);
                        }
                    }
                    if !d.is_finite() || d < 0.0 {
                        return Err(cycle_alarm(line, alarms::RETRACTION, "no retraction path along the tool"));
                    }
                    d
                };
                let start = self.pos;
                let mut end = start;
                for g in 0..3 {
                    if let Some(k) = geo[g] {
                        end[k] += distance * o[g];
                    }
                }
                self.rapid(start, end, cfg, line, out)?;
            }
            _ => {}
        }
        Ok(())
    }

    /// A rapid move from `start` to `end` (channel axes) as a prepared item.
    fn rapid(
        &mut self,
        start: crate::motion::AxisVec,
        end: crate::motion::AxisVec,
        cfg: &MachineConfig,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let n = cfg.channel_axes.len();
        let length = (0..n).map(|k| (end[k] - start[k]).powi(2)).sum::<f64>().sqrt();
        if length < 1e-9 {
            return Ok(());
        }
        let path = Path::line(start, end);
        check_software_limits(cfg, &path, line)?;
        let mv = Move::new(path, length, Feed::Rapid, &AxisLimit::for_channel(cfg), true, line);
        self.pos = end;
        let offsets = self.shared_offsets();
        self.trc.push(
            trc::Prepared { mv, feed: Feed::Rapid, line, offsets, approach: self.modal.approach, corner: None },
            None,
            &AxisLimit::for_channel(cfg),
            out,
        )
    }
}

fn mul_vec(r: &[[f64; 3]; 3], v: &Vec3) -> Vec3 {
    std::array::from_fn(|i| dot(&r[i], v))
}

fn no_solution(line: u32) -> Alarm {
    cycle_alarm(line, alarms::NO_SOLUTION, "no solution possible with the rotary axes' traversing ranges")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> bool {
        (0..3).all(|i| (0..3).all(|j| (a[i][j] - b[i][j]).abs() < 1e-12))
    }

    #[test]
    fn the_mode_codes_of_the_posts_decode_to_their_sequences() {
        for (code, seq) in
            [(57, [0, 1, 2]), (45, [0, 2, 1]), (54, [1, 0, 2]), (30, [1, 2, 0]), (39, [2, 0, 1]), (27, [2, 1, 0])]
        {
            assert_eq!(decode_mode(code), Some(SwivelMode::AxisByAxis(seq)), "{code}");
        }
        assert_eq!(decode_mode(64), Some(SwivelMode::Solid));
        assert_eq!(decode_mode(128 + 57), Some(SwivelMode::Projection([0, 1, 2])));
        assert_eq!(decode_mode(192), Some(SwivelMode::Direct));
        assert_eq!(decode_mode(0), None);
        assert_eq!(decode_mode(21), None, "X, X, X is no sequence");
    }

    #[test]
    fn projection_angles_about_x_and_y_keep_the_new_x_in_the_old_zx_plane() {
        let r = rotation(SwivelMode::Projection([0, 1, 2]), [30.0, 20.0, 0.0]).unwrap();
        // New X = Ry(20°)·ex.
        let (s, c) = 20f64.to_radians().sin_cos();
        assert!((r[0][0] - c).abs() < 1e-12 && r[1][0].abs() < 1e-12 && (r[2][0] + s).abs() < 1e-12);
        // The plane's trace in the old Y-Z plane is at 30°: the normal is perpendicular to it.
        let (s30, c30) = 30f64.to_radians().sin_cos();
        assert!((r[1][2] * c30 + r[2][2] * s30).abs() < 1e-12, "{r:?}");
        // Orthonormal and right-handed.
        let cols: [Vec3; 3] = std::array::from_fn(|j| [r[0][j], r[1][j], r[2][j]]);
        assert!((dot(&cross(&cols[0], &cols[1]), &cols[2]) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn solid_angle_is_z_then_the_new_y() {
        let r = rotation(SwivelMode::Solid, [90.0, 30.0, 0.0]).unwrap();
        // Rz(90)·Ry(30)·ez = Rz(90)·(sin30, 0, cos30) = (0, sin30, cos30).
        assert!((r[0][2]).abs() < 1e-12 && (r[1][2] - 0.5).abs() < 1e-12 && (r[2][2] - 0.75f64.sqrt()).abs() < 1e-12);
        let abc = rotation(SwivelMode::AxisByAxis([2, 1, 0]), [90.0, 30.0, 0.0]).unwrap();
        assert!(close(&r, &abc));
    }

    #[test]
    fn align_keeps_the_frame_when_the_tool_is_unchanged() {
        for mode in [2000, 2001, 2002] {
            assert!(close(&align([0.0, 0.0, 1.0], 2, mode), &frame::rpy(0.0, 0.0, 0.0)), "{mode}");
        }
        // Tool along +X with TOFRAME (new Z = tool), mode 2001: new X in the old X-Z plane.
        let r = align([1.0, 0.0, 0.0], 2, 2001);
        assert!(r[1][0].abs() < 1e-12 && (r[2][0] + 1.0).abs() < 1e-12, "{r:?}");
    }
}

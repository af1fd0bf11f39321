//! The setting data of Cartesian manual travel and the angle kinds of orientation JOG.
//!
//! - SD42650 `$SC_CART_JOG_MODE` (REFERENCE §9.4; bit layout from memory, the seeds only name
//!   the datum): bit 0 translation in the BCS, bit 1 in the WCS, bit 2 in the TCS; bit 8
//!   orientation in the BCS, bit 9 in the WCS, bit 10 in the TCS. A JOG request that names no
//!   coordinate system takes it from here: translation only while a transformation is active
//!   (Cartesian manual travel needs one, Transformations FM p.124), else the MCS; orientation
//!   (A2/B2/C2) in the BCS when no orientation bit is set. Several bits: the lowest wins.
//! - SD42660 `$SC_ORI_JOG_MODE` (seed 003, F2 3.8): 0 = defined by the transformation (here:
//!   A2/B2/C2 turn about X/Y/Z of the reference system), 1 = Euler angles ZX'Z'' (ORIEULER),
//!   2 = RPY XY'Z'' (ORIRPY), 3 = RPY ZY'X'' (ORIRPY2), 4 = MD21120 ORIAX_TURN_TAB_1
//!   (ORIVIRT1), 5 = MD21130 ORIAX_TURN_TAB_2 (ORIVIRT2).
//!
//! With an angle kind, A2/B2/C2 change the first/second/third angle of that convention
//! (`kinematics::orient::angles`). Changing one angle of a chain `R1(a)·R2(b)·R3(c)·ez` with the
//! others held turns the orientation about the fixed axis `R1…R(i−1)·e_i`, so the JOG is a cone
//! about that axis; the angles that do not influence the vector are taken as 0 (the free angle
//! of a 5-axis orientation).

use crate::channel::JogSystem;
use crate::channel::{Channel, CommandError};
use crate::kinematics::Vec3;
use crate::kinematics::orient::angles;
use crate::kinematics::orient::vec3::{cross, norm, rotate, unit};

/// How orientation JOG (A2, B2, C2) changes the tool orientation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OrientationJogKind {
    /// Rotations about the X, Y, Z axes of the reference system (SD42660 = 0).
    Axes,
    /// Euler angles ZX'Z'' (ORIEULER, SD42660 = 1).
    Euler,
    /// RPY angles XY'Z'' (ORIRPY, SD42660 = 2).
    Rpy,
    /// RPY angles ZY'X'' (ORIRPY2, SD42660 = 3).
    Rpy2,
    /// The rotation sequence of MD21120 ORIAX_TURN_TAB_1 (ORIVIRT1, SD42660 = 4).
    Virtual1,
    /// The rotation sequence of MD21130 ORIAX_TURN_TAB_2 (ORIVIRT2, SD42660 = 5).
    Virtual2,
}

impl OrientationJogKind {
    /// The kind SD42660 `$SC_ORI_JOG_MODE` selects.
    pub fn from_setting(value: i64) -> OrientationJogKind {
        match value {
            1 => OrientationJogKind::Euler,
            2 => OrientationJogKind::Rpy,
            3 => OrientationJogKind::Rpy2,
            4 => OrientationJogKind::Virtual1,
            5 => OrientationJogKind::Virtual2,
            _ => OrientationJogKind::Axes,
        }
    }
}

/// The rotation chain of an angle kind in the order of the factors: (reference axis 0..2, angle
/// index A2/B2/C2 = 0/1/2).
fn rotation_chain(kind: OrientationJogKind, tab: [u8; 3]) -> Option<[(usize, usize); 3]> {
    let axis = |e: u8| matches!(e, 1..=3).then(|| usize::from(e) - 1);
    match kind {
        OrientationJogKind::Axes => None,
        // o = Rz(A2)·Rx(B2)·Rz(C2)·ez
        OrientationJogKind::Euler => Some([(2, 0), (0, 1), (2, 2)]),
        // o = Rz(C2)·Ry(B2)·Rx(A2)·ez
        OrientationJogKind::Rpy => Some([(2, 2), (1, 1), (0, 0)]),
        // o = Rx(C2)·Ry(B2)·Rz(A2)·ez
        OrientationJogKind::Rpy2 => Some([(0, 2), (1, 1), (2, 0)]),
        OrientationJogKind::Virtual1 | OrientationJogKind::Virtual2 => {
            Some([(axis(tab[0])?, 0), (axis(tab[1])?, 1), (axis(tab[2])?, 2)])
        }
    }
}

/// The angles (degrees) of orientation `o` (unit, in the reference system) in `kind`, the free
/// angle taken as 0 (`angles.rs` does the conversion).
fn current_angles(kind: OrientationJogKind, tab: [u8; 3], o: &Vec3) -> Option<[f64; 3]> {
    match kind {
        OrientationJogKind::Axes => None,
        OrientationJogKind::Euler => Some(angles::euler_from_vector(o, 0.0, 0.0)),
        OrientationJogKind::Rpy => Some(angles::rpy_from_vector(o, 0.0)),
        OrientationJogKind::Rpy2 => Some(angles::rpy2_from_vector(o, 0.0)),
        OrientationJogKind::Virtual1 | OrientationJogKind::Virtual2 => angles::virt_from_vector(tab, o, 0.0, 0.0),
    }
}

/// The fixed axis (unit, in the reference system) about which changing angle `which` (0 = A2,
/// 1 = B2, 2 = C2) of `kind` turns orientation `o`; `Err` when that angle does not change the
/// orientation vector there, or the turn table names no axis.
pub(in crate::channel) fn angle_rotation_axis(
    kind: OrientationJogKind,
    tab: [u8; 3],
    o: &Vec3,
    which: usize,
) -> Result<Vec3, CommandError> {
    let bad_tab = || CommandError::Invalid("ORIAX_TURN_TAB names no reference axis for ORIVIRT".into());
    let chain = rotation_chain(kind, tab).ok_or_else(bad_tab)?;
    let angles = current_angles(kind, tab, o).ok_or_else(bad_tab)?;
    let p = chain.iter().position(|(_, i)| *i == which).expect("each angle is in the chain");
    let mut axis = unit(chain[p].0);
    for &(ax, i) in chain[..p].iter().rev() {
        axis = rotate(&unit(ax), angles[i].to_radians(), &axis);
    }
    if norm(&cross(&axis, o)) < 1e-9 {
        let name = ["A2", "B2", "C2"][which];
        return Err(CommandError::Invalid(format!(
            "{name} does not change the orientation vector in this position ({kind:?} angles {:.3}, {:.3}, {:.3})",
            angles[0], angles[1], angles[2]
        )));
    }
    Ok(axis)
}

impl Channel {
    /// SD42650 `$SC_CART_JOG_MODE`.
    fn cart_jog_mode(&self) -> u32 {
        self.data.num("$SC_CART_JOG_MODE", 0, 0) as u32
    }

    /// The system of a translation JOG that names none: SD42650 bits 0..2 while a
    /// transformation is active, else the MCS.
    pub(in crate::channel) fn default_translation_system(&self) -> JogSystem {
        let bits = self.cart_jog_mode();
        if self.trafo.is_none() {
            return JogSystem::Machine;
        }
        [JogSystem::Basic, JogSystem::Workpiece, JogSystem::Tool]
            .into_iter()
            .enumerate()
            .find(|(i, _)| bits & (1 << i) != 0)
            .map_or(JogSystem::Machine, |(_, s)| s)
    }

    /// The reference system of an orientation JOG that names none: SD42650 bits 8..10, else BCS.
    pub(in crate::channel) fn default_orientation_system(&self) -> JogSystem {
        let bits = self.cart_jog_mode();
        [JogSystem::Basic, JogSystem::Workpiece, JogSystem::Tool]
            .into_iter()
            .enumerate()
            .find(|(i, _)| bits & (1 << (8 + i)) != 0)
            .map_or(JogSystem::Basic, |(_, s)| s)
    }

    /// The orientation JOG kind SD42660 `$SC_ORI_JOG_MODE` selects.
    pub(in crate::channel) fn default_orientation_kind(&self) -> OrientationJogKind {
        OrientationJogKind::from_setting(self.data.num("$SC_ORI_JOG_MODE", 0, 0) as i64)
    }

    /// MD21120 / MD21130 ORIAX_TURN_TAB_1/2 for the ORIVIRT kinds.
    pub(in crate::channel) fn turn_tab(&self, kind: OrientationJogKind) -> [u8; 3] {
        let name = if kind == OrientationJogKind::Virtual2 { "$MC_ORIAX_TURN_TAB_2" } else { "$MC_ORIAX_TURN_TAB_1" };
        std::array::from_fn(|i| self.data.num(name, 0, i) as u8)
    }
}

//! ORIPATH on an arc: the orientation relative to the path holds across the whole block.
//!
//! Under ORIPATH the programmed LEAD and TILT hold relative to the path tangent and the
//! surface normal at every point of the block, not only at its end (Programming Manual,
//! orientation relative to the path; only ORIPATHS smoothing gives that up). On a straight
//! line the tangent does not turn, so the great circle from the start to the end orientation
//! is already that. On an arc whose axis is the surface normal the tangent frame turns about
//! that axis by the arc's sweep: the orientation turns with it ([`OriPath::turning_with`]).
//! Where the normal is not the arc's axis (an arc in another plane than the normal's) the
//! frame does not turn rigidly and the great circle between the end orientations is kept.

use crate::interp::Interpreter;
use crate::interp::frames::frame::Frame;
use crate::interp::orientation::words::{OriInterpolation, OriReference};
use crate::kinematics::Transformation;
use crate::kinematics::orient::vec3::{cross, norm, scale};
use crate::machine_data::MachineConfig;
use crate::motion::{OriPath, Path};

impl Interpreter {
    /// For an ORIPATH block on an arc, the orientation carried by the arc's turning tangent
    /// frame that replaces the great circle of `path`; `None` where the great circle stays.
    pub(in crate::interp) fn orientation_on_arc(
        &self,
        words: &crate::interp::modal::Words,
        cfg: &MachineConfig,
        frame: &Frame,
        path: &Path,
    ) -> Option<OriPath> {
        let (Some(arc), Some(ori)) = (path.arc.as_deref(), path.ori.as_deref()) else { return None };
        let modal = self.modal.ori;
        if modal.interpolation != OriInterpolation::Path
            || ori.curve.is_some()
            || ori.turn.is_some()
            || words.ori.programmed()
            || words.ori.upper.iter().any(Option::is_some)
        {
            return None;
        }
        let (active, _) = self.orientation_transformation()?;
        let slots = active.trafo.orientation_slots();
        if words.axes.iter().any(|(k, ..)| slots.contains(&Some(*k))) {
            return None;
        }
        let geo = cfg.geo_axes;
        let part = |v: &crate::motion::AxisVec| geo.map(|g| g.map_or(0.0, |k| v[k]));
        let k = cross(&part(&arc.u), &part(&arc.v));
        let kn = norm(&k);
        if kn < 1e-9 {
            return None;
        }
        let k = scale(&k, 1.0 / kn);
        let normal = match modal.reference {
            OriReference::Workpiece => frame.rotate_direction(modal.normal),
            OriReference::Machine => modal.normal,
        };
        if norm(&cross(&normal, &k)) > 1e-9 {
            return None;
        }
        let (start, end) = (ori.at(0.0), ori.at(1.0));
        // Both ends are unit vectors on a frame turned by the sweep: never antiparallel once
        // the turn is taken out, unless the programmed end says so; then keep the circle.
        OriPath::turning_with(start, end, k, arc.sweep).ok()
    }
}

//! The active swivel as an HMI shows it beside T, F, S: the toolholder data set CYCLE800 (or
//! TCARR) selected, the angles of its rotary axes, the swivelled plane's rotation and where the
//! WCS axes point in the BCS (for a coordinate triad turned with the swivelled frame).
//!
//! Input: the interpreter's toolholder and frame state (preparation's; at rest the main run's).
//! Output: [`ActiveSwivel`]. Read only: nothing here changes the channel.

use crate::interp::Interpreter;
use crate::interp::eval::scope::sys_view;
use crate::interp::frames::frame;
use crate::interp::frames::vars::ChainFrame;
use crate::machine_data::MachineConfig;

/// The active swivel of the channel.
#[derive(Debug, Clone, PartialEq)]
pub struct ActiveSwivel {
    /// The active toolholder data set (`$P_TCNUM`; 0 = none).
    pub data_set: u32,
    /// Its `$TC_CARR34` name (empty without one or without a data set).
    pub name: String,
    /// The positions of its rotary axes in degrees (`$P_TCANG[1]`, `[2]`).
    pub axis_angles: [f64; 2],
    /// The swivelled plane (`$P_TOOLFRAME`, where CYCLE800 writes it): its rotation about X,
    /// Y, Z in degrees as MD10600 gives frame angles; zeros when the plane is not turned.
    pub plane: [f64; 3],
    /// The unit directions of the WCS X, Y and Z axes in the BCS through the whole frame
    /// chain (`$P_ACTFRAME`): a display turns its WCS triad with them.
    pub wcs_axes: [[f64; 3]; 3],
}

impl Interpreter {
    /// The active swivel: data set, rotary axis angles, plane rotation and WCS directions.
    pub fn active_swivel(&self, cfg: &MachineConfig) -> ActiveSwivel {
        let sys = sys_view!(self, cfg);
        let number = self.holder.number;
        let name = cfg.carriers.get(&number).filter(|_| number != 0).map(|c| c.name.clone()).unwrap_or_default();
        let tool = sys.chain_frame(ChainFrame::Tool);
        let plane = if tool.linear_is_identity() { [0.0; 3] } else { frame::angles_of(cfg.frame_angles, &tool.lin) };
        let total = sys.chain(None);
        let wcs_axes =
            std::array::from_fn(|g| total.rotate_direction(std::array::from_fn(|k| f64::from(u8::from(k == g)))));
        ActiveSwivel {
            data_set: number,
            name,
            axis_angles: if number != 0 { self.holder.angles } else { [0.0; 2] },
            plane: plane.map(|a| if a.abs() < 1e-9 { 0.0 } else { a }),
            wcs_axes,
        }
    }
}

//! TRANSMIT (types 256, 257): milling on the face of a turned part. The contour is programmed
//! in Cartesian X/Y on the face; the machine has a radial linear axis, the spindle as rotary
//! axis C and the longitudinal axis Z (type 257: plus a real Y axis that only offsets the tool).
//!
//! Roles of `TRAFO_AXES_IN_n`: [0] radial linear axis, [1] rotary axis, [2] linear axis
//! parallel to the rotary axis, [3] (257) supplementary linear axis perpendicular to both.
//!
//! Math (REFERENCE §3.3, conventions of this product): with `q = M + B − L` the tool tip in the
//! non-rotating frame on the spindle axis (x radial, y lateral = `e`, z axial) and
//! `φ = s·(C − c0)` the polar angle of the radial axis seen in the workpiece,
//! `x = qx·cos φ − e·sin φ`, `y = qx·sin φ + e·cos φ`, `z = qz`. Inverse:
//! `qx = σ·√(r² − e²)`, `φ = atan2(y, x) − atan2(e, qx)`; points with `r < |e|` lie in the
//! unmachinable cylinder. σ is the pole side (`TRANSMIT_POLE_SIDE_FIX`: 1 ⇒ +1, 2 ⇒ −1,
//! 0 ⇒ the side that reaches the point fastest from the previous position, so a path through
//! the pole passes it with the radial axis changing sign while C keeps its angle).

use super::{POLE_EPS, Transformation, Unreachable, Vec3, radial_minima, role_geo, unwrap_near};
use crate::machine_data::{MachineConfig, TrafoDataSet, TrafoParams};
use crate::motion::{AxisVec, Path};

#[derive(Debug, Clone, PartialEq)]
pub struct Transmit {
    trafo_type: u32,
    /// (channel axis, geometry index) of the radial axis / Cartesian X.
    radial: (usize, usize),
    /// (channel axis, geometry index) of the rotary axis / Cartesian Y.
    rotary: (usize, usize),
    /// (channel axis, geometry index) of the axial axis / Cartesian Z.
    axial: Option<(usize, usize)>,
    /// Channel axis of the real Y axis (257).
    extra: Option<usize>,
    geo: [Option<usize>; 3],
    rot_offset: f64,
    sign: f64,
    pole_side_fix: u8,
    base_tool: Vec3,
    /// Seconds per mm of the radial axis and per degree of the rotary axis: the weights of the
    /// "closest solution" choice.
    w_lin: f64,
    w_rot: f64,
}

impl Transmit {
    pub fn new(set: &TrafoDataSet, cfg: &MachineConfig) -> Transmit {
        let TrafoParams::Transmit { rot_offset, sign_plus, pole_side_fix, base_tool, .. } = set.params else {
            unreachable!("a TRANSMIT data set has TRANSMIT parameters")
        };
        let radial = role_geo(set, 0).expect("checked at activation");
        let rotary = role_geo(set, 1).expect("checked at activation");
        Transmit {
            trafo_type: set.trafo_type,
            radial,
            rotary,
            axial: role_geo(set, 2),
            extra: if set.trafo_type == 257 { set.axes_in[3] } else { None },
            geo: set.geo_axes,
            rot_offset,
            sign: if sign_plus { 1.0 } else { -1.0 },
            pole_side_fix,
            base_tool,
            w_lin: 1.0 / cfg.axis(radial.0).max_velocity,
            w_rot: 1.0 / cfg.axis(rotary.0).max_velocity,
        }
    }

    /// `B − L` along the Cartesian axis of geometry index `g`.
    fn off(&self, tool: &Vec3, g: usize) -> f64 {
        self.base_tool[g] - tool[g]
    }

    /// Lateral offset `e` of the tool tip from the radial line through the pole.
    fn lateral(&self, pos: &AxisVec, tool: &Vec3) -> f64 {
        self.off(tool, self.rotary.1) + self.extra.map_or(0.0, |k| pos[k])
    }
}

impl Transformation for Transmit {
    fn name(&self) -> &'static str {
        "TRANSMIT"
    }

    fn trafo_type(&self) -> u32 {
        self.trafo_type
    }

    fn geo_slots(&self) -> [Option<usize>; 3] {
        self.geo
    }

    fn machine_slots(&self) -> Vec<usize> {
        [Some(self.radial.0), Some(self.rotary.0), self.axial.map(|a| a.0)].into_iter().flatten().collect()
    }

    fn rotary_slot(&self) -> Option<usize> {
        Some(self.rotary.0)
    }

    fn forward(&self, machine: &AxisVec, tool: &Vec3, bcs: &mut AxisVec) {
        let qx = machine[self.radial.0] + self.off(tool, self.radial.1);
        let e = self.lateral(machine, tool);
        let phi = (self.sign * (machine[self.rotary.0] - self.rot_offset)).to_radians();
        let (s, c) = phi.sin_cos();
        bcs[self.radial.0] = qx * c - e * s;
        bcs[self.rotary.0] = qx * s + e * c;
        if let Some((k, g)) = self.axial {
            bcs[k] = machine[k] + self.off(tool, g);
        }
    }

    fn inverse(&self, bcs: &AxisVec, prev: &AxisVec, tool: &Vec3, machine: &mut AxisVec) -> Result<(), Unreachable> {
        let (x, y) = (bcs[self.radial.0], bcs[self.rotary.0]);
        let e = self.lateral(bcs, tool);
        let off_x = self.off(tool, self.radial.1);
        let r = x.hypot(y);
        if r < e.abs() - 1e-7 {
            return Err(Unreachable);
        }
        let h = (r * r - e * e).max(0.0).sqrt();
        let prev_c = prev[self.rotary.0];
        let (qx, c) = if r < POLE_EPS && e.abs() < POLE_EPS {
            // In the pole the angle is undefined: C keeps its position.
            (0.0, prev_c)
        } else {
            let sides: &[f64] = match self.pole_side_fix {
                1 => &[1.0],
                2 => &[-1.0],
                _ => &[1.0, -1.0],
            };
            let prev_qx = prev[self.radial.0] + off_x;
            sides
                .iter()
                .map(|&sigma| {
                    let qx = sigma * h;
                    let phi = y.atan2(x) - e.atan2(qx);
                    let c = unwrap_near(self.rot_offset + self.sign * phi.to_degrees(), prev_c);
                    let cost = (qx - prev_qx).abs() * self.w_lin + (c - prev_c).abs() * self.w_rot;
                    (cost, qx, c)
                })
                // Ties (a corner exactly in the pole) go to the positive side: `min_by` keeps the first.
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .map(|(_, qx, c)| (qx, c))
                .expect("at least one pole side")
        };
        machine[self.radial.0] = qx - off_x;
        machine[self.rotary.0] = c;
        if let Some((k, g)) = self.axial {
            machine[k] = bcs[k] - self.off(tool, g);
        }
        Ok(())
    }

    fn check_path(&self, path: &Path, tool: &Vec3) -> Result<(), Unreachable> {
        let e = self.lateral(&path.start, tool).abs().max(self.lateral(&path.end, tool).abs());
        if e < POLE_EPS {
            return Ok(());
        }
        match radial_minima(path, self.radial.0, self.rotary.0).iter().any(|&(_, r)| r < e - 1e-7) {
            true => Err(Unreachable),
            false => Ok(()),
        }
    }

    fn poles(&self, path: &Path, tool: &Vec3) -> Vec<f64> {
        if self.lateral(&path.start, tool).abs() >= POLE_EPS {
            return Vec::new();
        }
        // A block that stays in the pole (a Z move on the axis) has no pole passage.
        let r = |p: &AxisVec| p[self.radial.0].hypot(p[self.rotary.0]);
        if r(&path.start) < POLE_EPS && r(&path.end) < POLE_EPS && path.arc.is_none() {
            return Vec::new();
        }
        radial_minima(path, self.radial.0, self.rotary.0)
            .into_iter()
            .filter(|&(_, r)| r < POLE_EPS)
            .map(|(u, _)| u)
            .collect()
    }

    fn critical_params(&self, path: &Path, _tool: &Vec3) -> Vec<f64> {
        radial_minima(path, self.radial.0, self.rotary.0).into_iter().map(|(u, _)| u).collect()
    }
}

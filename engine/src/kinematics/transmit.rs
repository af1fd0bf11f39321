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
//! the pole passes it with the radial axis changing sign while C keeps its angle). A machine
//! standing on the excluded side when TRANSMIT is selected keeps that side until the pole.

use super::{POLE_EPS, RotaryRoles, Transformation, Unreachable, Vec3, radial_minima, unwrap_near};
use crate::machine_data::{MachineConfig, TrafoDataSet, TrafoParams};
use crate::motion::{AxisVec, Path};

#[derive(Debug, Clone, PartialEq)]
pub struct Transmit {
    trafo_type: u32,
    axes: RotaryRoles,
    rot_offset: f64,
    sign: f64,
    pole_side_fix: u8,
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
        let axes = RotaryRoles::new(set, set.trafo_type == 257, base_tool);
        Transmit {
            trafo_type: set.trafo_type,
            w_lin: 1.0 / cfg.axis(axes.radial.0).max_velocity,
            w_rot: 1.0 / cfg.axis(axes.rotary.0).max_velocity,
            axes,
            rot_offset,
            sign: if sign_plus { 1.0 } else { -1.0 },
            pole_side_fix,
        }
    }
}

impl Transmit {
    /// The machine end position of a Cartesian PTP block to `bcs` with `STAT=` (Transformations
    /// FM, Cartesian PTP travel, TRANSMIT: STAT resolves the ambiguity of the pole). It matters
    /// only when the straight (CP) line from the start `prev` to the target passes through the
    /// pole: the radial axis can then travel through the pole (changing sign, C keeping its
    /// angle) or stay on its side while C turns by 180°.
    /// - Bit 0 (the manual: only with POLE_SIDE_FIX 1/2): 0 turns C through +180°, 1 through −180°.
    /// - Bit 1 (with POLE_SIDE_FIX 0; the excerpt names no meaning, decided here): 0 travels
    ///   through the pole as CP would, 1 turns C (direction by bit 0).
    ///
    /// Anywhere else the target has the one solution the block would reach anyway.
    pub fn ptp_end(&self, bcs: &AxisVec, prev: &AxisVec, tool: &Vec3, stat: u32) -> Result<AxisVec, Unreachable> {
        let mut machine = *bcs;
        self.inverse(bcs, prev, tool, &mut machine)?;
        let mut start = *prev;
        self.forward(prev, tool, &mut start);
        let (a, b) = (
            (start[self.axes.radial.0], start[self.axes.rotary.0]),
            (bcs[self.axes.radial.0], bcs[self.axes.rotary.0]),
        );
        let e = self.axes.side_offset(bcs, tool);
        // Distance of the pole (the rotary axis centre) from the straight line a → b.
        let d = (b.0 - a.0, b.1 - a.1);
        let len2 = d.0 * d.0 + d.1 * d.1;
        let t = if len2 > 0.0 { (-(a.0 * d.0 + a.1 * d.1) / len2).clamp(0.0, 1.0) } else { 0.0 };
        let through_pole = (a.0 + t * d.0).hypot(a.1 + t * d.1) < POLE_EPS && e.abs() < POLE_EPS && t > 0.0 && t < 1.0;
        if !through_pole {
            return Ok(machine);
        }
        let (radial, rotary) = (self.axes.radial.0, self.axes.rotary.0);
        let off_x = self.axes.off(tool, self.axes.radial.1);
        let prev_qx = prev[radial] + off_x;
        let side = if prev_qx < 0.0 { -1.0 } else { 1.0 };
        let r = b.0.hypot(b.1);
        if self.pole_side_fix == 0 && stat & 2 == 0 {
            // Through the pole: the radial axis changes sign, C keeps its angle.
            machine[radial] = -side * r - off_x;
            machine[rotary] = prev[rotary];
        } else {
            // Rotation in the pole: the radial axis keeps its side, C turns by ±180°.
            let keep = match self.pole_side_fix {
                1 => 1.0,
                2 => -1.0,
                _ => side,
            };
            machine[radial] = keep * r - off_x;
            machine[rotary] = prev[rotary] + if stat & 1 == 0 { 180.0 } else { -180.0 };
        }
        Ok(machine)
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
        self.axes.geo
    }

    fn machine_slots(&self) -> Vec<usize> {
        self.axes.machine_slots()
    }

    fn rotary_slot(&self) -> Option<usize> {
        Some(self.axes.rotary.0)
    }

    fn forward(&self, machine: &AxisVec, tool: &Vec3, bcs: &mut AxisVec) {
        let qx = machine[self.axes.radial.0] + self.axes.off(tool, self.axes.radial.1);
        let e = self.axes.side_offset(machine, tool);
        let phi = (self.sign * (machine[self.axes.rotary.0] - self.rot_offset)).to_radians();
        let (s, c) = phi.sin_cos();
        bcs[self.axes.radial.0] = qx * c - e * s;
        bcs[self.axes.rotary.0] = qx * s + e * c;
        if let Some((k, g)) = self.axes.axial {
            bcs[k] = machine[k] + self.axes.off(tool, g);
        }
    }

    fn inverse(&self, bcs: &AxisVec, prev: &AxisVec, tool: &Vec3, machine: &mut AxisVec) -> Result<(), Unreachable> {
        let (x, y) = (bcs[self.axes.radial.0], bcs[self.axes.rotary.0]);
        let e = self.axes.side_offset(bcs, tool);
        let off_x = self.axes.off(tool, self.axes.radial.1);
        let r = x.hypot(y);
        if r < e.abs() - 1e-7 {
            return Err(Unreachable);
        }
        let h = (r * r - e * e).max(0.0).sqrt();
        let prev_c = prev[self.axes.rotary.0];
        let (qx, c) = if r < POLE_EPS && e.abs() < POLE_EPS {
            // In the pole the angle is undefined: C keeps its position.
            (0.0, prev_c)
        } else {
            let prev_qx = prev[self.axes.radial.0] + off_x;
            let sides: &[f64] = match self.pole_side_fix {
                // Selected outside the pole on the side the machine data exclude, the axes
                // traverse without evaluating POLE_SIDE_FIX (Transformations FM, "Transformation
                // selection outside pole"): as with 0 the nearer side, so the radial axis keeps
                // its side until the path crosses the pole into the allowed one, which then holds.
                1 if prev_qx < -POLE_EPS => &[1.0, -1.0],
                2 if prev_qx > POLE_EPS => &[1.0, -1.0],
                1 => &[1.0],
                2 => &[-1.0],
                _ => &[1.0, -1.0],
            };
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
        machine[self.axes.radial.0] = qx - off_x;
        machine[self.axes.rotary.0] = c;
        if let Some((k, g)) = self.axes.axial {
            machine[k] = bcs[k] - self.axes.off(tool, g);
        }
        Ok(())
    }

    fn check_path(&self, path: &Path, tool: &Vec3) -> Result<(), Unreachable> {
        let e = self.axes.side_offset(&path.start, tool).abs().max(self.axes.side_offset(&path.end, tool).abs());
        if e < POLE_EPS {
            return Ok(());
        }
        match radial_minima(path, self.axes.radial.0, self.axes.rotary.0).iter().any(|&(_, r)| r < e - 1e-7) {
            true => Err(Unreachable),
            false => Ok(()),
        }
    }

    fn poles(&self, path: &Path, tool: &Vec3) -> Vec<f64> {
        if self.axes.side_offset(&path.start, tool).abs() >= POLE_EPS {
            return Vec::new();
        }
        // A block that stays in the pole (a Z move on the axis) has no pole passage.
        let r = |p: &AxisVec| p[self.axes.radial.0].hypot(p[self.axes.rotary.0]);
        if r(&path.start) < POLE_EPS && r(&path.end) < POLE_EPS && path.arc.is_none() {
            return Vec::new();
        }
        radial_minima(path, self.axes.radial.0, self.axes.rotary.0)
            .into_iter()
            .filter(|&(_, r)| r < POLE_EPS)
            .map(|(u, _)| u)
            .collect()
    }

    fn on_excluded_pole_side(&self, machine: &AxisVec, tool: &Vec3) -> bool {
        let qx = machine[self.axes.radial.0] + self.axes.off(tool, self.axes.radial.1);
        match self.pole_side_fix {
            1 => qx < -POLE_EPS,
            2 => qx > POLE_EPS,
            _ => false,
        }
    }

    fn critical_params(&self, path: &Path, _tool: &Vec3) -> Vec<f64> {
        radial_minima(path, self.axes.radial.0, self.axes.rotary.0).into_iter().map(|(u, _)| u).collect()
    }
}

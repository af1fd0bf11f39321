//! The blank: its shape in the workpiece coordinate system (WCS) and where that lies in the
//! BCS, from `WORKPIECE(..)` or from an API call.
//!
//! `WORKPIECE(ref, spindle, _, "type", flags, Z0, Z1, ZB, v1, v2, v3, v4)` is the blank line
//! SINUMERIK Operate writes into G-code programs (program header "Blank"). Read here:
//! - `type`: `"BOX"` or `"RECTANGLE"` (cuboid between corners X0/Y0 = v1/v2 and X1/Y1 = v3/v4),
//!   `"CYLINDER"` (outer diameter XA = v1), `"PIPE"` or `"TUBE"` (XA = v1, XI = v2), `"POLYGON"`
//!   (v1 edges, v2 width across flats, one flat parallel to X, centred on X0 Y0); `"NPRT"`
//!   or an empty type deletes the blank. Other types are refused (alarm 12560, value out of range).
//! - `flags`: bit 4 X values absolute, bit 5 Y values absolute, bit 6 Z1 absolute, bit 7 ZB
//!   absolute (Operate writes 112, 192 or 240). A clear bit makes the value incremental: Z1
//!   from Z0 (the bottom is Z0 + Z1), X1/Y1 from X0/Y0, and XI of a tube the wall thickness.
//! - `Z0` is the top of the blank, `ZB` (the machining limit) is not used.
//! - `ref`, `spindle` and the third parameter (the reference and the spindle of a ShopTurn
//!   blank) are accepted and not used: the blank sits on the machine's only workpiece carrier.
//!
//! These readings come from programs Operate writes and from CAM posts' comments; the manuals
//! at hand do not give the list, so each is a decision of this product. Cylinders, tubes and
//! polygons stand along Z with their axis through X0 Y0 of the WCS.

/// Flag bits of `WORKPIECE`'s fifth parameter.
const X_ABSOLUTE: i64 = 16;
const Y_ABSOLUTE: i64 = 32;
const Z_ABSOLUTE: i64 = 64;

/// The outline of a blank in the XY plane of the WCS.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// Cuboid between two corners.
    Box { x: [f64; 2], y: [f64; 2] },
    /// Solid cylinder about Z through X0 Y0.
    Cylinder { diameter: f64 },
    /// Tube about Z through X0 Y0.
    Tube { outer: f64, inner: f64 },
    /// Regular polygon about Z through X0 Y0, one flat parallel to X.
    Polygon { edges: u32, across_flats: f64 },
}

/// A blank in the WCS: its outline between `bottom` and `top` along Z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Blank {
    pub shape: Shape,
    pub top: f64,
    pub bottom: f64,
}

/// Where the WCS lies in the BCS: `p_bcs = lin · p_wcs + trans` (the active frame's linear part
/// and translation on the geometry axes X, Y, Z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    pub lin: [[f64; 3]; 3],
    pub trans: [f64; 3],
}

impl Default for Placement {
    fn default() -> Self {
        Placement { lin: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], trans: [0.0; 3] }
    }
}

/// What a `WORKPIECE(..)` line asks for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Request {
    Define(Blank),
    /// `"NPRT"` or no type: no blank.
    Delete,
}

impl Request {
    /// Reads `WORKPIECE`'s arguments from the type on: `kind` (upper case), `flags` and the
    /// numbers Z0, Z1, ZB, v1..v4 (`None` where omitted). `Err` says what is wrong.
    pub fn from_workpiece(kind: &str, flags: i64, numbers: &[Option<f64>]) -> Result<Request, String> {
        let get = |i: usize, name: &str| -> Result<f64, String> {
            match numbers.get(i).copied().flatten() {
                Some(v) if v.is_finite() => Ok(v),
                Some(v) => Err(format!("WORKPIECE: {name} = {v} is not a number")),
                None => Err(format!("WORKPIECE(\"{kind}\") needs {name}")),
            }
        };
        if kind.is_empty() || kind == "NPRT" {
            return Ok(Request::Delete);
        }
        let top = get(0, "Z0")?;
        let z1 = get(1, "Z1")?;
        let bottom = if flags & Z_ABSOLUTE != 0 { z1 } else { top + z1 };
        let shape = match kind {
            "BOX" | "RECTANGLE" => {
                let (x0, y0) = (get(3, "X0")?, get(4, "Y0")?);
                let (x1, y1) = (get(5, "X1")?, get(6, "Y1")?);
                let x1 = if flags & X_ABSOLUTE != 0 { x1 } else { x0 + x1 };
                let y1 = if flags & Y_ABSOLUTE != 0 { y1 } else { y0 + y1 };
                Shape::Box { x: [x0.min(x1), x0.max(x1)], y: [y0.min(y1), y0.max(y1)] }
            }
            "CYLINDER" => Shape::Cylinder { diameter: get(3, "XA")? },
            "PIPE" | "TUBE" => {
                let outer = get(3, "XA")?;
                let xi = get(4, "XI")?;
                let inner = if flags & X_ABSOLUTE != 0 { xi } else { outer - 2.0 * xi };
                Shape::Tube { outer, inner }
            }
            "POLYGON" => {
                let n = get(3, "N (edges)")?;
                if n.fract() != 0.0 || !(3.0..=64.0).contains(&n) {
                    return Err(format!("WORKPIECE(\"POLYGON\"): {n} edges (3..64)"));
                }
                Shape::Polygon { edges: n as u32, across_flats: get(4, "SW (width across flats)")? }
            }
            other => {
                return Err(format!(
                    "WORKPIECE: blank type \"{other}\" (BOX, RECTANGLE, CYLINDER, PIPE, TUBE, POLYGON or NPRT)"
                ));
            }
        };
        let blank = Blank { shape, top, bottom };
        blank.check()?;
        Ok(Request::Define(blank))
    }
}

impl Blank {
    /// `Err` for a blank without volume or with dimensions that contradict each other.
    pub fn check(&self) -> Result<(), String> {
        if self.top.partial_cmp(&self.bottom) != Some(std::cmp::Ordering::Greater) {
            return Err(format!("blank bottom Z{} is not below its top Z{}", self.bottom, self.top));
        }
        let ok = match self.shape {
            Shape::Box { x, y } => x[1] > x[0] && y[1] > y[0],
            Shape::Cylinder { diameter } => diameter > 0.0,
            Shape::Tube { outer, inner } => outer > inner && inner >= 0.0,
            Shape::Polygon { across_flats, .. } => across_flats > 0.0,
        };
        if ok { Ok(()) } else { Err(format!("blank {:?} has no area", self.shape)) }
    }

    /// The outline's bounding rectangle in the WCS: `([xmin, xmax], [ymin, ymax])`.
    pub fn extent(&self) -> ([f64; 2], [f64; 2]) {
        let r = match self.shape {
            Shape::Box { x, y } => return (x, y),
            Shape::Cylinder { diameter } => diameter / 2.0,
            Shape::Tube { outer, .. } => outer / 2.0,
            Shape::Polygon { edges, across_flats } => across_flats / 2.0 / (std::f64::consts::PI / edges as f64).cos(),
        };
        ([-r, r], [-r, r])
    }

    /// True if the point (x, y) of the WCS lies inside the outline.
    pub fn contains(&self, x: f64, y: f64) -> bool {
        let r2 = x * x + y * y;
        match self.shape {
            Shape::Box { x: bx, y: by } => bx[0] <= x && x <= bx[1] && by[0] <= y && y <= by[1],
            Shape::Cylinder { diameter } => r2 <= diameter * diameter / 4.0,
            Shape::Tube { outer, inner } => r2 <= outer * outer / 4.0 && r2 >= inner * inner / 4.0,
            Shape::Polygon { edges, across_flats } => (0..edges).all(|k| {
                // Outward normals from straight down (the flat parallel to X) round the circle.
                let a = -std::f64::consts::FRAC_PI_2 + k as f64 * std::f64::consts::TAU / edges as f64;
                x * a.cos() + y * a.sin() <= across_flats / 2.0
            }),
        }
    }
}

impl Placement {
    /// `Err` unless the frame keeps Z vertical (a rotation about Z, a mirror, a scale): a
    /// dexel grid is along the BCS's Z. Tilted frames (ROT about X or Y) are not supported yet.
    pub fn check_upright(&self) -> Result<(), String> {
        let l = &self.lin;
        let tilt = l[0][2].abs() + l[1][2].abs() + l[2][0].abs() + l[2][1].abs();
        let det2 = l[0][0] * l[1][1] - l[0][1] * l[1][0];
        if tilt > 1e-9 || l[2][2].abs() < 1e-9 || det2.abs() < 1e-12 {
            return Err("the blank's frame tilts Z (ROT about X or Y): not supported for the stock".into());
        }
        Ok(())
    }

    /// A point of the BCS's XY plane in the WCS (only for an upright placement).
    pub fn unapply_xy(&self, x: f64, y: f64) -> (f64, f64) {
        let l = &self.lin;
        let (dx, dy) = (x - self.trans[0], y - self.trans[1]);
        let det = l[0][0] * l[1][1] - l[0][1] * l[1][0];
        ((l[1][1] * dx - l[0][1] * dy) / det, (l[0][0] * dy - l[1][0] * dx) / det)
    }

    /// A point of the WCS in the BCS.
    pub fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let l = &self.lin;
        std::array::from_fn(|i| l[i][0] * p[0] + l[i][1] * p[1] + l[i][2] * p[2] + self.trans[i])
    }

    /// The blank's Z range in the BCS, low first.
    pub fn z_range(&self, blank: &Blank) -> [f64; 2] {
        let (a, b) = (self.lin[2][2] * blank.top + self.trans[2], self.lin[2][2] * blank.bottom + self.trans[2]);
        [a.min(b), a.max(b)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn numbers(v: &[f64]) -> Vec<Option<f64>> {
        v.iter().map(|&x| Some(x)).collect()
    }

    #[test]
    fn a_box_with_absolute_corners_spans_them() {
        // WORKPIECE(,"",,"BOX",112,0,-50,-80,0,0,100,100): X/Y/Z absolute.
        let r = Request::from_workpiece("BOX", 112, &numbers(&[0.0, -50.0, -80.0, 0.0, 0.0, 100.0, 100.0])).unwrap();
        assert_eq!(
            r,
            Request::Define(Blank { shape: Shape::Box { x: [0.0, 100.0], y: [0.0, 100.0] }, top: 0.0, bottom: -50.0 })
        );
    }

    #[test]
    fn incremental_values_count_from_the_first_corner_and_the_top() {
        // WORKPIECE(,"",,"BOX",0,2,-30,-80,-2,-2,184,170): 184 x 170 from X-2 Y-2, 30 deep from Z2.
        let r = Request::from_workpiece("BOX", 0, &numbers(&[2.0, -30.0, -80.0, -2.0, -2.0, 184.0, 170.0])).unwrap();
        assert_eq!(
            r,
            Request::Define(Blank {
                shape: Shape::Box { x: [-2.0, 182.0], y: [-2.0, 168.0] },
                top: 2.0,
                bottom: -28.0
            })
        );
    }

    #[test]
    fn a_cylinder_of_the_manual_example_is_179_across_and_180_long() {
        // TRAANG example: WORKPIECE(,"",,"CYLINDER",0,0,-180,-80,179).
        let r = Request::from_workpiece("CYLINDER", 0, &numbers(&[0.0, -180.0, -80.0, 179.0])).unwrap();
        assert_eq!(r, Request::Define(Blank { shape: Shape::Cylinder { diameter: 179.0 }, top: 0.0, bottom: -180.0 }));
    }

    #[test]
    fn a_tube_takes_the_wall_thickness_when_x_is_incremental() {
        let r = Request::from_workpiece("PIPE", 64, &numbers(&[0.0, -40.0, 0.0, 60.0, 5.0])).unwrap();
        assert_eq!(
            r,
            Request::Define(Blank { shape: Shape::Tube { outer: 60.0, inner: 50.0 }, top: 0.0, bottom: -40.0 })
        );
        let r = Request::from_workpiece("PIPE", 64 | 16, &numbers(&[0.0, -40.0, 0.0, 60.0, 40.0])).unwrap();
        assert_eq!(
            r,
            Request::Define(Blank { shape: Shape::Tube { outer: 60.0, inner: 40.0 }, top: 0.0, bottom: -40.0 })
        );
    }

    #[test]
    fn bad_blanks_are_refused_with_a_reason() {
        assert!(Request::from_workpiece("SPHERE", 0, &numbers(&[0.0, -1.0])).unwrap_err().contains("SPHERE"));
        assert!(
            Request::from_workpiece("CYLINDER", 64, &numbers(&[0.0, 10.0, 0.0, 20.0])).unwrap_err().contains("below")
        );
        assert!(Request::from_workpiece("CYLINDER", 64, &[Some(0.0), Some(-10.0)]).unwrap_err().contains("XA"));
        assert_eq!(Request::from_workpiece("NPRT", 0, &[]), Ok(Request::Delete));
    }

    #[test]
    fn a_hexagon_of_width_20_across_flats_holds_its_flats_and_not_beyond() {
        let b = Blank { shape: Shape::Polygon { edges: 6, across_flats: 20.0 }, top: 0.0, bottom: -1.0 };
        assert!(b.contains(0.0, -9.99) && !b.contains(0.0, -10.01));
        // The corners lie on the circumscribed circle, 10 / cos 30° = 11.547 from the centre.
        assert!(b.contains(11.54, 0.0) && !b.contains(11.56, 0.0));
    }
}

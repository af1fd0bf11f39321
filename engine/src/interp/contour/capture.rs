//! Contour capture for the cycles that machine a programmed contour (CYCLE95): the blocks
//! between `CONTCAPON(TABLE, COUNT)` and `CONTCAPOF` are prepared as usual but not run; each
//! path motion (G0, G1, G2, G3) is recorded as one element instead, in the working plane of the
//! workpiece coordinate system, and `CONTCAPOF` writes the elements into the program's array
//! `TABLE` and their number into `COUNT`.
//!
//! The control does the same with its contour preparation (`CONTPRON` ... `EXECUTE`), whose
//! table layout the manuals at hand do not give; NCTwin's own names keep the two apart. A cycle
//! calls the contour's subprogram (`CALL name`) between the two; the interpreter's position
//! follows the contour while it is recorded and returns to where it was at `CONTCAPOF`, so the
//! machine never moves. Corners (RND, CHF, CHR) and radius compensation (G41/G42) inside the
//! contour are neither applied to the recorded elements nor selected; the block's other words
//! (M functions, variables) act as usual.
//!
//! `TABLE` is a `REAL` array `[n, 7]`; row i holds element i: `[i,0]` its motion (0 G0, 1 G1,
//! 2 G2, 3 G3), `[i,1]`/`[i,2]` the start point's abscissa/ordinate (G18: Z/X), `[i,3]`/`[i,4]`
//! the end point's, `[i,5]`/`[i,6]` a circle's centre (0 for lines). `COUNT` is an `INT`.

use crate::alarm::Alarm;
use crate::interp::Interpreter;
use crate::interp::eval::value::Value;
use crate::interp::modal::MotionMode;
use crate::motion::AxisVec;

/// Columns of a row of the table.
const COLUMNS: usize = 7;

/// What a block asks of the capture.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum CaptureOp {
    /// `CONTCAPON(TABLE, COUNT)`: the names of the array and of the count variable.
    On { table: String, count: String },
    /// `CONTCAPOF`.
    Off,
}

/// A capture in progress.
#[derive(Debug, Clone, PartialEq)]
pub struct Capture {
    table: String,
    count: String,
    /// The interpreter's position when the capture began (restored at its end).
    pos: AxisVec,
    rows: Vec<[f64; COLUMNS]>,
}

impl Capture {
    /// Records one motion from `start` to `end` (abscissa, ordinate), with the circle's centre.
    pub(in crate::interp) fn record(
        &mut self,
        motion: MotionMode,
        start: (f64, f64),
        end: (f64, f64),
        center: Option<(f64, f64)>,
    ) {
        let kind = match motion {
            MotionMode::Rapid => 0.0,
            MotionMode::Linear => 1.0,
            MotionMode::Cw => 2.0,
            MotionMode::Ccw => 3.0,
        };
        let c = center.unwrap_or((0.0, 0.0));
        self.rows.push([kind, start.0, start.1, end.0, end.1, c.0, c.1]);
    }
}

impl Interpreter {
    /// Starts or ends the capture a block asks for.
    pub(in crate::interp) fn capture_op(&mut self, op: &CaptureOp, line: u32) -> Result<(), Alarm> {
        match op {
            CaptureOp::On { table, count } => {
                let var = self.vars.get(table).ok_or_else(|| Alarm::unknown_name(line, table))?;
                if var.dims.len() != 2 || var.dims[1] < COLUMNS {
                    return Err(Alarm::index_error(line, table, "CONTCAPON needs a REAL array [n, 7]"));
                }
                if self.vars.get(count).is_none() {
                    return Err(Alarm::unknown_name(line, count));
                }
                self.capture = Some(Box::new(Capture {
                    table: table.clone(),
                    count: count.clone(),
                    pos: self.pos,
                    rows: Vec::new(),
                }));
            }
            CaptureOp::Off => {
                let Some(capture) = self.capture.take() else {
                    return Err(Alarm::syntax(line, "CONTCAPOF without CONTCAPON"));
                };
                self.pos = capture.pos;
                let var = self.vars.get_mut(&capture.table).ok_or_else(|| Alarm::unknown_name(line, &capture.table))?;
                let (rows, width) = (var.dims[0], var.dims[1]);
                if capture.rows.len() > rows {
                    return Err(Alarm::index_error(
                        line,
                        &capture.table,
                        &format!("{} contour elements, room for {rows}", capture.rows.len()),
                    ));
                }
                for (i, row) in capture.rows.iter().enumerate() {
                    for (j, v) in row.iter().enumerate() {
                        var.data[i * width + j] = Value::Real(*v);
                    }
                }
                let n = capture.rows.len() as i64;
                let count =
                    self.vars.get_mut(&capture.count).ok_or_else(|| Alarm::unknown_name(line, &capture.count))?;
                count.data[0] = Value::Int(n);
            }
        }
        Ok(())
    }
}

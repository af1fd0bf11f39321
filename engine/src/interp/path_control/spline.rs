//! Spline and polynomial interpolation in block preparation (Programming Manual Job planning):
//! `ASPLINE`, `BSPLINE`, `CSPLINE` (G group 1) with `PW` (point weight, B spline), `SD`
//! (degree 2 or 3, B spline), `PL` (parameter interval length), `BAUTO`/`BNAT`/`BTAN` (G group
//! 19) and `EAUTO`/`ENAT`/`ETAN` (G group 20); `POLY` with `PO[axis]=(end, a2, a3, a4, a5)` and
//! `PL`.
//!
//! How the blocks become path elements: a spline block is prepared like a G1 block (frames,
//! tool offset and feed as there); its straight move is not handed out but kept with the
//! sequence of spline points. When the sequence ends (a block of another motion type, another
//! spline type, a block that hands out anything else, a preprocessing stop or the program's
//! end) the spline through or near the points is built in axis space (`motion::spline`) and
//! its pieces go out as free-form moves ([`crate::motion::Curve`]), each with the line, feed
//! and offsets of its block. A `POLY` block becomes one such element at once.
//!
//! Chosen where the manuals leave room:
//! - `BTAN` (the reset value) needs the previous block's tangent, which block preparation does
//!   not keep (the fast lane's blocks do not note it): it runs as `BAUTO`. `ETAN` takes the
//!   direction at the start of the block that ends the sequence when that is a move in the same
//!   block preparation step, else it runs as `EAUTO`.
//! - B spline: clamped at the first and last point (the manual: it starts and ends there,
//!   tangential to the control polygon); knot spans by `PL` of the block that closes them, else
//!   the mean chord of the control polygon; fewer points than degree + 1 lower the degree; the
//!   start point has weight 1. Spans belong to the blocks of their last control point.
//! - Blocks inside a sequence that hand out anything but their move (an M function, a message)
//!   end the sequence there; the next spline block starts a new one.
//! - With tool radius compensation active a spline is refused (alarm 12550 naming it): the
//!   compensation of free-form elements is not modelled.

use crate::alarm::Alarm;
use crate::interp::{Interpreter, Item, Prep, SharedOffsets, modal};
use crate::machine_data::MachineConfig;
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::spline::{self, BSpline, EndCondition, Piece};
use crate::motion::{AxisLimit, AxisVec, Curve, Feed, Move, Path};

/// The spline types of G group 1 (the motion type of the rest of the interpreter is G1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Akima,
    BSpline,
    Cubic,
    Poly,
}

/// G groups 19 and 20.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Transition {
    Auto,
    Natural,
    /// Reset value.
    #[default]
    Tangent,
}

/// The modal spline state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SplineModal {
    pub kind: Option<Kind>,
    pub begin: Transition,
    pub end: Transition,
    /// SD: 2 or 3.
    pub degree: u8,
}

impl Default for SplineModal {
    fn default() -> SplineModal {
        SplineModal { kind: None, begin: Transition::Tangent, end: Transition::Tangent, degree: 3 }
    }
}

/// The spline words of one block.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SplineWords {
    pub kind: Option<Kind>,
    pub begin: Option<Transition>,
    pub end: Option<Transition>,
    pub pw: Option<f64>,
    pub sd: Option<u8>,
    pub pl: Option<f64>,
    /// `PO[axis]=(end, a2, ..)`: channel axis and the coefficients a2..a5 (program units).
    pub po: Vec<(usize, [f64; 4])>,
}

impl SplineWords {
    /// Takes a spline keyword; false for any other.
    pub fn keyword(&mut self, name: &str) -> bool {
        match name {
            "ASPLINE" => self.kind = Some(Kind::Akima),
            "BSPLINE" => self.kind = Some(Kind::BSpline),
            "CSPLINE" => self.kind = Some(Kind::Cubic),
            "POLY" => self.kind = Some(Kind::Poly),
            "BAUTO" => self.begin = Some(Transition::Auto),
            "BNAT" => self.begin = Some(Transition::Natural),
            "BTAN" => self.begin = Some(Transition::Tangent),
            "EAUTO" => self.end = Some(Transition::Auto),
            "ENAT" => self.end = Some(Transition::Natural),
            "ETAN" => self.end = Some(Transition::Tangent),
            _ => return false,
        }
        true
    }

    /// Takes PW, SD or PL; false for any other address.
    pub fn address(&mut self, name: &str, v: f64, line: u32) -> Result<bool, Alarm> {
        match name {
            "PW" if (0.0..=3.0).contains(&v) => self.pw = Some(v),
            "PW" => return Err(Alarm::value_out_of_range(line, &format!("PW={v} (0..3)"))),
            "SD" if v == 2.0 || v == 3.0 => self.sd = Some(v as u8),
            "SD" => return Err(Alarm::value_out_of_range(line, &format!("SD={v} (2 or 3)"))),
            "PL" if v > 0.0 => self.pl = Some(v),
            "PL" => return Err(Alarm::value_out_of_range(line, &format!("PL={v}"))),
            _ => return Ok(false),
        }
        Ok(true)
    }
}

/// True for the addresses of splines and POLY.
pub fn is_address(name: &str) -> bool {
    matches!(name, "PW" | "SD" | "PL")
}

impl SplineModal {
    /// Applies a block's words; `motion` is the block's G0/G1/G2/G3 (which ends a spline).
    pub fn apply(&mut self, w: &SplineWords, motion: bool) {
        if motion {
            self.kind = None;
        }
        if let Some(k) = w.kind {
            self.kind = Some(k);
        }
        if let Some(b) = w.begin {
            self.begin = b;
        }
        if let Some(e) = w.end {
            self.end = e;
        }
        if let Some(d) = w.sd {
            self.degree = d;
        }
    }
}

/// A spline point: the block's straight move (item) and its PW and PL.
#[derive(Debug, Clone)]
struct Point {
    mv: Move,
    line: u32,
    offsets: SharedOffsets,
    pw: f64,
    pl: Option<f64>,
}

/// A spline sequence being collected.
#[derive(Debug, Clone)]
pub struct SplineRun {
    kind: Kind,
    begin: Transition,
    end: Transition,
    degree: u8,
    /// Where the sequence starts (the position before its first block).
    start: AxisVec,
    points: Vec<Point>,
}

/// 1.0 for the geometry axes (the path length's axes).
fn metric(cfg: &MachineConfig) -> AxisVec {
    let mut m = [0.0; MAX_CHANNEL_AXES];
    for &k in cfg.geo_axes.iter().flatten() {
        m[k] = 1.0;
    }
    m
}

fn chord(a: &AxisVec, b: &AxisVec, metric: &AxisVec) -> f64 {
    let geo: f64 = (0..MAX_CHANNEL_AXES).map(|k| (b[k] - a[k]).powi(2) * metric[k]).sum::<f64>().sqrt();
    if geo > 1e-9 { geo } else { (0..MAX_CHANNEL_AXES).map(|k| (b[k] - a[k]).powi(2)).sum::<f64>().sqrt() }
}

/// The free-form move of a piece with the feed, exact stop and line of its block's move.
fn curve_move(piece: Piece, like: &Move, metric: &AxisVec, limits: &[AxisLimit]) -> Move {
    let curve = Curve::hermite(piece, *metric);
    let length = curve.length();
    if length.is_nan() || length <= 1e-9 {
        // No motion of the geometry axes: the block's straight move (rotary axes only).
        let mut mv = like.clone();
        mv.path = Path::line(piece[0].0, piece[1].0);
        return mv;
    }
    let (start, end) = (piece[0].0, piece[1].0);
    let mut mv = Move::unlimited(
        Path { start, end, arc: None, ori: None, curve: Some(std::sync::Arc::new(curve)) },
        like.exact_stop,
        like.tag,
    );
    let feed = if like.is_rapid() { Feed::Rapid } else { Feed::Path(like.feed) };
    mv.set_limits(length, feed, limits);
    mv.per_rev = like.per_rev;
    mv
}

impl SplineRun {
    /// The moves of the sequence, in block order. `next` is the direction at the start of the
    /// block after it, if known (ETAN).
    fn build(self, next: Option<AxisVec>, cfg: &MachineConfig) -> Vec<Item> {
        let metric = metric(cfg);
        let limits = AxisLimit::for_channel(cfg);
        let mut pts = vec![self.start];
        pts.extend(self.points.iter().map(|p| p.mv.path.end));
        let n = self.points.len();
        let mut pieces: Vec<Vec<Piece>> = match self.kind {
            Kind::Akima | Kind::Cubic => {
                let h: Vec<f64> =
                    (0..n).map(|i| self.points[i].pl.unwrap_or_else(|| chord(&pts[i], &pts[i + 1], &metric))).collect();
                let begin = match self.begin {
                    Transition::Natural => EndCondition::Natural,
                    _ => EndCondition::Auto,
                };
                let end = match (self.end, next) {
                    (Transition::Natural, _) => EndCondition::Natural,
                    (Transition::Tangent, Some(t)) => EndCondition::Tangent(t),
                    _ => EndCondition::Auto,
                };
                let list = if self.kind == Kind::Cubic {
                    spline::cubic(&pts, &h, begin, end)
                } else {
                    spline::akima(&pts, &h, begin, end)
                };
                list.into_iter().map(|p| vec![p]).collect()
            }
            Kind::BSpline => {
                let degree = usize::from(self.degree).min(n);
                let mean = (0..n).map(|i| chord(&pts[i], &pts[i + 1], &metric)).sum::<f64>() / n as f64;
                let spans: Vec<f64> =
                    (0..=n - degree).map(|s| self.points[s + degree - 1].pl.unwrap_or(mean.max(1e-9))).collect();
                let mut weights = vec![1.0];
                weights.extend(self.points.iter().map(|p| p.pw));
                let b = BSpline { control: &pts, weights: &weights, degree, spans: &spans };
                let spans = b.pieces();
                // Span s belongs to the block of its last control point, s + degree.
                let mut per_block = vec![Vec::new(); n];
                for (s, list) in spans.into_iter().enumerate() {
                    per_block[s + degree - 1] = list;
                }
                per_block
            }
            Kind::Poly => unreachable!("POLY blocks are built at once"),
        };
        let mut out = Vec::new();
        for (point, list) in self.points.into_iter().zip(pieces.iter_mut()) {
            for piece in list.drain(..) {
                let mv = curve_move(piece, &point.mv, &metric, &limits);
                out.push(Item::Move { mv, line: point.line, offsets: point.offsets.clone() });
            }
        }
        out
    }
}

impl Interpreter {
    /// Keeps the move of a spline block (A, B, C spline) with its sequence instead of handing
    /// it out; a change of spline type first hands out the sequence before.
    pub(in crate::interp) fn spline_point(
        &mut self,
        mv: Move,
        words: &modal::Words,
        line: u32,
        offsets: SharedOffsets,
        cfg: &MachineConfig,
        out: &mut Vec<Item>,
    ) {
        let sm = self.modal.spline;
        let kind = sm.kind.expect("a spline block");
        if self.splines.as_ref().is_some_and(|r| r.kind != kind || r.degree != sm.degree) {
            let run = self.splines.take().expect("checked");
            out.extend(run.build(None, cfg));
        }
        let run = self.splines.get_or_insert_with(|| {
            Box::new(SplineRun {
                kind,
                begin: sm.begin,
                end: sm.end,
                degree: sm.degree,
                start: mv.path.start,
                points: Vec::new(),
            })
        });
        run.end = sm.end;
        run.points.push(Point { mv, line, offsets, pw: words.spline.pw.unwrap_or(1.0), pl: words.spline.pl });
    }

    /// After a block: hands out the spline sequence when it ends here (see the module doc).
    /// `mark` is where the block's items begin in `out`.
    pub(in crate::interp) fn settle_spline(
        &mut self,
        out: &mut Vec<Item>,
        mark: usize,
        prep: Prep,
        cfg: &MachineConfig,
    ) {
        let Some(run) = &self.splines else { return };
        let mark = mark.min(out.len());
        if prep == Prep::Prepared && out.len() == mark && self.modal.spline.kind == Some(run.kind) {
            return;
        }
        let run = self.splines.take().expect("checked");
        let next = out[mark..].iter().find_map(|i| match i {
            Item::Move { mv, .. } if mv.length > 1e-9 => {
                let t = mv.path.tangent(0.0);
                let l = t.iter().map(|x| x * x).sum::<f64>().sqrt();
                (l > 1e-12).then(|| t.map(|x| x / l))
            }
            _ => None,
        });
        let items = run.build(next, cfg);
        let end = mark + items.len();
        out.splice(mark..mark, items);
        if self.trc.idle() {
            // The compensator notes where the tool is, as for any move that passes it.
            self.trc.passed(&out[..end]);
        }
    }

    /// A POLY block's move as the programmed polynomial: `PO[axis]=(end, a2..a5)` over the
    /// parameter 0..PL (PL=1 if not programmed); axes written without PO move linearly.
    pub(in crate::interp) fn poly_move(
        &self,
        mv: &mut Move,
        words: &modal::Words,
        cfg: &MachineConfig,
        limits: &[AxisLimit],
    ) {
        if words.spline.po.iter().all(|(_, a)| a.iter().all(|x| *x == 0.0)) {
            return;
        }
        let pl = words.spline.pl.unwrap_or(1.0);
        let f = self.modal.length_factor();
        let frame = self.block_frame(words, cfg);
        let geo = &cfg.geo_axes;
        // WCS coefficients of u^j (j = 2..5) per axis, mapped to axis space by the frame's
        // linear part (geometry axes) or as they are (other axes).
        let mut high = [[0.0; MAX_CHANNEL_AXES]; 4];
        for &(k, a) in &words.spline.po {
            let unit = if cfg.axis(k).rotary { 1.0 } else { f };
            for (j, c) in a.iter().enumerate() {
                high[j][k] = unit * c * pl.powi(j as i32 + 2);
            }
        }
        let high = high.map(|c| frame.apply_vector(geo, &c));
        let (s, e) = (mv.path.start, mv.path.end);
        let mut coef = [[0.0; MAX_CHANNEL_AXES]; 5];
        for k in 0..MAX_CHANNEL_AXES {
            coef[0][k] = e[k] - s[k] - high.iter().map(|c| c[k]).sum::<f64>();
            for j in 0..4 {
                coef[j + 1][k] = high[j][k];
            }
        }
        let piece = spline::polynomial(&s, &coef);
        *mv = curve_move(piece, mv, &metric(cfg), limits);
    }
}

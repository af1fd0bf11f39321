//! The main run: moves prepared by the interpreter are planned with look-ahead and
//! interpolated one IPO cycle at a time.
//!
//! Input: [`Move`]s (a [`Path`] in channel-axis space plus feed and exact-stop flag) and the
//! axes' [`AxisLimit`]s. Output: one position of every axis per [`Planner::step`].

pub mod blend;
pub mod blend_axial;
pub mod blend_ori;
mod blend_tangent;
pub mod compress;
pub mod compress_ori;
mod curve;
pub mod drive;
mod front;
mod nearest;
mod ori_curve;
mod orientation;
pub mod orison;
mod path;
mod planner;
pub mod spline;

pub use curve::Curve;
pub use ori_curve::TwoCurves;
pub use orientation::{Antiparallel, OriKink, OriPath, rotate};
pub use path::{Arc, AxisVec, Path};
pub use planner::{AxisLimit, AxisLimits, Feed, Move, Planner, brake_speed, stop_speed};

//! Pure orientation mathematics shared by the orientation transformation (TRAORI) and the
//! orientable toolholder (TCARR): no machine data, no axis slots, only vectors and radians
//! (degrees where the NC programs angles, in [`angles`]).
//!
//! - [`vec3`]: vector helpers and rotation matrices on `[f64; 3]`.
//! - [`solve`]: Paden–Kahan subproblems 1 and 2 (which angles turn one vector into another).
//! - [`stepped`]: the angles of [`solve`] stepped from one IPO cycle to the next without `atan2`.
//! - [`chain`]: the vector chain of tool, part and mixed kinematics, forward and inverse.
//! - [`angles`]: ORIEULER, ORIRPY, ORIRPY2 and ORIVIRT1/2 angles ↔ orientation vector.
//! - [`interp`]: great-circle and cone interpolation of the orientation.
//! - [`rotation`]: the tool's rotation about its own axis (6-axis, THETA).

pub mod angles;
pub mod chain;
pub mod interp;
pub mod rotation;
pub mod solve;
pub mod stepped;
pub mod vec3;

pub use chain::{Chain, ChainKind, Pose};
pub use interp::{OriPathError, angle_between, cone, cone_sweep, cone_tangent, cone_through, slerp};

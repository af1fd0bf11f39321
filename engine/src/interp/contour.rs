//! The programmed contour's geometry: circles (G2/G3, CIP, CT, CR=) and the corner elements
//! RND, CHF and CHR inserted between two blocks.

pub mod angle_corner;
pub mod angle_line;
pub mod arc;
pub mod arc_rounding;
pub mod capture;
pub mod corner_feed;
pub mod corners;
pub mod tangent_circle;
pub mod through_point;

//! The orientation data of a cutting edge beside `$TC_DP1..25`: `$TC_DPV3..5` (tool orientation
//! vector) and `$TC_DPVN3..5` (orientation normal vector, 6-axis), F2 §3.7.5/§3.9.1. A generic
//! orientation transformation selected without a vector in TRAORI(n, x, y, z) takes them as its
//! basic orientation and tool normal while the edge is active.
//!
//! Like the tool lengths the components depend on the working plane (F2: "the orientation of a
//! tool is dependent on the selected plane"). This product reads them as the lengths: DPV5 / DPVN5
//! goes where length 1 acts (G17 Z, G18 Y, G19 X), DPV4 where length 2 (G17 Y, G18 X, G19 Z),
//! DPV3 where length 3 (G17 X, G18 Z, G19 Y); so in G17 they are the X, Y, Z components, as the
//! manual's example comments say.

use super::{EdgeParams, TOOL_PARAMS};

/// Slots of an edge: `$TC_DP1..25`, then DPV3..5, then DPVN3..5.
pub const EDGE_SLOTS: usize = TOOL_PARAMS + 6;

/// The slot of tool datum `$TC_DP<param>` (`param` = "3", "V4", "VN5", ...).
pub fn slot(param: &str) -> Option<usize> {
    let comp = |s: &str| s.parse::<usize>().ok().filter(|c| (3..=5).contains(c));
    if let Some(c) = param.strip_prefix("VN") {
        return comp(c).map(|c| TOOL_PARAMS + 3 + c - 3);
    }
    if let Some(c) = param.strip_prefix('V') {
        return comp(c).map(|c| TOOL_PARAMS + c - 3);
    }
    param.parse::<usize>().ok().filter(|p| (1..=TOOL_PARAMS).contains(p)).map(|p| p - 1)
}

/// The name suffix of slot `i` (inverse of [`slot`]).
pub fn name(i: usize) -> String {
    match i {
        i if i < TOOL_PARAMS => (i + 1).to_string(),
        i if i < TOOL_PARAMS + 3 => format!("V{}", i - TOOL_PARAMS + 3),
        i => format!("VN{}", i - TOOL_PARAMS),
    }
}

/// The edge's orientation vector and normal by geometry axis in `plane` (17, 18, 19); `None`
/// for a vector whose components are all zero (not given).
pub fn vectors(p: &EdgeParams, plane: u32) -> (Option<[f64; 3]>, Option<[f64; 3]>) {
    let by_axis = |base: usize| -> Option<[f64; 3]> {
        let [c3, c4, c5] = [p[base], p[base + 1], p[base + 2]];
        let v = match plane {
            18 => [c4, c5, c3],
            19 => [c5, c3, c4],
            _ => [c3, c4, c5],
        };
        (v != [0.0; 3]).then_some(v)
    };
    (by_axis(TOOL_PARAMS), by_axis(TOOL_PARAMS + 3))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slots_and_names_round_trip() {
        for (param, i) in [("1", 0), ("25", 24), ("V3", 25), ("V5", 27), ("VN3", 28), ("VN5", 30)] {
            assert_eq!(slot(param), Some(i), "{param}");
            assert_eq!(name(i), param);
        }
        assert_eq!(slot("V6"), None);
        assert_eq!(slot("26"), None);
        assert_eq!(slot("VN2"), None);
    }

    #[test]
    fn the_plane_permutes_like_the_tool_lengths() {
        let mut p = [0.0; EDGE_SLOTS];
        p[25..28].copy_from_slice(&[1.0, 2.0, 3.0]);
        assert_eq!(vectors(&p, 17), (Some([1.0, 2.0, 3.0]), None));
        // G18: length 1 (DPV5) along Y, length 2 (DPV4) along X, length 3 (DPV3) along Z.
        assert_eq!(vectors(&p, 18).0, Some([2.0, 3.0, 1.0]));
        assert_eq!(vectors(&p, 19).0, Some([3.0, 1.0, 2.0]));
    }
}

//! Orientation polynomials `PO[PHI]`, `PO[PSI]`, `PO[XH]`, `PO[YH]`, `PO[ZH]`, `PO[THT]`
//! (F2 §3.9.4, §3.11). Polynomial interpolation of the orientation is not modelled by this
//! product, so each is refused at its block with the alarm the manual names for a polynomial
//! that is not permitted: 14136 without an orientation transformation (orientation
//! polynomial generally not allowed), 14137 for PHI/PSI, 14138 for XH/YH/ZH, 14139 for THT.

use crate::alarm::{Alarm, Clear};
use crate::lang::Expr;

/// The alarm for `PO[index]=...`, or `None` if `index` is no orientation polynomial (an axis
/// polynomial `PO[X]`, which the caller refuses as it does any unknown address).
pub(in crate::interp) fn refused(index: &[Expr], orientation_active: bool, line: u32) -> Option<Alarm> {
    let [Expr::Var { name, indices }] = index else { return None };
    if !indices.is_empty() {
        return None;
    }
    let (number, what) = match name.to_ascii_uppercase().as_str() {
        _ if !["PHI", "PSI", "XH", "YH", "ZH", "THT"].contains(&name.to_ascii_uppercase().as_str()) => return None,
        _ if !orientation_active => (14136, "orientation polynomial not allowed"),
        "PHI" | "PSI" => (14137, "polynomials PO[PHI] and PO[PSI] not allowed"),
        "THT" => (14139, "polynomial for the angle of rotation PO[THT] not allowed"),
        _ => (14138, "polynomials PO[XH], PO[YH], PO[ZH] not allowed"),
    };
    Some(Alarm { number, message: format!("Channel 1 block {line} {what}"), line: Some(line), clear: Clear::Reset })
}

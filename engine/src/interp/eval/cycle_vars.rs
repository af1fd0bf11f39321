//! System variables the standard cycles read in preparation: the active tool's radius
//! (`$P_TOOLR`), the programmed feed (`$P_F`) and the names of the working plane's axes
//! (`$P_AXN1` abscissa, `$P_AXN2` ordinate, `$P_AXN3` applicate). With these a cycle written once
//! works in G17, G18 and G19 through indirect axis addressing (`AX[$P_AXN3]=...`) and keeps the
//! pocket walls clear of the tool's radius. Also the active edge's lengths (`$P_TOOLL[n]`) and
//! parameters (`$P_AD[n]`) the measuring cycles compare against.

use crate::alarm::Alarm;
use crate::interp::eval::scope::SysView;
use crate::interp::eval::value::Value;

/// The value of cycle variable `name`, or `None` if `name` is not one of them.
pub(in crate::interp) fn read(sys: &SysView, name: &str, indices: &[Value], line: u32) -> Option<Result<Value, Alarm>> {
    let k = match name {
        "$P_TOOLR" | "$P_F" => None,
        "$P_AXN1" => Some(0),
        "$P_AXN2" => Some(1),
        "$P_AXN3" => Some(2),
        _ => return None,
    };
    if !indices.is_empty() {
        return Some(Err(Alarm::index_error(line, name, "takes no index")));
    }
    Some(Ok(match (name, k) {
        // The radius of the active cutting edge (T, D); 0 with D0 or without tool data,
        // as on the control. Wear ($TC_DP15) is added as the control adds it.
        ("$P_TOOLR", _) => {
            let (t, d) = (sys.offsets.t, sys.offsets.d);
            let edge = sys.cfg.edge(t, d);
            let slot = |n: &str| crate::machine_data::tool_orient::slot(n);
            let radius = edge.map_or(0.0, |e| slot("6").map_or(0.0, |i| e[i]) + slot("15").map_or(0.0, |i| e[i]));
            Value::Real(radius)
        }
        // The feed in force (0 before any F), in the unit the program wrote it.
        ("$P_F", _) => Value::Real(sys.modal.feed.unwrap_or(0.0)),
        (_, Some(k)) => {
            let (a, o, p) = sys.modal.plane.axes();
            let g = [a, o, p][k];
            match sys.cfg.geo_axes[g] {
                Some(idx) => Value::Axis(sys.cfg.program_axis_name(idx).to_string()),
                None => Value::Axis(sys.cfg.geo_names[g].clone()),
            }
        }
        _ => unreachable!("matched above"),
    }))
}

/// `$P_TOOLL[n]`: total length n (1..3) of the active cutting edge: geometry ($TC_DP3..5) +
/// wear ($TC_DP12..14) + adapter ($TC_DP21..23), as the length offset takes it; 0 with D0.
pub(in crate::interp) fn tool_length(sys: &SysView, indices: &[Value], line: u32) -> Result<Value, Alarm> {
    let n = match indices {
        [n] => n.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?,
        _ => return Err(Alarm::index_error(line, "$P_TOOLL", "needs one index (length 1..3)")),
    };
    if !(1..=3).contains(&n) {
        return Err(Alarm::index_error(line, "$P_TOOLL", &format!("length {n} is not 1..3")));
    }
    let i = n as usize - 1;
    let edge = sys.cfg.edge(sys.offsets.t, sys.offsets.d);
    Ok(Value::Real(edge.map_or(0.0, |e| e[2 + i] + e[11 + i] + e[20 + i])))
}

/// `$P_AD[n]`: parameter n (1..25, `$TC_DPn`) of the active cutting edge, as the measuring and
/// tool-check cycles read it (`$P_AD[6]` the radius); 0 with D0, as on the control. Beyond
/// 1..25: 17020.
pub(in crate::interp) fn active_edge_param(sys: &SysView, indices: &[Value], line: u32) -> Result<Value, Alarm> {
    let n = match indices {
        [n] => n.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?,
        _ => return Err(Alarm::index_error(line, "$P_AD", "needs one parameter number")),
    };
    let slot = usize::try_from(n)
        .ok()
        .and_then(|n| crate::machine_data::tool_orient::slot(&n.to_string()))
        .ok_or_else(|| Alarm::index_error(line, "$P_AD", &format!("parameter {n} is not 1..25")))?;
    let edge = sys.cfg.edge(sys.offsets.t, sys.offsets.d);
    Ok(Value::Real(edge.map_or(0.0, |e| e[slot])))
}

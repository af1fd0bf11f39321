//! Machine and setting data in part programs: reads of `$MN_`, `$MC_`, `$MA_`, `$SN_`, `$SC_`
//! and `$SA_` data, and the axis index of axial data a program writes.
//!
//! A program reads the data as stored in the session's machine data ([`MachineData`], the
//! registry's values): a value written by an earlier block (machine data before its NEWCONF,
//! setting data at once) reads back as written, as the control's data management shows it.
//! Indices follow the control: `$MN_X`, `$MN_X[i]`, `$MC_X[i]`, `$MA_X[AX]`, `$MA_X[i, AX]`,
//! where `AX` is `AXn` (machine axis n), a machine axis name (`X1`) or a channel or geometry
//! axis name of the channel (then the machine axis it runs on).

use crate::alarm::Alarm;
use crate::interp::eval::value::Value;
use crate::machine_data::registry::{self, Def, Scope};
use crate::machine_data::{MachineConfig, MachineData, Value as MdValue};

/// The prefixes of machine data (`$M?_`) and setting data (`$S?_`) in programs.
const PREFIXES: [&str; 6] = ["$MN_", "$MC_", "$MA_", "$SN_", "$SC_", "$SA_"];

/// True if `name` is machine or setting data as a program writes it.
pub(crate) fn is_data_name(name: &str) -> bool {
    name.len() > 4 && PREFIXES.iter().any(|p| name.starts_with(p))
}

/// Reads `name[indices]` if `name` is machine or setting data; `None` for any other name.
pub(crate) fn read(
    stored: &MachineData,
    cfg: &MachineConfig,
    name: &str,
    indices: &[Value],
    line: u32,
) -> Option<Result<Value, Alarm>> {
    if !is_data_name(name) {
        return None;
    }
    Some(read_datum(stored, cfg, name, indices, line))
}

fn read_datum(
    stored: &MachineData,
    cfg: &MachineConfig,
    name: &str,
    indices: &[Value],
    line: u32,
) -> Result<Value, Alarm> {
    let def = registry::lookup(name).ok_or_else(|| {
        let what = match crate::machine_data::text::unmodelled(name) {
            Some(_) => format!("{name} (setting datum not modelled by NCTwin)"),
            None => name.to_string(),
        };
        Alarm::unknown_name(line, &what)
    })?;
    let (array, axis) = match (def.scope, indices) {
        (Scope::Axis, [ax]) => (None, Some(ax)),
        (Scope::Axis, [i, ax]) => (Some(i), Some(ax)),
        (Scope::Axis, _) => return Err(Alarm::index_error(line, name, "axial data takes [AXn] or [index, AXn]")),
        (_, []) => (None, None),
        (_, [i]) => (Some(i), None),
        _ => return Err(Alarm::index_error(line, name, "takes at most one index")),
    };
    // `[AXn]` alone on axial array data means entry 0, as in machine data text
    // (`$MA_MAX_AX_ACCEL[X]` is the entry of the first dynamic response mode).
    let index = match (def.scope, array) {
        (Scope::Axis, None) => 0,
        _ => array_index(def, name, array, line)?,
    };
    let axis = match axis {
        Some(ax) => machine_axis(stored, cfg, &ax.as_text())
            .ok_or_else(|| Alarm::index_error(line, name, &format!("{} is no machine axis", ax.as_text())))?,
        None => 0,
    };
    Ok(match stored.get(def, axis, index) {
        MdValue::Bool(b) => Value::Bool(b),
        MdValue::Int(i) => Value::Int(i),
        MdValue::Real(r) => Value::Real(r),
        MdValue::Str(s) => Value::Str(s),
    })
}

fn array_index(def: &Def, name: &str, index: Option<&Value>, line: u32) -> Result<usize, Alarm> {
    let Some(index) = index else {
        return match def.len {
            1 => Ok(0),
            n => Err(Alarm::index_error(line, name, &format!("an array of {n}: an index is needed"))),
        };
    };
    let i = index.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
    usize::try_from(i)
        .ok()
        .filter(|&i| i < def.len)
        .ok_or_else(|| Alarm::index_error(line, name, &format!("index {i} (valid: 0..{})", def.len - 1)))
}

/// The machine axis (0-based number) a program's axis index names: `AXn`, a machine axis name,
/// or a channel/geometry axis name of this channel.
fn machine_axis(stored: &MachineData, cfg: &MachineConfig, id: &str) -> Option<usize> {
    let id = id.trim();
    if let Some(n) = id.get(..2).filter(|p| p.eq_ignore_ascii_case("AX")).and_then(|_| id[2..].parse::<usize>().ok()) {
        return (1..=registry::MAX_MACHINE_AXES).contains(&n).then(|| n - 1);
    }
    let named =
        |wanted: &str| (0..registry::MAX_MACHINE_AXES).find(|&i| machine_name(stored, i).eq_ignore_ascii_case(wanted));
    named(id).or_else(|| {
        let k = cfg.program_axis(id)?;
        named(&cfg.axis(k).name)
    })
}

fn machine_name(stored: &MachineData, i: usize) -> String {
    let def = registry::lookup("$MN_AXCONF_MACHAX_NAME_TAB").expect("in the registry");
    match stored.get(def, 0, i) {
        MdValue::Str(s) => s,
        _ => String::new(),
    }
}

/// The axis index of axial data a program writes, as NC data text takes it (`AXn` or a machine
/// axis name): a channel or geometry axis name becomes `AXn` of its machine axis. Any other
/// index is returned unchanged (the data text then refuses it, naming it).
pub(crate) fn axis_index_for_text(stored: &MachineData, cfg: &MachineConfig, name: &str, id: String) -> String {
    if !(name.starts_with("$MA_") || name.starts_with("$SA_")) {
        return id;
    }
    match machine_axis(stored, cfg, &id) {
        Some(n) => format!("AX{}", n + 1),
        None => id,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mill() -> (MachineData, MachineConfig) {
        let mut data = MachineData::default();
        let cfg =
            data.apply_text(crate::machine_data::presets::find("mill-3axis").expect("preset").text).expect("valid");
        (data, cfg)
    }

    #[test]
    fn only_the_six_data_prefixes_are_machine_or_setting_data() {
        assert!(is_data_name("$MN_X") && is_data_name("$SA_X") && is_data_name("$SC_X"));
        assert!(!is_data_name("$P_UIFR") && !is_data_name("$TC_DP1") && !is_data_name("$MN_"));
    }

    #[test]
    fn axial_data_is_found_by_axn_machine_name_and_channel_name() {
        let (data, cfg) = mill();
        let by_number = machine_axis(&data, &cfg, "AX2");
        assert_eq!(by_number, Some(1));
        let machine = machine_name(&data, 1);
        assert_eq!(machine_axis(&data, &cfg, &machine), Some(1));
        assert_eq!(machine_axis(&data, &cfg, "Y"), Some(1));
        assert_eq!(machine_axis(&data, &cfg, "AX0"), None);
        assert_eq!(machine_axis(&data, &cfg, "Q7"), None);
    }
}

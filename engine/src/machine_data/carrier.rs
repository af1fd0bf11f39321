//! Orientable toolholders (swivel data sets): `$TC_CARR1..$TC_CARR65[m]` as stored NC data
//! and typed into [`Carrier`] for the interpreter (REFERENCE §7.1).
//!
//! Storage keeps only values that differ from the defaults, keyed by (holder m, parameter n),
//! like the tool data `$TC_DP`. Toolholders are numbered 1..MD18088 `MM_NUM_TOOL_CARRIER`.
//!
//! Parameter meanings: 1–3 l1, 4–6 l2, 7–9 v1, 10–12 v2, 13/14 angles, 15–17 l3, 18–20 l4,
//! 21/22 channel axis of v1/v2, 23 kinematic type T/P/M, 24/25 axis offsets (initial setting),
//! 26/27 Hirth offset, 28/29 Hirth increment, 30/31 minimum and 32/33 maximum positions,
//! 34 name, 35/36 rotary axis names (CYCLE800), 37 identifier, 38–40 retraction position,
//! 41–46 and 55–60 fine offsets of l1..l4, 64/65 fine offsets of 24/25. 47–54 and 61–63 are
//! not defined and are refused on read and write access (W1 FM 08/2005 p.2-86).

use std::collections::BTreeMap;

use super::Value;
use super::text::Literal;

/// Highest parameter number `$TC_CARRn`.
pub const CARR_PARAMS: u32 = 65;

/// Alarm 14153: invalid kinematic type in `$TC_CARR23` (PGA 04.00 system variable list).
pub const ALARM_INVALID_KIND: u32 = 14153;

/// How a parameter is typed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParamKind {
    Real,
    Int,
    /// A channel axis name (21, 22); stored upper case, 0 or "" = none.
    Axis,
    /// The kinematic type character (23).
    Kind,
    Str,
}

/// The type of parameter `n`, or `None` for an undefined number.
pub fn param_kind(n: u32) -> Option<ParamKind> {
    Some(match n {
        1..=20 | 24..=33 | 38..=46 | 55..=60 | 64 | 65 => ParamKind::Real,
        21 | 22 => ParamKind::Axis,
        23 => ParamKind::Kind,
        34..=36 => ParamKind::Str,
        37 => ParamKind::Int,
        _ => return None,
    })
}

/// The default value of parameter `n` (a defined one).
pub fn default_value(n: u32) -> Value {
    match param_kind(n) {
        Some(ParamKind::Kind) => Value::Str("T".into()),
        Some(ParamKind::Axis | ParamKind::Str) => Value::Str(String::new()),
        Some(ParamKind::Int) => Value::Int(0),
        _ => Value::Real(0.0),
    }
}

/// Converts a literal of NC data text into the stored value of parameter `n`; the error is
/// the message (the kinematic type names alarm 14153).
pub fn convert(n: u32, lit: &Literal) -> Result<Value, String> {
    let kind = param_kind(n).ok_or_else(|| format!("$TC_CARR{n} is not defined (1..46, 55..60, 64, 65)"))?;
    match (kind, lit) {
        (ParamKind::Real, Literal::Number(v)) => Ok(Value::Real(*v)),
        (ParamKind::Int, Literal::Number(v)) if v.fract() == 0.0 && v.abs() < 1e15 => Ok(Value::Int(*v as i64)),
        (ParamKind::Axis, Literal::Number(v)) if *v == 0.0 => Ok(Value::Str(String::new())),
        (ParamKind::Axis, Literal::Ident(s) | Literal::Str(s)) if s.len() <= 32 => {
            Ok(Value::Str(s.to_ascii_uppercase()))
        }
        (ParamKind::Kind, Literal::Str(s) | Literal::Ident(s)) => match s.to_ascii_uppercase().as_str() {
            k @ ("T" | "P" | "M") => Ok(Value::Str(k.to_string())),
            _ => Err(format!("alarm {ALARM_INVALID_KIND}: kinematic type \"{s}\" (T, P or M)")),
        },
        (ParamKind::Kind, _) => {
            Err(format!("alarm {ALARM_INVALID_KIND}: kinematic type must be \"T\", \"P\" or \"M\""))
        }
        (ParamKind::Str, Literal::Str(s)) if s.len() <= 32 => Ok(Value::Str(s.clone())),
        (ParamKind::Str, Literal::Str(_)) => Err("string longer than 32 characters".into()),
        (kind, lit) => Err(format!("expected {kind:?}, found {lit:?}")),
    }
}

/// The value as NC data text (right-hand side).
pub fn show(n: u32, v: &Value) -> String {
    match (param_kind(n), v) {
        (Some(ParamKind::Axis), Value::Str(s)) => s.clone(),
        (_, Value::Str(s)) => format!("\"{s}\""),
        (_, Value::Int(i)) => i.to_string(),
        (_, Value::Real(r)) => format!("{r:?}"),
        (_, Value::Bool(b)) => if *b { "TRUE" } else { "FALSE" }.to_string(),
    }
}

/// Kinematic type `$TC_CARR23`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CarrierKind {
    /// "T": only the tool rotates (swivel head).
    Tool,
    /// "P": only the workpiece rotates (swivel table).
    Part,
    /// "M": axis 1 turns the tool, axis 2 the workpiece.
    Mixed,
}

/// A Hirth-toothed rotary axis: positions `offset + k·increment` only.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hirth {
    pub offset: f64,
    pub increment: f64,
}

impl Hirth {
    /// The nearest toothed position to `angle` (degrees).
    pub fn snap(&self, angle: f64) -> f64 {
        self.offset + ((angle - self.offset) / self.increment).round() * self.increment
    }
}

/// One toolholder, typed. Vectors in mm in the machine's X, Y, Z; angles in degrees.
#[derive(Debug, Clone, PartialEq)]
pub struct Carrier {
    pub number: u32,
    /// `$TC_CARR34` (empty: addressed by number only).
    pub name: String,
    pub kind: CarrierKind,
    /// Offset vectors l1..l4, fine offsets added when SD42974 TOCARR_FINE_CORRECTION is set.
    pub l: [[f64; 3]; 4],
    /// The stored basic vectors (1..6, 15..20) and fine offsets (41..46, 55..60) as written.
    pub l_basic: [[f64; 3]; 4],
    pub l_fine: [[f64; 3]; 4],
    /// The stored `$TC_CARR24/25` and their fine offsets `$TC_CARR64/65`.
    pub offsets_basic: [f64; 2],
    pub offsets_fine: [f64; 2],
    /// Rotary axis directions v1, v2 as entered (not normalised; zero = axis absent).
    pub v: [[f64; 3]; 2],
    /// `$TC_CARR13/14`: the stored angles.
    pub angles: [f64; 2],
    /// `$TC_CARR21/22`: channel axis names of v1, v2 (upper case).
    pub axes: [Option<String>; 2],
    /// `$TC_CARR24/25` (+ 64/65 fine): axis position in the initial setting.
    pub offsets: [f64; 2],
    pub hirth: [Option<Hirth>; 2],
    /// Software limits `$TC_CARR30/32`, `31/33`; `None` when both are 0 (not checked).
    pub limits: [Option<(f64, f64)>; 2],
    /// `$TC_CARR35/36`: rotary axis names for CYCLE800.
    pub axis_names: [String; 2],
    /// `$TC_CARR37`: identifier / control word of the swivel data set.
    pub control: i64,
    /// `$TC_CARR38..40`: retraction position X, Y, Z (MCS).
    pub retract: [f64; 3],
}

impl Carrier {
    /// Types holder `m` from the stored parameters. `fine`: SD42974 is set.
    pub fn build(m: u32, params: &BTreeMap<u32, Value>, fine: bool) -> Carrier {
        let get = |n: u32| params.get(&n).cloned().unwrap_or_else(|| default_value(n));
        let num = |n: u32| get(n).as_f64().unwrap_or(0.0);
        let text = |n: u32| match get(n) {
            Value::Str(s) => s,
            _ => String::new(),
        };
        let f = if fine { 1.0 } else { 0.0 };
        let plain = |a: u32| -> [f64; 3] { std::array::from_fn(|i| num(a + i as u32)) };
        let vec = |a: u32, fine_at: u32| -> [f64; 3] {
            std::array::from_fn(|i| num(a + i as u32) + f * num(fine_at + i as u32))
        };
        let kind = match text(23).as_str() {
            "P" => CarrierKind::Part,
            "M" => CarrierKind::Mixed,
            _ => CarrierKind::Tool,
        };
        let hirth = |o: u32, inc: u32| (num(inc) > 0.0).then(|| Hirth { offset: num(o), increment: num(inc) });
        let limits = |lo: u32, hi: u32| (num(lo) != 0.0 || num(hi) != 0.0).then(|| (num(lo), num(hi)));
        let axis = |n: u32| Some(text(n)).filter(|s| !s.is_empty());
        Carrier {
            number: m,
            name: text(34),
            kind,
            l: [vec(1, 41), vec(4, 44), vec(15, 55), vec(18, 58)],
            l_basic: [plain(1), plain(4), plain(15), plain(18)],
            l_fine: [plain(41), plain(44), plain(55), plain(58)],
            offsets_basic: [num(24), num(25)],
            offsets_fine: [num(64), num(65)],
            v: [plain(7), plain(10)],
            angles: [num(13), num(14)],
            axes: [axis(21), axis(22)],
            offsets: [num(24) + f * num(64), num(25) + f * num(65)],
            hirth: [hirth(26, 28), hirth(27, 29)],
            limits: [limits(30, 32), limits(31, 33)],
            axis_names: [text(35), text(36)],
            control: num(37) as i64,
            retract: [num(38), num(39), num(40)],
        }
    }

    /// True if the holder has rotary axis `i` (0 or 1): a non-zero direction.
    pub fn has_axis(&self, i: usize) -> bool {
        self.v[i].iter().any(|x| *x != 0.0)
    }

    /// The direction-reference rotary axis of CYCLE800 (0 or 1): `$TC_CARR37` thousands digit
    /// 2 selects axis 2, anything else axis 1 (this product's choice: the IM9 names a
    /// direction reference set at commissioning but the consulted pages do not give its digit).
    pub fn direction_reference(&self) -> usize {
        if (self.control / 1000) % 10 == 2 && self.has_axis(1) { 1 } else { 0 }
    }
}

#[cfg(test)]
mod tests {
    use super::super::MachineData;
    use super::*;

    const HOLDER: &str = "$MN_MM_NUM_TOOL_CARRIER=2
$TC_CARR1[1]=0.5\n$TC_CARR7[1]=0\n$TC_CARR8[1]=1\n$TC_CARR13[1]=30\n$TC_CARR20[1]=15
$TC_CARR21[1]=B\n$TC_CARR23[1]=\"p\"\n$TC_CARR28[1]=2.5\n$TC_CARR30[1]=-90\n$TC_CARR32[1]=90
$TC_CARR34[1]=\"TABLE\"\n$TC_CARR37[1]=2003\n$TC_CARR40[1]=250\n$TC_CARR41[1]=0.25\n$TC_CARR64[1]=0.1";

    #[test]
    fn holder_data_is_typed_and_round_trips_as_text() {
        let mut md = MachineData::default();
        md.apply_text(HOLDER).unwrap();
        let c = &md.carriers()[&1];
        assert_eq!(c.kind, CarrierKind::Part);
        assert_eq!((c.name.as_str(), c.axes[0].as_deref(), c.axes[1].as_deref()), ("TABLE", Some("B"), None));
        assert_eq!((c.v[0], c.angles, c.l[3]), ([0.0, 1.0, 0.0], [30.0, 0.0], [0.0, 0.0, 15.0]));
        assert_eq!((c.hirth[0], c.hirth[1]), (Some(Hirth { offset: 0.0, increment: 2.5 }), None));
        assert_eq!((c.limits[0], c.limits[1]), (Some((-90.0, 90.0)), None));
        assert_eq!((c.control, c.retract, c.direction_reference()), (2003, [0.0, 0.0, 250.0], 0));
        // Fine offsets only count with SD42974.
        assert_eq!((c.l[0][0], c.offsets[0]), (0.5, 0.0));
        md.apply_text("$SC_TOCARR_FINE_CORRECTION=TRUE").unwrap();
        let c = &md.carriers()[&1];
        assert_eq!((c.l[0][0], c.offsets[0]), (0.75, 0.1));
        let mut again = MachineData::default();
        again.apply_text(&md.to_text()).unwrap_or_else(|e| panic!("{e}\n{}", md.to_text()));
        assert_eq!(again, md);
    }

    #[test]
    fn bad_holder_data_is_refused_with_its_line() {
        let mut md = MachineData::default();
        md.apply_text("$MN_MM_NUM_TOOL_CARRIER=2").unwrap();
        for (text, needle) in [
            ("$TC_CARR23[1]=\"X\"", "alarm 14153"),
            ("$TC_CARR23[1]=1", "alarm 14153"),
            ("$TC_CARR1[3]=1", "out of range 1..2"),
            ("$TC_CARR1[0]=1", "out of range 1..2"),
            ("$TC_CARR47[1]=1", "unknown name $TC_CARR47"),
            ("$TC_CARR66[1]=1", "unknown name"),
            ("$TC_CARR1=1", "needs [toolholder number]"),
            ("$TC_CARR37[1]=1.5", "expected Int"),
        ] {
            let e = md.apply_text(&format!("; first\n{text}")).unwrap_err();
            assert_eq!(e.line, Some(2), "{text}");
            assert!(e.message.contains(needle), "{text}: {}", e.message);
        }
        // Without MD18088 there is no toolholder at all.
        let e = MachineData::default().apply_text("$TC_CARR1[1]=1").unwrap_err();
        assert!(e.message.contains("MM_NUM_TOOL_CARRIER"), "{e}");
    }

    #[test]
    fn hirth_teeth_snap_to_the_nearest_tooth() {
        let h = Hirth { offset: 1.0, increment: 2.5 };
        assert_eq!((h.snap(10.0), h.snap(-3.0)), (11.0, -4.0));
    }
}

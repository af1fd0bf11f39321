//! Tool-management data as the control stores them beside the cutting edges: tool data
//! `$TC_TP1..11[t]`, magazine data `$TC_MAP1..10[m]`, magazine place data `$TC_MPP1..7[m,p]` and
//! monitoring data `$TC_MOP1..15[t,d]` (Function Manual Tool Management, "tool data",
//! "magazine data", "monitoring data").
//!
//! Input: one assignment line of NC data text. Output: the raw values, kept only where they
//! differ from the default, written back as text in a stable order. What the values mean
//! together (which tool sits in which place, free places) is worked out at activation in
//! [`super::tools_list`].

use std::collections::BTreeMap;

use super::text::{IndexTok, Literal};
use super::{MAX_EDGE_NUMBER, MAX_TOOL_NUMBER, MdError, Value};

/// Highest magazine number: 9998 is the buffer magazine (spindle, gripper), 9999 the loading
/// magazine of the control's tool management.
pub const MAX_MAGAZINE: i64 = 9999;
/// The buffer magazine: the spindle place is one of its places.
pub const BUFFER_MAGAZINE: u32 = 9998;
/// Highest place number within a magazine (this product's bound).
pub const MAX_PLACE: i64 = 999;

/// A family of tool-management data.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Family {
    /// `$TC_TPn[t]`: tool data (1 duplo, 2 name, 3..6 sizes, 7 place type, 8 state, 9
    /// monitoring type, 10 replacement strategy, 11 subgroup).
    Tool,
    /// `$TC_MAPn[m]`: magazine data (1 type, 2 name, 3 state, 6 rows, 7 places, ...).
    Magazine,
    /// `$TC_MPPn[m,p]`: place data (1 kind, 2 type, 3 adjacent, 4 state, 5 type index, 6 tool,
    /// 7 adapter).
    Place,
    /// `$TC_MOPn[t,d]`: monitoring data of a cutting edge (1/2 prewarning and remaining
    /// time, 3/4 count, 5/6 wear, 11 time setpoint, 13 count setpoint, 15 wear setpoint).
    Monitoring,
}

impl Family {
    /// The family and parameter of a `$TC_` name this module stores.
    pub fn of(name: &str) -> Option<(Family, u32)> {
        let upper = name.to_ascii_uppercase();
        let rest = upper.strip_prefix("$TC_")?;
        let split = rest.find(|c: char| c.is_ascii_digit())?;
        let (family, n) = rest.split_at(split);
        let n: u32 = n.parse().ok()?;
        let (family, max) = match family {
            "TP" => (Family::Tool, 11),
            "MAP" => (Family::Magazine, 10),
            "MPP" => (Family::Place, 7),
            "MOP" => (Family::Monitoring, 15),
            _ => return None,
        };
        (1..=max).contains(&n).then_some((family, n))
    }

    fn prefix(self) -> &'static str {
        match self {
            Family::Tool => "$TC_TP",
            Family::Magazine => "$TC_MAP",
            Family::Place => "$TC_MPP",
            Family::Monitoring => "$TC_MOP",
        }
    }

    /// Whether parameter `n` is a string (tool and magazine names).
    fn is_text(self, n: u32) -> bool {
        n == 2 && matches!(self, Family::Tool | Family::Magazine)
    }

    /// Whether parameter `n` is a real number (monitoring data); the rest are integers.
    fn is_real(self) -> bool {
        self == Family::Monitoring
    }
}

/// The raw tool-management data; the key is (family, first index, second index or 0,
/// parameter).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ToolMgmtData {
    values: BTreeMap<(Family, u32, u32, u32), Value>,
}

impl ToolMgmtData {
    /// Whether `name` is tool-management data this module stores.
    pub fn handles(name: &str) -> bool {
        Family::of(name).is_some()
    }

    /// Stores `name[indices]=value`, checking the indices and the value's type.
    pub fn assign(&mut self, line: u32, name: &str, indices: &[IndexTok], value: &Literal) -> Result<(), MdError> {
        let err = |m: String| MdError::at(line, m);
        let (family, n) = Family::of(name).ok_or_else(|| err(format!("unknown name {name}")))?;
        let number = |tok: &IndexTok| match tok {
            IndexTok::Number(v) => Some(*v),
            IndexTok::Name(_) => None,
        };
        let nums: Vec<Option<i64>> = indices.iter().map(number).collect();
        let (a, b) = match (family, nums.as_slice()) {
            (Family::Tool, [Some(t)]) => {
                if !(1..=MAX_TOOL_NUMBER).contains(t) {
                    return Err(err(format!("{name}[{t}]: tool number out of range 1..{MAX_TOOL_NUMBER}")));
                }
                (*t, 0)
            }
            (Family::Magazine, [Some(m)]) => {
                if !(1..=MAX_MAGAZINE).contains(m) {
                    return Err(err(format!("{name}[{m}]: magazine number out of range 1..{MAX_MAGAZINE}")));
                }
                (*m, 0)
            }
            (Family::Place, [Some(m), Some(p)]) => {
                if !(1..=MAX_MAGAZINE).contains(m) {
                    return Err(err(format!("{name}[{m},{p}]: magazine number out of range 1..{MAX_MAGAZINE}")));
                }
                if !(1..=MAX_PLACE).contains(p) {
                    return Err(err(format!("{name}[{m},{p}]: place number out of range 1..{MAX_PLACE}")));
                }
                (*m, *p)
            }
            (Family::Monitoring, [Some(t), Some(d)]) => {
                if !(1..=MAX_TOOL_NUMBER).contains(t) || !(1..=MAX_EDGE_NUMBER).contains(d) {
                    return Err(err(format!(
                        "{name}[{t},{d}]: tool 1..{MAX_TOOL_NUMBER} and cutting edge 1..{MAX_EDGE_NUMBER} expected"
                    )));
                }
                (*t, *d)
            }
            (Family::Tool, _) => return Err(err(format!("{name} needs [tool number], e.g. {name}[1]"))),
            (Family::Magazine, _) => return Err(err(format!("{name} needs [magazine number], e.g. {name}[1]"))),
            (Family::Place, _) => return Err(err(format!("{name} needs [magazine, place], e.g. {name}[1,1]"))),
            (Family::Monitoring, _) => {
                return Err(err(format!("{name} needs [tool number, cutting edge], e.g. {name}[1,1]")));
            }
        };
        let v = match value {
            Literal::Str(s) if family.is_text(n) => {
                if s.len() > 32 {
                    return Err(err(format!("{name}: a name has at most 32 characters")));
                }
                Value::Str(s.clone())
            }
            Literal::Number(x) if !family.is_text(n) && family.is_real() => Value::Real(*x),
            Literal::Number(x) if !family.is_text(n) && x.fract() == 0.0 && x.abs() <= i32::MAX as f64 => {
                Value::Int(*x as i64)
            }
            _ if family.is_text(n) => return Err(err(format!("{name}: expected a string in double quotes"))),
            _ if family.is_real() => return Err(err(format!("{name}: expected a number"))),
            _ => return Err(err(format!("{name}: expected an integer"))),
        };
        let key = (family, a as u32, b as u32, n);
        let default = match &v {
            Value::Int(i) => *i == 0,
            Value::Real(r) => *r == 0.0,
            Value::Str(s) => s.is_empty(),
            Value::Bool(b) => !*b,
        };
        if default {
            self.values.remove(&key);
        } else {
            self.values.insert(key, v);
        }
        Ok(())
    }

    /// The value of one datum, `None` where it has its default (0 or the empty string).
    pub fn get(&self, family: Family, a: u32, b: u32, n: u32) -> Option<&Value> {
        self.values.get(&(family, a, b, n))
    }

    /// Integer view of a datum (0 when not set).
    pub fn int(&self, family: Family, a: u32, b: u32, n: u32) -> i64 {
        match self.get(family, a, b, n) {
            Some(Value::Int(i)) => *i,
            Some(Value::Real(r)) => *r as i64,
            _ => 0,
        }
    }

    /// Every stored datum of `family` as ((first index, second index), parameter, value).
    pub fn of_family(&self, family: Family) -> impl Iterator<Item = ((u32, u32), u32, &Value)> {
        self.values.iter().filter(move |((f, ..), _)| *f == family).map(|((_, a, b, n), v)| ((*a, *b), *n, v))
    }

    /// Empties the place entries (`$TC_MPP6`) that hold tool `t`.
    pub fn clear_places_of(&mut self, t: u32) {
        self.values.retain(|(f, _, _, n), v| !(*f == Family::Place && *n == 6 && *v == Value::Int(t.into())));
    }

    /// Removes every datum of tool `t`: tool data, monitoring data and its place entry.
    pub fn delete_tool(&mut self, t: u32) {
        self.clear_places_of(t);
        self.values.retain(|(f, a, _, _), _| !(matches!(f, Family::Tool | Family::Monitoring) && *a == t));
    }

    /// Puts tool `t` into place (m, p), or empties the place for `None` (loading/unloading).
    pub fn set_place_tool(&mut self, m: u32, p: u32, t: Option<u32>) {
        match t {
            Some(t) => self.values.insert((Family::Place, m, p, 6), Value::Int(t.into())),
            None => self.values.remove(&(Family::Place, m, p, 6)),
        };
    }

    /// The data as NC data text lines, in a stable order.
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        for ((family, a, b, n), v) in &self.values {
            let index = match family {
                Family::Tool | Family::Magazine => format!("[{a}]"),
                Family::Place | Family::Monitoring => format!("[{a},{b}]"),
            };
            let value = match v {
                Value::Str(s) => format!("\"{s}\""),
                Value::Int(i) => i.to_string(),
                Value::Real(r) => format!("{r:?}"),
                Value::Bool(b) => u8::from(*b).to_string(),
            };
            out += &format!("{}{n}{index}={value}\n", family.prefix());
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine_data::MachineData;

    #[test]
    fn names_of_the_four_families_are_recognised_with_their_parameter_ranges() {
        assert_eq!(Family::of("$TC_TP2"), Some((Family::Tool, 2)));
        assert_eq!(Family::of("$TC_MPP6"), Some((Family::Place, 6)));
        assert_eq!(Family::of("$TC_MOP15"), Some((Family::Monitoring, 15)));
        assert_eq!(Family::of("$TC_TP12"), None);
        assert_eq!(Family::of("$TC_TPC1"), None, "user data stay unmodelled");
        assert_eq!(Family::of("$TC_DP1"), None);
    }

    #[test]
    fn tool_management_lines_round_trip_as_text() {
        let mut md = MachineData::default();
        let text = "$TC_TP1[3]=1\n$TC_TP2[3]=\"DRILL_8\"\n$TC_TP8[3]=2\n$TC_MAP1[1]=1\n$TC_MAP7[1]=10\n\
                    $TC_MPP6[1,4]=3\n$TC_MOP2[3,1]=12.5\n$TC_DP1[3,1]=200\n";
        md.apply_text(text).unwrap();
        let mut again = MachineData::default();
        again.apply_text(&md.to_text()).unwrap();
        assert_eq!(again, md);
    }

    #[test]
    fn bad_types_and_indices_name_the_line() {
        for (text, needle) in [
            ("$TC_TP2[1]=5", "expected a string"),
            ("$TC_TP8[1]=\"x\"", "expected an integer"),
            ("$TC_TP1[1]=1.5", "expected an integer"),
            ("$TC_MPP6[1]=3", "needs [magazine, place]"),
            ("$TC_MAP1[10000]=1", "magazine number out of range"),
            ("$TC_TP1[0]=1", "tool number out of range"),
        ] {
            let mut md = MachineData::default();
            let e = md.apply_text(&format!(";x\n{text}")).unwrap_err();
            assert_eq!(e.line, Some(2), "{text}");
            assert!(e.message.contains(needle), "{text}: {}", e.message);
        }
    }
}

//! `CHKDNO`: whether D numbers are unique across tools (Programming Manual "Job planning",
//! "Free assignment of D numbers: checking D numbers (CHKDNO)"; W1 "Free assignment of D
//! numbers").
//!
//! `CHKDNO` checks all D numbers of all tools against each other, `CHKDNO(T1)` those of T1
//! against every other tool, `CHKDNO(T1, T2)` those of T1 and T2 against each other,
//! `CHKDNO(T1, T2, D)` the one number D in T1 and T2. The value is TRUE when no D number occurs
//! in two tools of the checked range; replacement tools (duplos) are tools like the others.
//!
//! Decisions where this product differs from the control: the control writes the colliding
//! tool and D numbers back into the arguments (they are VAR parameters); here CHKDNO only gives
//! its value. A tool number that has no cutting edges checks as unique (no D number of its
//! own). NCTwin's relative D numbers are 1..12 per tool (MD18105/MD18106 are not modelled),
//! so a program uses CHKDNO to confirm a tool table in which every tool got its own D
//! numbers; with flat D numbers (MD18102 = 1, `machine_data/flat_d.rs`) the numbers are
//! unique by construction and CHKDNO looks at the tools' own edges only.

use std::collections::BTreeMap;

use super::super::eval::value::Value;
use crate::alarm::Alarm;
use crate::machine_data::MachineConfig;

/// `CHKDNO([T1[, T2[, D]]])`: TRUE when the D numbers of the checked tools are unique.
pub(in crate::interp) fn chkdno(cfg: &MachineConfig, args: &[Value], line: u32) -> Result<Value, Alarm> {
    let mut nums = Vec::with_capacity(args.len());
    for v in args {
        let n = v.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
        let n = u32::try_from(n)
            .map_err(|_| Alarm::value_out_of_range(line, &format!("CHKDNO: {n} is no tool or D number")))?;
        nums.push(n);
    }
    let edges = |t: u32| cfg.tools.range((t, 0)..=(t, u32::MAX)).map(|((_, d), _)| *d);
    let unique = match nums.as_slice() {
        [] => {
            let mut owners: BTreeMap<u32, u32> = BTreeMap::new();
            for (_, d) in cfg.tools.keys() {
                *owners.entry(*d).or_default() += 1;
            }
            owners.values().all(|n| *n == 1)
        }
        [t1] => edges(*t1).all(|d| !cfg.tools.keys().any(|(t, e)| t != t1 && *e == d)),
        [t1, t2] => t1 == t2 || edges(*t1).all(|d| !cfg.tools.contains_key(&(*t2, d))),
        [t1, t2, d] => t1 == t2 || !(cfg.tools.contains_key(&(*t1, *d)) && cfg.tools.contains_key(&(*t2, *d))),
        _ => return Err(Alarm::syntax(line, "CHKDNO takes at most two tool numbers and a D number")),
    };
    Ok(Value::Bool(unique))
}

//! The check of a program before Cycle start: its syntax ([`crate::lang::check`]) and, without
//! running it, the names it uses ([`names`]).
//!
//! Input: program text and a [`NameContext`] (the machine's axes, the session's program
//! names, the global user data defined so far). Output: [`Diagnostic`]s in line order, each
//! with the alarm the control gives when the block is reached: 12470 for an unknown G
//! function, 12550 for a name that is not defined, 14011 for a called program that does not
//! exist, 14080 for a jump destination that is not in the program. A synchronized action is
//! compiled as its block would be, and a name its compiler does not know is reported (12550).
//!
//! Why static: an HMI flags the names as the user types, for programs of millions of blocks,
//! without a trial run of the channel. The check is conservative: it flags only what a run
//! would refuse whatever the data (a name no branch of the program can make defined), and it
//! leaves system variables (`$...`) and the arguments of built-in keywords to the run.

mod names;

use std::collections::BTreeSet;
use std::sync::Arc;

use crate::lang::Diagnostic;
use crate::machine_data::MachineConfig;

/// What a name may refer to outside the program text.
#[derive(Debug, Clone)]
pub struct NameContext {
    cfg: Arc<MachineConfig>,
    /// The session's stored programs by upper-case name (any directory).
    programs: BTreeSet<String>,
    /// The global user variables (`DEF NCK`/`DEF CHAN`) declared so far.
    globals: BTreeSet<String>,
}

impl NameContext {
    /// A context of machine `cfg`, the session's programs and its global user variables.
    pub fn new(
        cfg: Arc<MachineConfig>,
        programs: impl IntoIterator<Item = String>,
        globals: impl IntoIterator<Item = String>,
    ) -> NameContext {
        NameContext { cfg, programs: programs.into_iter().collect(), globals: globals.into_iter().collect() }
    }

    /// Whether `name` is an axis a block may program: a channel or geometry axis, or, on a
    /// machine with transformation data, a geometry axis a transformation provides (TRANSMIT's
    /// Y on a lathe, which has no Y until TRANSMIT is selected).
    fn is_axis(&self, name: &str) -> bool {
        self.cfg.program_axis(name).is_some()
            || (!self.cfg.trafos.is_empty() && self.cfg.geo_names.iter().any(|g| g.eq_ignore_ascii_case(name)))
    }

    /// Whether a call finds program `name`: the session's programs, then the standard cycles.
    fn program_exists(&self, name: &str) -> bool {
        self.programs.contains(name) || crate::programs::cycles::find(name).is_some()
    }
}

/// Every error of `source` found before a run: the syntax errors of [`crate::lang::check`] and
/// the names of [`names`], sorted by line and column.
pub fn program(source: &str, ctx: &NameContext) -> Vec<Diagnostic> {
    let mut out = crate::lang::check(source);
    out.extend(names(source, ctx));
    out.sort_by_key(|d| (d.line, d.column));
    out
}

/// The names of `source` that a run would refuse (see the module doc); lines with syntax
/// errors are left to [`crate::lang::check`].
pub fn names(source: &str, ctx: &NameContext) -> Vec<Diagnostic> {
    names::Walker::new(&crate::lang::macros::expand(source), ctx).run()
}

//! User variables (DEF), R parameters and their scopes.
//!
//! Global user data (GUD-like, `DEF CHAN ...` / `DEF NCK ...`) and R parameters live for the
//! session; local variables (`DEF ...`) live for one program or subprogram call.

use crate::interp::eval::name_hash::NameMap;
use crate::interp::eval::value::{TypeError, Value};
use crate::interp::frames::frame::Frame;
use crate::lang::VarType;

/// Number of R parameters (MD28050 MM_NUM_R_PARAM default 100).
pub const R_PARAMS: usize = 100;

/// Bytes all user variables of a channel may hold together (global data, the locals of every
/// open program level, PROC parameters): the simulated control's user memory (the control sizes
/// it by MD18120/MD28040). A program that declares more gets alarm 12380 rather than the
/// server's memory; 16 MiB is some 500,000 REAL elements.
pub const USER_MEMORY_BYTES: usize = 16 << 20;

/// One declared variable: its type, array dimensions and elements in row-major order.
#[derive(Debug, Clone, PartialEq)]
pub struct Variable {
    pub ty: VarType,
    pub dims: Vec<usize>,
    pub data: Vec<Value>,
}

impl Variable {
    /// Bytes `elements` values of type `ty` occupy, counted against [`USER_MEMORY_BYTES`]
    /// before anything is allocated.
    pub fn footprint(ty: VarType, elements: usize) -> usize {
        let payload = match ty {
            VarType::Str(n) => usize::from(n),
            VarType::Frame => std::mem::size_of::<Frame>(),
            _ => 0,
        };
        elements.saturating_mul(std::mem::size_of::<Value>() + payload)
    }

    fn bytes(&self) -> usize {
        Variable::footprint(self.ty, self.data.len())
    }

    pub fn new(ty: VarType, dims: Vec<usize>) -> Variable {
        let n = dims.iter().product::<usize>().max(1);
        Variable { ty, dims, data: vec![Value::default_of(ty); n] }
    }

    /// Flat index of `indices` (0-based per dimension), checked against the dimensions.
    pub fn index(&self, indices: &[i64]) -> Result<usize, TypeError> {
        if indices.len() != self.dims.len() {
            return Err(TypeError(format!("needs {} index(es), got {}", self.dims.len(), indices.len())));
        }
        let mut flat = 0;
        for (i, (&ix, &dim)) in indices.iter().zip(&self.dims).enumerate() {
            if ix < 0 || ix as usize >= dim {
                return Err(TypeError(format!("index {ix} of dimension {} outside 0..{}", i + 1, dim - 1)));
            }
            flat = flat * dim + ix as usize;
        }
        Ok(flat)
    }
}

/// All variables visible to block preparation.
#[derive(Debug, Clone, PartialEq)]
pub struct Variables {
    pub r: Vec<f64>,
    /// By name, hashed (`name_hash`): read at nearly every statement of a cycle.
    globals: NameMap<Variable>,
    /// One frame of locals per active program level (main program, subprogram calls).
    locals: Vec<NameMap<Variable>>,
    /// What all declared variables occupy, by [`Variable::footprint`].
    bytes: usize,
}

impl Default for Variables {
    fn default() -> Self {
        Variables { r: vec![0.0; R_PARAMS], globals: NameMap::default(), locals: vec![NameMap::default()], bytes: 0 }
    }
}

impl Variables {
    pub fn get(&self, name: &str) -> Option<&Variable> {
        self.locals.last().and_then(|l| l.get(name)).or_else(|| self.globals.get(name))
    }

    /// The names of the global user variables (`DEF NCK`/`DEF CHAN`) declared so far.
    pub fn global_names(&self) -> impl Iterator<Item = &str> {
        self.globals.keys().map(String::as_str)
    }

    pub fn get_mut(&mut self, name: &str) -> Option<&mut Variable> {
        match self.locals.last_mut().filter(|l| l.contains_key(name)) {
            Some(l) => l.get_mut(name),
            None => self.globals.get_mut(name),
        }
    }

    /// Bytes of [`USER_MEMORY_BYTES`] still free for declarations.
    pub fn free_bytes(&self) -> usize {
        USER_MEMORY_BYTES.saturating_sub(self.bytes)
    }

    /// Declares a variable in the current program level or, for `global`, for the session.
    pub fn declare(&mut self, name: &str, var: Variable, global: bool) -> Result<(), TypeError> {
        let scope = if global { &mut self.globals } else { self.locals.last_mut().expect("a local frame") };
        if scope.contains_key(name) {
            return Err(TypeError(format!("{name} is already defined")));
        }
        self.bytes += var.bytes();
        scope.insert(name.to_string(), var);
        Ok(())
    }

    /// Enters a subprogram level.
    pub fn push_frame(&mut self) {
        self.locals.push(NameMap::default());
    }

    /// Leaves a subprogram level, dropping its locals.
    pub fn pop_frame(&mut self) {
        if self.locals.len() > 1 {
            let dropped: usize = self.locals.pop().into_iter().flatten().map(|(_, v)| v.bytes()).sum();
            self.bytes -= dropped;
        }
    }

    /// Starts a new main program: its locals are fresh, R parameters and globals stay.
    pub fn reset_locals(&mut self) {
        self.locals = vec![NameMap::default()];
        self.bytes = self.globals.values().map(Variable::bytes).sum();
    }
}

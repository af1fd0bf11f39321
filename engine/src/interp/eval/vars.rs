//! User variables (DEF), R parameters and their scopes.
//!
//! Global user data (GUD-like, `DEF CHAN ...` / `DEF NCK ...`) and R parameters live for the
//! session; local variables (`DEF ...`) live for one program or subprogram call.

use crate::interp::eval::name_hash::NameMap;
use crate::interp::eval::value::{TypeError, Value};
use crate::lang::VarType;

/// Number of R parameters (MD28050 MM_NUM_R_PARAM default 100).
pub const R_PARAMS: usize = 100;

/// One declared variable: its type, array dimensions and elements in row-major order.
#[derive(Debug, Clone, PartialEq)]
pub struct Variable {
    pub ty: VarType,
    pub dims: Vec<usize>,
    pub data: Vec<Value>,
}

impl Variable {
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
}

impl Default for Variables {
    fn default() -> Self {
        Variables { r: vec![0.0; R_PARAMS], globals: NameMap::default(), locals: vec![NameMap::default()] }
    }
}

impl Variables {
    pub fn get(&self, name: &str) -> Option<&Variable> {
        self.locals.last().and_then(|l| l.get(name)).or_else(|| self.globals.get(name))
    }

    pub fn get_mut(&mut self, name: &str) -> Option<&mut Variable> {
        match self.locals.last_mut().filter(|l| l.contains_key(name)) {
            Some(l) => l.get_mut(name),
            None => self.globals.get_mut(name),
        }
    }

    /// Declares a variable in the current program level or, for `global`, for the session.
    pub fn declare(&mut self, name: &str, var: Variable, global: bool) -> Result<(), TypeError> {
        let scope = if global { &mut self.globals } else { self.locals.last_mut().expect("a local frame") };
        if scope.contains_key(name) {
            return Err(TypeError(format!("{name} is already defined")));
        }
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
            self.locals.pop();
        }
    }

    /// Starts a new main program: its locals are fresh, R parameters and globals stay.
    pub fn reset_locals(&mut self) {
        self.locals = vec![NameMap::default()];
    }
}

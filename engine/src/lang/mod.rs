//! The part-program language, syntax only.
//!
//! Input: program text. Output: a [`Program`] of [`Block`]s whose words carry source lines and
//! offsets, plus every syntax error found ([`Diagnostic`]). What a word means (modal groups,
//! units, valid combinations) is decided by [`crate::interp`].

pub mod archive;
pub mod ast;
mod cursor;
mod definitions;
pub mod macros;
pub mod name;
mod parser;
mod plain_line;
mod statement_scan;
mod structure;
pub mod sync_action;
#[cfg(test)]
pub(crate) mod test_rng;
mod text;

pub use ast::*;
pub use parser::{
    COEFFICIENTS, MAX_EXPR_DEPTH, check, parse, parse_block, read_block, read_block_reusing, read_statement_block,
};
pub(crate) use plain_line::plain_words;
pub use text::ProgramText;

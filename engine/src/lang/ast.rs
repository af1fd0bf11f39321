//! Syntax tree of a part program: blocks of words with source positions. Meaning (modal
//! groups, units, which words may stand together) is the interpreter's business.

/// A parsed program: every block in source order, and every syntax error found.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Program {
    pub blocks: Vec<Block>,
    pub diagnostics: Vec<Diagnostic>,
}

/// A syntax error with the 1-based line it was found on.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    pub line: u32,
    /// Byte offset of the offending text within the whole program.
    pub offset: usize,
    pub message: String,
}

/// One NC block (one source line).
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// 1-based source line.
    pub line: u32,
    /// Byte offset of the line's start within the program (for highlighting in an HMI).
    pub offset: usize,
    /// The source text of the line without its line break.
    pub text: String,
    /// `/` at the start: skippable block.
    pub skip: bool,
    /// `N10` or `:10` block number.
    pub number: Option<u32>,
    /// `LABEL:` jump label.
    pub label: Option<String>,
    pub words: Vec<Word>,
    /// Text after `;`.
    pub comment: Option<String>,
}

/// One word of a block.
#[derive(Debug, Clone, PartialEq)]
pub enum Word {
    /// `G1`, `G17`, `G710`: a preparatory function by number.
    G(u32),
    /// `M3`, `M30`: a miscellaneous function by number.
    M(u32),
    /// An address with a value: `X10`, `F=100`, `CR=5`, `X=AC(10)`, `T1`, `D2`, `S1000`.
    Address { name: String, value: AddressValue },
    /// A bare keyword: `SUPA`, `TRAFOOF`, `ROT` (unknown keywords are reported by the interpreter).
    Keyword { name: String, args: Vec<Expr> },
}

/// The value of an address, with the coordinate mode if one was written.
#[derive(Debug, Clone, PartialEq)]
pub struct AddressValue {
    pub mode: Option<CoordMode>,
    pub expr: Expr,
}

/// Non-modal coordinate modes written around a value: `X=AC(10)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CoordMode {
    /// `AC(..)` absolute.
    Ac,
    /// `IC(..)` incremental.
    Ic,
    /// `DC(..)` rotary axis, shortest way.
    Dc,
    /// `ACP(..)` rotary axis, absolute in positive direction.
    Acp,
    /// `ACN(..)` rotary axis, absolute in negative direction.
    Acn,
}

/// An arithmetic expression.
#[derive(Debug, Clone, PartialEq)]
pub enum Expr {
    Number(f64),
    Str(String),
    /// `R1`, `$R[1]`: an R parameter by number.
    RParam(u32),
    Neg(Box<Expr>),
    Binary(BinOp, Box<Expr>, Box<Expr>),
    /// `SIN(30)`: a function call by name.
    Call(String, Vec<Expr>),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
}

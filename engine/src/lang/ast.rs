//! Syntax tree of a part program: blocks of words and statements with source positions.
//! Meaning (modal groups, units, which words may stand together, what a name refers to) is
//! the interpreter's business.

/// A parsed program: every block in source order, and every syntax error found.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Program {
    pub blocks: Vec<Block>,
    pub diagnostics: Vec<Diagnostic>,
}

/// An error found before the program runs, as the NC alarm the control shows for it.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    /// 1-based line.
    pub line: u32,
    /// 1-based column (byte) of the offending text within its line.
    pub column: u32,
    /// Byte offset of the offending text within the whole program.
    pub offset: usize,
    /// The alarm number: 12080 syntax error, 12640 invalid nesting of control structures,
    /// 12641 nesting too deep.
    pub alarm: u32,
    pub message: String,
}

/// Alarm 12080: syntax error.
pub const SYNTAX_ERROR: u32 = 12080;

impl Diagnostic {
    /// A syntax error (alarm 12080) at byte `col` of the line starting at `line_start`.
    pub fn syntax(line: u32, line_start: usize, col: usize, message: String) -> Diagnostic {
        Diagnostic::new(SYNTAX_ERROR, line, line_start, col, message)
    }

    /// An error with alarm `alarm` at byte `col` of the line starting at `line_start`.
    pub fn new(alarm: u32, line: u32, line_start: usize, col: usize, message: String) -> Diagnostic {
        Diagnostic {
            line,
            column: u32::try_from(col + 1).unwrap_or(u32::MAX),
            offset: line_start + col,
            alarm,
            message,
        }
    }
}

/// One NC block (one source line).
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// 1-based source line.
    pub line: u32,
    /// Byte offset of the line's start within the program (for highlighting in an HMI; the
    /// line's text is the program's from there to the line break).
    pub offset: usize,
    /// `/` or `/0`..`/9` at the start: the skip level (`/` is level 0) under which the block
    /// is skipped when that level is active (SKP, see `interp::program_control`).
    pub skip: Option<u8>,
    /// `N10` or `:10` block number.
    pub number: Option<u32>,
    /// `LABEL:` jump label.
    pub label: Option<String>,
    /// A control-flow or declaration statement filling the block (`IF`, `DEF`, `WHILE`, ...).
    pub stmt: Option<Stmt>,
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
    /// An address or assignment: `X10`, `F=100`, `CR=5`, `X=AC(10)`, `R1=2`, `ABC[2]=R1`,
    /// `$TC_DP1[1,1]=120`.
    Address { name: super::name::Name, indices: Vec<Expr>, value: AddressValue },
    /// A bare keyword or call: `SUPA`, `TRAFOOF`, `TRANSMIT(1)`, `MSG("x")`, `L100`-style calls.
    Keyword { name: String, args: Vec<Expr> },
    /// `GOTOF LABEL` and its kin at the end of a block.
    Goto(Goto),
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

/// Direction of a jump.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GotoKind {
    /// `GOTOF`: search forward.
    Forward,
    /// `GOTOB`: search backward.
    Backward,
    /// `GOTO`: forward, then backward.
    Both,
    /// `GOTOC`: like GOTO, but a missing target is not an error.
    Continue,
    /// `GOTOS`: back to the start of the program.
    Start,
}

/// A jump and its target.
#[derive(Debug, Clone, PartialEq)]
pub struct Goto {
    pub kind: GotoKind,
    pub target: JumpTarget,
}

/// Where a jump goes.
#[derive(Debug, Clone, PartialEq)]
pub enum JumpTarget {
    Label(String),
    /// `N100` or `:100`.
    BlockNumber(u32),
    /// A computed target: a STRING expression holding a label or block number
    /// (`GOTOF "N"<<R10`, `GOTOF DEST[2]`). A plain name (`GOTOF DEST`) is a [`JumpTarget::Label`]
    /// that the interpreter reads from a STRING variable of that name if one is defined.
    Expr(Expr),
    /// `GOTOS`: the first block of the program.
    ProgramStart,
}

/// Statements that fill a block (declarations and control flow).
#[derive(Debug, Clone, PartialEq)]
pub enum Stmt {
    /// `DEF REAL LEN, PTS[3]=SET(1,2,3)`; `global` for `DEF CHAN`/`DEF NCK` (global user data).
    Def {
        global: bool,
        ty: VarType,
        vars: Vec<VarDecl>,
    },
    /// `IF cond` (block form) or `IF cond GOTOF L` (jump form).
    If {
        cond: Expr,
        goto: Option<Goto>,
    },
    Else,
    EndIf,
    While(Expr),
    EndWhile,
    /// `FOR var = start TO end`.
    For {
        var: Lvalue,
        start: Expr,
        end: Expr,
    },
    EndFor,
    Repeat,
    /// `REPEAT START P=n` (from START to the block before the REPEAT, or to an `ENDLABEL:`
    /// between them) and `REPEAT START END P=n` (START to END, both included): program section
    /// repetition, `count` runs (one if `None`).
    RepeatSection {
        start: JumpTarget,
        end: Option<JumpTarget>,
        count: Option<Expr>,
    },
    /// `REPEATB LABEL P=n`: the block carrying LABEL, `count` times (once if `None`).
    RepeatBlock {
        target: JumpTarget,
        count: Option<Expr>,
    },
    Until(Expr),
    Loop,
    EndLoop,
    /// `CASE(expr) OF c1 GOTOF L1 c2 GOTOF L2 DEFAULT GOTOF L3`.
    Case {
        expr: Expr,
        arms: Vec<(Expr, Goto)>,
        default: Option<Goto>,
    },
    /// `GOTOF L` alone.
    Goto(Goto),
    /// `PROC NAME(type param, ...) [SAVE DISPLOF ACTBLOCNO ...]`.
    Proc {
        name: String,
        params: Vec<Param>,
        attributes: ProcAttributes,
    },
    /// `RET` (end of subprogram).
    Ret,
    /// `EXTERN NAME(types)`: the subprogram's parameters as (by reference, type).
    Extern {
        name: String,
        params: Vec<(bool, VarType)>,
    },
}

/// A declared variable.
#[derive(Debug, Clone, PartialEq)]
pub struct VarDecl {
    pub name: String,
    pub dims: Vec<Expr>,
    /// Initial values (one, or one per element in order).
    pub init: Vec<Expr>,
}

/// A formal parameter of a `PROC`.
#[derive(Debug, Clone, PartialEq)]
pub struct Param {
    pub by_reference: bool,
    pub ty: VarType,
    pub name: String,
    pub dims: Vec<Expr>,
}

/// Data types of the NC language.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VarType {
    Int,
    Real,
    Bool,
    Char,
    /// `STRING[n]`: maximum length.
    Str(u16),
    Axis,
    Frame,
}

/// A place a value can be assigned to.
#[derive(Debug, Clone, PartialEq)]
pub struct Lvalue {
    pub name: String,
    pub indices: Vec<Expr>,
}

/// An expression.
#[derive(Debug, Clone, PartialEq)]
pub enum Expr {
    Number(f64),
    Str(String),
    Bool(bool),
    /// `R1`, `R[i]`, `$R[1]`: an R parameter by number.
    RParam(Box<Expr>),
    /// A user variable, system variable (`$AA_IM[X]`) or name (an axis), with indices.
    Var {
        name: String,
        indices: Vec<Expr>,
    },
    Unary(UnOp, Box<Expr>),
    Binary(BinOp, Box<Expr>, Box<Expr>),
    /// `SIN(30)`: a function call by name.
    Call(String, Vec<Expr>),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnOp {
    Neg,
    Not,
    BNot,
}

/// Binary operators, from the lowest priority (comparison) to the highest (`*`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    /// `:` frame concatenation (may not be mixed with other operators).
    Chain,
    Eq,
    Ne,
    Gt,
    Lt,
    Ge,
    Le,
    Concat,
    Or,
    Xor,
    And,
    BOr,
    BXor,
    BAnd,
    Add,
    Sub,
    Mul,
    Div,
    IntDiv,
    Mod,
}

/// The attributes of a `PROC` line that change how the subprogram runs or is shown.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ProcAttributes {
    /// `SAVE`: the caller's modal G functions and frames come back at the return.
    pub save: bool,
    /// `DISPLOF`: the subprogram's blocks are not displayed; the block display shows the
    /// calling block while they run, and alarms name it.
    pub displof: bool,
    /// `ACTBLOCNO` (with DISPLOF): alarms name the subprogram's own block after all.
    pub actblocno: bool,
    /// `SBLOF`: in single block mode the subprogram runs as one step with its calling block
    /// (the standard cycles stop once, after the cycle).
    pub sblof: bool,
    /// `DISPLON`: the subprogram's blocks are displayed although its caller's are not.
    pub displon: bool,
}

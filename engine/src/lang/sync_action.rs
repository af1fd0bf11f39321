//! The syntax of motion-synchronous actions (Programming Manual Job Planning, "Motion-synchronous
//! actions"; Function Manual "Synchronized actions"):
//!
//! ```text
//! [ID=n | IDS=n] [WHEN | WHENEVER | FROM | EVERY [G70|G71|G700|G710] <condition>] DO <action> [<action> ...]
//! ```
//!
//! Syntax only: names stay names (`$AA_IM`, the axis `X`); what they refer to and whether a
//! synchronized action may read or write them is decided when the interpreter compiles the
//! action (`interp::synchronized`). The operators keep the control's priorities, under which
//! comparisons bind weakest: `$A_IN[1]==1 AND $A_IN[2]==1` needs brackets as on the control.
//!
//! The parser is called for the rest of a line that opens with one of the words above; the
//! block parser stores the text (`SYNC_ACTION_WORD`), so the line is checked before the run
//! and parsed once more when the block is prepared, never in the interpolation cycle.

/// The keyword the block parser files a synchronized action's line under: a `Word::Keyword`
/// of this name whose only argument is the text from `ID=`/`WHEN`/`DO` on.
pub const SYNC_ACTION_WORD: &str = "$SYNC_ACTION";

/// A parsed synchronized action.
#[derive(Debug, Clone, PartialEq)]
pub struct SyncAction {
    pub id: Option<SyncId>,
    pub trigger: Trigger,
    /// `G70`/`G71`/`G700`/`G710` before the condition: the unit its lengths are read in.
    pub units: Option<u32>,
    pub condition: Option<SExpr>,
    pub actions: Vec<SAction>,
    /// The condition as written (upper case, trimmed), for display.
    pub condition_text: String,
}

/// `ID=n` (modal: until the program ends or CANCEL) or `IDS=n` (static: beyond program end
/// and reset, in every mode).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SyncId {
    Modal(u32),
    Static(u32),
}

impl SyncId {
    pub fn number(self) -> u32 {
        match self {
            SyncId::Modal(n) | SyncId::Static(n) => n,
        }
    }
}

/// How often the condition is checked and the actions run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Trigger {
    /// No condition word: the actions run in every IPO cycle.
    Always,
    /// Once, the first cycle the condition holds.
    When,
    /// Every cycle the condition holds.
    Whenever,
    /// Every cycle from the first one in which the condition held.
    From,
    /// Once each time the condition changes from false to true.
    Every,
}

impl Trigger {
    pub fn as_str(self) -> &'static str {
        match self {
            Trigger::Always => "DO",
            Trigger::When => "WHEN",
            Trigger::Whenever => "WHENEVER",
            Trigger::From => "FROM",
            Trigger::Every => "EVERY",
        }
    }
}

/// An expression of a synchronized action.
#[derive(Debug, Clone, PartialEq)]
pub enum SExpr {
    Num(f64),
    Var(VarRef),
    Neg(Box<SExpr>),
    Not(Box<SExpr>),
    Bin(BinOp, Box<SExpr>, Box<SExpr>),
    /// A function: `SIN(..)`, `ABS(..)`, `ATAN2(a,b)`, ...
    Call(String, Vec<SExpr>),
}

/// A variable: `$AC_MARKER[1]`, `$AA_IM[X]`, `$R10` (read as `$R[10]`), `$AC_TIME`.
#[derive(Debug, Clone, PartialEq)]
pub struct VarRef {
    pub name: String,
    pub index: Option<Index>,
}

/// The index of a variable: an axis name or a number.
#[derive(Debug, Clone, PartialEq)]
pub enum Index {
    Axis(String),
    Expr(Box<SExpr>),
}

/// Binary operators, weakest last.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    Mul,
    Div,
    IntDiv,
    Mod,
    Add,
    Sub,
    And,
    Xor,
    Or,
    Eq,
    Ne,
    Lt,
    Gt,
    Le,
    Ge,
}

/// One action after `DO`.
#[derive(Debug, Clone, PartialEq)]
pub enum SAction {
    /// `$VAR[i]=expr`.
    Assign(VarRef, SExpr),
    /// `M99`, `M2=5`, `H7`, `H2=1.5`: output to the PLC.
    Aux { letter: char, extension: u32, value: SExpr },
    /// `DELDTG`: delete the path's distance to go.
    DelDtg,
    /// `POS[X]=..`, `FA[X]=..`, `MOV[X]=..`: command-axis motion.
    AxisCommand { word: String, axis: String, value: SExpr },
    /// A word without arguments: `STOPREOF`, `RDISABLE`.
    Word(String),
    /// A word with arguments: `SETM(1)`, `CLEARM(2)`, `PRESETON(X,0)`.
    Call(String, Vec<SExpr>),
}

/// A syntax error: byte column in the text handed to [`parse`] and the message.
#[derive(Debug, Clone, PartialEq)]
pub struct SyncSyntaxError {
    pub col: usize,
    pub message: String,
}

/// True if the code of a block (after its number and label) opens a synchronized action:
/// `ID=`, `IDS=`, `WHEN`, `WHENEVER`, `FROM`, `EVERY` or `DO` as a whole word.
pub fn opens(code: &str) -> bool {
    let b = code.as_bytes();
    // Most blocks start with another letter: one byte settles them.
    if !matches!(b.first().map(u8::to_ascii_uppercase), Some(b'I' | b'W' | b'F' | b'E' | b'D')) {
        return false;
    }
    let word_end = b.iter().position(|c| !c.is_ascii_alphanumeric() && *c != b'_').unwrap_or(b.len());
    let word = code[..word_end].to_ascii_uppercase();
    match word.as_str() {
        "WHEN" | "WHENEVER" | "FROM" | "EVERY" | "DO" => true,
        "ID" | "IDS" => code[word_end..].trim_start().starts_with('='),
        _ => false,
    }
}

/// Parses a synchronized action from its first word to the end of the line (no comment).
pub fn parse(text: &str) -> Result<SyncAction, SyncSyntaxError> {
    let mut p = P { src: text.as_bytes(), text, pos: 0 };
    let mut id = None;
    p.ws();
    let at = p.pos;
    if let Some(word) = p.ident() {
        if word == "ID" || word == "IDS" {
            p.ws();
            if !p.eat(b'=') {
                return p.err("'=' expected after ID");
            }
            p.ws();
            let n_at = p.pos;
            let n = p.integer().filter(|n| (1..=255).contains(n));
            let Some(n) = n else {
                p.pos = n_at;
                return p.err("ID needs a number 1..255");
            };
            id = Some(if word == "ID" { SyncId::Modal(n) } else { SyncId::Static(n) });
        } else {
            p.pos = at;
        }
    }
    p.ws();
    let at = p.pos;
    let trigger = match p.ident().as_deref() {
        Some("WHEN") => Trigger::When,
        Some("WHENEVER") => Trigger::Whenever,
        Some("FROM") => Trigger::From,
        Some("EVERY") => Trigger::Every,
        Some("DO") => {
            p.pos = at;
            Trigger::Always
        }
        _ => {
            p.pos = at;
            return p.err("WHEN, WHENEVER, FROM, EVERY or DO expected");
        }
    };
    let (mut units, mut condition, mut condition_text) = (None, None, String::new());
    if trigger != Trigger::Always {
        p.ws();
        let at = p.pos;
        if let Some(g) = p.ident() {
            match g.as_str() {
                "G70" => units = Some(70),
                "G71" => units = Some(71),
                "G700" => units = Some(700),
                "G710" => units = Some(710),
                _ => p.pos = at,
            }
        }
        p.ws();
        let start = p.pos;
        if p.keyword_ahead("DO") {
            return p.err("condition expected before DO");
        }
        condition = Some(p.expr(0)?);
        condition_text = text[start..p.pos].trim().to_ascii_uppercase();
    }
    p.ws();
    if !p.keyword_ahead("DO") {
        return p.err("DO expected");
    }
    p.ident();
    let mut actions = Vec::new();
    loop {
        p.ws();
        if p.at_end() {
            break;
        }
        actions.push(p.action()?);
    }
    if actions.is_empty() {
        return p.err("action expected after DO");
    }
    Ok(SyncAction { id, trigger, units, condition, actions, condition_text })
}

struct P<'a> {
    src: &'a [u8],
    text: &'a str,
    pos: usize,
}

/// Binding strength of a binary operator (larger binds tighter), the control's order:
/// NOT; * / DIV MOD; + -; AND; XOR; OR; comparisons.
fn strength(op: BinOp) -> u8 {
    match op {
        BinOp::Mul | BinOp::Div | BinOp::IntDiv | BinOp::Mod => 6,
        BinOp::Add | BinOp::Sub => 5,
        BinOp::And => 4,
        BinOp::Xor => 3,
        BinOp::Or => 2,
        _ => 1,
    }
}

impl P<'_> {
    fn err<T>(&self, message: &str) -> Result<T, SyncSyntaxError> {
        Err(SyncSyntaxError { col: self.pos, message: message.to_string() })
    }
    fn peek(&self) -> Option<u8> {
        self.src.get(self.pos).copied()
    }
    fn at_end(&self) -> bool {
        self.pos >= self.src.len()
    }
    fn eat(&mut self, c: u8) -> bool {
        let hit = self.peek() == Some(c);
        self.pos += usize::from(hit);
        hit
    }
    fn ws(&mut self) {
        while matches!(self.peek(), Some(b' ' | b'\t')) {
            self.pos += 1;
        }
    }
    /// A name (letters, digits, `_`, starting with a letter or `_`), upper-cased.
    fn ident(&mut self) -> Option<String> {
        let start = self.pos;
        if !self.peek().is_some_and(|c| c.is_ascii_alphabetic() || c == b'_') {
            return None;
        }
        while self.peek().is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_') {
            self.pos += 1;
        }
        Some(self.text[start..self.pos].to_ascii_uppercase())
    }
    fn keyword_ahead(&mut self, word: &str) -> bool {
        let at = self.pos;
        let hit = self.ident().is_some_and(|w| w == word);
        self.pos = at;
        hit
    }
    fn integer(&mut self) -> Option<u32> {
        let start = self.pos;
        while self.peek().is_some_and(|c| c.is_ascii_digit()) {
            self.pos += 1;
        }
        self.text[start..self.pos].parse().ok()
    }
    fn number(&mut self) -> Result<f64, SyncSyntaxError> {
        let start = self.pos;
        while self.peek().is_some_and(|c| c.is_ascii_digit() || c == b'.') {
            self.pos += 1;
        }
        // The exponent as in the part program: `1.5EX3`, `2EX-4` (see `Cursor::number`).
        let mantissa_end = self.pos;
        let mut exponent = None;
        if self.src.get(self.pos..self.pos + 2).is_some_and(|x| x.eq_ignore_ascii_case(b"EX")) {
            let after = self.pos + 2;
            let signed = usize::from(matches!(self.src.get(after), Some(b'-' | b'+')));
            if self.src.get(after + signed).is_some_and(u8::is_ascii_digit) {
                self.pos = after + signed;
                while self.peek().is_some_and(|c| c.is_ascii_digit()) {
                    self.pos += 1;
                }
                exponent = Some(&self.text[after..self.pos]);
            }
        }
        let text = match exponent {
            Some(e) => format!("{}e{e}", &self.text[start..mantissa_end]),
            None => self.text[start..mantissa_end].to_string(),
        };
        match text.parse::<f64>().ok().filter(|v| v.is_finite()) {
            Some(v) => Ok(v),
            None => {
                self.pos = start;
                self.err("invalid number")
            }
        }
    }

    /// The binary operator at the cursor (consumed), if one follows.
    fn operator(&mut self) -> Option<BinOp> {
        self.ws();
        let at = self.pos;
        let two = self.src.get(self.pos..self.pos + 2);
        let op = match two {
            Some(b"==") => Some((BinOp::Eq, 2)),
            Some(b"<>") => Some((BinOp::Ne, 2)),
            Some(b"<=") => Some((BinOp::Le, 2)),
            Some(b">=") => Some((BinOp::Ge, 2)),
            _ => match self.peek() {
                Some(b'<') => Some((BinOp::Lt, 1)),
                Some(b'>') => Some((BinOp::Gt, 1)),
                Some(b'+') => Some((BinOp::Add, 1)),
                Some(b'-') => Some((BinOp::Sub, 1)),
                Some(b'*') => Some((BinOp::Mul, 1)),
                Some(b'/') => Some((BinOp::Div, 1)),
                _ => None,
            },
        };
        if let Some((op, n)) = op {
            self.pos += n;
            return Some(op);
        }
        let op = match self.ident().as_deref() {
            Some("AND") => Some(BinOp::And),
            Some("OR") => Some(BinOp::Or),
            Some("XOR") => Some(BinOp::Xor),
            Some("DIV") => Some(BinOp::IntDiv),
            Some("MOD") => Some(BinOp::Mod),
            _ => None,
        };
        if op.is_none() {
            self.pos = at;
        }
        op
    }

    fn expr(&mut self, min: u8) -> Result<SExpr, SyncSyntaxError> {
        let mut left = self.unary()?;
        loop {
            let at = self.pos;
            let Some(op) = self.operator() else { break };
            let s = strength(op);
            if s < min || s == 0 {
                self.pos = at;
                break;
            }
            let right = self.expr(s + 1)?;
            left = SExpr::Bin(op, Box::new(left), Box::new(right));
        }
        Ok(left)
    }

    fn unary(&mut self) -> Result<SExpr, SyncSyntaxError> {
        self.ws();
        if self.eat(b'-') {
            return Ok(SExpr::Neg(Box::new(self.unary()?)));
        }
        if self.eat(b'+') {
            return self.unary();
        }
        if self.keyword_ahead("NOT") {
            self.ident();
            return Ok(SExpr::Not(Box::new(self.unary()?)));
        }
        self.operand()
    }

    fn operand(&mut self) -> Result<SExpr, SyncSyntaxError> {
        self.ws();
        match self.peek() {
            Some(b'(') => {
                self.pos += 1;
                let e = self.expr(0)?;
                self.ws();
                if !self.eat(b')') {
                    return self.err("')' expected");
                }
                Ok(e)
            }
            Some(c) if c.is_ascii_digit() || c == b'.' => Ok(SExpr::Num(self.number()?)),
            Some(b'$') => Ok(SExpr::Var(self.variable()?)),
            Some(c) if c.is_ascii_alphabetic() => {
                let at = self.pos;
                let name = self.ident().unwrap_or_default();
                match name.as_str() {
                    "TRUE" => return Ok(SExpr::Num(1.0)),
                    "FALSE" => return Ok(SExpr::Num(0.0)),
                    _ => {}
                }
                self.ws();
                if !self.eat(b'(') {
                    self.pos = at;
                    return self.err(&format!(
                        "{name}: only system variables ($...) and functions are read in synchronized actions"
                    ));
                }
                let args = self.args()?;
                Ok(SExpr::Call(name, args))
            }
            _ => self.err("operand expected"),
        }
    }

    /// Arguments after `(` up to the closing `)`.
    fn args(&mut self) -> Result<Vec<SExpr>, SyncSyntaxError> {
        let mut args = Vec::new();
        self.ws();
        if self.eat(b')') {
            return Ok(args);
        }
        loop {
            args.push(self.expr(0)?);
            self.ws();
            if self.eat(b')') {
                return Ok(args);
            }
            if !self.eat(b',') {
                return self.err("',' or ')' expected");
            }
        }
    }

    /// `$NAME`, `$NAME[index]`, `$R10`.
    fn variable(&mut self) -> Result<VarRef, SyncSyntaxError> {
        let at = self.pos;
        self.pos += 1;
        let Some(name) = self.ident() else {
            self.pos = at;
            return self.err("variable name expected after $");
        };
        if let Some(n) = name.strip_prefix('R').filter(|n| !n.is_empty() && n.bytes().all(|c| c.is_ascii_digit())) {
            let n: f64 = n.parse().unwrap_or(0.0);
            return Ok(VarRef { name: "$R".into(), index: Some(Index::Expr(Box::new(SExpr::Num(n)))) });
        }
        let name = format!("${name}");
        if !self.eat(b'[') {
            return Ok(VarRef { name, index: None });
        }
        self.ws();
        let at = self.pos;
        // A bare name is an axis (X, X1, AX2, SPI(1) is no axis here).
        if let Some(axis) = self.ident() {
            self.ws();
            if self.eat(b']') {
                return Ok(VarRef { name, index: Some(Index::Axis(axis)) });
            }
            self.pos = at;
        }
        let e = self.expr(0)?;
        self.ws();
        if !self.eat(b']') {
            return self.err("']' expected");
        }
        Ok(VarRef { name, index: Some(Index::Expr(Box::new(e))) })
    }

    fn action(&mut self) -> Result<SAction, SyncSyntaxError> {
        if self.peek() == Some(b'$') {
            let var = self.variable()?;
            self.ws();
            if !self.eat(b'=') {
                return self.err("'=' expected in the assignment");
            }
            return Ok(SAction::Assign(var, self.expr(0)?));
        }
        let at = self.pos;
        let Some(word) = self.ident() else { return self.err("action expected") };
        // M and H functions: M99, M2=5, H7, H=1.5, H2=1.5; spindle speeds S1000, S2=500.
        if let Some(letter @ ('M' | 'H' | 'S')) = word.chars().next() {
            let rest = &word[1..];
            if rest.is_empty() || rest.bytes().all(|c| c.is_ascii_digit()) {
                self.ws();
                if self.eat(b'=') {
                    let extension = rest.parse().unwrap_or(0);
                    return Ok(SAction::Aux { letter, extension, value: self.expr(0)? });
                }
                if let Ok(v) = rest.parse::<u32>() {
                    return Ok(SAction::Aux { letter, extension: 0, value: SExpr::Num(f64::from(v)) });
                }
                self.pos = at;
                return self.err(&format!("{letter} needs a value"));
            }
        }
        if word == "DELDTG" {
            return Ok(SAction::DelDtg);
        }
        if word == "SPOS" && self.peek() == Some(b'=') {
            // SPOS=.. positions the master spindle.
            self.pos += 1;
            return Ok(SAction::AxisCommand { word, axis: String::new(), value: self.expr(0)? });
        }
        if matches!(word.as_str(), "POS" | "FA" | "MOV" | "SPOS" | "POSA") {
            if !self.eat(b'[') {
                return self.err(&format!("{word}[axis] expected"));
            }
            self.ws();
            // SPOS[n]: the spindle number.
            let number = if word == "SPOS" { self.integer().map(|n| n.to_string()) } else { None };
            let Some(axis) = number.or_else(|| self.ident()) else { return self.err("axis name expected") };
            self.ws();
            if !self.eat(b']') {
                return self.err("']' expected");
            }
            self.ws();
            if !self.eat(b'=') {
                return self.err("'=' expected");
            }
            return Ok(SAction::AxisCommand { word, axis, value: self.expr(0)? });
        }
        if word == "PRESETON" && self.eat(b'(') {
            // PRESETON(axis, value): the first argument is an axis name.
            self.ws();
            let Some(axis) = self.ident() else { return self.err("axis name expected") };
            self.ws();
            if !self.eat(b',') {
                return self.err("',' expected");
            }
            let value = self.expr(0)?;
            self.ws();
            if !self.eat(b')') {
                return self.err("')' expected");
            }
            let axis = SExpr::Var(VarRef { name: axis, index: None });
            return Ok(SAction::Call(word, vec![axis, value]));
        }
        if self.eat(b'(') {
            return Ok(SAction::Call(word, self.args()?));
        }
        if self.peek() == Some(b'=') || self.peek() == Some(b'[') {
            self.pos = at;
            return self.err(&format!("{word}: only system variables ($...) are written in synchronized actions"));
        }
        Ok(SAction::Word(word))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn var(name: &str, index: Option<Index>) -> SExpr {
        SExpr::Var(VarRef { name: name.into(), index })
    }

    #[test]
    fn modal_whenever_with_axis_index_and_override() {
        let a = parse("ID=1 WHENEVER $AA_IM[X]>20 DO $AC_OVR=0").unwrap();
        assert_eq!(a.id, Some(SyncId::Modal(1)));
        assert_eq!(a.trigger, Trigger::Whenever);
        assert_eq!(
            a.condition,
            Some(SExpr::Bin(
                BinOp::Gt,
                Box::new(var("$AA_IM", Some(Index::Axis("X".into())))),
                Box::new(SExpr::Num(20.0))
            ))
        );
        assert_eq!(a.condition_text, "$AA_IM[X]>20");
        assert_eq!(a.actions, vec![SAction::Assign(VarRef { name: "$AC_OVR".into(), index: None }, SExpr::Num(0.0))]);
    }

    #[test]
    fn several_actions_follow_do() {
        let a = parse("ids=3 every G71 $AC_TIME > 0.1 do $AC_MARKER[1]=$AC_MARKER[1]+1 M99 H2=1.5 DELDTG").unwrap();
        assert_eq!(a.id, Some(SyncId::Static(3)));
        assert_eq!(a.units, Some(71));
        assert_eq!(a.actions.len(), 4);
        assert_eq!(a.actions[1], SAction::Aux { letter: 'M', extension: 0, value: SExpr::Num(99.0) });
        assert_eq!(a.actions[2], SAction::Aux { letter: 'H', extension: 2, value: SExpr::Num(1.5) });
        assert_eq!(a.actions[3], SAction::DelDtg);
    }

    #[test]
    fn do_alone_has_no_condition() {
        let a = parse("DO $A_OUTA[1]=$AA_IM[X] $R10=$R10+1").unwrap();
        assert_eq!((a.id, a.trigger, a.condition), (None, Trigger::Always, None));
        let SAction::Assign(r, _) = &a.actions[1] else { panic!() };
        assert_eq!(r.index, Some(Index::Expr(Box::new(SExpr::Num(10.0)))));
    }

    #[test]
    fn comparisons_bind_weakest_as_on_the_control() {
        // 1 + 2 * 3 == 7 AND 1: AND binds tighter than ==, so this is 7 == (7 AND 1).
        let a = parse("WHEN 1+2*3==7 AND 1 DO M1").unwrap();
        let Some(SExpr::Bin(BinOp::Eq, _, right)) = a.condition else { panic!() };
        assert!(matches!(*right, SExpr::Bin(BinOp::And, _, _)));
    }

    #[test]
    fn bad_syntax_names_the_column() {
        assert_eq!(parse("WHENEVER $AA_IM[X]>20 $AC_OVR=0").unwrap_err().col, 22);
        assert_eq!(parse("WHEN DO M1").unwrap_err().message, "condition expected before DO");
        assert_eq!(parse("ID=0 DO M1").unwrap_err().message, "ID needs a number 1..255");
        assert!(parse("WHEN $A_IN[1]==1 DO").is_err());
        assert!(parse("WHEN R1==1 DO M1").is_err());
        assert!(parse("WHEN $A_IN[1]==1 DO R1=2").is_err());
        assert!(parse("WHEN ($A_IN[1]==1 DO M1").is_err());
    }

    #[test]
    fn numbers_take_the_part_programs_ex_exponent() {
        // 1.5EX3 = 1500, 2EX-4 = 0.0002 (the exponent form of the Programming Manual); a plain E
        // is a name as in the part program, and a value beyond f64 is no number.
        let a = parse("WHEN $AA_IM[X]>1.5EX3 DO $AC_PARAM[1]=2EX-4 $AC_PARAM[2]=1ex+2").unwrap();
        let Some(SExpr::Bin(_, _, limit)) = a.condition else { panic!() };
        assert_eq!(*limit, SExpr::Num(1500.0));
        assert!(matches!(&a.actions[0], SAction::Assign(_, SExpr::Num(v)) if *v == 0.0002));
        assert!(matches!(&a.actions[1], SAction::Assign(_, SExpr::Num(v)) if *v == 100.0));
        assert!(parse("WHEN $AA_IM[X]>1E3 DO M1").is_err());
        assert_eq!(parse("DO $AC_PARAM[1]=1EX400").unwrap_err().message, "invalid number");
    }

    #[test]
    fn opening_words_are_whole_words() {
        assert!(opens("WHEN $A_IN[1] DO M1") && opens("id = 2 DO M1") && opens("DO M1"));
        assert!(!opens("DOX=1") && !opens("IDX=1") && !opens("D1") && !opens("G1 X1") && !opens("ID"));
    }
}

//! Property tests: arbitrary input never panics the parser, the NC data reader or a channel.

use nctwin_engine::{Channel, MachineData, lang};
use proptest::prelude::*;

/// Text built from the characters part programs and NC data are made of.
fn nc_text() -> impl Strategy<Value = String> {
    proptest::string::string_regex("[GXYZFIJKNMTDSR0-9=.+\\-*/() ;\\n$\\[\\],\"'ACPHB_]{0,120}").unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, .. ProptestConfig::default() })]

    #[test]
    fn arbitrary_unicode_never_panics_the_parsers(text in "\\PC{0,200}") {
        let _ = lang::parse(&text);
        let _ = MachineData::default().apply_text(&text);
    }

    #[test]
    fn arbitrary_bytes_never_panic_the_check(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
        let text = String::from_utf8_lossy(&bytes);
        for d in lang::check(&text) {
            prop_assert!(d.line >= 1 && d.column >= 1 && d.offset <= text.len() + 1);
        }
    }

    #[test]
    fn the_parser_accepts_or_reports_any_text(text in nc_text()) {
        let p = lang::parse(&text);
        for d in &p.diagnostics {
            prop_assert!(d.line >= 1 && d.offset <= text.len() + 1);
        }
    }

    #[test]
    fn blocks_read_into_recycled_word_lists_are_the_blocks_read_fresh(text in nc_text()) {
        // The interpreter parses each block into the emptied word list of the one before;
        // what it reads must not depend on that (lines, offsets, words, errors alike).
        let (mut fresh, mut reused) = ((0usize, 1u32), (0usize, 1u32));
        let mut spare = Vec::new();
        // And both read what the whole-program parser finds, block for block.
        let whole = lang::parse(&text);
        let (mut blocks, mut errors) = (whole.blocks.iter(), whole.diagnostics.iter());
        loop {
            let a = lang::read_block(&text, fresh.0, fresh.1);
            let b = lang::read_block_reusing(&text, reused.0, reused.1, &mut spare);
            let ((a, ao, al), (b, bo, bl)) = match (a, b) {
                (Some(a), Some(b)) => (a, b),
                (None, None) => {
                    prop_assert!(blocks.next().is_none() && errors.next().is_none(), "blocks left unread");
                    break;
                }
                (a, b) => return Err(TestCaseError::fail(format!("one reader ended: {a:?} / {b:?}"))),
            };
            prop_assert_eq!(&a, &b);
            prop_assert_eq!((ao, al), (bo, bl));
            match &b {
                Ok(block) => prop_assert_eq!(Some(block), blocks.next()),
                Err(d) => prop_assert_eq!(Some(d), errors.next()),
            }
            if let Ok(block) = b {
                let mut words = block.words;
                words.clear();
                spare = words;
            }
            (fresh, reused) = ((ao, al), (bo, bl));
        }
    }

    #[test]
    fn machine_data_text_is_applied_whole_or_not_at_all(text in nc_text()) {
        let mut md = MachineData::default();
        let before = md.clone();
        if md.apply_text(&text).is_err() {
            prop_assert_eq!(md, before);
        }
    }

    #[test]
    fn any_parsable_program_runs_to_an_end_or_an_alarm(text in nc_text()) {
        let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
        if ch.run_program(&text).is_ok() {
            let mut ticks = 0;
            while ch.is_busy() && ticks < 200_000 {
                ch.step();
                ticks += 1;
            }
            for p in ch.axis_positions() {
                prop_assert!(p.is_finite());
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 120, .. ProptestConfig::default() })]

    #[test]
    fn programs_of_control_statements_run_or_are_refused(lines in proptest::collection::vec(statement_line(), 0..25)) {
        let text = lines.join("\n");
        let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
        if ch.run_program(&text).is_ok() {
            let mut ticks = 0;
            while ch.is_busy() && ticks < 5_000 {
                ch.step();
                ticks += 1;
            }
        }
    }
}

/// One line of a program made of control statements, jumps (literal and computed) and
/// assignments, nested or not, well-formed or not.
fn statement_line() -> impl Strategy<Value = String> {
    proptest::sample::select(vec![
        "IF R1<3",
        "ELSE",
        "ENDIF",
        "WHILE R1<5",
        "ENDWHILE",
        "FOR R2=1 TO 3",
        "ENDFOR",
        "REPEAT",
        "UNTIL R1>2",
        "LOOP",
        "ENDLOOP",
        "R1=R1+1",
        "GOTOF L1",
        "GOTOB L1",
        "GOTOC NOWHERE",
        "GOTOF \"N\"<<R1",
        "GOTOB \"L1\"",
        "L1: R3=R3+1",
        "N1 R4=1",
        "N2 G0 X=R1",
        "GOTOS",
        "IF R3>4 GOTOF END",
        "END: M30",
        "CASE(R1) OF 1 GOTOF L1 DEFAULT GOTOF END",
        "DEF STRING[8] LBL=\"L1\"",
        "GOTOF LBL",
        "M17",
        "RET",
        "R1=1/R5",
    ])
    .prop_map(str::to_string)
}

/// An arithmetic expression tree for the reference evaluator.
#[derive(Debug, Clone)]
enum Tree {
    Num(u8),
    Neg(Box<Tree>),
    Op(char, Box<Tree>, Box<Tree>),
}

fn tree() -> impl Strategy<Value = Tree> {
    (0u8..20).prop_map(Tree::Num).prop_recursive(5, 32, 2, |inner| {
        prop_oneof![
            inner.clone().prop_map(|t| Tree::Neg(Box::new(t))),
            (prop::sample::select(vec!['+', '-', '*', '/']), inner.clone(), inner).prop_map(|(op, a, b)| Tree::Op(
                op,
                Box::new(a),
                Box::new(b)
            )),
        ]
    })
}

/// Straightforward evaluation of the tree; `None` on division by zero.
fn reference(t: &Tree) -> Option<f64> {
    Some(match t {
        Tree::Num(n) => f64::from(*n),
        Tree::Neg(a) => -reference(a)?,
        Tree::Op(op, a, b) => {
            let (a, b) = (reference(a)?, reference(b)?);
            match op {
                '+' => a + b,
                '-' => a - b,
                '*' => a * b,
                _ if b == 0.0 => return None,
                _ => a / b,
            }
        }
    })
}

fn priority(op: char) -> u8 {
    if op == '+' || op == '-' { 1 } else { 2 }
}

/// Writes the tree with only the parentheses the control's priorities require.
fn render(t: &Tree) -> String {
    match t {
        Tree::Num(n) => n.to_string(),
        Tree::Neg(a) => match **a {
            Tree::Num(_) => format!("-{}", render(a)),
            _ => format!("-({})", render(a)),
        },
        Tree::Op(op, a, b) => {
            let side = |child: &Tree, right: bool| {
                let needs = match child {
                    Tree::Op(c, ..) => priority(*c) < priority(*op) || (right && priority(*c) == priority(*op)),
                    _ => false,
                };
                if needs { format!("({})", render(child)) } else { render(child) }
            };
            format!("{}{op}{}", side(a, false), side(b, true))
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, .. ProptestConfig::default() })]

    #[test]
    fn random_expressions_evaluate_like_the_reference(t in tree()) {
        let text = format!("R1={}\nM30", render(&t));
        let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
        ch.run_program(&text).unwrap();
        while ch.is_busy() {
            ch.step();
        }
        match reference(&t) {
            Some(want) if want.is_finite() => {
                let got = ch.r_param(1);
                prop_assert!((got - want).abs() <= 1e-9 * want.abs().max(1.0), "{text}: {got} vs {want}");
            }
            _ => prop_assert!(ch.alarms().iter().any(|a| a.number == 14051), "{text}: {:?}", ch.alarms()),
        }
    }
}

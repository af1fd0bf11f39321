//! Deeply nested and very long expressions (issue 20): every one beyond
//! [`lang::MAX_EXPR_DEPTH`] levels is refused with alarm 12080 at the token that goes one level
//! too deep, by the check and by a channel; one at the limit still evaluates. All of it on a
//! thread with half the stack of the server's worker threads, in the debug build the tests run
//! in: the other half is left for the server's own frames above the engine.

use nctwin_engine::lang::{self, MAX_EXPR_DEPTH};
use nctwin_engine::{Channel, CommandError, Status};
use proptest::prelude::*;

const M: usize = MAX_EXPR_DEPTH as usize;

/// Half the 2 MiB stack of a tokio worker or blocking thread (and of `std::thread::spawn`).
const WORKER_STACK: usize = 1 << 20;

/// Runs `f` on a thread with [`WORKER_STACK`].
fn on_worker_stack<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new().stack_size(WORKER_STACK).spawn(f).expect("thread").join().expect("no panic")
}

/// An attack: the text of line 2 and the column of the token one level too deep.
struct Attack {
    name: &'static str,
    line: String,
    column: u32,
}

/// `n` nested pieces `open`, the innermost `inner`, then the closers.
fn nested(open: &str, inner: &str, close: &str, n: usize) -> String {
    format!("{}{inner}{}", open.repeat(n), close.repeat(n))
}

/// `n` copies of `term` joined by `op`.
fn chain(term: &str, op: &str, n: usize) -> String {
    vec![term; n].join(op)
}

/// Each attack far beyond the limit (thousands of levels: a stack overflow before the fix).
/// Line 2 is `R1=` (3 bytes) and the attack; a nesting piece of `w` bytes puts the first token
/// one level too deep at byte 3 + M·w, column M·w + 4; in a chain the M-th operator makes the
/// tree one level too deep.
fn attacks() -> Vec<Attack> {
    const N: usize = 5_000;
    let col = |bytes_before: usize| u32::try_from(bytes_before + 1).unwrap();
    vec![
        Attack { name: "parentheses", line: format!("R1={}", nested("(", "1", ")", N)), column: col(3 + M) },
        Attack { name: "unary minus", line: format!("R1={}1", "-".repeat(N)), column: col(3 + M) },
        Attack { name: "unary plus", line: format!("R1={}1", "+".repeat(N)), column: col(3 + M) },
        Attack { name: "NOT", line: format!("R1={}TRUE", "NOT ".repeat(N)), column: col(3 + 4 * M) },
        Attack { name: "B_NOT", line: format!("R1={}5", "B_NOT ".repeat(N)), column: col(3 + 6 * M) },
        Attack { name: "SIN(SIN(", line: format!("R1={}", nested("SIN(", "0", ")", N)), column: col(3 + 4 * M) },
        Attack { name: "R[R[", line: format!("R1={}", nested("R[", "1", "]", N)), column: col(3 + 2 * M) },
        // `1+1+...+1`: the j-th `+` is at byte 3 + 2j - 1.
        Attack { name: "flat sum", line: format!("R1={}", chain("1", "+", 30_000)), column: col(2 + 2 * M) },
        Attack { name: "flat product", line: format!("R1={}", chain("1", "*", 30_000)), column: col(2 + 2 * M) },
        // `IF "A"<<"A"...`: the j-th `<<` is at byte 3 + 3j + 2(j - 1).
        Attack {
            name: "string concatenation",
            line: format!("IF {}==\"A\"", chain("\"A\"", "<<", 30_000)),
            column: col(5 * M + 1),
        },
        // `$P_PFRAME=CTRANS():...`: the j-th `:` is at byte 10 + 8j + (j - 1).
        Attack {
            name: "frame chain",
            line: format!("$P_PFRAME={}", chain("CTRANS()", ":", 30_000)),
            column: col(9 * M + 9),
        },
        // Every piece one level: `(`, `-`, `NOT `, `SIN(`, `R[`, `B_NOT `, `+`.
        Attack { name: "mixed", line: format!("R1={}", mixed(N).0), column: col(3 + mixed(M).1) },
        // The attack in an index of the assigned name (a whole expression of its own).
        Attack { name: "index", line: format!("R[{}]=1", nested("(", "1", ")", N)), column: col(2 + M) },
    ]
}

/// `n` levels of the mixed pieces around `1` and the bytes of the openers.
fn mixed(n: usize) -> (String, usize) {
    const PIECES: [(&str, &str); 7] =
        [("(", ")"), ("-", ""), ("NOT ", ""), ("SIN(", ")"), ("R[", "]"), ("B_NOT ", ""), ("+", "")];
    let (mut open, mut close) = (String::new(), String::new());
    for k in 0..n {
        let (o, c) = PIECES[k % PIECES.len()];
        open.push_str(o);
        close.insert_str(0, c);
    }
    let bytes = open.len();
    (format!("{open}1{close}"), bytes)
}

fn program(line: &str) -> String {
    format!("G0 X0\n{line}\nM30\n")
}

/// The check reports alarm 12080 at line 2, at the column of the token one level too deep.
#[test]
fn every_attack_is_a_syntax_error_at_its_line_and_column() {
    on_worker_stack(|| {
        for a in attacks() {
            let errors = lang::check(&program(&a.line));
            let first = errors.first().unwrap_or_else(|| panic!("{}: no error", a.name));
            assert_eq!((first.alarm, first.line, first.column), (12080, 2, a.column), "{}: {first:?}", a.name);
            assert!(first.message.contains("nested too deeply"), "{}: {}", a.name, first.message);
            // The whole parse (with blocks built) says the same.
            let parsed = lang::parse(&program(&a.line));
            assert_eq!(parsed.diagnostics.first().map(|d| (d.line, d.column)), Some((2, a.column)), "{}", a.name);
        }
    });
}

/// A channel refuses each program before it runs (and as MDA text and a stored program); a run
/// without the check stops with alarm 12080 of line 2 when preparation gets there.
#[test]
fn a_channel_refuses_every_attack_and_keeps_working() {
    on_worker_stack(|| {
        for a in attacks() {
            let text = program(&a.line);
            let mut ch = Channel::from_preset("mill-3axis", "").expect("preset");
            match ch.run_program(&text) {
                Err(CommandError::Syntax { line: 2, errors, .. }) => {
                    assert_eq!((errors[0].alarm, errors[0].column), (12080, a.column), "{}", a.name)
                }
                other => panic!("{}: {other:?}", a.name),
            }
            assert!(matches!(ch.mda(&a.line), Err(CommandError::Syntax { line: 1, .. })), "{}", a.name);
            assert!(ch.store_program("DEEP", &text).is_err(), "{}", a.name);
            ch.run_program_prechecked(text.as_str()).expect("starts");
            for _ in 0..100_000 {
                if !ch.is_busy() {
                    break;
                }
                ch.step();
            }
            assert_eq!(ch.status(), Status::Alarm, "{}", a.name);
            let alarm = &ch.alarms()[0];
            assert_eq!((alarm.number, alarm.line), (12080, Some(2)), "{}: {alarm:?}", a.name);
            // The channel still runs programs after a reset.
            ch.reset();
            ch.run_program("R1=2+3\nM30").expect("runs");
            while ch.is_busy() {
                ch.step();
            }
            assert_eq!(ch.r_param(1), 5.0, "{}", a.name);
        }
    });
}

/// Runs `R1=<expr>` (and `R0` etc. set before) in a channel on the worker stack; R1 at the end.
fn r1_after(setup: &'static str, expr: String) -> f64 {
    on_worker_stack(move || {
        let mut ch = Channel::from_preset("mill-3axis", "").expect("preset");
        let text = format!("{setup}\nR1={expr}\nM30\n");
        assert!(lang::check(&text).is_empty(), "{:?}", lang::check(&text).first());
        ch.run_program(&text).expect("starts");
        while ch.is_busy() {
            ch.step();
        }
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        ch.r_param(1)
    })
}

/// At the limit itself every class still evaluates, to values worked out by hand.
#[test]
fn expressions_at_the_limit_evaluate() {
    let n = M - 1; // nesting pieces around a leaf: M levels in all
    // (((7))): 7.
    assert_eq!(r1_after("", nested("(", "7", ")", n)), 7.0);
    // An odd number of minus signs: -7; an even number: 7.
    assert_eq!(r1_after("", format!("{}7", "-".repeat(n | 1))), -7.0);
    assert_eq!(r1_after("", format!("{}7", "-".repeat(n & !1))), 7.0);
    // NOT applied n times to FALSE: TRUE (1) when n is odd, else FALSE (0).
    assert_eq!(r1_after("", format!("{}FALSE", "NOT ".repeat(n))), (n % 2) as f64);
    // B_NOT twice is the number itself: B_NOT 5 = -6.
    assert_eq!(r1_after("", format!("{}5", "B_NOT ".repeat(n & !1))), 5.0);
    assert_eq!(r1_after("", format!("{}5", "B_NOT ".repeat(n | 1))), -6.0);
    // SIN(0) = 0, n times.
    assert_eq!(r1_after("", nested("SIN(", "0", ")", n)), 0.0);
    // ABS(-3) = 3, and ABS of that stays 3.
    assert_eq!(r1_after("", nested("ABS(", "-3", ")", n - 1)), 3.0);
    // R2 = 2 and R[R[...R[2]]] reads R2 each time: 2.
    assert_eq!(r1_after("R2=2", nested("R[", "2", "]", n)), 2.0);
    // 1+1+...+1 of M terms: M (the tree is M levels deep).
    assert_eq!(r1_after("", chain("1", "+", M)), M as f64);
    // 2*...*2 of 30 factors (30 levels) then M - 30 times +1: 2^30 + M - 30.
    let long = format!("{}+{}", chain("2", "*", 30), chain("1", "+", M - 30));
    assert_eq!(r1_after("", long), f64::from(1u32 << 30) + (M - 30) as f64);
}

/// Nested IF/WHILE beyond the 16 levels the control allows, thousands deep: alarm 12641, no
/// overflow in the check or the run.
#[test]
fn thousands_of_nested_control_structures_are_refused() {
    on_worker_stack(|| {
        let text = format!("{}{}M30\n", "IF 1\nWHILE 1\n".repeat(5_000), "ENDWHILE\nENDIF\n".repeat(5_000));
        let errors = lang::check(&text);
        assert!(errors.iter().any(|d| d.alarm == 12641 && d.line == 17), "{:?}", errors.first());
        let mut ch = Channel::from_preset("mill-3axis", "").expect("preset");
        ch.run_program_prechecked(text.as_str()).expect("starts");
        while ch.is_busy() {
            ch.step();
        }
        assert_eq!(ch.alarms().first().map(|a| a.number), Some(12641));
    });
}

/// Random pieces of nesting and chains, deep and long, mixed: the check and a run on the worker
/// stack end with an answer (refused, alarm or a value), never an overflow.
fn deep_text() -> impl Strategy<Value = String> {
    let piece = prop_oneof![
        Just(("(", ")")),
        Just(("-", "")),
        Just(("+", "")),
        Just(("NOT ", "")),
        Just(("B_NOT ", "")),
        Just(("SIN(", ")")),
        Just(("ATAN2(1,", ")")),
        Just(("R[", "]")),
        Just(("1+", "")),
        Just(("2*", "")),
        Just(("\"A\"<<", "")),
        Just(("(1)*", "")),
    ];
    // Around the limit mostly (about half refused), now and then thousands of levels.
    let run = (piece, prop_oneof![4 => 1usize..60, 1 => 1usize..3000]);
    (proptest::collection::vec(run, 1..5), prop_oneof![Just("1"), Just("R2"), Just("TRUE")], 0usize..200).prop_map(
        |(runs, leaf, tail)| {
            let (mut open, mut close) = (String::new(), String::new());
            for ((o, c), k) in runs {
                open.push_str(&o.repeat(k));
                close.insert_str(0, &c.repeat(k));
            }
            format!("R1={open}{leaf}{close}{}", "+1".repeat(tail))
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, .. ProptestConfig::default() })]

    #[test]
    fn deep_and_long_expressions_never_overflow(line in deep_text()) {
        on_worker_stack(move || {
            let text = program(&line);
            for d in lang::check(&text) {
                assert!(d.line == 2 && d.column >= 1, "{d:?}");
            }
            let mut ch = Channel::from_preset("mill-3axis", "").expect("preset");
            if ch.run_program(&text).is_ok() {
                for _ in 0..100_000 {
                    if !ch.is_busy() {
                        break;
                    }
                    ch.step();
                }
            }
            ch.reset();
            ch.run_program_prechecked(text.as_str()).expect("starts");
            for _ in 0..100_000 {
                if !ch.is_busy() {
                    break;
                }
                ch.step();
            }
        });
    }
}

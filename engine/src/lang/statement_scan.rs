//! Skipping a branch (`IF` ... `ELSE`, a loop never entered) reads every line up to its end only
//! for the statements in them. A statement keyword is an identifier of the line, so a line that
//! does not even contain one of the keywords' texts (any case, anywhere) holds no statement:
//! one byte scan passes it over without the parser, whatever its expressions.

/// Texts every statement keyword contains (`ENDIF` contains `IF`, `GOTOF` contains `GOTO` ...).
const KEYWORD_CORES: [&[u8]; 13] = [
    b"DEF", b"IF", b"ELSE", b"WHILE", b"FOR", b"REPEAT", b"UNTIL", b"LOOP", b"CASE", b"GOTO", b"PROC", b"RET",
    b"EXTERN",
];

/// False only if `text` (one line) cannot hold a statement; true sends it to the parser.
pub(super) fn may_hold_statement(text: &str) -> bool {
    let b = text.as_bytes();
    (0..b.len()).any(|i| {
        // Cheap first test: the keywords start with one of these letters.
        matches!(b[i].to_ascii_uppercase(), b'D' | b'I' | b'E' | b'W' | b'F' | b'R' | b'U' | b'L' | b'C' | b'G' | b'P')
            && KEYWORD_CORES.iter().any(|k| b.len() >= i + k.len() && b[i..i + k.len()].eq_ignore_ascii_case(k))
    })
}

#[cfg(test)]
mod tests {
    use super::may_hold_statement;
    use crate::lang::parser::parse_block;

    #[test]
    fn statements_and_their_look_alikes_go_to_the_parser() {
        for line in [
            "IF R1>0",
            "  endif",
            "N10 WHILE R1<3",
            ":10ENDWHILE",
            "/ LABEL: GOTOF END",
            "DEF REAL AA",
            "R1=R1 ; ELSE in a comment",
            "Ret",
            "CASE(R1) OF 1 GOTOF A",
            "X=DIFF",
        ] {
            assert!(may_hold_statement(line), "{line}");
        }
        for line in ["G1 X10 Y20", "R4=R3-R2*0.5", "TRANS X=R1*0.05 Y=R4*0.1", "", "; comment", "M30"] {
            assert!(!may_hold_statement(line), "{line}");
        }
    }

    /// Every line the scan passes over, the parser reads without a statement: random lines from
    /// keywords, parts of them and the characters around them.
    #[test]
    fn lines_passed_over_hold_no_statement() {
        const PREFIXES: [&str; 7] = ["", "", "/", "N10 ", ":1", "LABEL: ", " "];
        const PIECES: [&str; 22] = [
            "IF R1>0",
            "ENDIF",
            "ELSE",
            "ENDWHILE",
            "LOOP",
            "RET",
            "GOTOF L",
            "END",
            "IF",
            "ELS",
            "E",
            "WHIL",
            "GOT",
            "R1",
            "=",
            "1",
            " ",
            "X",
            "(",
            ")",
            "F",
            "DEF REAL AA",
        ];
        const TAILS: [&str; 5] = ["", "", " ", " ;x", " X1"];
        let mut next = crate::lang::test_rng::xorshift(0x9e37_79b9_7f4a_7c15u64);
        let (mut passed, mut statements) = (0, 0);
        for _ in 0..100_000 {
            let len = (next() % 3) as usize + 1;
            let mut line = PREFIXES[(next() % PREFIXES.len() as u64) as usize].to_string();
            for _ in 0..len {
                line.push_str(PIECES[(next() % PIECES.len() as u64) as usize]);
            }
            line.push_str(TAILS[(next() % TAILS.len() as u64) as usize]);
            let statement = matches!(parse_block(&line, 1, 0), Ok(Some(b)) if b.stmt.is_some());
            statements += usize::from(statement);
            if !may_hold_statement(&line) {
                passed += 1;
                assert!(!statement, "{line:?} holds a statement but was passed over");
            }
        }
        // The test proves nothing unless both kinds of line occur often.
        assert!(passed > 1_000 && statements > 1_000, "{passed} passed over, {statements} statements");
    }
}

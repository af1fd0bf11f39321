use super::*;

fn words(src: &str) -> Vec<Word> {
    let p = parse(src);
    assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
    p.blocks.into_iter().flat_map(|b| b.words).collect()
}

fn stmt(src: &str) -> Stmt {
    let p = parse(src);
    assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
    p.blocks[0].stmt.clone().expect("a statement")
}

fn expr(src: &str) -> Expr {
    let mut cur = Cursor::new(src);
    let e = parse_expr(&mut cur).unwrap();
    cur.skip_ws();
    assert!(cur.at_end(), "unparsed rest of {src}");
    e
}

fn num(name: &str, v: f64) -> Word {
    Word::Address {
        name: name.to_string().into(),
        indices: vec![],
        value: AddressValue { mode: None, expr: Expr::Number(v) },
    }
}

fn bin(op: BinOp, a: Expr, b: Expr) -> Expr {
    Expr::Binary(op, Box::new(a), Box::new(b))
}

fn var(name: &str) -> Expr {
    Expr::Var { name: name.into(), indices: vec![] }
}

#[test]
fn empty_input_yields_no_blocks() {
    assert!(parse("").blocks.is_empty());
    assert!(parse("\n  \n").blocks.is_empty());
}

#[test]
fn words_may_be_written_without_spaces() {
    assert_eq!(words("G1X10Y-20.5F1000"), vec![Word::G(1), num("X", 10.0), num("Y", -20.5), num("F", 1000.0)]);
}

#[test]
fn leading_zeros_and_trailing_points_are_numbers() {
    assert_eq!(words("G01 X10. Z.5"), vec![Word::G(1), num("X", 10.0), num("Z", 0.5)]);
}

#[test]
fn block_numbers_skip_marks_labels_and_comments_are_recognised() {
    let p = parse("/N20 G0 X1 ; rapid\nSTART: G1 X2\n:30 M30");
    let b = &p.blocks;
    assert_eq!(b[0].skip, Some(0), "a plain slash is level /0");
    assert_eq!(b[0].number, Some(20));
    assert_eq!(b[0].comment.as_deref(), Some("rapid"));
    assert_eq!(b[1].label.as_deref(), Some("START"));
    assert_eq!(b[2].number, Some(30));
    assert_eq!(b[2].words, vec![Word::M(30)]);
}

#[test]
fn skip_levels_keep_their_digit() {
    let p = parse("/0 X1\n/7N70 X2\n  /9 X3\nX4");
    let levels: Vec<_> = p.blocks.iter().map(|b| b.skip).collect();
    assert_eq!(levels, vec![Some(0), Some(7), Some(9), None]);
    assert_eq!(p.blocks[1].number, Some(70));
}

#[test]
fn addresses_with_equals_take_expressions_and_coordinate_modes() {
    let w = words("X=AC(10) CR=-5 F=2*(R1+3)");
    assert_eq!(
        w[0],
        Word::Address {
            name: "X".into(),
            indices: vec![],
            value: AddressValue { mode: Some(CoordMode::Ac), expr: Expr::Number(10.0) }
        }
    );
    assert!(matches!(&w[1], Word::Address { name, value, .. } if name == "CR" && value.expr == Expr::Number(-5.0)));
    assert!(
        matches!(&w[2], Word::Address { name, value: AddressValue { expr: Expr::Binary(BinOp::Mul, _, _), .. }, .. } if name == "F")
    );
    // A number followed by an operator word is an expression, not a plain value.
    let w = words("X=10 MOD 3 Y=-2*2");
    assert!(matches!(&w[0], Word::Address { value: AddressValue { expr: Expr::Binary(BinOp::Mod, _, _), .. }, .. }));
    assert!(matches!(&w[1], Word::Address { value: AddressValue { expr: Expr::Binary(BinOp::Mul, _, _), .. }, .. }));
}

#[test]
fn axis_names_with_digits_need_equals() {
    assert_eq!(words("X1=5"), vec![num("X1", 5.0)]);
    assert_eq!(words("X1"), vec![num("X", 1.0)]);
}

#[test]
fn keywords_with_and_without_arguments_are_words() {
    let w = words("SUPA TRANSMIT(2)");
    assert_eq!(w[0], Word::Keyword { name: "SUPA".into(), args: vec![] });
    assert_eq!(w[1], Word::Keyword { name: "TRANSMIT".into(), args: vec![Expr::Number(2.0)] });
}

#[test]
fn every_syntax_error_is_reported_with_its_line() {
    let p = parse("G1 X10\nG1 X=\nG1 #\nG1.5\n");
    let lines: Vec<u32> = p.diagnostics.iter().map(|d| d.line).collect();
    assert_eq!(lines, vec![2, 3, 4]);
    assert_eq!(p.blocks.len(), 1);
}

#[test]
fn offsets_point_into_the_source() {
    let p = parse("G0 X0\nG1 X=(\n");
    assert_eq!(p.blocks[0].offset, 0);
    assert!(p.diagnostics[0].offset >= 6);
}

#[test]
fn multiplication_binds_tighter_than_addition() {
    assert_eq!(
        expr("1+2*3"),
        bin(BinOp::Add, Expr::Number(1.0), bin(BinOp::Mul, Expr::Number(2.0), Expr::Number(3.0)))
    );
}

#[test]
fn equal_priorities_associate_to_the_left() {
    assert_eq!(
        expr("8-4-2"),
        bin(BinOp::Sub, bin(BinOp::Sub, Expr::Number(8.0), Expr::Number(4.0)), Expr::Number(2.0))
    );
    assert_eq!(
        expr("8 DIV 4 MOD 3"),
        bin(BinOp::Mod, bin(BinOp::IntDiv, Expr::Number(8.0), Expr::Number(4.0)), Expr::Number(3.0))
    );
}

#[test]
fn comparison_has_the_lowest_priority_so_logic_needs_parentheses() {
    // `A==1 AND B==2` is `A == (1 AND B) == 2` on the control.
    let e = expr("A==1 AND B==2");
    assert_eq!(
        e,
        bin(BinOp::Eq, bin(BinOp::Eq, var("A"), bin(BinOp::And, Expr::Number(1.0), var("B"))), Expr::Number(2.0))
    );
    let e = expr("(A==1) AND (B==2)");
    assert!(matches!(e, Expr::Binary(BinOp::And, _, _)));
}

#[test]
fn word_operators_need_word_boundaries() {
    assert_eq!(expr("ANDY"), var("ANDY"));
    assert_eq!(expr("A OR B"), bin(BinOp::Or, var("A"), var("B")));
    assert_eq!(expr("A B_AND 3"), bin(BinOp::BAnd, var("A"), Expr::Number(3.0)));
}

#[test]
fn less_than_is_not_confused_with_concatenation_or_not_equal() {
    assert!(matches!(expr("A<<B"), Expr::Binary(BinOp::Concat, _, _)));
    // Word operators in any case (the first-byte check before the operator lists compares
    // upper case).
    assert_eq!(expr("a or b"), expr("A OR B"));
    assert_eq!(expr("8 div 4 mod 3"), expr("8 DIV 4 MOD 3"));
    assert_eq!(expr("x b_xor 2 xor y"), expr("X B_XOR 2 XOR Y"));
    assert_eq!(expr("a and b b_or c"), expr("A AND B B_OR C"));
    assert!(matches!(expr("A<>B"), Expr::Binary(BinOp::Ne, _, _)));
    assert!(matches!(expr("A<=B"), Expr::Binary(BinOp::Le, _, _)));
    assert!(matches!(expr("A<B"), Expr::Binary(BinOp::Lt, _, _)));
}

#[test]
fn literals_of_every_kind_are_parsed() {
    assert_eq!(expr("'H1F'"), Expr::Number(31.0));
    assert_eq!(expr("'B101'"), Expr::Number(5.0));
    assert_eq!(expr("1.5EX3"), Expr::Number(1500.0));
    assert_eq!(expr("\"abc\""), Expr::Str("abc".into()));
    assert_eq!(expr("TRUE"), Expr::Bool(true));
    assert_eq!(expr("$R[2]"), Expr::RParam(Box::new(Expr::Number(2.0))));
    assert_eq!(expr("$AA_IM[X]"), Expr::Var { name: "$AA_IM".into(), indices: vec![var("X")] });
}

#[test]
fn assignments_to_array_elements_and_system_variables_are_words() {
    let w = words("ABC[2]=5 $TC_DP1[1,1]=120");
    assert!(matches!(&w[0], Word::Address { name, indices, .. } if name == "ABC" && indices.len() == 1));
    assert!(matches!(&w[1], Word::Address { name, indices, .. } if name == "$TC_DP1" && indices.len() == 2));
}

#[test]
fn def_declares_typed_variables_with_arrays_and_initial_values() {
    let s = stmt("DEF REAL AA=1.5, BB[3]=SET(1,2,3), CC");
    let Stmt::Def { ty, vars, global: false } = s else { panic!() };
    assert_eq!(ty, VarType::Real);
    assert_eq!(vars.len(), 3);
    assert_eq!(vars[1].init.len(), 3);
    assert_eq!(
        stmt("DEF STRING[12] TXT=\"x\""),
        Stmt::Def {
            global: false,
            ty: VarType::Str(12),
            vars: vec![VarDecl { name: "TXT".into(), dims: vec![], init: vec![Expr::Str("x".into())] }]
        }
    );
}

#[test]
fn user_names_begin_with_two_letters_or_underscores() {
    // Programming Manual, Fundamentals, "Identifiers": the first two characters are letters or
    // underscores. `E1` would read as address E with the value 1, `I` as the address I.
    for bad in ["DEF INT E1", "DEF REAL I", "DEF INT N, COUNT", "DEF REAL _1", "DEF INT ROW, J"] {
        let diagnostics = parse(bad).diagnostics;
        assert!(
            diagnostics.iter().any(|d| d.message.contains("begins with two letters or underscores")),
            "{bad}: {diagnostics:?}"
        );
    }
    assert!(!parse("PROC SUB(REAL A)").diagnostics.is_empty());
    assert!(!parse("PROC SUB(REAL DIA, VAR INT N2)").diagnostics.is_empty());
    for good in ["DEF INT ROW, COL", "DEF REAL _X", "DEF REAL A_", "DEF INT IX1", "PROC SUB(REAL DIA, VAR INT NN)"] {
        assert!(parse(good).diagnostics.is_empty(), "{good}");
    }
}

#[test]
fn control_flow_statements_are_recognised() {
    assert!(matches!(stmt("IF R1>5 GOTOF END"), Stmt::If { goto: Some(Goto { kind: GotoKind::Forward, .. }), .. }));
    assert!(matches!(stmt("IF (R1>5) AND (R2<1)"), Stmt::If { goto: None, .. }));
    assert!(matches!(stmt("FOR I=1 TO 10"), Stmt::For { .. }));
    assert!(matches!(stmt("WHILE R1<10"), Stmt::While(_)));
    assert!(matches!(stmt("UNTIL R1>=3"), Stmt::Until(_)));
    assert_eq!(stmt("GOTOB N100"), Stmt::Goto(Goto { kind: GotoKind::Backward, target: JumpTarget::BlockNumber(100) }));
    assert!(matches!(
        stmt("PROC P DISPLOF SBLOF"),
        Stmt::Proc {
            attributes: ProcAttributes { save: false, displof: true, actblocno: false, sblof: true, displon: false },
            ..
        }
    ));
    assert!(matches!(
        stmt("PROC P DISPLON"),
        Stmt::Proc { attributes: ProcAttributes { displof: false, sblof: false, displon: true, .. }, .. }
    ));
    assert!(matches!(
        stmt("PROC P(INT COUNT) DISPLOF, SAVE"),
        Stmt::Proc { attributes: ProcAttributes { save: true, displof: true, .. }, .. }
    ));
    let Stmt::Case { arms, default, .. } = stmt("CASE(R1) OF 1 GOTOF ONE 2 GOTOF TWO DEFAULT GOTOF OTHER") else {
        panic!()
    };
    assert_eq!(arms.len(), 2);
    assert!(default.is_some());
    assert!(
        matches!(stmt("PROC CONTOUR(REAL XX1, VAR REAL RES) SAVE"), Stmt::Proc { params, attributes: ProcAttributes { save: true, displof: false, .. }, .. } if params.len() == 2 && params[1].by_reference)
    );
}

#[test]
fn statements_followed_by_stray_text_are_errors() {
    assert!(!parse("ENDIF X10").diagnostics.is_empty());
    assert!(!parse("FOR I=1 10").diagnostics.is_empty());
}

#[test]
fn reading_block_by_block_gives_the_same_blocks_as_parsing_at_once() {
    let src = "N10 G0 X1\n\n; only a comment\r\nG1 X2 F3\nM30";
    let mut streamed = Vec::new();
    let (mut offset, mut line) = (0, 1);
    while let Some((block, next_offset, next_line)) = read_block(src, offset, line) {
        streamed.push(block.unwrap());
        (offset, line) = (next_offset, next_line);
    }
    assert_eq!(streamed, parse(src).blocks);
}

#[test]
fn check_reports_what_parse_reports() {
    let src = "G1 X=\nG0 X1\nG1 #";
    assert_eq!(check(src), parse(src).diagnostics);
}

#[test]
fn jump_targets_are_labels_block_numbers_or_string_expressions() {
    let target = |src: &str| match stmt(src) {
        Stmt::Goto(g) => g.target,
        other => panic!("{other:?}"),
    };
    assert_eq!(target("GOTOF MARKE"), JumpTarget::Label("MARKE".into()));
    assert_eq!(target("GOTOF 200"), JumpTarget::BlockNumber(200));
    assert_eq!(target("GOTOF :30"), JumpTarget::BlockNumber(30));
    assert_eq!(
        target("GOTOF \"N\"<<R10"),
        JumpTarget::Expr(bin(BinOp::Concat, Expr::Str("N".into()), Expr::RParam(Box::new(Expr::Number(10.0)))))
    );
    assert!(matches!(target("GOTOB DEST[1]"), JumpTarget::Expr(Expr::Var { .. })));
    assert_eq!(stmt("GOTOS"), Stmt::Goto(Goto { kind: GotoKind::Start, target: JumpTarget::ProgramStart }));
    // In a block, after other words, and behind IF.
    assert!(matches!(words("X10 GOTOF \"L\"<<R1").last(), Some(Word::Goto(Goto { target: JumpTarget::Expr(_), .. }))));
    assert!(matches!(
        stmt("IF R1 GOTOB \"N10\""),
        Stmt::If { goto: Some(Goto { target: JumpTarget::Expr(_), .. }), .. }
    ));
}

#[test]
fn check_finds_nesting_errors_beside_syntax_errors_with_alarms_and_columns() {
    let d = check("WHILE R1<1\n  X=(\nENDIF\nENDWHILE\nIF R1\n");
    let found: Vec<(u32, u32, u32)> = d.iter().map(|d| (d.alarm, d.line, d.column)).collect();
    // Line 2: `(` never closed, reported at the end of the line (column 6). Line 3: ENDIF
    // without IF. Line 5: the IF is never closed. The WHILE of line 1 is closed in line 4.
    assert_eq!(found, [(12080, 2, 6), (12640, 3, 1), (12640, 5, 1)]);
    // A closer that belongs to an outer structure ends the inner ones with one error.
    let d = check("WHILE 1\nIF 1\nENDWHILE\n");
    assert_eq!(d.len(), 1);
    assert!(d[0].message.contains("IF of line 2"), "{}", d[0].message);
    assert!(check("IF 1\nELSE\nELSE\nENDIF").iter().any(|d| d.line == 3 && d.alarm == 12640));
    assert!(check("REPEAT\nLOOP\nENDLOOP\nUNTIL 1\nFOR I=1 TO 2\nENDFOR").is_empty());
}

/// The former descent, one call per priority level: the reference `parse_binary` must agree
/// with (tree, error and where the cursor stops).
fn reference_level(cur: &mut Cursor, level: usize) -> PResult<Expr> {
    if level == LEVELS.len() {
        return Ok(parse_unary(cur, MAX_EXPR_DEPTH)?.0);
    }
    let mut lhs = reference_level(cur, level + 1)?;
    while let Some(op) = peek_operator(cur, LEVELS[level]) {
        cur.skip_ws();
        let rhs = reference_level(cur, level + 1)?;
        lhs = Expr::Binary(op, Box::new(lhs), Box::new(rhs));
    }
    Ok(lhs)
}

#[test]
fn precedence_climbing_parses_as_the_descent_through_the_levels() {
    // Operands, every operator of every level (with the look-alikes `<<`/`<`, `B_OR`/`OR`,
    // glued word operators), spacing and stray bytes that end or break an expression.
    const PIECES: [&str; 44] = [
        "R1", "2", "0.5", "(R2)", "A", "SIN(30)", "\"S\"", "TRUE", "-", "NOT ", "+", "*", "/", " DIV ", " MOD ", "-",
        "+", "==", "<>", ">=", "<=", ">", "<", "<<", " OR ", " XOR ", " AND ", " B_OR ", " B_XOR ", " B_AND ", "ORX",
        " ", " ", "X1", ")", ",", ":", "=", "DIVA", " B_NOT ", "R[1]", "'H1F'", "==", "<",
    ];
    let mut next = crate::lang::test_rng::xorshift(0x51ce_57a7);
    let mut agreed = 0;
    for _ in 0..30000 {
        let n = 1 + (next() % 9) as usize;
        let text: String = (0..n).map(|_| PIECES[(next() % PIECES.len() as u64) as usize]).collect();
        let (mut a, mut b) = (Cursor::new(&text), Cursor::new(&text));
        let climbed = parse_binary(&mut a, 0, MAX_EXPR_DEPTH).map(|(e, _)| e);
        let descended = reference_level(&mut b, 0);
        assert_eq!(climbed, descended, "{text:?}");
        assert_eq!(a.pos, b.pos, "{text:?}: the cursor stops at the same place");
        agreed += usize::from(climbed.is_ok());
    }
    assert!(agreed > 3000, "only {agreed} texts parsed: the pieces make too few expressions");
}

#[test]
fn r_parameters_by_number_in_any_case_and_names_that_only_start_like_them() {
    let r = |n: f64| Expr::RParam(Box::new(Expr::Number(n)));
    assert_eq!(expr("r12*R0"), bin(BinOp::Mul, r(12.0), r(0.0)));
    assert_eq!(expr("R[r1]"), Expr::RParam(Box::new(r(1.0))));
    // Not an R parameter by number: names that only start with R and digits.
    assert_eq!(expr("RX"), var("RX"));
    assert_eq!(expr("r1x"), var("R1X"));
    assert_eq!(expr("R"), var("R"));
    assert_eq!(expr("true AND False"), bin(BinOp::And, Expr::Bool(true), Expr::Bool(false)));
}

//! Syntax of NC data text: one assignment per line in the control's own notation.
//!
//! Input: text such as `$MA_IS_ROT_AX[AX4]=TRUE`. Output: [`Line`]s with their 1-based line
//! numbers. This module knows nothing about which names exist; [`super::registry`] does.

use super::MdError;

/// A literal on the right-hand side of an assignment.
#[derive(Debug, Clone, PartialEq)]
pub enum Literal {
    Number(f64),
    Bool(bool),
    Str(String),
    /// A bare identifier, e.g. an axis name for AXIS-typed data (`$TC_CARR21[1]=C`).
    Ident(String),
}

/// One index inside `[...]`: a number or a name (`AX1`, `XM`, `TR`).
#[derive(Debug, Clone, PartialEq)]
pub enum IndexTok {
    Number(i64),
    Name(String),
}

/// One meaningful line of NC data text.
#[derive(Debug, Clone, PartialEq)]
pub enum Line {
    Assign {
        line: u32,
        /// Full upper-case name including `$` and prefix, e.g. `$MC_TRAFO_TYPE_1`.
        name: String,
        indices: Vec<IndexTok>,
        value: Literal,
    },
    /// `CHANDATA(n)`: the following channel data belongs to channel n.
    ChanData { line: u32, channel: i64 },
}

/// Splits NC data text into lines; the first syntax error is returned with its line number.
pub fn parse(text: &str) -> Result<Vec<Line>, MdError> {
    let mut out = Vec::new();
    // After `INCH` (until `METRIC`) the file's lengths are inch; they are stored in mm.
    let mut inch = false;
    let mut converted = 0;
    for (i, raw) in text.lines().enumerate() {
        if inch {
            for l in &mut out[converted..] {
                super::inch::to_metric(l)?;
            }
        }
        converted = out.len();
        let line = i as u32 + 1;
        let src = strip_comment(raw).trim();
        if src.is_empty() {
            continue;
        }
        let upper = src.to_ascii_uppercase();
        // Archives end with M17/M30; they carry no data. Their header line (`%_N_TOA_INI`)
        // names the file.
        if upper == "M17" || upper == "M30" || upper == "M02" || upper == "M2" || src.starts_with('%') {
            continue;
        }
        // `METRIC`: the values that follow are in mm, as NCTwin stores them; `INCH`: in inch.
        if upper == "METRIC" || upper == "INCH" {
            inch = upper == "INCH";
            continue;
        }
        if let Some(frames) = frame_constructors(line, src)? {
            out.extend(frames);
            continue;
        }
        if let Some(rest) = upper.strip_prefix("CHANDATA") {
            let inner = rest
                .trim()
                .strip_prefix('(')
                .and_then(|r| r.strip_suffix(')'))
                .ok_or_else(|| MdError::at(line, format!("expected CHANDATA(<n>), found `{src}`")))?;
            let channel =
                inner.trim().parse::<i64>().map_err(|_| MdError::at(line, format!("bad channel number in `{src}`")))?;
            out.push(Line::ChanData { line, channel });
            continue;
        }
        out.push(parse_assignment(line, src)?);
    }
    if inch {
        for l in &mut out[converted..] {
            super::inch::to_metric(l)?;
        }
    }
    Ok(out)
}

/// The frame variables a data file may assign as a whole.
pub(super) const FRAME_NAMES: [&str; 4] = ["$P_UIFR", "$P_CHBFR", "$P_NCBFR", "$P_UBFR"];

/// `$P_UIFR[1]=CTRANS(X,10,Y,0):CROT(Z,45):CSCALE(X,2):CMIRROR(Y)`, as `_N_UFR_INI` files write
/// whole frames: one component assignment (`$P_UIFR[1,X,TR]=10`) per axis value. `None` for
/// any other line.
fn frame_constructors(line: u32, src: &str) -> Result<Option<Vec<Line>>, MdError> {
    let err = |m: String| MdError::at(line, m);
    let Some(eq) = find_top_level_eq(src) else { return Ok(None) };
    let (lhs, rhs) = (src[..eq].trim(), src[eq + 1..].trim());
    let upper = lhs.to_ascii_uppercase();
    let Some(name) = FRAME_NAMES.iter().find(|n| upper.starts_with(**n) && upper[n.len()..].starts_with('[')) else {
        return Ok(None);
    };
    let rhs_upper = rhs.to_ascii_uppercase();
    if !rhs_upper.starts_with('C') || !rhs_upper.contains('(') {
        return Ok(None);
    }
    let index = upper[name.len()..].trim_start_matches('[').trim_end_matches(']').trim();
    let frame = index.parse::<i64>().map_err(|_| err(format!("{name}[{index}]: a frame number is needed")))?;
    let mut out = Vec::new();
    for part in rhs_upper.split(':') {
        let part = part.trim();
        let (function, args) = part
            .strip_suffix(')')
            .and_then(|p| p.split_once('('))
            .ok_or_else(|| err(format!("bad frame value `{part}` (CTRANS(X,10,...), CROT, CSCALE, CMIRROR, CFINE)")))?;
        let component = match function.trim() {
            "CTRANS" => "TR",
            "CFINE" => "FI",
            "CROT" => "RT",
            "CSCALE" => "SC",
            "CMIRROR" => "MI",
            other => return Err(err(format!("unknown frame function {other} (CTRANS, CFINE, CROT, CSCALE, CMIRROR)"))),
        };
        let args: Vec<&str> = args.split(',').map(str::trim).filter(|a| !a.is_empty()).collect();
        let mut assign = |axis: &str, value: f64| {
            out.push(Line::Assign {
                line,
                name: (*name).to_string(),
                indices: vec![
                    IndexTok::Number(frame),
                    IndexTok::Name(axis.to_string()),
                    IndexTok::Name(component.into()),
                ],
                value: Literal::Number(value),
            });
        };
        if component == "MI" {
            args.iter().for_each(|axis| assign(axis, 1.0));
            continue;
        }
        if !args.len().is_multiple_of(2) {
            return Err(err(format!("{function}: axis and value pairs expected")));
        }
        for pair in args.chunks(2) {
            let value = parse_number(pair[1]).ok_or_else(|| err(format!("bad value `{}` in {function}", pair[1])))?;
            assign(pair[0], value);
        }
    }
    Ok(Some(out))
}

/// Tool-management families of `$TC_` data (tool, magazine, location, monitoring, user data):
/// the control keeps them; NCTwin models the cutting edges (`$TC_DP`, `$TC_DPV`), the
/// toolholders (`$TC_CARR`) and tool, magazine, place and monitoring data (`$TC_TP`, `$TC_MAP`,
/// `$TC_MPP`, `$TC_MOP`, see `tools_mgmt.rs`), not the user and other data listed here.
const UNMODELLED_TC: &[&str] = &[
    "TPC", "TPG", "TPH", "TPCS", "MOPC", "MAMP", "MAPC", "MPPC", "MDP", "MLSR", "MPTH", "DPC", "DPCE", "DPCS", "DPE",
    "DPH", "DPNT", "ADPT", "SCP", "ECP", "SCPR", "ECPR", "TPM", "MDPC",
];

/// What a datum NCTwin knows but does not model is (for its warning): tool-management `$TC_`
/// data, and setting data `$SN_`/`$SC_`/`$SA_` not in the registry. Such lines are accepted and
/// ignored. `None` for everything else (modelled, or an unknown name, which is an error).
pub fn unmodelled(name: &str) -> Option<String> {
    let upper = name.to_ascii_uppercase();
    if let Some(rest) = upper.strip_prefix("$TC_") {
        let family = rest.trim_end_matches(|c: char| c.is_ascii_digit());
        return UNMODELLED_TC.contains(&family).then(|| format!("$TC_{family}"));
    }
    let setting = ["$SN_", "$SC_", "$SA_"].iter().find(|p| upper.starts_with(**p))?;
    super::registry::lookup(&upper).is_none().then(|| format!("{setting} setting data ({upper})"))
}

/// One warning per family of lines in `text` that are accepted and ignored ([`unmodelled`]),
/// in the order they first appear; empty when the text does not parse.
pub fn warnings(text: &str) -> Vec<String> {
    let Ok(lines) = parse(text) else { return Vec::new() };
    let mut families: Vec<(String, u32, usize)> = Vec::new();
    for line in lines {
        let Line::Assign { line, name, .. } = line else { continue };
        let Some(family) = unmodelled(&name) else { continue };
        match families.iter_mut().find(|(f, _, _)| *f == family) {
            Some((_, _, count)) => *count += 1,
            None => families.push((family, line, 1)),
        }
    }
    families
        .into_iter()
        .map(|(family, first, count)| {
            format!("{family}: {count} line(s) from line {first} not modelled by NCTwin: accepted and ignored")
        })
        .collect()
}

fn strip_comment(raw: &str) -> &str {
    let mut in_str = false;
    for (i, c) in raw.char_indices() {
        match c {
            '"' => in_str = !in_str,
            ';' if !in_str => return &raw[..i],
            _ => {}
        }
    }
    raw
}

fn parse_assignment(line: u32, src: &str) -> Result<Line, MdError> {
    let err = |msg: String| MdError::at(line, msg);
    if !src.starts_with('$') {
        return Err(err(format!("expected an assignment `$NAME=value`, found `{src}`")));
    }
    let eq = find_top_level_eq(src).ok_or_else(|| err(format!("missing `=` in `{src}`")))?;
    let (lhs, rhs) = (src[..eq].trim(), src[eq + 1..].trim());
    let (name, indices) = match lhs.find('[') {
        Some(open) => {
            let close = lhs
                .rfind(']')
                .filter(|&c| c > open && lhs[c + 1..].trim().is_empty())
                .ok_or_else(|| err(format!("unbalanced `[` in `{lhs}`")))?;
            let inner = &lhs[open + 1..close];
            let indices = inner
                .split(',')
                .map(|t| parse_index(t.trim()).ok_or_else(|| err(format!("bad index `{}` in `{lhs}`", t.trim()))))
                .collect::<Result<Vec<_>, _>>()?;
            (lhs[..open].trim(), indices)
        }
        None => (lhs, Vec::new()),
    };
    if name.len() < 2 || !name[1..].chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(err(format!("bad name `{name}`")));
    }
    let value = parse_literal(rhs).ok_or_else(|| err(format!("bad value `{rhs}` for {name}")))?;
    Ok(Line::Assign { line, name: name.to_ascii_uppercase(), indices, value })
}

fn find_top_level_eq(src: &str) -> Option<usize> {
    let mut in_str = false;
    for (i, c) in src.char_indices() {
        match c {
            '"' => in_str = !in_str,
            '=' if !in_str => return Some(i),
            _ => {}
        }
    }
    None
}

fn parse_index(tok: &str) -> Option<IndexTok> {
    if tok.is_empty() {
        return None;
    }
    if let Ok(n) = tok.parse::<i64>() {
        return Some(IndexTok::Number(n));
    }
    let valid_name =
        tok.chars().next()?.is_ascii_alphabetic() && tok.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    valid_name.then(|| IndexTok::Name(tok.to_ascii_uppercase()))
}

/// Parses a literal in the control's notation. Decimal comma (`1,0`) is not a number.
pub fn parse_literal(src: &str) -> Option<Literal> {
    let s = src.trim();
    if s.is_empty() {
        return None;
    }
    if let Some(inner) = s.strip_prefix('"') {
        let inner = inner.strip_suffix('"')?;
        return (!inner.contains('"')).then(|| Literal::Str(inner.to_string()));
    }
    if let Some(inner) = s.strip_prefix('\'') {
        let inner = inner.strip_suffix('\'')?;
        let (radix, digits) = match inner.chars().next()?.to_ascii_uppercase() {
            'H' => (16, &inner[1..]),
            'B' => (2, &inner[1..]),
            _ => return None,
        };
        return u64::from_str_radix(digits, radix).ok().map(|v| Literal::Number(v as f64));
    }
    match s.to_ascii_uppercase().as_str() {
        "TRUE" => return Some(Literal::Bool(true)),
        "FALSE" => return Some(Literal::Bool(false)),
        _ => {}
    }
    if let Some(n) = parse_number(s) {
        return Some(Literal::Number(n));
    }
    let is_ident = s.chars().next()?.is_ascii_alphabetic() && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    is_ident.then(|| Literal::Ident(s.to_ascii_uppercase()))
}

/// `1`, `1.`, `-2.5`, `.5`, `+3`, `1.5E3`: digits with at most one point, optional exponent.
fn parse_number(s: &str) -> Option<f64> {
    let body = s.strip_prefix(['+', '-']).unwrap_or(s);
    let (mantissa, exponent) = match body.find(['E', 'e']) {
        Some(i) => (&body[..i], Some(&body[i + 1..])),
        None => (body, None),
    };
    let digits = mantissa.chars().filter(|c| c.is_ascii_digit()).count();
    let points = mantissa.chars().filter(|&c| c == '.').count();
    if digits == 0 || points > 1 || digits + points != mantissa.len() {
        return None;
    }
    if let Some(e) = exponent {
        let e = e.strip_prefix(['+', '-']).unwrap_or(e);
        if e.is_empty() || !e.chars().all(|c| c.is_ascii_digit()) {
            return None;
        }
    }
    let normalized = s.replace(['E', 'e'], "e");
    let normalized = if normalized.contains(".e") || normalized.ends_with('.') {
        normalized.replacen('.', ".0", 1)
    } else {
        normalized
    };
    normalized.parse::<f64>().ok().filter(|v| v.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn assign(text: &str) -> Line {
        parse(text).unwrap().remove(0)
    }

    #[test]
    fn numbers_in_control_notation_are_accepted() {
        for (src, want) in [("1", 1.0), ("1.", 1.0), ("-2.5", -2.5), (".5", 0.5), ("+3", 3.0), ("1.5E3", 1500.0)] {
            assert_eq!(parse_literal(src), Some(Literal::Number(want)), "{src}");
        }
    }

    #[test]
    fn decimal_comma_is_not_a_number() {
        assert_eq!(parse_literal("1,0"), None);
        assert!(parse("$MA_MAX_AX_VELO[AX1]=1,0").is_err());
    }

    #[test]
    fn hex_and_binary_literals_are_numbers() {
        assert_eq!(parse_literal("'H1F'"), Some(Literal::Number(31.0)));
        assert_eq!(parse_literal("'B101'"), Some(Literal::Number(5.0)));
    }

    #[test]
    fn assignment_with_named_and_numeric_indices_is_split() {
        let l = assign("$tc_dp6[1,1]=6. ; radius");
        assert_eq!(
            l,
            Line::Assign {
                line: 1,
                name: "$TC_DP6".into(),
                indices: vec![IndexTok::Number(1), IndexTok::Number(1)],
                value: Literal::Number(6.0)
            }
        );
        let l = assign("$MA_IS_ROT_AX[AX4]=TRUE");
        assert!(matches!(l, Line::Assign { value: Literal::Bool(true), .. }));
    }

    #[test]
    fn tool_data_files_read_their_header_units_and_whole_frames() {
        let text = "%_N_TOA_INI\r\n;$PATH=/_N_TOA_DIR\r\nCHANDATA(1)\r\nMETRIC\r\n$TC_TP2[1]=\"DRILL\"\r\n\
                    $P_UIFR[1]=CTRANS(X,10.5,Y,-2):CROT(Z,45):CMIRROR(Y)\r\nM17\r\n";
        let lines = parse(text).unwrap();
        let frame = |axis: &str, comp: &str, v: f64| Line::Assign {
            line: 6,
            name: "$P_UIFR".into(),
            indices: vec![IndexTok::Number(1), IndexTok::Name(axis.into()), IndexTok::Name(comp.into())],
            value: Literal::Number(v),
        };
        assert_eq!(lines[0], Line::ChanData { line: 3, channel: 1 });
        assert!(matches!(&lines[1], Line::Assign { name, .. } if name == "$TC_TP2"));
        assert_eq!(
            lines[2..],
            [frame("X", "TR", 10.5), frame("Y", "TR", -2.0), frame("Z", "RT", 45.0), frame("Y", "MI", 1.0)]
        );
        // INCH switches the units (machine_data::inch): alone it carries no data.
        assert_eq!(parse("INCH\n"), Ok(Vec::new()));
    }

    #[test]
    fn unmodelled_tool_management_and_setting_data_are_named_in_warnings() {
        // Tool, magazine, place and monitoring data are modelled (tools_mgmt.rs); user data not.
        assert_eq!(unmodelled("$TC_TP8"), None);
        assert_eq!(unmodelled("$TC_MPP1"), None);
        assert_eq!(unmodelled("$TC_TPC1").as_deref(), Some("$TC_TPC"));
        assert_eq!(unmodelled("$TC_MPPC1").as_deref(), Some("$TC_MPPC"));
        assert_eq!(unmodelled("$TC_DP3"), None);
        assert_eq!(unmodelled("$TC_XYZ1"), None);
        assert_eq!(unmodelled("$SC_TOFRAME_MODE"), None, "modelled");
        assert!(unmodelled("$SN_JOG_CONT_MODE_LEVELTRIGGRD").is_some());
        assert_eq!(unmodelled("$MN_NO_SUCH_DATUM"), None);
        let w = warnings("$TC_TPC1[1]=1\n$TC_TPC2[1]=2\n$TC_TP2[1]=\"A\"\n$TC_MPPC1[1,1]=1\n");
        assert_eq!(
            w,
            [
                "$TC_TPC: 2 line(s) from line 1 not modelled by NCTwin: accepted and ignored",
                "$TC_MPPC: 1 line(s) from line 4 not modelled by NCTwin: accepted and ignored",
            ]
        );
    }

    #[test]
    fn strings_may_contain_semicolons() {
        let l = assign("$MN_AXCONF_MACHAX_NAME_TAB[0]=\"X;M\"");
        assert!(matches!(l, Line::Assign { value: Literal::Str(ref s), .. } if s == "X;M"));
    }

    #[test]
    fn comments_blank_lines_and_chandata_are_understood() {
        let lines = parse("; header\n\nCHANDATA(1)\n$MC_TRAFO_TYPE_1=256\nM17\n").unwrap();
        assert_eq!(lines.len(), 2);
        assert_eq!(lines[0], Line::ChanData { line: 3, channel: 1 });
    }

    #[test]
    fn errors_name_the_line() {
        let e = parse("$MC_A=1\n$MC_B 2\n").unwrap_err();
        assert_eq!(e.line, Some(2));
    }
}

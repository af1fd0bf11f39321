//! `INCH` in NC data files (`_N_TOA_INI`, `_N_UFR_INI`, ...): the lengths that follow are in
//! inch; NCTwin stores NC data in mm, so they are converted as they are read (1 in = 25.4 mm
//! exactly). `METRIC` switches back.
//!
//! Lengths converted: the tool offsets' geometry, wear and adapter lengths ($TC_DP3..9,
//! $TC_DP12..18, $TC_DP21..23; not the type, cutting edge position or angles), the
//! toolholders' offset vectors l1..l4 ($TC_CARR1..6, $TC_CARR15..20), and translations
//! (`TR`, `FI`) of frames ($P_UIFR, $P_CHBFR, $P_NCBFR, $P_UBFR) on linear axes. An axis whose
//! name begins with A, B or C is taken for a rotary axis (degrees, not converted): data text is
//! read without the machine's axis list. Machine and setting data are written in the machine's
//! basic system, which NCTwin does not convert: after `INCH` they are refused.

use super::MdError;
use super::text::{FRAME_NAMES, IndexTok, Line, Literal};

/// Millimetres per inch, exact by definition.
pub const MM_PER_INCH: f64 = 25.4;

/// Converts `l`, read after `INCH`, to mm where it is a length.
pub(super) fn to_metric(l: &mut Line) -> Result<(), MdError> {
    let Line::Assign { line, name, indices, value } = l else { return Ok(()) };
    if name.starts_with("$M") || name.starts_with("$S") {
        return Err(MdError::at(
            *line,
            format!(
                "{name} after INCH: machine and setting data are in the machine's basic system; write them before INCH or after METRIC"
            ),
        ));
    }
    if let Literal::Number(v) = value
        && is_length(name, indices)
    {
        *v *= MM_PER_INCH;
    }
    Ok(())
}

fn is_length(name: &str, indices: &[IndexTok]) -> bool {
    let number = |prefix: &str| name.strip_prefix(prefix).and_then(|n| n.parse::<u32>().ok());
    if let Some(n) = number("$TC_DP") {
        return matches!(n, 3..=9 | 12..=18 | 21..=23);
    }
    if let Some(n) = number("$TC_CARR") {
        return matches!(n, 1..=6 | 15..=20);
    }
    if FRAME_NAMES.contains(&name) {
        return match indices {
            [_, IndexTok::Name(axis), IndexTok::Name(component)] => {
                matches!(component.to_ascii_uppercase().as_str(), "TR" | "FI")
                    && !axis.to_ascii_uppercase().starts_with(['A', 'B', 'C'])
            }
            _ => false,
        };
    }
    false
}

#[cfg(test)]
mod tests {
    use super::super::text::{Line, Literal, parse};

    fn values(text: &str) -> Vec<(String, f64)> {
        parse(text)
            .unwrap()
            .into_iter()
            .filter_map(|l| match l {
                Line::Assign { name, value: Literal::Number(v), .. } => Some((name, v)),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn lengths_after_inch_are_stored_in_mm_until_metric() {
        let got = values(
            "CHANDATA(1)\nINCH\n$TC_DP1[1,1]=120\n$TC_DP3[1,1]=2\n$TC_DP6[1,1]=0.25\n$TC_DP12[1,1]=-0.001\n\
             $TC_DP24[1,1]=7\n$P_UIFR[1]=CTRANS(X,1,C,90)\nMETRIC\n$TC_DP4[1,1]=2\nM17\n",
        );
        // 2 in = 50.8 mm, 0.25 in = 6.35 mm, -0.001 in = -0.0254 mm; type 120, the relief angle 7°,
        // the C translation 90° stay; after METRIC 2 is 2 mm.
        let want = [
            ("$TC_DP1", 120.0),
            ("$TC_DP3", 2.0 * 25.4),
            ("$TC_DP6", 0.25 * 25.4),
            ("$TC_DP12", -0.001 * 25.4),
            ("$TC_DP24", 7.0),
            ("$P_UIFR", 25.4),
            ("$P_UIFR", 90.0),
            ("$TC_DP4", 2.0),
        ];
        assert_eq!(got, want.map(|(n, v)| (n.to_string(), v)));
        assert_eq!(got[1].1, 50.8);
    }

    #[test]
    fn machine_data_after_inch_is_refused_with_its_line() {
        let e = parse("INCH\n$TC_DP3[1,1]=1\n$MA_POS_LIMIT_PLUS[AX1]=10\n").unwrap_err();
        assert_eq!(e.line, Some(3));
        assert!(parse("$MA_POS_LIMIT_PLUS[AX1]=10\nINCH\n$TC_DP3[1,1]=1\n").is_ok());
    }
}

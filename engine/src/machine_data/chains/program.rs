//! The kinematic chain data of a session as a part program and back: the export is a program
//! a control runs unchanged (DELOBJ of both object types, every `$NK_`/`$NT_` assignment that
//! differs from the defaults, NEWCONF), the import accepts such a program and nothing else, so a
//! file passed between sessions or edited by hand cannot change other data.

use super::KinData;
use crate::machine_data::{MachineConfig, MachineData, MdError};

const PREAMBLE: &str = "; Kinematic chain elements ($NK_) and transformations defined by kinematic chains ($NT_)\n\
                        DELOBJ(\"TRAFO_DATA\")\nDELOBJ(\"KIN_CHAIN_ELEM\")\n";

/// `kin` as a part program: the DELOBJ preamble, the assignments, NEWCONF.
pub fn export_program(kin: &KinData) -> String {
    format!("{PREAMBLE}{}NEWCONF\n", kin.to_text())
}

/// The position of the first `;` outside double quotes: where a comment starts.
fn comment_start(line: &str) -> Option<usize> {
    let mut quoted = false;
    for (i, c) in line.char_indices() {
        match c {
            '"' => quoted = !quoted,
            ';' if !quoted => return Some(i),
            _ => {}
        }
    }
    None
}

/// `N123 rest` → `rest` (a block number in front of the statement).
fn strip_block_number(line: &str) -> &str {
    let Some(rest) = line.strip_prefix(['N', 'n']) else { return line };
    let digits = rest.len() - rest.trim_start_matches(|c: char| c.is_ascii_digit()).len();
    if digits == 0 {
        return line;
    }
    rest[digits..].trim_start()
}

impl MachineData {
    /// Runs a kinematic chain program (as [`export_program`] writes it) on a copy of the data
    /// and activates the result, all-or-nothing: allowed are `$NK_`/`$NT_` assignments,
    /// `DELOBJ("TRAFO_DATA")`, `DELOBJ("KIN_CHAIN_ELEM")`, NEWCONF and M30/M2/M17 (the program
    /// end), comments, blank lines and block numbers. Anything else is an error naming its line.
    pub fn import_chain_program(&mut self, program: &str) -> Result<MachineConfig, MdError> {
        let mut staged = self.clone();
        for (i, raw) in program.lines().enumerate() {
            let line = i as u32 + 1;
            let code = comment_start(raw).map_or(raw, |c| &raw[..c]).trim();
            let code = strip_block_number(code);
            if code.is_empty() {
                continue;
            }
            let compact: String = code.chars().filter(|c| !c.is_whitespace()).collect::<String>().to_ascii_uppercase();
            match compact.as_str() {
                "DELOBJ(\"TRAFO_DATA\")" => staged.delete_kin(false, true),
                "DELOBJ(\"KIN_CHAIN_ELEM\")" => staged.delete_kin(true, false),
                "NEWCONF" | "M30" | "M2" | "M02" | "M17" => {}
                _ if super::is_chain_name(&compact) => {
                    staged.stage_text(code).map_err(|e| MdError { line: Some(line), message: e.message })?;
                }
                _ => {
                    return Err(MdError::at(
                        line,
                        format!(
                            "`{code}`: a kinematic chain program holds only $NK_/$NT_ assignments, \
                             DELOBJ(\"TRAFO_DATA\"), DELOBJ(\"KIN_CHAIN_ELEM\") and NEWCONF"
                        ),
                    ));
                }
            }
        }
        let cfg = staged.activate().map_err(|e| MdError::general(e.message))?;
        *self = staged;
        Ok(cfg)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_and_block_numbers_are_recognised() {
        assert_eq!(comment_start("$NK_NAME[0]=\"A;B\" ; note"), Some(18));
        assert_eq!(strip_block_number("N100 $NK_NAME[0]=\"A\""), "$NK_NAME[0]=\"A\"");
        assert_eq!(strip_block_number("NEWCONF"), "NEWCONF");
    }
}

//! Auxiliary functions for the PLC: the M and H functions of a block, with their address
//! extension, handed to the main run as [`crate::interp::Item::Aux`] and published there as
//! [`crate::channel::Event::AuxFunction`] (the simulated PLC's interface: the event log).
//!
//! Output timing (the control sets it per function with MD22200 and its kin; these are the
//! defaults NCTwin uses): M and H functions are output before the block's motion, so they are
//! seen in the order the blocks run; M0, M1, M2, M17 and M30 are output with their stop or end,
//! after the block's motion, which is where the control acts on them. M functions are whole
//! numbers; H functions carry a REAL value (`H2=1.5`).

/// One auxiliary function as the PLC receives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AuxFunction {
    /// `'M'` or `'H'`.
    pub letter: char,
    /// The address extension (`M2=5`: 2; `M5`, `H7`: 0).
    pub extension: u32,
    /// The function's value (`M5`: 5; `H2=1.5`: 1.5).
    pub value: f64,
}

impl AuxFunction {
    /// True for the M functions of program control (M0, M1, M2, M17, M30 without an
    /// extension), which are output with their stop, after the block's motion.
    pub fn is_program_control(&self) -> bool {
        self.letter == 'M' && self.extension == 0 && matches!(self.value as u32, 0 | 1 | 2 | 17 | 30)
    }

    /// `M5`, `M2=3`, `H7`, `H2=1.5`: as a program writes it.
    pub fn text(&self) -> String {
        match self.extension {
            0 if self.letter == 'M' => format!("M{}", self.value),
            0 => format!("H{}", self.value),
            ext => format!("{}{ext}={}", self.letter, self.value),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn program_control_is_m0_m1_m2_m17_m30_without_extension() {
        let m = |extension, value| AuxFunction { letter: 'M', extension, value };
        assert!(m(0, 30.0).is_program_control() && m(0, 17.0).is_program_control());
        assert!(!m(0, 8.0).is_program_control() && !m(1, 2.0).is_program_control());
        assert!(!AuxFunction { letter: 'H', extension: 0, value: 2.0 }.is_program_control());
    }

    #[test]
    fn text_is_written_as_in_a_program() {
        assert_eq!(AuxFunction { letter: 'M', extension: 0, value: 8.0 }.text(), "M8");
        assert_eq!(AuxFunction { letter: 'M', extension: 2, value: 5.0 }.text(), "M2=5");
        assert_eq!(AuxFunction { letter: 'H', extension: 3, value: 1.5 }.text(), "H3=1.5");
    }
}

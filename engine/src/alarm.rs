//! NC alarms: numbers and texts as the control shows them, and how each one is cleared.

/// How an alarm is acknowledged.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Clear {
    /// Cleared by a channel reset.
    Reset,
    /// Cleared by the cancel key (or a reset).
    Cancel,
}

/// One active alarm.
#[derive(Debug, Clone, PartialEq)]
pub struct Alarm {
    pub number: u32,
    pub message: String,
    /// 1-based program line, when the alarm belongs to a block.
    pub line: Option<u32>,
    pub clear: Clear,
}

impl Alarm {
    fn new(number: u32, message: String, line: Option<u32>) -> Alarm {
        Alarm { number, message, line, clear: Clear::Reset }
    }

    /// 10720: the programmed end point lies beyond a software limit switch.
    pub fn software_limit(line: u32, axis: &str, plus: bool) -> Alarm {
        let sign = if plus { '+' } else { '-' };
        Alarm::new(10720, format!("Channel 1 block {line} axis {axis} software limit switch {sign}"), Some(line))
    }

    /// 10730: a programmed point lies behind the working-area limitation (G25/G26, SD43400..).
    pub fn work_area_limit(line: u32, axis: &str, plus: bool) -> Alarm {
        let sign = if plus { '+' } else { '-' };
        Alarm::new(
            10730,
            format!("Channel 1 block {line} axis {axis} programmed end point behind working area limitation {sign}"),
            Some(line),
        )
    }

    /// 10910: near a pole the machine axes cannot follow the programmed path velocity; the
    /// block runs at the velocity they allow. Information only: the program goes on.
    pub fn irregular_velocity(line: u32) -> Alarm {
        Alarm {
            clear: Clear::Cancel,
            ..Alarm::new(10910, format!("Channel 1 block {line} irregular velocity run in a path axis"), Some(line))
        }
    }

    /// 21800: the watched workpiece counter reached `$AC_REQUIRED_PARTS`
    /// (`channel/counters.rs`). Information only: the program goes on.
    pub fn workpiece_setpoint_reached(required: u32) -> Alarm {
        Alarm {
            clear: Clear::Cancel,
            ..Alarm::new(21800, format!("Channel 1 workpiece setpoint {required} reached"), None)
        }
    }

    /// 10621: a JOG motion stopped at a software limit switch.
    pub fn rests_on_software_limit(axis: &str, plus: bool) -> Alarm {
        let sign = if plus { '+' } else { '-' };
        Alarm {
            clear: Clear::Cancel,
            ..Alarm::new(10621, format!("Channel 1 axis {axis} rests on software limit switch {sign}"), None)
        }
    }

    /// 14092: a path block programs an axis that still travels as a POSA positioning axis (no
    /// WAITP between them), or WAITP names an axis that cannot be one (a spindle).
    pub fn wrong_axis_type(line: u32, axis: &str) -> Alarm {
        Alarm::new(14092, format!("Channel 1 block {line} axis {axis} is wrong axis type"), Some(line))
    }

    /// 17610: POS/POSA/POSP on an axis of the active transformation (Function Manual F2: the
    /// kinematic transformation does not act on positioning axes, so its axes cannot be ones).
    pub fn positioning_trafo_axis(line: u32, axis: &str) -> Alarm {
        Alarm::new(
            17610,
            format!("Channel 1 block {line} axis {axis} involved in the transformation, action cannot be carried out"),
            Some(line),
        )
    }

    /// 16430: a geometry axis as a positioning axis under a frame with a rotation (its path
    /// in the rotated system would move several machine axes, one interpolator cannot).
    pub fn positioning_rotated(line: u32, axis: &str) -> Alarm {
        Alarm::new(
            16430,
            format!(
                "Channel 1 block {line} geometry axis {axis} cannot traverse as positioning axis in rotated coordinate system"
            ),
            Some(line),
        )
    }

    /// 20141: a synchronized action commands an axis (POS/MOV) that is a path axis of the
    /// block in execution, or a spindle as an axis.
    pub fn sync_axis_type(line: Option<u32>, axis: &str) -> Alarm {
        Alarm::new(20141, format!("Channel 1 axis {axis} motion synchronous action: invalid axis type"), line)
    }

    /// 10860: a feed motion without a feedrate.
    pub fn no_feed(line: u32) -> Alarm {
        Alarm::new(10860, format!("Channel 1 block {line} feedrate not programmed"), Some(line))
    }

    /// 16510: diameter programming without a transverse axis (MD20100 empty).
    pub fn no_transverse_axis(line: u32) -> Alarm {
        Alarm::new(16510, format!("Channel 1 block {line} no transverse axis available"), Some(line))
    }

    /// 12080: syntax error.
    pub fn syntax(line: u32, detail: &str) -> Alarm {
        Alarm::new(12080, format!("Channel 1 block {line} syntax error in text area {detail}"), Some(line))
    }

    /// 12470: unknown G function.
    pub fn unknown_g(line: u32, code: u32) -> Alarm {
        Alarm::new(12470, format!("Channel 1 block {line} G function G{code} is unknown"), Some(line))
    }

    /// 12550: name not defined or function not available.
    pub fn unknown_name(line: u32, name: &str) -> Alarm {
        Alarm::new(
            12550,
            format!("Channel 1 block {line} name {name} not defined or option/function not available"),
            Some(line),
        )
    }

    /// 17070: a program wrote a datum that is write-protected (a read-only system variable).
    pub fn write_protected(line: u32, name: &str) -> Alarm {
        Alarm::new(17070, format!("Channel 1 block {line} data write-protected: {name}"), Some(line))
    }

    /// 12000: address programmed more than once.
    pub fn repeated_address(line: u32, address: &str) -> Alarm {
        Alarm::new(12000, format!("Channel 1 block {line} address {address} programmed repeatedly"), Some(line))
    }

    /// 14040: circle end point error.
    pub fn circle_end_point(line: u32) -> Alarm {
        Alarm::new(14040, format!("Channel 1 block {line} error in end point of circle"), Some(line))
    }

    /// 14800: programmed path velocity not positive.
    pub fn feed_not_positive(line: u32) -> Alarm {
        Alarm::new(
            14800,
            format!("Channel 1 block {line} programmed path velocity smaller than or equal to zero"),
            Some(line),
        )
    }

    /// 17180: the cutting edge D does not exist.
    pub fn illegal_d(line: u32, d: u32) -> Alarm {
        Alarm::new(17180, format!("Channel 1 block {line} illegal D number D{d}"), Some(line))
    }

    /// 17190: the tool T does not exist.
    pub fn illegal_t(line: u32, t: u32) -> Alarm {
        Alarm::new(17190, format!("Channel 1 block {line} illegal T number T{t}"), Some(line))
    }

    /// 17191: no tool has the programmed name (`T="name"`, `TCA`).
    pub fn unknown_tool_name(line: u32, name: &str) -> Alarm {
        Alarm::new(17191, format!("Channel 1 block {line} T= {name} not existing"), Some(line))
    }

    /// 17230: NEWT names a tool whose name and duplo number another tool already has.
    pub fn duplo_assigned(line: u32, name: &str, duplo: i64) -> Alarm {
        Alarm::new(
            17230,
            format!("Channel 1 block {line} duplo no. {duplo} of tool {name} already assigned"),
            Some(line),
        )
    }

    /// 17200: DELT names the tool in the spindle or the one prepared for the change.
    pub fn tool_in_use(line: u32, t: u32) -> Alarm {
        Alarm::new(
            17200,
            format!("Channel 1 block {line} tool data of T{t} cannot be deleted: tool in use"),
            Some(line),
        )
    }

    /// 22069: every duplo of the programmed name is disabled, so the tool group has no tool
    /// ready for use.
    pub fn no_usable_tool(line: u32, name: &str) -> Alarm {
        Alarm::new(
            22069,
            format!("Channel 1 tool management: no tool ready in tool group {name}, block {line}"),
            Some(line),
        )
    }

    /// 6411: a cutting edge of the tool in the spindle reached its prewarning limit while the
    /// program ran (time or count). Information only: the program goes on.
    pub fn tool_prewarning(name: &str, d: u32) -> Alarm {
        Alarm {
            clear: Clear::Cancel,
            ..Alarm::new(6411, format!("Channel 1 tool {name} has reached its prewarning limit with D = {d}"), None)
        }
    }

    /// 6413: a cutting edge reached its monitoring limit while the program ran; the tool is
    /// disabled. Information only: the tool in the spindle keeps cutting until it is changed.
    pub fn tool_limit(name: &str, d: u32) -> Alarm {
        Alarm {
            clear: Clear::Cancel,
            ..Alarm::new(6413, format!("Channel 1 tool {name} has reached its monitoring limit with D = {d}"), None)
        }
    }

    /// 14760: the same auxiliary function group programmed twice (M3 with M5, M0 with M30, ...).
    pub fn conflicting_functions(line: u32, what: &str) -> Alarm {
        Alarm::new(
            14760,
            format!("Channel 1 block {line} auxiliary function of a group programmed repeatedly ({what})"),
            Some(line),
        )
    }

    /// A number as an alarm text shows it: plain, or in exponent form beyond 1e12 so that a
    /// programmed `1EX300` does not fill the alarm line with 300 digits.
    pub fn shown(value: f64) -> String {
        if value.abs() < 1e12 { value.to_string() } else { format!("{value:e}") }
    }

    /// 17620 (G75) / 17630 (G74): a fixed or reference point approach of an axis that an
    /// active transformation moves.
    pub fn fixed_point_transformed(line: u32, reference: bool, axis: &str) -> Alarm {
        let (number, what) = if reference { (17630, "reference point") } else { (17620, "fixed point") };
        Alarm::new(
            number,
            format!("Channel 1 block {line} axis {axis} {what} approach not allowed for a transformed axis"),
            Some(line),
        )
    }

    /// 12560: a value outside its allowed range.
    pub fn value_out_of_range(line: u32, what: &str) -> Alarm {
        Alarm::new(12560, format!("Channel 1 block {line} programmed value {what} exceeds allowed limits"), Some(line))
    }
}

impl Alarm {
    /// 14051: arithmetic error (division by zero, root of a negative number, ...).
    pub fn arithmetic(line: u32, what: &str) -> Alarm {
        Alarm::new(14051, format!("Channel 1 block {line} arithmetic error in part program: {what}"), Some(line))
    }
}

impl Alarm {
    /// 12150: an operation does not fit the data type.
    pub fn type_error(line: u32, what: &str) -> Alarm {
        Alarm::new(12150, format!("Channel 1 block {line} operation not compatible with data type: {what}"), Some(line))
    }

    /// 17020: an array index outside the declared dimension.
    pub fn index_error(line: u32, name: &str, what: &str) -> Alarm {
        Alarm::new(17020, format!("Channel 1 block {line} illegal array index of {name}: {what}"), Some(line))
    }

    /// 17020 for index `shown` of a list of `size` elements numbered from `first`; a list the
    /// machine data sized to nothing (MD28254 = 0 ..) says so instead of a range.
    pub fn index_outside(line: u32, name: &str, shown: impl std::fmt::Display, size: usize, first: usize) -> Alarm {
        let valid = match size {
            0 => "none: size 0".to_string(),
            _ => format!("{first}..{}", first + size - 1),
        };
        Alarm::index_error(line, name, &format!("{shown} ({valid})"))
    }

    /// 14080: the jump destination does not exist.
    pub fn jump_not_found(line: u32, target: &str) -> Alarm {
        Alarm::new(14080, format!("Channel 1 block {line} jump destination {target} not found"), Some(line))
    }

    /// 12640: control structures are not properly nested (ENDIF without IF, ...).
    pub fn nesting(line: u32, what: &str) -> Alarm {
        Alarm::new(12640, format!("Channel 1 block {line} invalid nesting of control structures: {what}"), Some(line))
    }

    /// 12380: the user memory of the channel cannot hold another variable.
    pub fn user_memory_full(line: u32, name: &str) -> Alarm {
        Alarm::new(
            12380,
            format!("Channel 1 block {line} maximum memory capacity reached: no room for {name}"),
            Some(line),
        )
    }

    /// 12170: a name defined twice.
    pub fn defined_twice(line: u32, name: &str) -> Alarm {
        Alarm::new(12170, format!("Channel 1 block {line} name {name} defined repeatedly"), Some(line))
    }

    /// 14011: a called program does not exist.
    pub fn program_not_found(line: u32, name: &str) -> Alarm {
        Alarm::new(14011, format!("Channel 1 block {line} program {name} not available"), Some(line))
    }
}

impl Alarm {
    /// A cycle alarm set by the program with SETAL (60000..67999).
    pub fn user(line: u32, number: u32, text: &str) -> Alarm {
        let message = if text.is_empty() { format!("Channel 1 block {line} cycle alarm") } else { text.to_string() };
        Alarm::new(number, message, Some(line))
    }
}

impl Alarm {
    /// The same alarm named at block `line` instead (its text's "block n" with it).
    pub fn at_block(mut self, line: u32) -> Alarm {
        if let Some(old) = self.line {
            let from = format!("block {old}");
            let at = self
                .message
                .match_indices(&from)
                .map(|(i, _)| i)
                .find(|&i| !self.message[i + from.len()..].starts_with(|c: char| c.is_ascii_digit()));
            if let Some(i) = at {
                self.message.replace_range(i..i + from.len(), &format!("block {line}"));
            }
        }
        self.line = Some(line);
        self
    }

    /// 10751: the compensated path would violate the contour (bottleneck, radius too large).
    pub fn collision(line: u32, what: &str) -> Alarm {
        Alarm::new(
            10751,
            format!("Channel 1 block {line} danger of collision with tool radius compensation: {what}"),
            Some(line),
        )
    }

    /// 10763: tool radius compensation omitted a block (its path in the compensation plane
    /// becomes zero: too short for the tool, or skipped by bottleneck detection). Information
    /// only: the program goes on, the block's motion outside the plane still runs.
    pub fn trc_block_omitted(line: u32) -> Alarm {
        Alarm {
            clear: Clear::Cancel,
            ..Alarm::new(
                10763,
                format!("Channel 1 block {line} path component of the block in the compensation plane becomes zero"),
                Some(line),
            )
        }
    }

    /// 10750: G41/G42 with no cutting edge active (D0).
    pub fn trc_without_tool(line: u32) -> Alarm {
        Alarm::new(
            10750,
            format!("Channel 1 block {line} tool radius compensation activated without tool number"),
            Some(line),
        )
    }

    /// 10753: tool radius compensation selected in a block that is not a straight line.
    pub fn trc_selection(line: u32) -> Alarm {
        Alarm::new(
            10753,
            format!("Channel 1 block {line} selection of tool radius compensation only possible in linear block"),
            Some(line),
        )
    }

    /// 10754: tool radius compensation deselected (G40) in a block that is not a straight line.
    pub fn trc_deselection(line: u32) -> Alarm {
        Alarm::new(
            10754,
            format!("Channel 1 block {line} deselection of tool radius compensation only possible in linear block"),
            Some(line),
        )
    }

    /// 10755 (approach) / 10756 (retract): KONT cannot go round the contour's start or end point
    /// because the programmed start or end point lies within the tool radius of it.
    pub fn trc_kont(line: u32, retract: bool) -> Alarm {
        let (number, what) = if retract {
            (10756, "deselection of tool radius compensation via KONT not possible at programmed end point")
        } else {
            (10755, "selection of tool radius compensation via KONT not possible at present starting point")
        };
        Alarm::new(number, format!("Channel 1 block {line} {what}"), Some(line))
    }

    /// 10757: G17/G18/G19 changed while tool radius compensation is active.
    pub fn trc_plane_change(line: u32) -> Alarm {
        Alarm::new(
            10757,
            format!(
                "Channel 1 block {line} changing the compensation plane while tool radius compensation is active not possible"
            ),
            Some(line),
        )
    }

    /// 10760: a circle (or helix) whose plane is not the compensation plane.
    pub fn trc_helix_axis(line: u32) -> Alarm {
        Alarm::new(
            10760,
            format!("Channel 1 block {line} helical axis is not parallel to tool orientation"),
            Some(line),
        )
    }

    /// 10762: more blocks without motion in the compensation plane in a row than MD20250
    /// CUTCOM_MAXNUM_DUMMY_BLOCKS allows.
    pub fn trc_dummy_blocks(line: u32, max: usize) -> Alarm {
        Alarm::new(
            10762,
            format!(
                "Channel 1 block {line} too many empty blocks between 2 traversing blocks with active tool radius compensation (MD20250 CUTCOM_MAXNUM_DUMMY_BLOCKS={max})"
            ),
            Some(line),
        )
    }

    /// 10741: the infeed of a smooth approach or retract would reverse its direction (the start
    /// point lies between the DISCL plane and the contour).
    pub fn sar_direction_reversal(line: u32) -> Alarm {
        Alarm::new(10741, format!("Channel 1 block {line} direction reversal with infeed movement"), Some(line))
    }

    /// 10742: DISR missing or invalid for smooth approach or retract.
    pub fn sar_distance(line: u32) -> Alarm {
        Alarm::new(10742, format!("Channel 1 block {line} invalid distance or distance not programmed"), Some(line))
    }

    /// 10743: two approach or retract contours (G147..G348) in one block.
    pub fn sar_repeated(line: u32) -> Alarm {
        Alarm::new(10743, format!("Channel 1 block {line} SAR programmed more than once"), Some(line))
    }

    /// 10744: no approach direction: G143 with the start point on the contour's tangent, or a
    /// SAR form this model does not run (see `compensation/sar.rs`).
    pub fn sar_direction(line: u32) -> Alarm {
        Alarm::new(10744, format!("Channel 1 block {line} no valid SAR direction defined"), Some(line))
    }

    /// 10748: DISRP's retraction plane between the DISCL plane and the contour.
    pub fn sar_retraction_plane(line: u32) -> Alarm {
        Alarm::new(10748, format!("Channel 1 block {line} illegal retraction plane with SAR"), Some(line))
    }

    /// 10747: retract with G143 without an end point in the plane (its side is undefined).
    pub fn sar_retract_direction(line: u32) -> Alarm {
        Alarm::new(10747, format!("Channel 1 block {line} retraction direction for SAR not defined"), Some(line))
    }
}

impl Alarm {
    /// 12641: more control structures open at once than the control allows.
    pub fn nesting_too_deep(line: u32, what: &str) -> Alarm {
        Alarm::new(
            12641,
            format!("Channel 1 block {line} nesting depth of control structures too large: {what}"),
            Some(line),
        )
    }

    /// 14012: more nested subprogram calls than program levels.
    pub fn too_many_levels(line: u32, levels: usize) -> Alarm {
        Alarm::new(14012, format!("Channel 1 block {line} maximum subprogram level ({levels}) exceeded"), Some(line))
    }

    /// 12340: more arguments in a call than the called PROC has parameters.
    pub fn too_many_arguments(line: u32, what: &str) -> Alarm {
        Alarm::new(12340, format!("Channel 1 block {line} number of parameters too high: {what}"), Some(line))
    }

    /// 12320: a call-by-reference (VAR) parameter given something that is not a variable.
    pub fn not_a_variable(line: u32, param: &str) -> Alarm {
        Alarm::new(12320, format!("Channel 1 block {line} parameter {param} is not a variable"), Some(line))
    }

    /// 12260: more initial values than the array has elements.
    pub fn too_many_initial_values(line: u32, name: &str) -> Alarm {
        Alarm::new(
            12260,
            format!("Channel 1 block {line} too many initialization values specified for {name}"),
            Some(line),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::Alarm;

    #[test]
    fn an_alarm_moved_to_another_block_names_it_in_its_text() {
        let moved = Alarm::no_feed(26).at_block(7);
        assert_eq!(moved.line, Some(7));
        assert_eq!(moved.message, "Channel 1 block 7 feedrate not programmed");
    }

    #[test]
    fn only_the_whole_block_number_is_replaced() {
        let alarm = Alarm::user(2, 65000, "block 26 then block 2 of 260");
        assert_eq!(alarm.at_block(9).message, "block 26 then block 9 of 260");
    }
}

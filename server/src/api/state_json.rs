//! The `{"type": "state", ...}` stream message written by hand into a reused buffer.
//!
//! A real-time session with a viewer sends 20 state messages a second, and serde's generic path
//! (a `Serializer` call per field, a new buffer per message) cost about as much as the 12 IPO
//! cycles behind each one. This writer produces the same bytes as serde_json does for
//! `StreamMessage::State` (tested byte for byte, on running programs and on every optional
//! part): the same key order, floats through `zmij` as serde_json formats them (`null` when not
//! finite), integers through `itoa`, strings escaped as serde_json escapes them.

use axum::extract::ws::Utf8Bytes;
use nctwin_engine::channel::PositioningInfo;
use nctwin_engine::channel::ReferencePhase;
use nctwin_engine::channel::StockInfo;
use nctwin_engine::channel::sync::SyncActionInfo;
use nctwin_engine::interp::program_control::SkipLevels;
use nctwin_engine::{Mode, Overrides, Snapshot, Status};

/// Room for a whole state message of a 7-axis machine, so the buffer is allocated once.
const BUFFER_CAPACITY: usize = 3072;

/// Encodes state messages into one reused buffer; each message is then copied out once into
/// its own shared bytes (one allocation of the exact size).
///
/// The message's tail (`message` to the end: MSG text, overrides, options, G codes, reference
/// state) rarely changes while a program runs; its text is kept with the values it was written
/// from and reused while they are equal.
#[derive(Debug, Default)]
pub struct StateEncoder {
    buf: String,
    tail: Option<Tail>,
    tail_text: String,
}

/// The values of the message's tail as last written.
#[derive(Debug)]
struct Tail {
    message: Option<String>,
    overrides: Overrides,
    single_block: bool,
    optional_stop: bool,
    dry_run: bool,
    skip_levels: SkipLevels,
    gcodes: Vec<String>,
    referenced: Vec<(String, bool)>,
    repos_pending: bool,
    referencing: Option<(String, ReferencePhase)>,
    sync_actions: Vec<SyncActionInfo>,
    stock: Option<StockInfo>,
}

impl Tail {
    fn of(s: &Snapshot) -> Tail {
        Tail {
            message: s.message.clone(),
            overrides: s.overrides,
            single_block: s.single_block,
            optional_stop: s.optional_stop,
            dry_run: s.dry_run,
            skip_levels: s.skip_levels,
            gcodes: s.gcodes.clone(),
            referenced: s.referenced.clone(),
            repos_pending: s.repos_pending,
            referencing: s.referencing.clone(),
            sync_actions: s.sync_actions.clone(),
            stock: s.stock,
        }
    }

    /// Takes over the tail of `s`, reusing the strings already held.
    fn store(&mut self, s: &Snapshot) {
        self.message.clone_from(&s.message);
        self.overrides = s.overrides;
        self.single_block = s.single_block;
        self.optional_stop = s.optional_stop;
        self.dry_run = s.dry_run;
        self.skip_levels = s.skip_levels;
        self.gcodes.clone_from(&s.gcodes);
        self.referenced.clone_from(&s.referenced);
        self.repos_pending = s.repos_pending;
        self.referencing.clone_from(&s.referencing);
        self.sync_actions.clone_from(&s.sync_actions);
        self.stock = s.stock;
    }

    fn matches(&self, s: &Snapshot) -> bool {
        self.message == s.message
            && self.overrides == s.overrides
            && self.single_block == s.single_block
            && self.optional_stop == s.optional_stop
            && self.dry_run == s.dry_run
            && self.skip_levels == s.skip_levels
            && self.gcodes == s.gcodes
            && self.referenced == s.referenced
            && self.repos_pending == s.repos_pending
            && self.referencing == s.referencing
            && self.sync_actions == s.sync_actions
            && self.stock == s.stock
    }
}

impl StateEncoder {
    /// The state message of `s` as JSON text.
    pub fn encode(&mut self, s: &Snapshot) -> Utf8Bytes {
        self.buf.clear();
        self.buf.reserve(BUFFER_CAPACITY);
        write_head(&mut self.buf, s);
        match &self.tail {
            Some(tail) if tail.matches(s) => self.buf.push_str(&self.tail_text),
            _ => {
                let start = self.buf.len();
                write_tail(&mut self.buf, s);
                self.tail_text.clear();
                self.tail_text.push_str(&self.buf[start..]);
                match &mut self.tail {
                    Some(tail) => tail.store(s),
                    none => *none = Some(Tail::of(s)),
                }
            }
        }
        Utf8Bytes::from(self.buf.as_str().to_owned())
    }
}

/// Appends the state message of `s` to `out`.
pub fn write_state(out: &mut String, s: &Snapshot) {
    write_head(out, s);
    write_tail(out, s);
}

/// The message from its start to `spindles`.
fn write_head(out: &mut String, s: &Snapshot) {
    out.push_str("{\"type\":\"state\",\"status\":\"");
    out.push_str(status_name(s.status));
    out.push_str("\",\"mode\":\"");
    out.push_str(mode_name(s.mode));
    out.push_str("\",\"time\":");
    write_f64(out, s.time);
    out.push_str(",\"tick\":");
    write_int(out, s.tick);
    out.push_str(",\"positions\":{\"machine\":");
    write_named(out, &s.machine, write_f64);
    out.push_str(",\"basic\":");
    write_named(out, &s.basic, write_f64);
    out.push_str(",\"workpiece\":");
    write_named(out, &s.workpiece, write_f64);
    out.push_str("},\"servo\":{\"setpoint\":");
    write_named(out, &s.machine, write_f64);
    out.push_str(",\"actual\":");
    write_named(out, &s.actual, write_f64);
    out.push_str(",\"following_error\":");
    write_named(out, &s.following_error, write_f64);
    out.push_str("},\"orientation\":");
    match s.orientation {
        None => out.push_str("null"),
        Some([x, y, z]) => {
            out.push('[');
            write_f64(out, x);
            out.push(',');
            write_f64(out, y);
            out.push(',');
            write_f64(out, z);
            out.push(']');
        }
    }
    out.push_str(",\"transformation\":");
    match &s.transformation {
        None => out.push_str("null"),
        Some(t) => {
            out.push_str("{\"name\":");
            write_str(out, &t.name);
            out.push_str(",\"type\":");
            write_int(out, t.trafo_type);
            out.push_str(",\"index\":");
            write_int(out, t.index);
            out.push('}');
        }
    }
    out.push_str(",\"block\":");
    match &s.block {
        None => out.push_str("null"),
        Some(b) => {
            out.push_str("{\"line\":");
            write_int(out, b.line);
            out.push_str(",\"text\":");
            write_str(out, &b.text);
            out.push_str(",\"program\":");
            match &b.program {
                None => out.push_str("null"),
                Some(p) => write_str(out, p),
            }
            out.push('}');
        }
    }
    out.push_str(",\"alarms\":[");
    for (i, a) in s.alarms.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        out.push_str("{\"number\":");
        write_int(out, a.number);
        out.push_str(",\"message\":");
        write_str(out, &a.message);
        out.push_str(",\"line\":");
        match a.line {
            None => out.push_str("null"),
            Some(line) => write_int(out, line),
        }
        out.push('}');
    }
    out.push_str("],\"tool\":{\"t\":");
    write_int(out, s.tool.0);
    out.push_str(",\"d\":");
    write_int(out, s.tool.1);
    out.push_str(",\"name\":");
    write_str(out, &s.tool_name);
    out.push_str(",\"prepared\":");
    write_int(out, s.prepared_tool);
    out.push_str("},\"path_velocity\":");
    write_f64(out, s.path_velocity);
    out.push_str(",\"program_serial\":");
    write_int(out, s.program_serial);
    out.push_str(",\"distance_to_go\":");
    write_f64(out, s.distance_to_go);
    out.push_str(",\"programmed_feed\":");
    write_opt_f64(out, s.programmed_feed);
    if s.preprocessing_stop_wait {
        out.push_str(",\"preprocessing_stop_wait\":true");
    }
    let p = &s.parts;
    out.push_str(",\"parts\":{\"required\":");
    write_int(out, p.required);
    out.push_str(",\"total\":");
    write_int(out, p.total);
    out.push_str(",\"actual\":");
    write_int(out, p.actual);
    out.push_str(",\"special\":");
    write_int(out, p.special);
    out.push_str("},\"runtimes\":{\"operating\":");
    write_f64(out, s.runtimes.operating);
    out.push_str(",\"cycle\":");
    write_f64(out, s.runtimes.cycle);
    out.push_str(",\"cutting\":");
    write_f64(out, s.runtimes.cutting);
    out.push('}');
    out.push_str(",\"spindles\":");
    write_named(out, &s.spindles, write_f64);
    out.push_str(",\"spindle_info\":{");
    for (i, (name, sp)) in s.spindle_states.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        write_str(out, name);
        out.push_str(":{\"number\":");
        write_int(out, sp.number);
        out.push_str(",\"speed\":");
        write_f64(out, sp.speed);
        out.push_str(",\"mode\":");
        write_str(out, sp.mode.name());
        out.push_str(",\"position\":");
        write_f64(out, sp.position);
        out.push_str(",\"master\":");
        write_bool(out, sp.master);
        out.push_str(",\"gear\":");
        match sp.gear {
            None => out.push_str("null"),
            Some(g) => write_int(out, g),
        }
        out.push_str(",\"cutting\":");
        write_bool(out, sp.cutting);
        out.push_str(",\"position_control\":");
        write_bool(out, sp.position_control);
        out.push('}');
    }
    out.push('}');
    if !s.positioning.is_empty() {
        write_positioning(out, &s.positioning);
    }
}

/// `,"positioning":[...]` as serde writes `api::positioning_dto::PositioningState`.
fn write_positioning(out: &mut String, list: &[PositioningInfo]) {
    out.push_str(",\"positioning\":");
    write_items(out, list, |out, p| {
        out.push_str("{\"axis\":");
        write_str(out, &p.axis);
        out.push_str(",\"target\":");
        write_opt_f64(out, p.target);
        out.push_str(",\"velocity\":");
        write_f64(out, p.velocity);
        out.push_str(",\"kind\":");
        write_str(out, p.kind);
        out.push_str(",\"waiting\":");
        write_bool(out, p.waiting);
        out.push('}');
    });
}

/// The message from `message` to its end.
fn write_tail(out: &mut String, s: &Snapshot) {
    out.push_str(",\"message\":");
    match &s.message {
        None => out.push_str("null"),
        Some(m) => write_str(out, m),
    }
    out.push_str(",\"overrides\":{\"feed\":");
    write_f64(out, s.overrides.feed);
    out.push_str(",\"rapid\":");
    write_f64(out, s.overrides.rapid);
    out.push_str(",\"spindle\":");
    write_f64(out, s.overrides.spindle);
    out.push_str("},\"single_block\":");
    write_bool(out, s.single_block);
    out.push_str(",\"optional_stop\":");
    write_bool(out, s.optional_stop);
    out.push_str(",\"dry_run\":");
    write_bool(out, s.dry_run);
    out.push_str(",\"skip_levels\":[");
    for (i, level) in s.skip_levels.levels().into_iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        out.push(char::from(b'0' + level));
    }
    out.push(']');
    out.push_str(",\"gcodes\":[");
    for (i, g) in s.gcodes.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        write_str(out, g);
    }
    out.push_str("],\"referenced\":");
    write_named(out, &s.referenced, write_bool);
    out.push_str(",\"repos_pending\":");
    write_bool(out, s.repos_pending);
    if let Some((axis, phase)) = &s.referencing {
        out.push_str(",\"referencing\":{\"axis\":");
        write_str(out, axis);
        out.push_str(",\"phase\":");
        write_str(out, phase_name(*phase));
        out.push('}');
    }
    if !s.sync_actions.is_empty() {
        out.push_str(",\"synchronized_actions\":");
        write_items(out, &s.sync_actions, |out, a| {
            out.push_str("{\"id\":");
            match a.id {
                Some(n) => write_int(out, n),
                None => out.push_str("null"),
            }
            out.push_str(",\"kind\":");
            write_str(out, a.kind);
            out.push_str(",\"trigger\":");
            write_str(out, a.trigger);
            out.push_str(",\"condition\":");
            write_str(out, &a.condition);
            out.push_str(",\"fired\":");
            write_bool(out, a.fired);
            out.push_str(",\"locked\":");
            write_bool(out, a.locked);
            out.push_str(",\"line\":");
            write_int(out, a.line);
            out.push('}');
        });
    }
    if let Some(stock) = &s.stock {
        write_stock(out, stock);
    }
    out.push('}');
}

/// `,"stock":{...}` as serde writes `api::stock::StockSummary`.
fn write_stock(out: &mut String, s: &StockInfo) {
    out.push_str(",\"stock\":{\"model\":");
    write_str(out, if s.turning { "turning" } else { "milling" });
    for (key, v) in [
        ("resolution", s.resolution),
        ("initial_volume", s.initial_volume),
        ("volume", s.volume),
        ("removed", s.removed),
    ] {
        out.push_str(",\"");
        out.push_str(key);
        out.push_str("\":");
        write_f64(out, v);
    }
    out.push_str(",\"warnings\":");
    write_int(out, s.warnings);
    out.push_str(",\"last_warning\":");
    match &s.last_warning {
        None => out.push_str("null"),
        Some(w) => {
            out.push_str("{\"check\":");
            write_str(out, w.check.as_str());
            out.push_str(",\"line\":");
            write_int(out, w.line);
            out.push_str(",\"volume\":");
            write_f64(out, w.volume);
            out.push_str(",\"depth\":");
            write_f64(out, w.depth);
            out.push_str(",\"position\":[");
            for (i, c) in w.position.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                write_f64(out, *c);
            }
            out.push_str("]}");
        }
    }
    out.push_str(",\"version\":");
    write_int(out, s.version);
    out.push_str(",\"frame\":");
    match &s.frame {
        None => out.push_str("null"),
        Some(rows) => {
            for (i, row) in rows.iter().enumerate() {
                out.push_str(if i == 0 { "[[" } else { "],[" });
                for (j, v) in row.iter().enumerate() {
                    if j > 0 {
                        out.push(',');
                    }
                    write_f64(out, *v);
                }
            }
            out.push_str("]]");
        }
    }
    out.push('}');
}

/// `dto::ChannelStatus` as serde names it (lowercase).
fn status_name(s: Status) -> &'static str {
    match s {
        Status::Idle => "idle",
        Status::Running => "running",
        Status::Stopped => "stopped",
        Status::Alarm => "alarm",
    }
}

/// `dto::OpMode` as serde names it (uppercase).
fn mode_name(m: Mode) -> &'static str {
    match m {
        Mode::Jog => "JOG",
        Mode::Mda => "MDA",
        Mode::Auto => "AUTO",
    }
}

fn phase_name(p: ReferencePhase) -> &'static str {
    p.as_str()
}

/// Named values as a JSON object in their order.
fn write_named<T: Copy>(out: &mut String, list: &[(String, T)], value: fn(&mut String, T)) {
    out.push('{');
    for (i, (name, v)) in list.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        write_str(out, name);
        out.push(':');
        value(out, *v);
    }
    out.push('}');
}

/// `[a,b,...]`, each item written by `item`.
fn write_items<T>(out: &mut String, items: &[T], item: impl Fn(&mut String, &T)) {
    out.push('[');
    for (i, x) in items.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        item(out, x);
    }
    out.push(']');
}

/// A number, or `null` for `None`.
fn write_opt_f64(out: &mut String, v: Option<f64>) {
    match v {
        None => out.push_str("null"),
        Some(v) => write_f64(out, v),
    }
}

/// A float as serde_json writes it: the shortest text that reads back the same (`zmij`, as serde_json 1.0.15x), `null`
/// for NaN and infinities.
fn write_f64(out: &mut String, v: f64) {
    if v.is_finite() {
        out.push_str(zmij::Buffer::new().format_finite(v));
    } else {
        out.push_str("null");
    }
}

fn write_int(out: &mut String, v: impl itoa::Integer) {
    out.push_str(itoa::Buffer::new().format(v));
}

fn write_bool(out: &mut String, v: bool) {
    out.push_str(if v { "true" } else { "false" });
}

/// A JSON string, escaped as serde_json escapes: `"` and `\`, the short forms `\b \t \n \f
/// \r`, every other control character as `\u00xx` (lowercase hex).
fn write_str(out: &mut String, s: &str) {
    out.push('"');
    let mut start = 0;
    for (i, b) in s.bytes().enumerate() {
        let escape = match b {
            b'"' => "\\\"",
            b'\\' => "\\\\",
            0x08 => "\\b",
            b'\t' => "\\t",
            b'\n' => "\\n",
            0x0c => "\\f",
            b'\r' => "\\r",
            0x00..=0x1f => "",
            _ => continue,
        };
        // `i` is at an ASCII byte, so both slices end on character boundaries.
        out.push_str(&s[start..i]);
        if escape.is_empty() {
            const HEX: &[u8; 16] = b"0123456789abcdef";
            out.push_str("\\u00");
            out.push(char::from(HEX[usize::from(b >> 4)]));
            out.push(char::from(HEX[usize::from(b & 0xf)]));
        } else {
            out.push_str(escape);
        }
        start = i + 1;
    }
    out.push_str(&s[start..]);
    out.push('"');
}

#[cfg(test)]
mod tests {
    use nctwin_engine::channel::{ReferencePhase, TransformationInfo};
    use nctwin_engine::{Alarm, Channel};

    use super::*;
    use crate::dto::{self, StreamMessage};

    /// The reference: the state DTO through serde_json, as the stream always sent it.
    fn via_dto(s: &Snapshot) -> String {
        serde_json::to_string(&StreamMessage::State(Box::new(dto::State::from(s)))).expect("JSON")
    }

    fn check(encoder: &mut StateEncoder, s: &Snapshot) {
        assert_eq!(encoder.encode(s).as_str(), via_dto(s), "at tick {}", s.tick);
    }

    /// Every frame of a program on a machine, through one encoder (its buffer reused).
    fn run(encoder: &mut StateEncoder, preset: &str, program: &str) -> usize {
        let mut channel = Channel::from_preset(preset, "").expect("preset");
        check(encoder, &channel.snapshot());
        channel.run_program(program).expect("program");
        let mut frames = 0;
        while channel.is_busy() && frames < 5_000 {
            for _ in 0..12 {
                channel.step();
            }
            check(encoder, &channel.snapshot());
            frames += 1;
        }
        frames
    }

    #[test]
    fn every_frame_of_running_programs_is_byte_for_byte_the_dtos_json() {
        let mut encoder = StateEncoder::default();
        let mill =
            "G54 T1 D1\nMSG(\"Schruppen ü\")\nG0 X10.5 Y-3 Z5\nG1 Z-1 F600\nG2 X20 Y10 I5 J0\nG3 X10 Y10 I-5 J0\nM30";
        assert!(run(&mut encoder, "mill-3axis", mill) > 10);
        let transmit = "T1 D1 G17 F5000\nG0 X20 Z10\nTRANSMIT\nG1 X10 Y-10\nX-10\nY10\nTRAFOOF\nM30";
        assert!(run(&mut encoder, "transmit-example", transmit) > 10);
        assert!(run(&mut encoder, "lathe-2axis", "T1 D1 S500 M4\nG0 X40 Z5\nG1 Z-20 F200\nM30") > 10);
        assert!(run(&mut encoder, "mill7-generic", "G1 X10 Y5 Z-2 A10 F2000\nGOTOF NOWHERE\nM30") > 1);
        let sync = "ID=2 WHENEVER $AA_IM[X]>5 DO $AC_OVR=50\nWHEN $A_IN[1]==1 DO DELDTG\nG1 X10 F600\nM30";
        assert!(run(&mut encoder, "mill-3axis", sync) > 10);
        // A blank cut by a rapid (the stock summary with its last warning).
        let stock = "T1 D1\nG0 Z50\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,,-10,-10,50,40)\nG0 X-20 Y15 Z-3\nG0 X60\nM30";
        assert!(run(&mut encoder, "mill-3axis", stock) > 10);
        // A blank on a trunnion table that turns: the stock's frame in the summary.
        let table = "T1 D1\nG0 Z80\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,,-10,-10,30,10)\nG0 A20 C30\nM30";
        assert!(run(&mut encoder, "mill5-table-ac", table) > 10);
        // Positioning axes: POSA across a block, POS waited for, POSP in parts, a command axis.
        let positioning = "POSA[Z]=-5 FA[Z]=300\nG1 X4 F600\nWAITP(Z)\nPOSP[Y]=(3, 1) FA[Y]=900\nM30";
        assert!(run(&mut encoder, "mill-3axis", positioning) > 10);
        // The path standing at a STOPRE while the POSA axis travels.
        let stopre = "POSA[Z]=-5 FA[Z]=300\nSTOPRE\nG1 X4 F600\nM30";
        assert!(run(&mut encoder, "mill-3axis", stopre) > 10);
        let command = "ID=1 WHEN $AA_IM[X]>1 DO MOV[Z]=-1 FA[Z]=600\nG1 X6 F600\nM30";
        assert!(run(&mut encoder, "mill-3axis", command) > 10);
    }

    #[test]
    fn a_posa_axis_on_its_way_is_in_the_state_message() {
        // FA[Z]=300 is 300 mm/min: at full speed after one cycle, towards machine Z −5.
        let mut channel = Channel::from_preset("mill-3axis", "").expect("preset");
        channel.run_program("POSA[Z]=-5 FA[Z]=300\nG4 F2\nM30").expect("program");
        for _ in 0..30 {
            channel.step();
        }
        let text = StateEncoder::default().encode(&channel.snapshot());
        let want =
            r#","positioning":[{"axis":"Z","target":-5.0,"velocity":-300.0,"kind":"POSA","waiting":false}],"message""#;
        assert!(text.as_str().contains(want), "{}", text.as_str());
    }

    #[test]
    fn optional_parts_escapes_and_odd_numbers_are_the_dtos_json() {
        let mut channel = Channel::from_preset("mill-3axis", "").expect("preset");
        channel.run_program("G1 X10 Y5 F600\nM30").expect("program");
        for _ in 0..20 {
            channel.step();
        }
        let mut s = channel.snapshot();
        s.transformation =
            Some(TransformationInfo { name: "TRA\"ORI\"".into(), trafo_type: 72, index: 2, diameter: Some(40.0) });
        s.alarms = vec![
            Alarm::syntax(7, "column 3: \"bad\" word \\ back"),
            Alarm::syntax(9, "ctl \u{1}\u{1f}\u{8}\u{c}\r\n\t"),
        ];
        s.alarms[1].line = None;
        s.spindles = vec![("S1".into(), -1200.5), ("S2".into(), 1e21)];
        s.message = Some("tab\tand \"quotes\", Grüße ✓ \u{7f}".into());
        s.referencing = Some(("Y".into(), ReferencePhase::Marker));
        s.referenced[1].1 = false;
        s.orientation = Some([0.0, -0.0, 1.0e-7]);
        s.machine[0].1 = f64::NAN;
        s.machine[1].1 = f64::INFINITY;
        s.basic[0].1 = 123_456_789.012_345_67;
        s.workpiece[2].1 = -1.0e-300;
        s.time = 1e16;
        s.tick = u64::MAX;
        s.tool = (u32::MAX, 0);
        (s.tool_name, s.prepared_tool) = ("DRILL_\"8\"".into(), 7);
        s.single_block = true;
        s.optional_stop = true;
        s.dry_run = true;
        s.skip_levels = SkipLevels::from_levels(&[0, 4, 9]).unwrap();
        s.repos_pending = true;
        s.preprocessing_stop_wait = true;
        s.parts = nctwin_engine::interp::eval::process_vars::PartCounts {
            required: 999_999_999,
            total: 12,
            actual: 0,
            special: 7,
        };
        s.runtimes.cycle = 12.345_678_9;
        s.runtimes.cutting = f64::MIN_POSITIVE;
        s.block = Some(nctwin_engine::channel::BlockRef { line: 3, text: String::new(), program: Some("HOLE".into()) });
        s.positioning = vec![
            PositioningInfo { axis: "Z\"1".into(), target: None, velocity: -0.0, kind: "MOV", waiting: false },
            PositioningInfo {
                axis: "A".into(),
                target: Some(359.999_999_9),
                velocity: 1e-9,
                kind: "POSP",
                waiting: true,
            },
        ];
        let mut encoder = StateEncoder::default();
        check(&mut encoder, &s);
        for phase in [ReferencePhase::Cam, ReferencePhase::Position] {
            s.referencing = Some(("X1".into(), phase));
            check(&mut encoder, &s);
        }
        s.orientation = None;
        s.transformation = None;
        s.block = None;
        s.message = None;
        s.alarms.clear();
        s.spindles.clear();
        s.referencing = None;
        check(&mut encoder, &s);
    }

    #[test]
    fn a_change_in_any_part_of_the_kept_tail_is_written() {
        let mut channel = Channel::from_preset("lathe-2axis", "").expect("preset");
        channel.run_program("G1 X10 F600\nM30").expect("program");
        channel.step();
        let mut s = channel.snapshot();
        let mut encoder = StateEncoder::default();
        check(&mut encoder, &s);
        let changes: [&dyn Fn(&mut Snapshot); 13] = [
            &|s| s.message = Some("MSG 1".into()),
            &|s| s.message = Some("MSG 2".into()),
            &|s| s.overrides.feed = 50.0,
            &|s| s.single_block = true,
            &|s| s.optional_stop = true,
            &|s| s.dry_run = true,
            &|s| s.skip_levels = SkipLevels::from_levels(&[3]).unwrap(),
            &|s| s.gcodes[0] = "G3".into(),
            &|s| s.referenced[0].1 = false,
            &|s| s.repos_pending = true,
            &|s| s.referencing = Some(("X1".into(), ReferencePhase::Cam)),
            &|s| {
                s.sync_actions = vec![SyncActionInfo {
                    id: None,
                    kind: "block",
                    trigger: "WHEN",
                    condition: "$A_IN[1]==\"1\"".into(),
                    fired: false,
                    locked: false,
                    line: 4,
                }]
            },
            &|s| {
                s.sync_actions[0].fired = true;
                s.sync_actions.push(SyncActionInfo {
                    id: Some(255),
                    kind: "static",
                    trigger: "DO",
                    condition: String::new(),
                    fired: true,
                    locked: true,
                    line: 1,
                });
            },
        ];
        for change in changes {
            change(&mut s);
            check(&mut encoder, &s);
            // The same tail again, with a new position: the kept text is reused.
            s.machine[0].1 += 1.0;
            check(&mut encoder, &s);
        }
        s.message = None;
        s.referencing = None;
        check(&mut encoder, &s);
    }

    #[test]
    fn every_status_and_mode_is_named_as_serde_names_it() {
        for status in [Status::Idle, Status::Running, Status::Stopped, Status::Alarm] {
            let serde = serde_json::to_string(&dto::ChannelStatus::from(status)).expect("JSON");
            assert_eq!(serde, format!("\"{}\"", status_name(status)));
        }
        for mode in [Mode::Jog, Mode::Mda, Mode::Auto] {
            let serde = serde_json::to_string(&dto::OpMode::from(mode)).expect("JSON");
            assert_eq!(serde, format!("\"{}\"", mode_name(mode)));
        }
    }
}

//! The `{"type": "state", ...}` stream message written by hand into a reused buffer.
//!
//! A real-time session with a viewer sends 20 state messages a second, and serde's generic path
//! (a `Serializer` call per field, a new buffer per message) cost about as much as the 12 IPO
//! cycles behind each one. This writer produces the same bytes as serde_json does for
//! `StreamMessage::State` (tested byte for byte, on running programs and on every optional
//! part): the same key order, floats through `zmij` as serde_json formats them (`null` when not
//! finite), integers through `itoa`, strings escaped as serde_json escapes them.

use axum::extract::ws::Utf8Bytes;
use nctwin_engine::channel::ReferencePhase;
use nctwin_engine::{Mode, Snapshot, Status};

/// Room for a whole state message of a 7-axis machine, so the buffer is allocated once.
const BUFFER_CAPACITY: usize = 2048;

/// Encodes state messages into one reused buffer; each message is then copied out once into
/// its own shared bytes (one allocation of the exact size).
#[derive(Debug, Default)]
pub struct StateEncoder {
    buf: Vec<u8>,
}

impl StateEncoder {
    /// The state message of `s` as JSON text.
    pub fn encode(&mut self, s: &Snapshot) -> Utf8Bytes {
        self.buf.clear();
        self.buf.reserve(BUFFER_CAPACITY);
        write_state(&mut self.buf, s);
        // Only `str` pieces and ASCII are written, so the buffer is UTF-8.
        match std::str::from_utf8(&self.buf) {
            Ok(text) => Utf8Bytes::from(text.to_owned()),
            Err(_) => Utf8Bytes::from_static("{}"),
        }
    }
}

/// Appends the state message of `s` to `out`.
pub fn write_state(out: &mut Vec<u8>, s: &Snapshot) {
    out.extend_from_slice(b"{\"type\":\"state\",\"status\":\"");
    out.extend_from_slice(status_name(s.status).as_bytes());
    out.extend_from_slice(b"\",\"mode\":\"");
    out.extend_from_slice(mode_name(s.mode).as_bytes());
    out.extend_from_slice(b"\",\"time\":");
    write_f64(out, s.time);
    out.extend_from_slice(b",\"tick\":");
    write_int(out, s.tick);
    out.extend_from_slice(b",\"positions\":{\"machine\":");
    write_named(out, &s.machine, write_f64);
    out.extend_from_slice(b",\"basic\":");
    write_named(out, &s.basic, write_f64);
    out.extend_from_slice(b",\"workpiece\":");
    write_named(out, &s.workpiece, write_f64);
    out.extend_from_slice(b"},\"orientation\":");
    match s.orientation {
        None => out.extend_from_slice(b"null"),
        Some([x, y, z]) => {
            out.push(b'[');
            write_f64(out, x);
            out.push(b',');
            write_f64(out, y);
            out.push(b',');
            write_f64(out, z);
            out.push(b']');
        }
    }
    out.extend_from_slice(b",\"transformation\":");
    match &s.transformation {
        None => out.extend_from_slice(b"null"),
        Some(t) => {
            out.extend_from_slice(b"{\"name\":");
            write_str(out, &t.name);
            out.extend_from_slice(b",\"type\":");
            write_int(out, t.trafo_type);
            out.extend_from_slice(b",\"index\":");
            write_int(out, t.index);
            out.push(b'}');
        }
    }
    out.extend_from_slice(b",\"block\":");
    match &s.block {
        None => out.extend_from_slice(b"null"),
        Some(b) => {
            out.extend_from_slice(b"{\"line\":");
            write_int(out, b.line);
            out.extend_from_slice(b",\"text\":");
            write_str(out, &b.text);
            out.push(b'}');
        }
    }
    out.extend_from_slice(b",\"alarms\":[");
    for (i, a) in s.alarms.iter().enumerate() {
        if i > 0 {
            out.push(b',');
        }
        out.extend_from_slice(b"{\"number\":");
        write_int(out, a.number);
        out.extend_from_slice(b",\"message\":");
        write_str(out, &a.message);
        out.extend_from_slice(b",\"line\":");
        match a.line {
            None => out.extend_from_slice(b"null"),
            Some(line) => write_int(out, line),
        }
        out.push(b'}');
    }
    out.extend_from_slice(b"],\"tool\":{\"t\":");
    write_int(out, s.tool.0);
    out.extend_from_slice(b",\"d\":");
    write_int(out, s.tool.1);
    out.extend_from_slice(b"},\"path_velocity\":");
    write_f64(out, s.path_velocity);
    out.extend_from_slice(b",\"spindles\":");
    write_named(out, &s.spindles, write_f64);
    out.extend_from_slice(b",\"message\":");
    match &s.message {
        None => out.extend_from_slice(b"null"),
        Some(m) => write_str(out, m),
    }
    out.extend_from_slice(b",\"overrides\":{\"feed\":");
    write_f64(out, s.overrides.feed);
    out.extend_from_slice(b",\"rapid\":");
    write_f64(out, s.overrides.rapid);
    out.extend_from_slice(b",\"spindle\":");
    write_f64(out, s.overrides.spindle);
    out.extend_from_slice(b"},\"single_block\":");
    write_bool(out, s.single_block);
    out.extend_from_slice(b",\"optional_stop\":");
    write_bool(out, s.optional_stop);
    out.extend_from_slice(b",\"gcodes\":[");
    for (i, g) in s.gcodes.iter().enumerate() {
        if i > 0 {
            out.push(b',');
        }
        write_str(out, g);
    }
    out.extend_from_slice(b"],\"referenced\":");
    write_named(out, &s.referenced, write_bool);
    out.extend_from_slice(b",\"repos_pending\":");
    write_bool(out, s.repos_pending);
    if let Some((axis, phase)) = &s.referencing {
        out.extend_from_slice(b",\"referencing\":{\"axis\":");
        write_str(out, axis);
        out.extend_from_slice(b",\"phase\":");
        write_str(out, phase_name(*phase));
        out.push(b'}');
    }
    out.push(b'}');
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
fn write_named<T: Copy>(out: &mut Vec<u8>, list: &[(String, T)], value: fn(&mut Vec<u8>, T)) {
    out.push(b'{');
    for (i, (name, v)) in list.iter().enumerate() {
        if i > 0 {
            out.push(b',');
        }
        write_str(out, name);
        out.push(b':');
        value(out, *v);
    }
    out.push(b'}');
}

/// A float as serde_json writes it: the shortest text that reads back the same (`zmij`, as serde_json 1.0.15x), `null`
/// for NaN and infinities.
fn write_f64(out: &mut Vec<u8>, v: f64) {
    if v.is_finite() {
        out.extend_from_slice(zmij::Buffer::new().format_finite(v).as_bytes());
    } else {
        out.extend_from_slice(b"null");
    }
}

fn write_int(out: &mut Vec<u8>, v: impl itoa::Integer) {
    out.extend_from_slice(itoa::Buffer::new().format(v).as_bytes());
}

fn write_bool(out: &mut Vec<u8>, v: bool) {
    out.extend_from_slice(if v { b"true" } else { b"false" });
}

/// A JSON string, escaped as serde_json escapes: `"` and `\`, the short forms `\b \t \n \f
/// \r`, every other control character as `\u00xx` (lowercase hex).
fn write_str(out: &mut Vec<u8>, s: &str) {
    out.push(b'"');
    let bytes = s.as_bytes();
    let mut start = 0;
    for (i, &b) in bytes.iter().enumerate() {
        let escape: &[u8] = match b {
            b'"' => b"\\\"",
            b'\\' => b"\\\\",
            0x08 => b"\\b",
            b'\t' => b"\\t",
            b'\n' => b"\\n",
            0x0c => b"\\f",
            b'\r' => b"\\r",
            0x00..=0x1f => b"",
            _ => continue,
        };
        out.extend_from_slice(&bytes[start..i]);
        if escape.is_empty() {
            const HEX: &[u8; 16] = b"0123456789abcdef";
            out.extend_from_slice(&[b'\\', b'u', b'0', b'0', HEX[usize::from(b >> 4)], HEX[usize::from(b & 0xf)]]);
        } else {
            out.extend_from_slice(escape);
        }
        start = i + 1;
    }
    out.extend_from_slice(&bytes[start..]);
    out.push(b'"');
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
        s.single_block = true;
        s.optional_stop = true;
        s.repos_pending = true;
        s.block = Some(nctwin_engine::channel::BlockRef { line: 3, text: String::new() });
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

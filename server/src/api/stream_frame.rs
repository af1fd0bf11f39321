//! The encoded state message of a session, shared by all its stream clients.
//!
//! A state message is JSON of about 800 bytes; encoding it cost more than stepping the 12 IPO
//! cycles of a 50 ms frame. So a session watched by a class of 30 viewers encodes it once per
//! published state, and every client sends the same bytes (`Utf8Bytes` is reference counted);
//! and it is written straight from the engine's snapshot by [`StateEncoder`] (the same JSON as
//! the `State` DTO through serde, [`encode_state`]) into a buffer reused from one message to
//! the next, instead of copying every name and text into a DTO first.

use std::sync::{Arc, Mutex};

use axum::extract::ws::Utf8Bytes;
use nctwin_engine::Snapshot;
use serde::ser::{SerializeMap, SerializeStruct};
use serde::{Serialize, Serializer};

pub use super::state_json::StateEncoder;
use crate::dto::{
    AlarmInfo, ChannelStatus, OpMode, OverridesInfo, ReferencingInfo, StreamMessage, Tool, Transformation,
};

/// The last state message of one session, keyed by the snapshot it was made from.
#[derive(Debug, Default)]
pub struct FrameCache {
    /// Held for one look-up or one encoding, never across an await.
    inner: Mutex<Cached>,
}

#[derive(Debug, Default)]
struct Cached {
    /// Keeping the snapshot's `Arc` makes the pointer comparison sound (its address cannot be
    /// reused meanwhile).
    last: Option<(Arc<Snapshot>, Utf8Bytes)>,
    /// Its buffer is reused from one message to the next.
    encoder: StateEncoder,
}

impl FrameCache {
    /// The `{"type": "state", ...}` message of `snapshot`, encoded once per snapshot.
    pub fn state(&self, snapshot: &Arc<Snapshot>) -> Utf8Bytes {
        let mut cached = self.inner.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((last, text)) = cached.last.as_ref()
            && Arc::ptr_eq(last, snapshot)
        {
            return text.clone();
        }
        // Let go of the previous snapshot first, so the actor can refresh it in place again.
        cached.last = None;
        let text = cached.encoder.encode(snapshot);
        cached.last = Some((snapshot.clone(), text.clone()));
        text
    }
}

/// One stream message as JSON text.
pub fn encode(message: &StreamMessage) -> Utf8Bytes {
    // Serializing plain data with string keys cannot fail; an empty object would be harmless.
    Utf8Bytes::from(serde_json::to_string(message).unwrap_or_else(|_| "{}".into()))
}

/// Room for a whole state message, so encoding does not grow the buffer.
const STATE_MESSAGE_CAPACITY: usize = 2048;

/// The `{"type": "state", ...}` message of a snapshot as JSON text, through serde (the
/// reference for [`StateEncoder`], and its fallback nowhere: kept for tests and benches).
pub fn encode_state(snapshot: &Snapshot) -> Utf8Bytes {
    let mut out = Vec::with_capacity(STATE_MESSAGE_CAPACITY);
    if serde_json::to_writer(&mut out, &StateMessage(snapshot)).is_err() {
        return Utf8Bytes::from_static("{}");
    }
    // serde_json writes valid UTF-8.
    Utf8Bytes::try_from(out).unwrap_or_else(|_| Utf8Bytes::from_static("{}"))
}

/// `StreamMessage::State(State::from(snapshot))` as serde sees it (same keys, order and
/// values; tested), borrowing the snapshot's names and texts.
struct StateMessage<'a>(&'a Snapshot);

impl Serialize for StateMessage<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let s = self.0;
        let mut m = serializer.serialize_struct("State", 31)?;
        m.serialize_field("type", "state")?;
        m.serialize_field("status", &ChannelStatus::from(s.status))?;
        m.serialize_field("mode", &OpMode::from(s.mode))?;
        m.serialize_field("time", &s.time)?;
        m.serialize_field("tick", &s.tick)?;
        m.serialize_field("positions", &Positions(s))?;
        m.serialize_field("servo", &Servo(s))?;
        m.serialize_field("orientation", &s.orientation)?;
        m.serialize_field("transformation", &s.transformation.as_ref().map(Transformation::from))?;
        m.serialize_field(
            "block",
            &s.block.as_ref().map(|b| Block { line: b.line, text: &b.text, program: b.program.as_deref() }),
        )?;
        m.serialize_field("alarms", &s.alarms.iter().map(AlarmInfo::from).collect::<Vec<_>>())?;
        let tool = Tool { t: s.tool.0, d: s.tool.1, name: s.tool_name.clone(), prepared: s.prepared_tool };
        m.serialize_field("tool", &tool)?;
        m.serialize_field("path_velocity", &s.path_velocity)?;
        m.serialize_field("program_serial", &s.program_serial)?;
        m.serialize_field("distance_to_go", &s.distance_to_go)?;
        m.serialize_field("programmed_feed", &s.programmed_feed)?;
        m.serialize_field("parts", &crate::dto::Parts::from(s.parts))?;
        m.serialize_field("runtimes", &crate::dto::Runtimes::from(s.runtimes))?;
        m.serialize_field("spindles", &Named(&s.spindles))?;
        m.serialize_field("spindle_info", &super::spindle_dto::SpindleInfos::of(&s.spindle_states))?;
        m.serialize_field("message", &s.message)?;
        let o = s.overrides;
        m.serialize_field("overrides", &OverridesInfo { feed: o.feed, rapid: o.rapid, spindle: o.spindle })?;
        m.serialize_field("single_block", &s.single_block)?;
        m.serialize_field("optional_stop", &s.optional_stop)?;
        m.serialize_field("dry_run", &s.dry_run)?;
        m.serialize_field("skip_levels", &s.skip_levels.levels())?;
        m.serialize_field("gcodes", &s.gcodes)?;
        m.serialize_field("referenced", &Named(&s.referenced))?;
        m.serialize_field("repos_pending", &s.repos_pending)?;
        if let Some((axis, phase)) = &s.referencing {
            let info = ReferencingInfo { axis: axis.clone(), phase: phase.as_str().into() };
            m.serialize_field("referencing", &info)?;
        }
        m.end()
    }
}

/// The `positions` object.
struct Positions<'a>(&'a Snapshot);

impl Serialize for Positions<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut m = serializer.serialize_struct("Positions", 3)?;
        m.serialize_field("machine", &Named(&self.0.machine))?;
        m.serialize_field("basic", &Named(&self.0.basic))?;
        m.serialize_field("workpiece", &Named(&self.0.workpiece))?;
        m.end()
    }
}

/// The `servo` object.
struct Servo<'a>(&'a Snapshot);

impl Serialize for Servo<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut m = serializer.serialize_struct("ServoInfo", 3)?;
        m.serialize_field("setpoint", &Named(&self.0.machine))?;
        m.serialize_field("actual", &Named(&self.0.actual))?;
        m.serialize_field("following_error", &Named(&self.0.following_error))?;
        m.end()
    }
}

/// The `block` object.
#[derive(Serialize)]
struct Block<'a> {
    line: u32,
    text: &'a str,
    program: Option<&'a str>,
}

/// Named values as a JSON object in their given order (as `dto::AxisValues`/`AxisFlags`).
struct Named<'a, T>(&'a [(String, T)]);

impl<T: Serialize> Serialize for Named<'_, T> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (name, value) in self.0 {
            map.serialize_entry(name, value)?;
        }
        map.end()
    }
}

#[cfg(test)]
mod tests {
    use nctwin_engine::Alarm;
    use nctwin_engine::Channel;
    use nctwin_engine::channel::{ReferencePhase, TransformationInfo};
    use serde_json::Value;

    use super::*;
    use crate::dto;

    #[test]
    fn one_snapshot_is_encoded_once_and_its_bytes_are_shared() {
        let mut channel = Channel::from_preset("mill-3axis", "").expect("preset");
        let cache = FrameCache::default();
        let first = Arc::new(channel.snapshot());
        let a = cache.state(&first);
        let b = cache.state(&first);
        assert_eq!(a.as_str().as_ptr(), b.as_str().as_ptr(), "the same bytes, not a second encoding");

        channel.run_program("G1 X10 F600\nM30").expect("program");
        for _ in 0..5 {
            channel.step();
        }
        let next = Arc::new(channel.snapshot());
        let c = cache.state(&next);
        assert_ne!(a.as_str().as_ptr(), c.as_str().as_ptr());
        // The message is the state DTO with its type tag, as the stream has always sent it.
        let json: Value = serde_json::from_str(c.as_str()).expect("JSON");
        assert_eq!(json["type"], "state");
        assert_eq!(json["tick"], 5);
        let expected = serde_json::to_value(dto::State::from(next.as_ref())).expect("state JSON");
        for (key, value) in expected.as_object().expect("an object") {
            assert_eq!(&json[key], value, "field {key}");
        }
    }

    /// The DTO's JSON, the way the stream encoded states before (the reference).
    fn via_dto(snapshot: &Snapshot) -> String {
        serde_json::to_string(&StreamMessage::State(Box::new(dto::State::from(snapshot)))).expect("JSON")
    }

    #[test]
    fn the_state_message_is_byte_for_byte_the_dtos() {
        let mut channel = Channel::from_preset("mill-3axis", "").expect("preset");
        let idle = channel.snapshot();
        assert_eq!(encode_state(&idle).as_str(), via_dto(&idle));

        channel.run_program("G1 X10 Y5 F600\nM30").expect("program");
        for _ in 0..20 {
            channel.step();
        }
        let running = channel.snapshot();
        assert!(running.block.is_some(), "a block is shown while running");
        assert_eq!(encode_state(&running).as_str(), via_dto(&running));

        // Every optional part present, and texts that need escaping.
        let mut full = running.clone();
        full.transformation =
            Some(TransformationInfo { name: "TRANSMIT".into(), trafo_type: 256, index: 1, diameter: None });
        full.alarms = vec![Alarm::syntax(7, "column 3: \"bad\" word")];
        full.spindles = vec![("S1".into(), -1200.5)];
        full.message = Some("tab\tand \"quotes\"".into());
        full.referencing = Some(("Y".into(), ReferencePhase::Marker));
        full.orientation = None;
        full.repos_pending = true;
        if let Some(b) = full.block.as_mut() {
            b.program = Some("HOLE".into());
        }
        let text = encode_state(&full);
        assert_eq!(text.as_str(), via_dto(&full));
        let json: Value = serde_json::from_str(text.as_str()).expect("JSON");
        assert_eq!(json["referencing"]["phase"], "marker");
        assert_eq!(json["alarms"][0]["line"], 7);
    }
}

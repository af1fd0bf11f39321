//! Tool monitoring in the main run (Function Manual Tool Management / W1 "Tool monitoring"):
//! time monitoring counts down `$TC_MOP2` (remaining life in minutes) of the cutting edge in
//! the spindle while it cuts, count monitoring counts down `$TC_MOP4` (remaining pieces).
//!
//! What counts, where the manuals leave it open:
//! * Time: every IPO cycle in which a feed move (G1/G2/G3, not G0) of a program is executing
//!   with a monitored edge active; dwells, tool changes and rapid traverse do not count.
//! * Count: the control counts workpieces, not tool changes. The main run remembers each
//!   cutting edge that is active in the spindle while a program runs; `SETPIECE(n)`
//!   ([`crate::interp::Item::SetPiece`], `interp/tools/setpiece.rs`) lowers `$TC_MOP4` by n
//!   for each remembered count-monitored edge, in the order they were first used, and forgets
//!   all but the edge still in the spindle. The memory outlives program end and reset (as
//!   the control's does until the next `SETPIECE`); it is no part of the checkpoint.
//! * An edge is monitored when its tool has `$TC_TP9` bit 0 (time) or bit 1 (count) and the
//!   edge's remaining value or setpoint (`$TC_MOP11`/`$TC_MOP13`) is set; an edge whose
//!   monitoring data are all zero is left alone.
//! * Reaching the prewarning limit (remaining <= `$TC_MOP1`/`$TC_MOP3`) sets `$TC_TP8` bit 4
//!   and raises 6411; reaching the limit (remaining <= 0) sets bit 2 (disabled) and raises
//!   6413. Both are information only: the program goes on and the tool in the spindle keeps
//!   cutting; a later `T="name"` selects another duplo.
//!
//! The count goes into the tool data (and so into the tool list, `$TC_MOP` reads and the REST
//! list) when a threshold is crossed, when the edge changes and when the program is no longer
//! running; in between [`Channel::monitored_edge`] gives the live value. Without any monitored
//! tool the per-cycle call is one test of a flag.

use crate::alarm::Alarm;
use crate::channel::{Channel, Status};
use crate::machine_data::tools_list::{MONITOR_COUNT, MONITOR_TIME, STATE_DISABLED, STATE_PREWARNING};

/// The counting of the time-monitored edge in the spindle.
#[derive(Debug, Clone, Default)]
pub(in crate::channel) struct ToolMonitor {
    /// The edge whose cutting time is being counted.
    counting: Option<Counting>,
    /// The edge (T, D) the main run had active at the last cycle.
    last_edge: (u32, u32),
    /// The edges active in the spindle since the last `SETPIECE`, in the order first used.
    used: Vec<(u32, u32)>,
}

#[derive(Debug, Clone)]
struct Counting {
    t: u32,
    d: u32,
    /// `$TC_MOP2` when counting started, minutes.
    start: f64,
    /// IPO cycles cut since then (an integer count keeps the sum exact and deterministic).
    cycles: u64,
    /// `$TC_MOP1`, minutes (0: no prewarning).
    prewarning: f64,
    warned: bool,
    limited: bool,
}

impl ToolMonitor {
    /// Notes edge `d` of tool `t` (none: 0) as used since the last `SETPIECE`.
    fn remember(&mut self, t: u32, d: u32) {
        if t != 0 && d != 0 && !self.used.contains(&(t, d)) {
            self.used.push((t, d));
        }
    }
}

impl Channel {
    /// One IPO cycle of tool monitoring (called once per [`Channel::step`]).
    #[inline]
    pub(in crate::channel) fn monitor_tools(&mut self) {
        if self.cfg.tool_list.monitored {
            self.monitor_tools_cycle();
        }
    }

    /// Out of line: the IPO cycle's own code stays small when no tool is monitored.
    #[inline(never)]
    fn monitor_tools_cycle(&mut self) {
        let (t, d) = (self.offsets.t, self.offsets.d);
        let running = self.status == Status::Running && self.jog.is_none();
        if running && (t, d) != self.tool_monitor.last_edge {
            self.tool_monitor.last_edge = (t, d);
            self.tool_monitor.remember(t, d);
        }
        // (Not the cycle at rest after an exact stop: the tool stands.)
        let cutting = running
            && self.in_planner.front().is_some_and(|(_, m)| m.feed.is_finite() && m.line > 0)
            && !self.planner.is_resting();
        if !cutting || t == 0 || d == 0 {
            if !running {
                self.flush_tool_monitor();
            }
            return;
        }
        if self.tool_monitor.counting.as_ref().is_none_or(|c| (c.t, c.d) != (t, d)) {
            self.flush_tool_monitor();
            self.tool_monitor.counting = self.start_counting(t, d);
        }
        let minutes = self.cfg.ipo_cycle / 60.0;
        let Some(c) = self.tool_monitor.counting.as_mut() else { return };
        c.cycles += 1;
        let remaining = c.start - c.cycles as f64 * minutes;
        let warn = !c.warned && c.prewarning > 0.0 && remaining <= c.prewarning;
        let limit = !c.limited && remaining <= 0.0;
        c.warned |= warn;
        c.limited |= limit;
        if warn || limit {
            self.reach(t, d, 2, remaining, warn, limit);
        }
    }

    /// The time-monitored edge being counted and its live remaining life in minutes.
    pub fn monitored_edge(&self) -> Option<(u32, u32, f64)> {
        let c = self.tool_monitor.counting.as_ref()?;
        Some((c.t, c.d, c.start - c.cycles as f64 * self.cfg.ipo_cycle / 60.0))
    }

    /// Writes the counted time into the tool data and stops counting.
    pub(in crate::channel) fn flush_tool_monitor(&mut self) {
        let Some(c) = self.tool_monitor.counting.take() else { return };
        if c.cycles > 0 {
            let remaining = c.start - c.cycles as f64 * self.cfg.ipo_cycle / 60.0;
            self.write_monitor_data(&format!("$TC_MOP2[{},{}]={remaining:.9}\n", c.t, c.d));
        }
    }

    fn start_counting(&self, t: u32, d: u32) -> Option<Counting> {
        let list = &self.cfg.tool_list;
        let tool = list.tools.get(&t)?;
        if tool.monitoring & MONITOR_TIME == 0 {
            return None;
        }
        let mop = |n: u32| list.read(&format!("$TC_MOP{n}"), t, d).and_then(|v| v.as_f64()).unwrap_or(0.0);
        let (start, setpoint) = (mop(2), mop(11));
        if start == 0.0 && setpoint == 0.0 {
            return None;
        }
        Some(Counting {
            t,
            d,
            start,
            cycles: 0,
            prewarning: mop(1),
            warned: tool.state & STATE_PREWARNING != 0,
            limited: tool.state & STATE_DISABLED != 0,
        })
    }

    /// `SETPIECE(pieces)` reached the main run: each count-monitored edge used since the
    /// last one counts `pieces` workpieces; the memory keeps only the edge in the spindle.
    pub(in crate::channel) fn set_piece(&mut self, pieces: u32) {
        let (t, d) = (self.offsets.t, self.offsets.d);
        self.tool_monitor.remember(t, d);
        let used = std::mem::take(&mut self.tool_monitor.used);
        if pieces > 0 {
            for &(t, d) in &used {
                self.count_pieces(t, d, pieces);
            }
        }
        self.tool_monitor.last_edge = (t, d);
        self.tool_monitor.remember(t, d);
    }

    /// Count monitoring: edge `d` of tool `t` cut `pieces` more workpieces.
    fn count_pieces(&mut self, t: u32, d: u32, pieces: u32) {
        let list = &self.cfg.tool_list;
        let Some(tool) = list.tools.get(&t) else { return };
        if tool.monitoring & MONITOR_COUNT == 0 || d == 0 {
            return;
        }
        let mop = |n: u32| list.read(&format!("$TC_MOP{n}"), t, d).and_then(|v| v.as_f64()).unwrap_or(0.0);
        let (remaining, prewarning, setpoint) = (mop(4), mop(3), mop(13));
        if remaining == 0.0 && setpoint == 0.0 {
            return;
        }
        let remaining = remaining - f64::from(pieces);
        let warn = tool.state & STATE_PREWARNING == 0 && prewarning > 0.0 && remaining <= prewarning;
        let limit = tool.state & STATE_DISABLED == 0 && remaining <= 0.0;
        self.write_monitor_data(&format!("$TC_MOP4[{t},{d}]={remaining}\n"));
        if warn || limit {
            self.reach(t, d, 4, remaining, warn, limit);
        }
    }

    /// A threshold was crossed: the remaining value (`$TC_MOP<param>`) and the tool state go
    /// into the tool data, and the alarm is raised.
    fn reach(&mut self, t: u32, d: u32, param: u32, remaining: f64, warn: bool, limit: bool) {
        let Some(tool) = self.cfg.tool_list.tools.get(&t) else { return };
        let name = if tool.name.is_empty() { t.to_string() } else { tool.name.clone() };
        let mut state = tool.state;
        if warn {
            state |= STATE_PREWARNING;
        }
        if limit {
            state |= STATE_DISABLED;
        }
        let value = if param == 2 { format!("{remaining:.9}") } else { format!("{remaining}") };
        self.write_monitor_data(&format!("$TC_MOP{param}[{t},{d}]={value}\n$TC_TP8[{t}]={state}\n"));
        if warn {
            self.notify_alarm(Alarm::tool_prewarning(&name, d));
        }
        if limit {
            self.notify_alarm(Alarm::tool_limit(&name, d));
        }
    }

    /// Writes monitoring results into the tool data and activates them at once (as a
    /// program's `$TC_` write does). The values are the control's own, so they cannot be
    /// refused; should activation fail all the same, the data stay as they were.
    fn write_monitor_data(&mut self, text: &str) {
        let mut data = self.data.clone();
        if data.stage_text(text).is_err() {
            return;
        }
        let mut cfg = (*self.cfg).clone();
        if cfg.refresh_data(&data).is_ok() {
            self.data = data;
            self.cfg = std::sync::Arc::new(cfg);
        }
    }
}

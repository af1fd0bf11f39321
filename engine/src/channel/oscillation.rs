//! Asynchronous oscillation in the main run (`interp/path_control/oscillation.rs` for the
//! words and what is modelled): an oscillating axis is a positioning axis whose target, when
//! it lands, is the other reversal point, after the stop time there. `OS[ax]=0` lets it run on
//! to the reversal point it stops at, then make its spark-out strokes and travel to the end
//! position, as the control bits say; then it stands and the path takes it back.

use super::Channel;
use crate::interp::path_control::oscillation::{Oscillation, ctrl};

/// Where an oscillation is in its course.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Phase {
    /// To the start position (OSB), then to reversal point 1.
    ToStart,
    /// To and fro.
    Running,
    /// `OS=0` read: on to the reversal point it stops at.
    Ending,
    /// Spark-out: the one-way strokes left, the one under way included.
    SparkOut(u32),
    /// Braking where it was (no reversal point, OSCTRL 3) or travelling to the end position.
    Leaving,
}

/// The state of one oscillating axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Swing {
    pub osc: Oscillation,
    phase: Phase,
    /// The reversal point (1, 2) travelled to or stood on; 0 on the way to the start or end.
    toward: u8,
    /// Seconds of the stop time left at the reversal point it stands on.
    pub dwell: f64,
    /// `OS=0` came while it stood at a reversal point: that point is where it stops, and its
    /// stop time there is the one already running.
    stood: bool,
}

impl Swing {
    /// The oscillation `osc` starting; the axis travels to the start position or reversal
    /// point 1 first (the target `Item::Positioning` gives).
    pub fn new(osc: Oscillation) -> Swing {
        let from_start = osc.start.is_some() && osc.control & ctrl::FROM_START != 0;
        let (phase, toward) = if from_start { (Phase::ToStart, 0) } else { (Phase::Running, 1) };
        Swing { osc, phase, toward, dwell: 0.0, stood: false }
    }

    fn point(&self, n: u8) -> f64 {
        if n == 1 { self.osc.point1 } else { self.osc.point2 }
    }

    /// Goes on to the other reversal point: its position.
    fn reverse(&mut self) -> f64 {
        self.toward = if self.toward == 1 { 2 } else { 1 };
        self.point(self.toward)
    }

    /// The axis has landed on its target: the next target (after the stop time at a
    /// reversal point), or `None` when the oscillation is over.
    pub fn arrived(&mut self) -> Option<f64> {
        if self.toward != 0 && !std::mem::take(&mut self.stood) {
            self.dwell = if self.toward == 1 { self.osc.dwell1 } else { self.osc.dwell2 };
        }
        match self.phase {
            Phase::ToStart => {
                self.phase = Phase::Running;
                self.toward = 1;
                Some(self.osc.point1)
            }
            Phase::Running => Some(self.reverse()),
            Phase::Ending => {
                let stop_at = match self.osc.control & ctrl::NO_REVERSAL {
                    ctrl::STOP_AT_1 => 1,
                    ctrl::STOP_AT_2 => 2,
                    _ => self.toward,
                };
                if stop_at != self.toward {
                    return Some(self.reverse());
                }
                let double = if self.osc.control & ctrl::DOUBLE_STROKE != 0 { 2 } else { 1 };
                match self.osc.strokes * double {
                    0 => self.leave(),
                    strokes => {
                        self.phase = Phase::SparkOut(strokes);
                        Some(self.reverse())
                    }
                }
            }
            Phase::SparkOut(left) if left > 1 => {
                self.phase = Phase::SparkOut(left - 1);
                Some(self.reverse())
            }
            Phase::SparkOut(_) => self.leave(),
            Phase::Leaving => None,
        }
    }

    /// After the last stroke: to the end position if OSCTRL 4 asks for it, else done.
    fn leave(&mut self) -> Option<f64> {
        self.phase = Phase::Leaving;
        self.toward = 0;
        match self.osc.end {
            Some(end) if self.osc.control & ctrl::TO_END != 0 => Some(end),
            _ => {
                self.dwell = 0.0;
                None
            }
        }
    }

    /// `OS=0` came while it stands on a reversal point (its stop time running): that point is
    /// the next one, where it stops; landing there again adds no stop time.
    fn stop_where_standing(&mut self) {
        self.toward = if self.toward == 1 { 2 } else { 1 };
        self.stood = true;
    }

    /// `OS=0` reached the main run. Returns true if the axis is to brake where it is (OSCTRL 3
    /// without spark-out strokes); it then leaves from where it stops.
    fn end(&mut self) -> bool {
        match self.phase {
            Phase::ToStart | Phase::Running => {
                let stay = self.osc.control & ctrl::NO_REVERSAL == ctrl::NO_REVERSAL && self.osc.strokes == 0;
                self.phase = if stay { Phase::Leaving } else { Phase::Ending };
                if stay {
                    self.toward = 0;
                }
                stay
            }
            _ => false,
        }
    }
}

impl Channel {
    /// `OS[ax]=1` in the main run: axis `k` starts oscillating towards `first`; again while it
    /// oscillates, the new settings act from its next reversal (the feed at once).
    pub(super) fn start_oscillation(&mut self, k: usize, first: f64, feed: f64, osc: Oscillation) {
        if let Some(t) = self.positioning.axes[k].as_mut()
            && let Some(swing) = t.swing.as_mut()
        {
            swing.osc = osc;
            t.feed = feed.min(self.cfg.axis(k).max_velocity);
            return;
        }
        self.start_positioning(k, first, feed, false);
        if let Some(t) = self.positioning.axes[k].as_mut() {
            t.motion = Some(crate::interp::path_control::positioning::Motion::Oscillate(osc));
            t.swing = Some(Swing::new(osc));
        }
    }

    /// `OS[ax]=0` in the main run (see [`Swing::end`]).
    pub(super) fn end_oscillation(&mut self, k: usize) {
        let Some(t) = self.positioning.axes[k].as_mut() else { return };
        let Some(swing) = t.swing.as_mut() else { return };
        let dwelling = swing.dwell > 0.0;
        if swing.end() {
            self.stop_positioning(k);
        } else if dwelling {
            swing.stop_where_standing();
            t.target = t.position;
        }
    }

    /// The program's end with axes still oscillating: they brake where they are, as at a
    /// reset (no spark-out strokes, no end position).
    pub(super) fn brake_oscillations(&mut self) {
        for k in 0..self.positioning.axes.len() {
            if let Some(t) = self.positioning.axes[k].as_mut()
                && t.swing.take().is_some()
            {
                self.stop_positioning(k);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn osc(control: u32, strokes: u32, end: Option<f64>) -> Oscillation {
        Oscillation { point1: 10.0, point2: 60.0, dwell1: 0.0, dwell2: 0.5, end, start: None, strokes, control }
    }

    /// The targets after each landing, starting on the way to point 1.
    fn course(swing: &mut Swing, end_after: usize) -> Vec<f64> {
        let mut out = Vec::new();
        for i in 0.. {
            if i == end_after {
                swing.end();
            }
            match swing.arrived() {
                Some(t) => out.push(t),
                None => return out,
            }
            assert!(i < 50);
        }
        out
    }

    #[test]
    fn it_reverses_with_the_stop_time_of_each_point_and_stops_at_the_next_one() {
        let mut s = Swing::new(osc(0, 0, None));
        assert_eq!(s.arrived(), Some(60.0), "landed on 1: on to 2");
        assert_eq!(s.dwell, 0.0);
        assert_eq!(s.arrived(), Some(10.0));
        assert_eq!(s.dwell, 0.5, "OST2 at point 2");
        // Ended on the way to 1: it stops at 1.
        let mut s = Swing::new(osc(0, 0, None));
        assert_eq!(course(&mut s, 2), [60.0, 10.0]);
    }

    #[test]
    fn control_bits_choose_the_stop_point_the_strokes_and_the_end_position() {
        // Stop at point 2 (bit 2), ended on the way to 1: on to 2 and stop.
        assert_eq!(course(&mut Swing::new(osc(2, 0, None)), 2), [60.0, 10.0, 60.0]);
        // Two single strokes after stopping at 1, then the end position (bit 4).
        assert_eq!(course(&mut Swing::new(osc(4, 2, Some(70.0))), 2), [60.0, 10.0, 60.0, 10.0, 70.0]);
        // Double strokes (bit 256): one spark-out stroke is there and back.
        assert_eq!(course(&mut Swing::new(osc(256, 1, None)), 2), [60.0, 10.0, 60.0, 10.0]);
        // An end position without bit 4 is not approached.
        assert_eq!(course(&mut Swing::new(osc(0, 0, Some(70.0))), 2), [60.0, 10.0]);
    }

    #[test]
    fn ended_while_standing_at_a_point_it_stops_there_without_a_second_stop_time() {
        // Landed on 2 (OST2 0.5 s running, on to 1 next); OS=0 now: it stops at 2, where it
        // stands, and that landing adds no stop time of its own.
        let mut s = Swing::new(osc(0, 0, None));
        assert_eq!(s.arrived(), Some(60.0));
        assert_eq!(s.arrived(), Some(10.0));
        assert_eq!(s.dwell, 0.5);
        s.end();
        s.stop_where_standing();
        s.dwell = 0.0; // the running stop time over
        assert_eq!(s.arrived(), None, "stops at 2");
        assert_eq!(s.dwell, 0.0);
    }

    #[test]
    fn the_start_position_comes_first_with_bit_512() {
        let mut o = osc(512, 0, None);
        o.start = Some(35.0);
        let mut s = Swing::new(o);
        assert_eq!(s.arrived(), Some(10.0), "from the start position to point 1");
        assert_eq!(s.dwell, 0.0, "no stop time at the start position");
        assert_eq!(s.arrived(), Some(60.0));
    }
}

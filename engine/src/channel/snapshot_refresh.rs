//! Filling a [`Snapshot`] in place: a real-time session publishes its state 20 times a second,
//! and building a new snapshot each time (a dozen names, the G codes and the block text as new
//! strings) cost about as much as the IPO cycles of the frame. Refreshing the previous one
//! reuses its vectors and strings, so while the shape of the state stays the same (the same
//! axes, transformation, G codes) no allocation is made. `Channel::snapshot` is a refresh into
//! an empty snapshot, so both give the same value by construction.

use super::Channel;
use super::snapshot::{BlockRef, GCodesSeen, Snapshot, TransformationInfo};
use crate::kinematics::{AnyTrafo, Transformation};
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::AxisVec;

impl Channel {
    /// Updates `out` to what [`Channel::snapshot`] would return now, reusing its vectors and
    /// strings. `out` must come from `snapshot()` or earlier refreshes (of any channel): its
    /// G code names are rewritten only when the channel's G functions differ from the ones they
    /// were written from.
    pub fn refresh_snapshot(&self, out: &mut Snapshot) {
        refresh(self, out);
    }

    /// The text of program line `line` (without its line end) while that block is current or
    /// in the main run's queue, and the name of the subprogram it is in (`None`: the main
    /// program).
    pub(super) fn block_text(&self, line: u32) -> Option<(&str, Option<&str>)> {
        let block = self
            .current_block
            .as_ref()
            .filter(|b| b.line == line)
            .or_else(|| self.queued_blocks.iter().rev().find(|b| b.line == line))?;
        let program = match &block.level {
            Some(level) => &level.text,
            None => self.program.as_ref()?,
        };
        let raw = program.get(block.offset..)?.split('\n').next().unwrap_or("");
        Some((raw.strip_suffix('\r').unwrap_or(raw), block.level.as_deref().map(|l| l.name())))
    }
}

/// Writes the channel's state into `s` (see [`Channel::refresh_snapshot`]).
pub(super) fn refresh(ch: &Channel, s: &mut Snapshot) {
    let cfg = &ch.cfg;
    let pos = &ch.machine;
    let n = cfg.channel_axes.len().min(MAX_CHANNEL_AXES);
    // A spindle in speed mode shows its own position, not the axis'.
    let value = |k: usize| -> f64 {
        match ch.spindles.iter().find(|s| s.axis == k && !s.axis_mode) {
            Some(s) => s.position,
            None => pos[k],
        }
    };
    let display = |k: usize, v: f64| -> f64 {
        match cfg.axis(k).modulo {
            Some((start, range)) => start + (v - start).rem_euclid(range),
            None => v,
        }
    };
    s.status = ch.status;
    s.mode = ch.mode;
    s.time = ch.time();
    s.tick = ch.tick;

    // MCS and reference state: channel axes in machine axis order.
    // A spindle without axis function is shown only under `spindles`.
    let mut by_machine: [usize; MAX_CHANNEL_AXES] = std::array::from_fn(|k| k);
    let mut shown = 0;
    for k in (0..n).filter(|&k| cfg.shown(k)) {
        by_machine[shown] = k;
        shown += 1;
    }
    let by_machine = &mut by_machine[..shown];
    by_machine.sort_unstable_by_key(|&k| (cfg.channel_axes[k].machine_axis, k));
    fill_named(&mut s.machine, by_machine.iter().map(|&k| (cfg.axis(k).name.as_str(), display(k, value(k)))));
    let error = |k: usize| ch.servo.following_error(k);
    fill_named(&mut s.actual, by_machine.iter().map(|&k| (cfg.axis(k).name.as_str(), display(k, value(k) - error(k)))));
    fill_named(&mut s.following_error, by_machine.iter().map(|&k| (cfg.axis(k).name.as_str(), error(k))));
    fill_named(&mut s.referenced, by_machine.iter().map(|&k| (cfg.axis(k).name.as_str(), ch.referenced[k])));

    // BCS: with a transformation the forward map of the machine position (the tool tip), the
    // geometry axes named by the transformation's assignment; the axes it drives have no BCS
    // value of their own.
    let mut driven = [false; MAX_CHANNEL_AXES];
    let (geo_axes, bcs) = match &ch.trafo {
        Some(t) => {
            // An orientation transformation's rotary axes keep their own value in the BCS, so
            // does the 7th axis of a 7-axis TRAORI (it turns the workpiece).
            let ori = t.trafo.orientation_slots();
            let seventh = match &t.trafo {
                AnyTrafo::Traori(t) => t.seventh_slot(),
                _ => None,
            };
            for k in t.trafo.machine_slots() {
                if !ori.contains(&Some(k))
                    && Some(k) != seventh
                    && let Some(d) = driven.get_mut(k)
                {
                    *d = true;
                }
            }
            // With the tool lengthened by the online offset: the display keeps the tool tip.
            (t.trafo.geo_slots(), ch.space_of_machine())
        }
        None => {
            let mut b: AxisVec = std::array::from_fn(value);
            for (g, k) in cfg.geo_axes.iter().enumerate() {
                if let Some(k) = k {
                    b[*k] -= ch.toff.current[g];
                }
            }
            (cfg.geo_axes, b)
        }
    };
    let mut is_geo = [false; MAX_CHANNEL_AXES];
    for &k in geo_axes.iter().flatten() {
        if let Some(g) = is_geo.get_mut(k) {
            *g = true;
        }
    }
    // Geometry axes first, then the other channel axes the transformation does not drive.
    let mut order = [0usize; MAX_CHANNEL_AXES + 3];
    let mut len = 0;
    for k in geo_axes.iter().flatten().copied().chain((0..n).filter(|&k| !is_geo[k] && !driven[k] && cfg.shown(k))) {
        order[len] = k;
        len += 1;
    }
    let order = &order[..len];
    let name = |k: usize| -> &str {
        match geo_axes.iter().position(|g| *g == Some(k)) {
            Some(g) => &cfg.geo_names[g],
            None => &cfg.channel_axes[k].name,
        }
    };
    // A Cartesian coordinate in a rotary axis' slot is not shown modulo.
    let show = |k: usize, v: f64| if ch.trafo.is_some() && is_geo[k] { v } else { display(k, v) };
    let offsets = &ch.offsets;
    let mut basic_vec = [0.0; MAX_CHANNEL_AXES];
    for (k, b) in basic_vec.iter_mut().enumerate().take(n) {
        *b = bcs[k] - offsets.tool[k];
    }
    fill_named(&mut s.basic, order.iter().map(|&k| (name(k), show(k, basic_vec[k]))));
    let wcs = offsets.frame.unapply(&geo_axes, &basic_vec).unwrap_or(basic_vec);
    // Diameter programming (G group 29): the transverse axis shows the diameter in the WCS.
    // Other axes with axis-specific diameter programming (DIAMONA[ax]) show diameters too.
    let diameter_axis = cfg.transverse_axis.filter(|_| ch.trafo.is_none() && ch.offsets.gcodes.diameter_display());
    let others = if ch.trafo.is_none() { offsets.diameter_axes } else { 0 };
    let wcs_value = |k: usize| if Some(k) == diameter_axis || others & 1 << k != 0 { 2.0 * wcs[k] } else { wcs[k] };
    fill_named(&mut s.workpiece, order.iter().map(|&k| (name(k), show(k, wcs_value(k)))));

    // The tool direction in the WCS: through the orientation transformation when one is
    // active, else the fixed +Z of a milling head (when the channel has three geometry axes).
    s.orientation = match ch.trafo.as_ref().and_then(|t| t.trafo.orientation(pos)) {
        Some(o) => Some(offsets.frame.unrotate_direction(o)),
        None => geo_axes[2].map(|_| [0.0, 0.0, 1.0]).filter(|_| geo_axes.iter().all(Option::is_some)),
    };
    match &ch.trafo {
        None => s.transformation = None,
        Some(t) => {
            let info = s.transformation.get_or_insert_with(|| TransformationInfo {
                name: String::new(),
                trafo_type: 0,
                index: 0,
                diameter: None,
            });
            set_text(&mut info.name, t.trafo.name());
            info.trafo_type = t.trafo.trafo_type();
            info.index = t.number as u32;
            info.diameter = match &t.trafo {
                AnyTrafo::Tracyl(c) => Some(c.diameter()),
                _ => None,
            };
        }
    }
    match ch.current_line.and_then(|line| Some((line, ch.block_text(line)?))) {
        None => s.block = None,
        Some((line, (text, program))) => {
            let block = s.block.get_or_insert_with(|| BlockRef { line, text: String::new(), program: None });
            block.line = line;
            set_text(&mut block.text, text);
            match program {
                None => block.program = None,
                Some(name) => set_text(block.program.get_or_insert_with(String::new), name),
            }
        }
    }
    // Alarms are few and rarely change: compare first, so the texts are not copied per frame.
    if s.alarms != ch.alarms {
        s.alarms.clone_from(&ch.alarms);
    }
    s.tool = ch.interp.tool_in_main_run(&ch.offsets);
    s.prepared_tool = ch.offsets.prepared;
    set_text(&mut s.tool_name, cfg.tool_list.tools.get(&s.tool.0).map_or("", |e| e.name.as_str()));
    s.path_velocity = ch.planner.velocity() * 60.0;
    fill_named(&mut s.spindles, ch.spindles.iter().map(|sp| (cfg.spindle_name(sp.axis), sp.speed)));
    let at_feed = ch.in_planner.front().is_some_and(|(_, m)| m.feed.is_finite());
    let cutting = at_feed && ch.stock_removing() && ch.planner.velocity() > 0.0;
    fill_named(
        &mut s.spindle_states,
        ch.spindles.iter().map(|sp| {
            let number = cfg.axis(sp.axis).spindle.unwrap_or(0);
            let master = Some(sp.axis) == ch.master_spindle;
            let mut state = sp.state(number, master, pos[sp.axis]);
            state.cutting = master && state.speed != 0.0 && cutting;
            (cfg.spindle_name(sp.axis), state)
        }),
    );
    match &ch.message {
        None => s.message = None,
        Some(m) => set_text(s.message.get_or_insert_with(String::new), m),
    }
    s.overrides = ch.overrides;
    s.single_block = ch.single_block;
    s.program_serial = ch.program_serial;
    let to_go = ch.planner.block_to_go().filter(|_| ch.jog.is_none());
    s.distance_to_go = to_go.map_or(0.0, |(d, _)| d);
    s.programmed_feed = to_go.and_then(|(_, f)| f.is_finite().then_some(f * 60.0));
    s.preprocessing_stop_wait = ch.stands_at_preprocessing_stop();
    s.parts = ch.part_counts();
    s.runtimes = ch.runtimes();
    s.optional_stop = ch.optional_stop;
    s.dry_run = ch.dry_run;
    s.skip_levels = ch.skip_levels;
    let gcodes = ch.offsets.gcodes;
    if s.gcodes_seen.0 != Some(gcodes) {
        gcodes.write_names(&mut s.gcodes);
        s.gcodes_seen = GCodesSeen(Some(gcodes));
    }
    match ch.referencing() {
        None => s.referencing = None,
        // Only while an axis is being referenced (JOG REF), so the name's copy does not matter.
        Some(now) => match &mut s.referencing {
            Some((axis, phase)) => {
                set_text(axis, &now.0);
                *phase = now.1;
            }
            none => *none = Some(now),
        },
    }
    s.jog_serial = ch.jog_serial;
    s.repos_pending = ch.repos_pending();
    ch.sync.refresh_list(&mut s.sync_actions);
    ch.refresh_positioning(&mut s.positioning);
    s.stock = ch.stock_summary();
}

/// Sets `to` to `text`, keeping its buffer.
fn set_text(to: &mut String, text: &str) {
    if to != text {
        to.clear();
        to.push_str(text);
    }
}

/// Makes `list` the named values of `items`, in their order, reusing its entries' names.
fn fill_named<'a, T: Copy>(list: &mut Vec<(String, T)>, items: impl Iterator<Item = (&'a str, T)>) {
    let mut len = 0;
    for (name, value) in items {
        match list.get_mut(len) {
            Some((old, v)) => {
                set_text(old, name);
                *v = value;
            }
            None => list.push((name.to_string(), value)),
        }
        len += 1;
    }
    list.truncate(len);
}

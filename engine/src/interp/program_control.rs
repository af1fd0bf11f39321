//! Operate's program control that acts in block preparation: skip blocks (SKP, levels `/0`..`/9`)
//! and dry-run feed (DRY).
//!
//! - SKP (Programming Manual Fundamentals, "Skipping blocks"): a block marked `/` (= `/0`) or
//!   `/1`..`/9` whose level is active is not executed at all, statements included; the
//!   program goes on with the next block. The level is read when the block is prepared: a
//!   change reaches only blocks not yet prepared (as on the control, where the interface
//!   signal must be set before the block is decoded; a STOPRE before the blocks makes it
//!   certain).
//! - DRY (Function Manual K1, SD42100 `$SC_DRY_RUN_FEED`, SD42101 `$SC_DRY_RUN_FEED_MODE`): the
//!   path feed of G1/G2/G3/CIP/CT.. blocks becomes the dry-run feed, combined with the
//!   programmed one by the mode; G0 keeps rapid traverse. Prepared blocks keep the feed they
//!   were prepared with; the feed override still applies in the main run.

use super::Interpreter;
use crate::lang::Block;

impl Interpreter {
    /// Takes over SKP and DRY for the blocks prepared from now on.
    pub fn set_program_control(&mut self, control: ProgramControl) {
        self.env.dry_run = control.dry_run.is_some();
        self.program_control = control;
    }
}

/// The set of active skip levels: bit `n` for `/n`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SkipLevels(u16);

impl SkipLevels {
    /// The highest level: `/0`..`/9` (ten levels, DB21 DBX2.0..DBX3.1).
    pub const MAX_LEVEL: u8 = 9;

    /// The levels in `levels`; `Err` names the first outside 0..=9.
    pub fn from_levels(levels: &[u8]) -> Result<SkipLevels, u8> {
        let mut mask = 0u16;
        for &level in levels {
            if level > Self::MAX_LEVEL {
                return Err(level);
            }
            mask |= 1 << level;
        }
        Ok(SkipLevels(mask))
    }

    /// The active levels, ascending.
    pub fn levels(self) -> Vec<u8> {
        (0..=Self::MAX_LEVEL).filter(|&l| self.is_active(l)).collect()
    }

    pub fn is_active(self, level: u8) -> bool {
        level <= Self::MAX_LEVEL && self.0 & (1 << level) != 0
    }

    pub fn is_empty(self) -> bool {
        self.0 == 0
    }
}

/// How SD42101 `$SC_DRY_RUN_FEED_MODE` combines the dry-run feed with the programmed feed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DryRunMode {
    /// 0: the larger of the two.
    Max,
    /// 1: the smaller of the two.
    Min,
    /// 2: the dry-run feed whatever is programmed.
    Direct,
}

/// SD42100/SD42101 as block preparation uses them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DryRunFeed {
    /// SD42100 (mm/min).
    pub feed: f64,
    pub mode: DryRunMode,
    /// Modes 10/11/12: thread cutting and tapping keep their programmed feed. (NCTwin's
    /// threads always do: their feed is the spindle's, see [`DryRunFeed::path_feed`].)
    pub except_threads: bool,
}

impl DryRunFeed {
    /// From the setting data's values; a mode the manual does not list (3..9) acts as 0.
    pub fn from_settings(feed: f64, mode: i64) -> DryRunFeed {
        let kind = match mode % 10 {
            1 => DryRunMode::Min,
            2 => DryRunMode::Direct,
            _ => DryRunMode::Max,
        };
        DryRunFeed { feed, mode: kind, except_threads: mode >= 10 }
    }

    /// The path feed (mm/min) replacing `programmed` (mm/min, already converted from G95/G96
    /// or inch). Threads (G33/G34/G35/G331/G332) never come here: their feed follows the
    /// spindle, which dry run does not move faster (modes 0..2 would run them at the dry-run
    /// feed on the control; NCTwin keeps them coupled, as modes 10..12 do).
    pub fn path_feed(&self, programmed: f64) -> f64 {
        match self.mode {
            DryRunMode::Max => programmed.max(self.feed),
            DryRunMode::Min => programmed.min(self.feed),
            DryRunMode::Direct => self.feed,
        }
    }
}

/// The program-control options that act on block preparation, handed over by the channel.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ProgramControl {
    /// DRY on: the setting data that shape the feed; `None` with DRY off.
    pub dry_run: Option<DryRunFeed>,
    pub skip_levels: SkipLevels,
}

impl ProgramControl {
    /// Whether `block` is skipped: it carries a skip mark whose level is active.
    pub fn skips(&self, block: &Block) -> bool {
        block.skip.is_some_and(|level| self.skip_levels.is_active(level))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_outside_zero_to_nine_are_named() {
        assert_eq!(SkipLevels::from_levels(&[0, 3, 10]), Err(10));
        let levels = SkipLevels::from_levels(&[9, 0, 3]).unwrap();
        assert_eq!(levels.levels(), vec![0, 3, 9]);
        assert!(!levels.is_active(1) && !levels.is_active(12));
    }

    #[test]
    fn modes_combine_as_sd42101_says() {
        // SD42100 = 5000 mm/min against a programmed F100 and F8000.
        let dry = |mode| DryRunFeed::from_settings(5000.0, mode);
        assert_eq!((dry(0).path_feed(100.0), dry(0).path_feed(8000.0)), (5000.0, 8000.0));
        assert_eq!((dry(1).path_feed(100.0), dry(1).path_feed(8000.0)), (100.0, 5000.0));
        assert_eq!((dry(2).path_feed(100.0), dry(2).path_feed(8000.0)), (5000.0, 5000.0));
        assert_eq!(dry(12).mode, DryRunMode::Direct);
        assert!(dry(11).except_threads && !dry(1).except_threads);
    }
}

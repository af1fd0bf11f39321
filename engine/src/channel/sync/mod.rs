//! Motion-synchronous actions in the main run, one job per file: the active actions and
//! their data (`actions.rs`), what a condition reads and an action does in an IPO cycle
//! (`eval.rs`), which actions a cycle looks at (`schedule.rs`), how long a condition provably
//! sleeps (`horizon.rs`), and actions whose stores are computed only when read (`lazy.rs`).

pub mod actions;
mod eval;
mod horizon;
mod lazy;
mod schedule;

pub use actions::{INPUT_LOG, InputRecord, MAX_ACTIVE, SyncActionInfo, SyncActions};

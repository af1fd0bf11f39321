//! NCTwin engine: a pure, deterministic model of one SINUMERIK 840D sl-style NC channel.
//!
//! The caller steps a [`Channel`] one interpolation (IPO) cycle at a time; the same inputs give
//! the same outputs bit for bit. No I/O, no clocks, no threads, no randomness.
//!
//! Pipeline, one module per stage:
//! - [`machine_data`]: NC data text → validated, typed [`MachineConfig`].
//! - [`lang`]: program text → blocks of words with source lines (syntax only).
//! - [`check`]: the check before Cycle start: syntax and, statically, the names a run refuses.
//! - [`interp`]: block preparation: modal state, offsets, arc geometry → [`motion::Move`]s and
//!   channel actions.
//! - [`kinematics`]: TRANSMIT, TRACYL, TRAANG: BCS ↔ machine axes, poles, working areas.
//! - [`motion`]: look-ahead planning and IPO-cycle interpolation within every axis' limits.
//! - [`channel`]: modes, program control, JOG, MDA, alarms, and the [`Snapshot`] of the state.
//! - [`programs`]: program names, directories and archive files; the store calls are resolved in.
//! - [`stock`]: material removal: the blank cut by the simulated motion (Z-dexels, turned profile).

pub mod alarm;
pub mod channel;
pub mod check;
pub mod interp;
pub mod kinematics;
pub mod lang;
pub mod machine_data;
pub mod motion;
pub mod programs;
pub mod stock;

pub use alarm::Alarm;
pub use channel::{
    Channel, CommandError, Event, JogRequest, Mode, Overrides, Snapshot, SpindleMode, SpindleState, Status,
};
pub use machine_data::{MachineConfig, MachineData, MdError};

//! Continuous-path smoothing in the main run's feed: corner rounding (G641..G645,
//! `blending.rs`, under a transformation `blending_trafo.rs`), the compressor under a
//! transformation (`compress_trafo.rs`) and ORISON's orientation smoothing (`orison.rs`).
//! The geometry itself is made in `motion::blend*`, `motion::compress*` and `motion::orison`.

mod blending;
mod blending_trafo;
mod compress_trafo;
mod orison;

pub(super) use blending::Blending;

//! The server's integration tests, one module per concern, linked into one test binary (a
//! binary per file linked the server and its dependencies 43 times over, each some 190 MB).
//! Run one concern with `cargo test -p nctwin-server --test integration stream::`.

// Helpers shared by several concerns.
mod common;
mod pg;
mod process;
#[path = "../../engine/tests/stl_support/mod.rs"]
mod stl_support;

mod active_program;
mod api;
mod auth;
mod binary;
mod class_view;
mod cross_site;
mod deep_expressions;
mod durability;
mod executed_path;
mod expiry;
mod frames;
mod hmi_views;
mod kinematic_chains;
mod lifecycle;
mod limits;
mod machine_data_programs;
mod manual;
mod manual_modes;
mod parts;
mod persistence;
mod preview;
mod probe;
mod program_archives;
mod program_check_3d;
mod program_check_names;
mod program_dirs;
mod program_files;
mod program_io;
mod programs;
mod replies;
mod search_subprograms;
mod session_ids;
mod set_wo;
mod simulate;
mod simulate_stock;
mod stock;
mod stock_stream;
mod stop_unlimited;
mod storage;
mod stream;
mod stream_abuse;
mod swivel_display;
mod synchronized_actions;
mod tools;

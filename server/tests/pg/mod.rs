//! The test PostgreSQL server of `scripts/test.sh` (`NCTWIN_TEST_POSTGRES_URL`): a new, empty
//! database per test case.

use std::sync::atomic::{AtomicUsize, Ordering};

pub const POSTGRES_URL_VAR: &str = "NCTWIN_TEST_POSTGRES_URL";

/// A URL of a new, empty database on the test PostgreSQL server, or `None` (with a note) when
/// there is none. Blocks.
pub fn postgres_database(test: &str) -> Option<String> {
    let Ok(base) = std::env::var(POSTGRES_URL_VAR) else {
        eprintln!("note: {POSTGRES_URL_VAR} is not set: PostgreSQL part of `{test}` skipped (scripts/test.sh sets it)");
        return None;
    };
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let name = format!("nctwin_{}_{}_{test}", std::process::id(), NEXT.fetch_add(1, Ordering::Relaxed));
    let mut admin = postgres::Client::connect(&base, postgres::NoTls).expect("connect to the test PostgreSQL");
    admin.batch_execute(&format!("CREATE DATABASE {name}")).expect("create a test database");
    let separator = if base.contains('?') { '&' } else { '?' };
    Some(format!("{base}{separator}dbname={name}"))
}

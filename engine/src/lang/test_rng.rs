//! A tiny deterministic random source for the randomised unit tests (the scanners, the parser,
//! plain arithmetic): the same inputs on every run, so a failure names an input that fails again.

/// Marsaglia's xorshift64 from `seed` (not zero).
pub(crate) fn xorshift(mut seed: u64) -> impl FnMut() -> u64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    }
}

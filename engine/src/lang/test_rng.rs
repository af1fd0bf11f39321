//! A tiny deterministic random source for the randomised unit tests of the scanners: the same
//! lines on every run, so a failure names a line that fails again.

/// Marsaglia's xorshift64 from `seed` (not zero).
pub(super) fn xorshift(mut seed: u64) -> impl FnMut() -> u64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    }
}

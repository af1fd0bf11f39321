//! A fixed hash for variable names: FNV-1a over the name's bytes.
//!
//! Every statement of a cycle reads and writes its variables by name, and a lookup in a
//! B-tree compares the name with a dozen others byte by byte. A hash map finds it with one
//! short hash and (usually) one comparison. The hash is fixed, not seeded at random, so the
//! engine stays deterministic; nothing iterates these maps, so their order reaches no output.

use std::hash::{BuildHasherDefault, Hasher};

/// FNV-1a, 64 bit: a few instructions per byte for the short names of NC programs.
#[derive(Debug, Clone, Copy)]
pub struct NameHasher(u64);

impl Default for NameHasher {
    fn default() -> Self {
        NameHasher(0xcbf2_9ce4_8422_2325)
    }
}

impl Hasher for NameHasher {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// A map keyed by variable name with [`NameHasher`].
pub type NameMap<V> = std::collections::HashMap<String, V, BuildHasherDefault<NameHasher>>;

#[cfg(test)]
mod tests {
    use super::*;
    use std::hash::Hash;

    fn hash(name: &str) -> u64 {
        let mut h = NameHasher::default();
        name.hash(&mut h);
        h.finish()
    }

    #[test]
    fn the_hash_is_fixed_and_tells_names_apart() {
        // FNV-1a of the empty input is its offset basis; `str::hash` adds a 0xff byte.
        let mut h = NameHasher::default();
        h.write(&[]);
        assert_eq!(h.finish(), 0xcbf2_9ce4_8422_2325);
        assert_eq!(hash("_DEPTH"), hash("_DEPTH"));
        assert_ne!(hash("_DEPTH"), hash("_DEPTF"));
    }
}

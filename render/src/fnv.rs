//! A stable 64-bit hash for names on disk and content checks (reference-cache keys, an
//! environment map's identity). It sits at the bottom of the crate's layers: anything may
//! hash with it without importing what else uses it.

/// FNV-1a, 64 bit: stable across platforms, Rust versions and runs (std's `DefaultHasher`
/// promises none of that). Not cryptographic; the stored key text guards against collisions.
#[derive(Clone, Copy)]
pub struct Fnv64(u64);

impl Default for Fnv64 {
    fn default() -> Self {
        Fnv64(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv64 {
    pub fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= b as u64;
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    pub fn finish(self) -> u64 {
        self.0
    }

    pub fn of(bytes: &[u8]) -> u64 {
        let mut h = Fnv64::default();
        h.write(bytes);
        h.finish()
    }
}

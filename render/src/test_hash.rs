//! Deterministic noise for the plain-Rust models' unit tests (the denoiser's, the light
//! BVH's) and for the light probe's points: the same numbers on every machine and run, so
//! their thresholds stay measured.

/// A uniform number in [0, 1) per (index, stream): a murmur-style integer hash.
pub fn hash(i: u32, stream: u32) -> f32 {
    let mut h = i.wrapping_mul(0x9E37_79B9) ^ stream.wrapping_mul(0x85EB_CA6B);
    h ^= h >> 16;
    h = h.wrapping_mul(0x7FEB_352D);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846C_A68B);
    h ^= h >> 16;
    (h >> 8) as f32 / (1u32 << 24) as f32
}

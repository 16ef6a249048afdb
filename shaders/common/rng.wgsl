// Per-pixel random numbers: a PCG hash chain (Jarzynski & Olano 2020).
#include "common/frame_bindings.wgsl"

fn pcg_hash(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A stream per (pixel, frame, seed, purpose) so passes never share random numbers.
fn rng_seed(pixel: vec2<u32>, stream: u32) -> u32 {
    let p = pcg_hash(pixel.x + pcg_hash(pixel.y + pcg_hash(frame.seed)));
    return pcg_hash(p ^ pcg_hash(frame.frame_index * STREAM_COUNT + stream));
}

// Uniform in [0, 1): 24 random mantissa bits, never 1.0.
fn rand_f32(state: ptr<function, u32>) -> f32 {
    *state = pcg_hash(*state);
    return f32(*state >> 8u) * (1.0 / 16777216.0);
}

fn rand_vec2(state: ptr<function, u32>) -> vec2<f32> {
    let a = rand_f32(state);
    let b = rand_f32(state);
    return vec2<f32>(a, b);
}

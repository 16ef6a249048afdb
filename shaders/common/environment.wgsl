// The environment as a light (docs/src/environment.md, "Convention"): equirectangular, +Y up,
// row 0 = zenith, the image centre looking along +X. Directions are drawn in proportion
// to luminance × solid angle: a row from the marginal alias table, a column from that
// row's conditional table, then uniform in φ and cos θ inside the texel. Every function
// is mirrored in render/src/environment/ (mod.rs, distribution.rs) and tested there.
// A sample is stored as its image coordinate uv; it has no position and no Jacobian.
#include "common/scene_bindings.wgsl"
#include "common/math.wgsl"

fn env_local_to_world(d: vec3<f32>) -> vec3<f32> {
    let c = env.rotation.x;
    let s = env.rotation.y;
    return vec3<f32>(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}

fn env_direction_to_uv(d: vec3<f32>) -> vec2<f32> {
    let c = env.rotation.x;
    let s = env.rotation.y;
    let local = vec3<f32>(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
    let u = 0.5 + atan2(local.z, local.x) / (2.0 * PI);
    let v = acos(clamp(local.y, -1.0, 1.0)) / PI;
    return vec2<f32>(u, v);
}

fn env_uv_to_direction(uv: vec2<f32>) -> vec3<f32> {
    let phi = 2.0 * PI * (uv.x - 0.5);
    let theta = PI * uv.y;
    let local = vec3<f32>(sin(theta) * cos(phi), cos(theta), sin(theta) * sin(phi));
    return env_local_to_world(local);
}

fn env_texel(uv: vec2<f32>) -> vec2<u32> {
    let t = vec2<u32>(max(uv * vec2<f32>(env.size), vec2<f32>(0.0)));
    return min(t, env.size - 1u);
}

// Radiance arriving from uv (nearest texel: piecewise constant like the distribution).
fn env_radiance_at(uv: vec2<f32>) -> vec3<f32> {
    return textureLoad(env_radiance, vec2<i32>(env_texel(uv)), 0).rgb * env.strength;
}

// What a camera ray that leaves the scene sees.
fn env_background(dir: vec3<f32>) -> vec3<f32> {
    return env_radiance_at(env_direction_to_uv(dir));
}

// Density of env_sample_uv's directions at uv, per steradian.
fn env_pdf(uv: vec2<f32>) -> f32 {
    let t = env_texel(uv);
    return env_table[t.y * env.size.x + t.x].pdf;
}

// Alias pick among the n entries starting at `base` (the same as lights.wgsl).
fn env_alias_pick(base: u32, n: u32, u: vec2<f32>) -> u32 {
    let slot = min(u32(u.x * f32(n)), n - 1u);
    let e = env_table[base + slot];
    return select(e.alias_index, slot, u.y < e.alias_threshold);
}

fn env_sample_uv(u_row: vec2<f32>, u_col: vec2<f32>, u_texel: vec2<f32>) -> vec2<f32> {
    let w = env.size.x;
    let h = env.size.y;
    let row = env_alias_pick(w * h, h, u_row);
    let col = env_alias_pick(row * w, w, u_col);
    let cos0 = cos(PI * f32(row) / f32(h));
    let cos1 = cos(PI * f32(row + 1u) / f32(h));
    let cos_theta = cos0 - u_texel.y * (cos0 - cos1);
    return vec2<f32>((f32(col) + u_texel.x) / f32(w), acos(clamp(cos_theta, -1.0, 1.0)) / PI);
}

// Light tiles (docs/src/ris.md, "Light tiles"): draw LIGHT_TILE_COUNT × LIGHT_TILE_SIZE lights from
// the power alias table once per frame, each packed with its point, radiance and source pdf. The
// initial pass then picks candidates uniformly from one tile per pixel block: still samples of
// p_src (the tile entries are i.i.d. draws from it), but read from a few KB that a whole block
// shares instead of from the full light table.
#include "common/frame_bindings.wgsl"
#include "common/lights.wgsl"

@group(2) @binding(0) var<storage, read_write> light_tiles: array<PresampledLight>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= LIGHT_TILE_COUNT * LIGHT_TILE_SIZE || frame.light_count == 0u {
        return;
    }
    // A stream of its own: the "pixel" (i, 0xffffffff) lies outside every image.
    var rng = rng_seed(vec2<u32>(i, 0xffffffffu), STREAM_LIGHT_TILES);
    let y = sample_light(&rng);
    let lp = light_point(y.light, y.uv);
    // An exact draw: its contribution weight is 1 / its density.
    light_tiles[i] = pack_presampled_light(y, lp, select(0.0, 1.0 / lp.source_pdf, lp.source_pdf > 0.0));
}

// ReGIR's fill (docs/src/light-samplers.md, "ReGIR"): every slot of every cell draws
// regir_build_samples lights from the power table and keeps one by streaming RIS toward
// the cell's target, with its contribution weight W = w_sum / (M p̂_cell(y)).
#include "common/frame_bindings.wgsl"
#include "common/regir.wgsl"

@group(2) @binding(0) var<storage, read_write> regir_slots: array<PresampledLight>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    let cells = params.regir_grid * params.regir_grid * params.regir_grid;
    if i >= cells * params.regir_slots || frame.light_count == 0u {
        return;
    }
    let centre = regir_cell_centre(i / params.regir_slots);
    let reach = regir_reach();
    // The light presampling stream, at "pixels" (i, 0xfffffffe) outside every image (the
    // tiles use row 0xffffffff, and never run in the same frame).
    var rng = rng_seed(vec2<u32>(i, 0xfffffffeu), STREAM_LIGHT_TILES);
    var w_sum = 0.0;
    var chosen = LightSampleId(NO_LIGHT, vec2<f32>(0.0));
    var chosen_point: LightPoint;
    var chosen_target = 0.0;
    for (var s = 0u; s < params.regir_build_samples; s++) {
        let y = sample_light(&rng);
        let lp = light_point(y.light, y.uv);
        let t = regir_cell_target(centre, reach, lp);
        let w = t / lp.source_pdf;
        if !(w > 0.0) || !is_finite_f32(w) {
            continue;
        }
        w_sum += w;
        if rand_f32(&rng) * w_sum < w {
            chosen = y;
            chosen_point = lp;
            chosen_target = t;
        }
    }
    // The slot keeps the point's power-table density (what the balance heuristic uses
    // for it) and its contribution weight; an empty slot has W = 0.
    var weight = 0.0;
    if chosen_target > 0.0 {
        weight = w_sum / (f32(params.regir_build_samples) * chosen_target);
    }
    regir_slots[i] = pack_presampled_light(chosen, chosen_point, weight);
}

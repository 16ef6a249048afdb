// ReGIR's fill (docs/src/light-samplers.md, "ReGIR"): every slot of every cell draws
// regir_build_samples lights and keeps one by streaming RIS toward the cell's target, with
// its contribution weight W = w_sum / (M p̂_cell(y)), w = p̂_cell / p_build. The build
// samples come from the power table or, with REGIR_FROM_BVH (`regir_build_from_bvh`), from
// the light BVH walked at the cell's centre: then a cell's samples find its near lights
// even among a million (the hybrid, "ReGIR fed by the tree"). Either density is exact, so
// W stays an unbiased estimate of 1 / p_slot.
#include "common/frame_bindings.wgsl"
#include "common/regir.wgsl"

@group(2) @binding(0) var<storage, read_write> regir_slots: array<PresampledLight>;
// The light BVH (placeholders unless REGIR_FROM_BVH is compiled).
@group(2) @binding(1) var<storage, read> light_bvh_nodes: array<LightBvhNode>;
@group(2) @binding(2) var<storage, read> light_bvh_trails: array<LightBvhTrail>;

#ifdef REGIR_FROM_BVH
#include "common/light_bvh.wgsl"
#endif

// One build sample for the cell at `centre` and its density: a light point keeps the power
// table's (what the slot stores, for the balance heuristic of the pass that reads it), and
// `build_pdf` is the density it was drawn with.
struct BuildSample {
    id: LightSampleId,
    point: LightPoint,
    build_pdf: f32,
}

fn build_sample(centre: vec3<f32>, rng: ptr<function, u32>) -> BuildSample {
    let y0 = sample_light(rng);
#ifdef REGIR_FROM_BVH
    // As DI's candidates with the tree: the table picks between the lights with a position
    // (then the tree, walked at the centre with no surface to face, picks which one) and
    // the others (kept). The walk bounds the whole sphere of reach around the centre, so
    // every light some pixel reading the cell can receive keeps a probability (the cell's
    // target is 0 only past that sphere). NO_LIGHT: the tree holds no light with power.
    if light_is_finite(y0.light) {
        let walk = light_bvh_sample(centre, vec3<f32>(0.0), regir_reach(), rand_f32(rng));
        if walk.light == NO_LIGHT {
            var none: BuildSample;
            none.id = LightSampleId(NO_LIGHT, vec2<f32>(0.0));
            none.build_pdf = 0.0;
            return none;
        }
        let y = sample_point_on_light(walk.light, rng);
        let lp = light_point(y.light, y.uv);
#ifdef PLANTED_REGIR_BVH_TABLE_PDF
        return BuildSample(y, lp, lp.source_pdf);
#else
        return BuildSample(y, lp, with_selection_pdf(lp, y.light, frame.finite_light_share * walk.pdf).source_pdf);
#endif
    }
#endif
    let lp = light_point(y0.light, y0.uv);
    return BuildSample(y0, lp, lp.source_pdf);
}

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
        let b = build_sample(centre, &rng);
        if b.id.light == NO_LIGHT {
            continue;
        }
        let t = regir_cell_target(centre, reach, b.point);
        let w = t / b.build_pdf;
        if !(w > 0.0) || !is_finite_f32(w) {
            continue;
        }
        w_sum += w;
        if rand_f32(&rng) * w_sum < w {
            chosen = b.id;
            chosen_point = b.point;
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

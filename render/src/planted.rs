//! Every planted-bug switch in the shaders, in one table: the `#ifdef` a test turns on
//! (`Renderer::plant_for_tests`), the tests that plant it, and what it breaks. Each is an
//! error an estimator test exists to catch; the twin keeps the detector honest
//! (docs/src/mis-and-bias.md, "The planted-error tests"). A test reads every shader and
//! fails on a switch missing here, an entry no shader has, or a named test file that does
//! not plant it; every twin of every pass it changes validates
//! (render/tests/shaders_and_layouts.rs).

/// One switch: its name, the test files that plant it (repository paths; none only where
/// `breaks` says that no GPU test plants it and which model does), what it breaks.
pub struct PlantedSwitch {
    pub name: &'static str,
    pub tests: &'static [&'static str],
    pub breaks: &'static str,
}

const fn switch(
    name: &'static str,
    tests: &'static [&'static str],
    breaks: &'static str,
) -> PlantedSwitch {
    PlantedSwitch {
        name,
        tests,
        breaks,
    }
}

pub const PLANTED: &[PlantedSwitch] = &[
    // Direct light: sampling and reuse.
    switch(
        "PLANTED_SAMPLE_REJECTION",
        &["render/tests/unbiased_reuse.rs"],
        "pairwise MIS rejects on the sample (null, target 0), not only on the G-buffer",
    ),
    switch(
        "PLANTED_DROPPED_ONE_OVER_M",
        &["render/tests/bias_matrix.rs"],
        "a neighbour's confidence share c_i / c_total dropped: the MIS weights no longer sum to one",
    ),
    switch(
        "PLANTED_WINDOW_ON_STORED_TARGETS",
        &["render/tests/transparency.rs"],
        "the temporal ratio window reads the stored targets instead of re-evaluating them",
    ),
    switch(
        "PLANTED_REGIR_WEIGHT_IGNORED",
        &["render/tests/light_samplers.rs"],
        "a ReGIR slot's contribution weight ignored: candidates weighted as exact draws",
    ),
    switch(
        "PLANTED_BVH_PDF_WITHOUT_ORIENTATION",
        &[
            "render/tests/light_samplers.rs",
            "render/tests/bias_matrix.rs",
        ],
        "the light BVH's PDF without its orientation bound: not the density the walk drew from",
    ),
    switch(
        "PLANTED_VERTEX_TABLE_PDF",
        &["render/tests/vertex_light_sampler.rs"],
        "a path vertex (GI, PT, the reference) divides by the power table's PDF after the light BVH drew",
    ),
    switch(
        "PLANTED_REGIR_BVH_TABLE_PDF",
        &["render/tests/light_samplers.rs"],
        "ReGIR's fill weighs a build sample the light BVH drew by the power table's PDF",
    ),
    switch(
        "PLANTED_MCMC_NO_TARGET_RATIO",
        &["render/tests/mcmc_mutation.rs"],
        "the mutation's acceptance without T(y') / T(y): the kernel no longer keeps T invariant",
    ),
    switch(
        "PLANTED_MCMC_PROPOSAL_WITHOUT_AREA",
        &["render/tests/mcmc_mutation.rs"],
        "the independent proposal's density without the triangle's 1/area (the Jacobian)",
    ),
    switch(
        "PLANTED_MCMC_WEIGHT_KEPT",
        &["render/tests/mcmc_mutation.rs"],
        "W left as it was after a mutation moved the sample",
    ),
    switch(
        "TEST_TRACE_SURVIVOR",
        &["render/tests/unbiased_reuse.rs"],
        "not an error: shading traces the ray MIS visibility saves, which must change nothing",
    ),
    // Reference and path tracing.
    switch(
        "PLANTED_NO_BSDF_MIS",
        &["render/tests/multi_bounce.rs"],
        "BSDF-sampled light without its MIS weight against light sampling",
    ),
    switch(
        "PLANTED_LIGHT_SAMPLES_UNWEIGHTED",
        &["render/tests/multi_bounce.rs"],
        "n light samples per reference vertex, each weighed as if it were the only one",
    ),
    switch(
        "PLANTED_NO_THROUGHPUT_PDF",
        &["render/tests/multi_bounce.rs"],
        "the path throughput without the BSDF sample's 1/pdf",
    ),
    switch(
        "PLANTED_BSDF_F_TOWARD_HIT",
        &["render/tests/glass_fresnel.rs"],
        "the BRDF evaluated toward the hit point instead of along the sampled direction",
    ),
    // Indirect light.
    switch(
        "PLANTED_GI_NO_JACOBIAN",
        &[],
        "GI reuse as if the reconnection Jacobian were 1; no GPU test plants it: the CPU model plants the same error (render/src/gi/model/tests.rs)",
    ),
    switch(
        "PLANTED_GI_INVERTED_JACOBIAN",
        &["render/tests/restir_gi.rs"],
        "GI's reconnection Jacobian the wrong way round",
    ),
    switch(
        "PLANTED_GI_NO_TEMPORAL_VISIBILITY",
        &["render/tests/restir_gi.rs"],
        "GI temporal reuse never re-traces the history's visibility when the camera moved",
    ),
    switch(
        "PLANTED_PT_NO_JACOBIAN",
        &["render/tests/restir_pt.rs", "render/tests/bias_matrix.rs"],
        "PT reuse as if the shift's Jacobian were 1",
    ),
    switch(
        "PLANTED_PT_INVERTED_JACOBIAN",
        &["render/tests/restir_pt.rs"],
        "PT's shift Jacobian the wrong way round",
    ),
    switch(
        "PLANTED_PT_FAILED_SHIFT_DROPPED",
        &["render/tests/restir_pt.rs"],
        "a path that cannot be shifted counts in M but leaves the canonical weight",
    ),
    switch(
        "PLANTED_PT_PROBE_WRONG_NUMBERS",
        &["render/tests/restir_pt_inspect.rs"],
        "the inspector's path probe rebuilds the path with another path's random numbers",
    ),
    // The denoiser.
    switch(
        "PLANTED_NO_EDGE_STOPPING",
        &["render/tests/denoiser.rs"],
        "the à-trous filter without edge-stopping: a plain blur",
    ),
    switch(
        "PLANTED_CENTRE_VARIANCE_GATE",
        &["render/tests/denoiser.rs"],
        "the luminance gate scaled by the centre's variance alone",
    ),
    switch(
        "PLANTED_NO_REPROJECTION",
        &["render/tests/denoiser.rs"],
        "the denoiser's history read where the pixel is now, not where it was",
    ),
    // Views and the boiling window.
    switch(
        "PLANTED_WINDOW_CURRENT_FRAME_ONLY",
        &["render/tests/temporal_window.rs"],
        "the boiling view from this frame's neighbourhood: noise, not flicker",
    ),
    // Materials, glass and the loader.
    switch(
        "PLANTED_NO_FRESNEL",
        &["render/tests/glass_fresnel.rs"],
        "glass without its Fresnel reflection: all of it passes",
    ),
    switch(
        "PLANTED_OPAQUE_GLASS",
        &["render/tests/transparency.rs"],
        "glass and BLEND materials as opaque (the old loader)",
    ),
    switch(
        "PLANTED_RANDOM_LAYER_CHOICE",
        &["render/tests/transparency.rs"],
        "the G-buffer picks solid or pass at random per frame at each transparent layer",
    ),
    switch(
        "PLANTED_UNLIT_AS_LIT",
        &["render/tests/unlit.rs"],
        "KHR_materials_unlit shaded as a lit surface",
    ),
    switch(
        "PLANTED_UNLIT_UNBLENDED",
        &["render/tests/transparency.rs"],
        "an unlit colour at full strength whatever its alpha",
    ),
    switch(
        "PLANTED_NO_UV_TRANSFORM",
        &["render/tests/scene_loading/extensions.rs"],
        "KHR_texture_transform ignored",
    ),
    switch(
        "PLANTED_UNCLAMPED_BARYCENTRICS",
        &["render/tests/hard_cases.rs"],
        "the rasteriser's barycentrics used unclamped: points off the triangle at its edges",
    ),
    // Tracing.
    switch(
        "PLANTED_BVH_LAST_HIT_NOT_NEAREST",
        &["render/tests/ray_backends.rs"],
        "the software BVH reports the last hit it meets, not the nearest",
    ),
    switch(
        "PLANTED_RAY_QUERY_NO_GEOMETRY_OFFSET",
        &["render/tests/ray_backends.rs"],
        "ray queries read a tested geometry's primitives as the opaque geometry's",
    ),
    switch(
        "PLANTED_RAY_QUERY_NO_CULLING",
        &["render/tests/ray_backends.rs"],
        "ray queries without the culling flags the software BVH applies",
    ),
];

/// The entry of a switch, if it is one.
pub fn find(name: &str) -> Option<&'static PlantedSwitch> {
    PLANTED.iter().find(|p| p.name == name)
}

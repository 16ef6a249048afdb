// GPU structs shared by every pass. Each one has a `#[repr(C)]` twin in
// render/src/gpu_types.rs; render/tests/shaders_and_layouts.rs checks sizes and offsets match.

#include "di/params.wgsl"
#include "gi/params.wgsl"
#include "pt/params.wgsl"
#include "denoise/params.wgsl"

struct Triangle {
    p0: vec3<f32>,
    material: u32,
    p1: vec3<f32>,
    light: u32,         // light table index, or NO_LIGHT when the triangle does not emit
    p2: vec3<f32>,
    source_index: u32,  // index in the source scene, before BVH reordering
}

struct TriangleShading {
    normals: array<u32, 3>,  // octahedral (pack2x16snorm)
    has_normals: u32,        // 0: the source had no normals, use the geometric one
    uvs: array<vec2<f32>, 3>,
}

struct Material {
    base_color: vec4<f32>,
    emission: vec3<f32>,
    metallic: f32,
    roughness: f32,
    specular: f32,
    alpha_cutoff: f32,
    flags: u32,                      // MATERIAL_* bits (gpu_types.rs)
    base_color_texture: u32,         // NO_TEXTURE when absent
    metallic_roughness_texture: u32,
    emissive_texture: u32,
    transmission_texture: u32,       // R = transmission (linear)
    transmission: f32,               // KHR_materials_transmission factor, 0 when absent
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// Packed so that a lookup reads two words of its record (every word a shader loads is
// compiled per lane on a CPU driver: docs/src/compile-time.md); the transform is read only
// where some material has one (TEXTURE_TRANSFORM).
struct Texture {
    // first texel in `texels` | wrap_u << TEXEL_OFFSET_BITS | wrap_v << TEXEL_OFFSET_BITS + 2
    // (0 repeat, 1 clamp, 2 mirrored repeat), width | height << 16
    placement: vec2<u32>,
    uv_transform: mat3x2<f32>,  // KHR_texture_transform: uv' = uv_transform * vec3(uv, 1)
}

struct Light {
    kind_prim: u32,        // kind << LIGHT_KIND_SHIFT | triangle or punctual index
    select_pdf: f32,       // probability of picking this light (power / total power)
    alias_threshold: f32,
    alias_index: u32,
}

struct PunctualLight {
    position: vec3<f32>,
    kind: u32,             // PUNCTUAL_POINT, PUNCTUAL_SPOT, PUNCTUAL_DIRECTIONAL
    direction: vec3<f32>,  // where the light points
    range: f32,            // 0 = infinite
    intensity: vec3<f32>,  // candela (point, spot) or lux (directional)
    cos_outer: f32,
    cos_inner: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
}

struct BvhNode {
    min: vec3<f32>,
    first: u32,  // leaf: first triangle; interior: left child (right = first + 1)
    max: vec3<f32>,
    count: u32,  // triangles in a leaf, 0 for an interior node
}

// A streaming reservoir (docs/src/ris.md, "The streaming reservoir"). `m` is the confidence M: 1
// for a fresh initial reservoir, summed by reuse and capped by `m_cap`.
struct Reservoir {
    light: u32,    // light table index, NO_LIGHT for the null sample
    p_hat: f32,   // p̂ (× V with mis_visibility) at the pixel that finalised it: the ratio test, pairwise weights
    uv: vec2<f32>, // barycentrics of the point on a triangle light
    w_sum: f32,
    weight: f32,   // W = w_sum / (M · p̂)
    m: f32,
    source: u32,   // SOURCE_* | age << AGE_SHIFT (frames since the sample was drawn)
}

// One presampled light of a light tile (a packed LightPoint plus its identity).
// A presampled light: a light tile's entry or a ReGIR slot (docs/src/light-samplers.md),
// its point packed, the density the balance heuristic uses for it (source_pdf) and its
// contribution weight W (1 / source_pdf for a tile's exact draw; 0: an empty slot).
struct PresampledLight {
    position: vec3<f32>,
    source_pdf: f32,
    radiance: vec3<f32>,
    light: u32,
    uv: vec2<f32>,
    normal: u32,   // octahedral
    flags: u32,    // kind | double_sided << 2 | punctual index << 8
    weight: f32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// A light BVH node (render/src/light_sampler.rs builds them; light_bvh.wgsl walks them):
// bounds of its lights' positions, normals' cone and power. Interior: the first child is
// the next node, child_or_light the second; a leaf: LIGHT_BVH_LEAF | light.
struct LightBvhNode {
    min: vec3<f32>,
    phi: f32,
    max: vec3<f32>,
    child_or_light: u32,
    axis: u32,          // octahedral
    cos_theta_o: f32,
    cos_theta_e: f32,
    _pad: u32,
}

// A light-BVH node's bounds in full precision (light_bvh.rs's LightBounds), which the
// GPU refit unions (lights/light_bvh_refit.wgsl): its record above holds them quantised.
struct LightBounds {
    min: vec3<f32>,
    phi: f32,
    max: vec3<f32>,
    cos_theta_o: f32,   // the normals' cone; -1: every direction
    w: vec3<f32>,       // the cone's axis
    cos_theta_e: f32,
}

// One level of the GPU refit: its nodes are work[first .. first + count]; `leaves`: they
// are leaves, taking the changed lights' bounds leaf_bounds[0 .. count].
struct RefitLevel {
    first: u32,
    count: u32,
    leaves: u32,
    _pad: u32,
}

// A light's branch choices from the root (bit k: the second child at depth k) and depth.
struct LightBvhTrail {
    bits: vec2<u32>,
    depth: u32,         // LIGHT_BVH_NOT_IN_TREE: no leaf
    _pad: u32,
}

// One pixel's primary surface (docs/src/frame.md, "The G-buffer"), kept for one frame for
// temporal validation.
struct Surface {
    position: vec3<f32>,
    depth: f32,               // distance to the camera; 0 = no surface
    normal: u32,              // octahedral shading normal, facing the camera
    geo_normal: u32,          // octahedral geometric normal, facing the camera
    material: u32,
    base_color_metallic: u32, // pack4x8unorm(linear base colour, metallic)
    roughness: f32,
    specular: f32,
    motion: vec2<f32>,        // previous-frame pixel position of this point
    emission: vec3<f32>,      // radiance toward the camera: this surface's emission, and the
                              // emission and glass reflection of the layers before it
    transparent_first: u32,   // 1: the rasterised surface was a transparent layer (reference.wgsl)
    throughput: vec3<f32>,    // weight of the camera path through transparent layers (1: none)
    _pad2: f32,
}

struct PixelDebug {
    source: u32,
    temporal_mask: u32,
    spatial_mask: u32,
    flags: u32,        // DEBUG_FLAG_*
    m_initial: f32,
    m_temporal: f32,
    m_spatial: f32,
    weight: f32,       // W of the survivor at shading
    p_hat: f32,       // p̂ of the survivor at shading
    spatial_accepted: u32,
    gradient: vec2<f32>, // the history sample's shading last frame and now (denoiser gradients)
    proposer: u32,       // PROPOSER_* of the initial survivor
    useful_candidates: f32, // share of light candidates with p̂ > 0 (unshadowed)
}

struct Frame {
    view_proj: mat4x4<f32>,       // unjittered
    inv_view_proj: mat4x4<f32>,
    prev_view_proj: mat4x4<f32>,
    camera_position: vec3<f32>,
    frame_index: u32,
    prev_camera_position: vec3<f32>,
    seed: u32,
    jitter: vec2<f32>,            // this frame's sub-pixel offset, in pixels
    size: vec2<u32>,
    scene_scale: f32,             // scene bounds diagonal
    history_valid: u32,
    light_count: u32,
    punctual_count: u32,
    prev_jitter: vec2<f32>,       // the previous frame's jitter, for reprojection
    inspect_pixel: u32,           // the inspector's pixel index, or NO_INSPECT_PIXEL
    finite_light_share: f32,      // Σ select_pdf of lights with a position (light BVH)
}

// The pipeline parameters (`GpuParams`, built from the settings table). The fields no
// one technique owns are here; each technique's are its struct, declared in its folder
// (di/params.wgsl, gi/, pt/, denoise/): `gi_m_cap` in the settings is `params.gi.m_cap`.
// In the uniform address space a struct member starts on 16 bytes, hence the padding.
struct Params {
    normal_threshold: f32,
    depth_threshold: f32,
    checks: u32,                  // enabled REJECT_* checks
    flags: u32,                   // PARAM_FLAG_*
    reference_spp: u32,
    max_bounces: u32,             // path vertices the reference shades (1 = direct only)
    // ReGIR (docs/src/light-samplers.md, "ReGIR")
    regir_grid: u32,              // cells per side
    regir_slots: u32,             // slots per cell
    regir_cell_size: f32,         // a fraction of frame.scene_scale
    regir_build_samples: u32,
    regir_jitter: f32,            // cells
    reference_light_samples: u32, // light samples per reference vertex, ≥ 1
    di: DiParams,
    gi: GiParams,
    pt: PtParams,
    denoise: DenoiseParams,
}

struct Display {
    scale: f32,          // 1/N for an accumulation of N frames
    exposure: f32,       // linear (2^EV)
    tonemapper: u32,     // TONEMAP_*
    view: u32,           // VIEW_*
    reason_mask: u32,    // temporal rejection reasons shown (bits 0..REJECT_REASON_COUNT)
    m_scale: f32,        // M drawn at the top of the heatmap
    reference_scale: f32,
    spatial_tries: u32,  // neighbours tried per pixel (K × passes); 0 hides the spatial count
    comparison_scale: f32, // radiance scale of the comparison image (difference view)
    reference_noise: f32,  // the reference's own luma RMSE (bias view)
    _pad0: u32,
    _pad1: u32,
}

struct PassInfo {
    pass_index: u32,
    is_last: u32,
    _pad0: u32,
    _pad1: u32,
}

// The environment's sampling table (render/src/environment/distribution.rs).
struct EnvTexel {
    alias_threshold: f32,
    alias_index: u32,
    pdf: f32,             // per steradian (conditional entries) or P(row) (marginal ones)
}

struct Environment {
    size: vec2<u32>,
    light: u32,           // light table index, NO_LIGHT when it does not emit
    strength: f32,
    rotation: vec2<f32>,  // (cos, sin) about +Y
    _pad0: u32,
    _pad1: u32,
}

// A ReSTIR GI reservoir (docs/src/restir-gi.md; functions in gi/reservoir.wgsl, math in
// render/src/gi/model.rs). The pixel's Surface is its visible point.
struct GiReservoir {
    position: vec3<f32>,  // x_s, the secondary hit
    normal: u32,          // octahedral n_s, either orientation
    radiance: vec3<f32>,  // L_o(x_s -> x_v), cached when drawn
    w_sum: f32,
    weight: f32,          // W; 0 for the null sample
    m: f32,
    p_hat: f32,           // p̂ at the pixel that selected it
    packed: u32,          // SOURCE_* | GI flags << GI_FLAGS_SHIFT | age << GI_AGE_SHIFT
}

// A ReSTIR PT path reservoir (docs/src/restir-pt.md; functions in pt/reservoir.wgsl and
// pt/path.wgsl, the CPU model in render/src/pt/model). The pixel's Surface is the
// path's first vertex x_1; the path x_1 → … → x_n → z (a light point) is stored as what
// its shifts need: its random seed (replay), its reconnection vertex x_{k+1} and what lies
// beyond it (reconnection), and the densities and geometry of the side it was found on.
struct PtReservoir {
    value: vec3<f32>,     // f(x̄) at this pixel: the path's integrand (rgb), visibility included
    p_hat: f32,           // luminance(value)
    w_sum: f32,
    weight: f32,          // W; 0 for the null sample
    m: f32,
    seed: u32,            // the path's random numbers (pt_rng)
    packed: u32,          // source | n | end | k | lobes (pt/reservoir.wgsl)
    rc_triangle: u32,     // x_{k+1}: triangle and barycentrics (unused when k is PT_RC_NONE)
    rc_u: f32,
    rc_v: f32,
    rc_out: u32,          // octahedral direction leaving x_{k+1} (to x_{k+2} or to z)
    light: u32,           // z: light_table index and uv
    light_u: f32,
    light_v: f32,
    rc_suffix: vec3<f32>, // the integrand beyond x_{k+1}'s own factor
    replay_pdf: f32,      // density of the replayed directions (and a BSDF end) where found
    rc_from_d2: f32,      // |x_k − x_{k+1}|² where found
    rc_from_cos: f32,     // cos at x_{k+1} toward x_k (signed, triangle's own normal)
    jacobian: f32,        // |J| of the shift that brought it here (1: found here)
    _pad: u32,
}

// Per-pixel ReSTIR PT debug record (GpuPtPixelDebug): how the shifts into this pixel went.
struct PtPixelDebug {
    temporal_mask: u32,     // REJECT_* bits of the previous pixel's G-buffer checks
    temporal_failure: u32,  // PT_FAIL_* of the previous path's shift here; PT_FAIL_NOT_TRIED
    spatial_outcomes: u32,  // 4 bits per PT_FAIL_* value: the neighbours' shifts here by outcome
    spatial_tried: u32,     // neighbours that passed the G-buffer checks with a path to shift
    jacobian: f32,          // |J| of the survivor's last shift (1: found here)
    m_initial: f32,
    m_temporal: f32,
    m_spatial: f32,
}

// One PT stage's path at the inspected pixel (GpuPtProbeStage): the reservoir the stage
// kept and its vertices x_1 … x_n, z rebuilt from the record (pt/probe.wgsl).
struct PtProbeStage {
    written: u32,           // 1 when the stage ran this frame
    vertex_count: u32,
    _pad0: u32,
    _pad1: u32,
    reservoir: PtReservoir,
    vertices: array<vec4<f32>, PT_PROBE_VERTICES>,  // xyz; w: PT_VERTEX_* bits (bitcast)
}

// Per-pixel ReSTIR GI debug record (GpuGiPixelDebug).
struct GiPixelDebug {
    temporal_mask: u32,   // GI_REJECT_* bits
    spatial_mask: u32,
    spatial_accepted: u32,
    jacobian: f32,        // |J| of the survivor's last shift, 1 for the pixel's own sample
    m_initial: f32,
    m_temporal: f32,
    m_spatial: f32,
    _pad: u32,
}

// One pixel's temporal window (GpuWindowPixel; the `temporal window` pass writes it, the
// boiling and survivor-change views read it): its luminance in the last
// TEMPORAL_WINDOW_FRAMES frames and in which of them the survivor's light changed.
struct WindowPixel {
    luma: array<f32, TEMPORAL_WINDOW_FRAMES>,  // a ring: frame n is in slot n % frames
    count: u32,            // frames pushed since the window restarted
    last_light: u32,       // the survivor's light in the last real-time frame
    changes: u32,          // bit s: the survivor's light changed in slot s's frame
    rel_std: f32,          // σ / mean of the luminance over the filled slots (0 below 2)
    change_fraction: f32,  // changes / transitions inside the window
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// One pixel of the denoiser's temporal history (GpuDenoiseHistory; denoise/temporal.wgsl).
struct DenoiseHistory {
    illumination: vec3<f32>,  // accumulated, divided by the pixel's demodulation
    length: f32,              // frames accumulated (0: no surface)
    moments: vec2<f32>,       // (E[l], E[l²]) of the luminance
    _pad0: f32,
    _pad1: f32,
}

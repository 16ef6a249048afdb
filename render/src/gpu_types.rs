//! Host-side twins of the structs in `shaders/common/types.wgsl`.
//!
//! Each struct here is `#[repr(C)]` + `Pod` and has exactly the size and field offsets of
//! its WGSL namesake; `tests/shaders_and_layouts.rs` checks that with naga's layouter, so a field
//! added on one side only fails the build's tests instead of corrupting a buffer.

use bytemuck::{Pod, Zeroable};

use crate::denoise::params::GpuDenoiseParams;
use crate::di::params::GpuDiParams;
use crate::gi::params::GpuGiParams;
use crate::pt::params::GpuPtParams;

wgsl_constants! {
    fn absent_markers;
    /// Marks "no light" in a reservoir and "not an emitter" in `GpuTriangle::light`.
    pub const NO_LIGHT: u32 = u32::MAX;
    /// Marks an absent texture slot in `GpuMaterial`.
    pub const NO_TEXTURE: u32 = u32::MAX;
}

/// Triangle positions in BVH order (what rays and the rasteriser read).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuTriangle {
    pub p0: [f32; 3],
    pub material: u32,
    pub p1: [f32; 3],
    /// Index into the light table when this triangle emits, else `NO_LIGHT`.
    pub light: u32,
    pub p2: [f32; 3],
    /// Index of the triangle in the source scene (before BVH reordering).
    pub source_index: u32,
}

/// Per-vertex shading attributes of a triangle, same order as `GpuTriangle`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuTriangleShading {
    /// Octahedral-encoded vertex normals (`pack2x16snorm`).
    pub normals: [u32; 3],
    /// 0 when the source had no normals: shaders use the geometric normal.
    pub has_normals: u32,
    pub uvs: [[f32; 2]; 3],
}

wgsl_constants! {
    fn material_flags;
    pub const MATERIAL_DOUBLE_SIDED: u32 = 1;
    pub const MATERIAL_ALPHA_MASK: u32 = 2;
    /// Alpha BLEND: base-colour alpha is coverage (transparency.wgsl).
    pub const MATERIAL_ALPHA_BLEND: u32 = 4;
    /// Light can pass through (BLEND or transmission > 0): rays treat the surface as a layer.
    pub const MATERIAL_TRANSPARENT: u32 = 8;
    /// KHR_materials_unlit: seen as its base colour, black to every other light path.
    pub const MATERIAL_UNLIT: u32 = 16;
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuMaterial {
    pub base_color: [f32; 4],
    pub emission: [f32; 3],
    pub metallic: f32,
    pub roughness: f32,
    pub specular: f32,
    pub alpha_cutoff: f32,
    pub flags: u32,
    pub base_color_texture: u32,
    pub metallic_roughness_texture: u32,
    pub emissive_texture: u32,
    pub transmission_texture: u32,
    pub transmission: f32,
    pub _pad: [u32; 3],
}

/// Where a texture's RGBA8 texels start in the shared texel buffer, and how its uvs move.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuTexture {
    /// `first texel | wrap_u << TEXEL_OFFSET_BITS | wrap_v << TEXEL_OFFSET_BITS + 2` (each
    /// 0 repeat, 1 clamp, 2 mirrored repeat) and `width | height << 16`: two words, so a
    /// lookup loads little (docs/src/compile-time.md).
    pub placement: [u32; 2],
    /// `KHR_texture_transform` of the slot reading this record: uv' = M · (u, v, 1), M's
    /// three columns (WGSL `mat3x2<f32>`). Each distinct (texture, transform) pair of the
    /// scene's materials is its own record over the same texels.
    pub uv_transform: [[f32; 2]; 3],
}

wgsl_constants! {
    fn texture_packing;
    /// Bits of `GpuTexture::placement[0]` that hold the first texel: the texel buffer holds at
    /// most 2^28 texels (1 GiB), the two wrap modes take the top four bits.
    pub const TEXEL_OFFSET_BITS: u32 = 28;
}
/// The largest texture side `GpuTexture::placement[1]` holds.
pub const MAX_TEXTURE_SIDE: u32 = 0xffff;

wgsl_constants! {
    fn light_kinds;
    pub const LIGHT_KIND_TRIANGLE: u32 = 0;
    pub const LIGHT_KIND_PUNCTUAL: u32 = 1;
    /// The environment's one entry; its sample's `uv` is an image coordinate.
    pub const LIGHT_KIND_ENVIRONMENT: u32 = 2;
    /// The light kind lives in the top two bits of `GpuLight::kind_prim`.
    pub const LIGHT_KIND_SHIFT: u32 = 30;
    pub const LIGHT_PRIM_MASK: u32 = (1 << LIGHT_KIND_SHIFT) - 1;
}

/// One entry of the power-proportional light table, with its alias-table slot.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuLight {
    /// `kind << 30 | index`: a triangle index (BVH order) or a punctual light index.
    pub kind_prim: u32,
    /// Probability of picking this light (its power over the total).
    pub select_pdf: f32,
    /// Alias method: keep this slot when u < threshold, else take `alias`.
    pub alias_threshold: f32,
    pub alias_index: u32,
}

wgsl_constants! {
    fn punctual_kinds;
    pub const PUNCTUAL_POINT: u32 = 0;
    pub const PUNCTUAL_SPOT: u32 = 1;
    pub const PUNCTUAL_DIRECTIONAL: u32 = 2;
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuPunctualLight {
    pub position: [f32; 3],
    pub kind: u32,
    /// Unit direction the light points to.
    pub direction: [f32; 3],
    /// 0 means infinite range.
    pub range: f32,
    pub intensity: [f32; 3],
    pub cos_outer: f32,
    pub cos_inner: f32,
    pub _pad: [f32; 3],
}

/// A flattened BVH node. `count > 0`: leaf holding triangles `first..first+count`;
/// `count == 0`: interior node whose children are `first` and `first + 1`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuBvhNode {
    pub min: [f32; 3],
    pub first: u32,
    pub max: [f32; 3],
    pub count: u32,
}

/// A streaming reservoir (docs/src/ris.md, "The streaming reservoir"): the selected light
/// sample and its weights.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuReservoir {
    /// Light table index of the sample, `NO_LIGHT` for the null sample.
    pub light: u32,
    /// p̂ of the sample at the pixel that finalised this reservoir (used only by the
    /// temporal target-ratio test, never as the current target).
    pub p_hat: f32,
    /// Barycentric (u, v) of the point on a triangle light; unused for punctual lights.
    pub uv: [f32; 2],
    pub w_sum: f32,
    /// W = w_sum / (M · p̂): the unbiased contribution weight of the sample.
    pub weight: f32,
    /// Confidence M: 1 for a fresh initial reservoir, summed by reuse, capped by `m_cap`.
    pub m: f32,
    /// Which stage's candidate survived (`SOURCE_*`, bits 0..8) and the age of its sample
    /// in frames (bits `AGE_SHIFT`..): see `shader_constants::SOURCE_MASK`.
    pub source: u32,
}

/// A presampled light: a light tile's entry or a ReGIR slot (docs/src/light-samplers.md).
/// Everything the initial pass needs to score it in one contiguous read (lights.wgsl
/// `LightPoint`, packed), with the density the balance heuristic uses for it and its
/// contribution weight W: 1 / density for a tile's exact draw, the RIS weight for a slot.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuPresampledLight {
    pub position: [f32; 3],
    pub source_pdf: f32,
    pub radiance: [f32; 3],
    pub light: u32,
    pub uv: [f32; 2],
    /// Octahedral normal of a triangle light.
    pub normal: u32,
    /// `kind | double_sided << 2 | punctual index << 8`.
    pub flags: u32,
    /// W; 0 for an empty slot.
    pub weight: f32,
    pub _pad: [u32; 3],
}

/// A node of the light BVH (light_bvh.wgsl; built by `light_sampler.rs` from the plain-Rust
/// `LightBvh`): what its lights' positions, directions and power are bounded by. An
/// interior node's first child is the next node, `child_or_light` the second; a leaf has
/// `LIGHT_BVH_LEAF | light`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuLightBvhNode {
    pub min: [f32; 3],
    pub phi: f32,
    pub max: [f32; 3],
    pub child_or_light: u32,
    /// The normals' cone: octahedral axis, cos θ_o (widened a little for the encoding).
    pub axis: u32,
    pub cos_theta_o: f32,
    /// cos θ_e: how far past its normal a light emits (0: 90°).
    pub cos_theta_e: f32,
    pub _pad: u32,
}

/// A light-BVH node's bounds in full precision (`light_bvh::LightBounds`), which the GPU
/// refit unions: the node records hold them quantised.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuLightBounds {
    pub min: [f32; 3],
    pub phi: f32,
    pub max: [f32; 3],
    /// The normals' cone: cos θ_o (-1: every direction) and its axis.
    pub cos_theta_o: f32,
    pub w: [f32; 3],
    pub cos_theta_e: f32,
}

/// One level of the GPU refit (one dispatch): nodes `work[first..first + count]`, leaves
/// (taking the changed lights' bounds) or interior nodes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuRefitLevel {
    pub first: u32,
    pub count: u32,
    pub leaves: u32,
    pub _pad: u32,
}

/// Per light entry: its branch choices from the root (bit k: the second child at depth k)
/// and how deep its leaf is (`LIGHT_BVH_NOT_IN_TREE`: no leaf).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuLightBvhTrail {
    pub bits: [u32; 2],
    pub depth: u32,
    pub _pad: u32,
}

/// Per-pixel surface written by the G-buffer resolve pass and kept one frame for
/// temporal validation (docs/src/temporal-reuse.md, "Validation").
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuSurface {
    pub position: [f32; 3],
    /// Linear view depth; 0 means the pixel sees no surface.
    pub depth: f32,
    /// Octahedral shading normal, flipped to face the camera.
    pub normal: u32,
    /// Octahedral geometric normal, facing the camera (ray offsets, sidedness).
    pub geo_normal: u32,
    pub material: u32,
    /// `pack4x8unorm(linear base colour, metallic)`.
    pub base_color_metallic: u32,
    pub roughness: f32,
    pub specular: f32,
    /// Where this surface point was in the previous frame, in pixels (x, y);
    /// negative when it was behind the previous camera.
    pub motion: [f32; 2],
    /// Radiance toward the camera: the surface's emission (or unlit colour) and that of
    /// the transparent layers in front of it with their glass reflection, each weighted by
    /// what lies before it.
    pub emission: [f32; 3],
    /// 1 when the rasterised surface was a transparent layer (the reference then draws
    /// its own choice of layer per sample).
    pub transparent_first: u32,
    /// What the camera path through transparent layers is worth (1 with none in front):
    /// shading here is multiplied by it. Also set where the pixel sees no surface, for
    /// the background behind glass.
    pub throughput: [f32; 3],
    pub _pad2: f32,
}

/// Per-pixel debug record (the debug views and the stats: selection source, M per stage,
/// masks).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuPixelDebug {
    pub source: u32,
    /// Bits `REJECT_*` of the temporal candidate.
    pub temporal_mask: u32,
    /// Union of the `REJECT_*` bits of all spatial neighbours.
    pub spatial_mask: u32,
    /// `DEBUG_FLAG_*` bits.
    pub flags: u32,
    pub m_initial: f32,
    pub m_temporal: f32,
    pub m_spatial: f32,
    /// W and p̂ of the survivor at shading time.
    pub weight: f32,
    pub p_hat: f32,
    pub spatial_accepted: u32,
    /// The temporal pass's gradient sample for the denoiser: the history's sample shaded
    /// last frame (p̂·W at the previous pixel) and now (p̂·V·W here); 0, 0 where it had none
    /// (docs/src/denoiser.md, "Temporal gradients").
    pub gradient: [f32; 2],
    /// The initial pass: which strategy proposed its survivor (`PROPOSER_*`), and the share
    /// of its light candidates with a non-zero unshadowed contribution.
    pub proposer: u32,
    pub useful_candidates: f32,
}

/// Uniforms that change every frame.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuFrame {
    /// Unjittered world → clip of the current camera.
    pub view_proj: [[f32; 4]; 4],
    pub inv_view_proj: [[f32; 4]; 4],
    /// Unjittered world → clip of the previous frame's camera.
    pub prev_view_proj: [[f32; 4]; 4],
    pub camera_position: [f32; 3],
    pub frame_index: u32,
    pub prev_camera_position: [f32; 3],
    pub seed: u32,
    /// Sub-pixel offset of this frame's G-buffer, in pixels within [-0.5, 0.5].
    pub jitter: [f32; 2],
    pub size: [u32; 2],
    /// Length of the scene bounds' diagonal: the unit for scale-relative thresholds.
    pub scene_scale: f32,
    /// 0 after a resize, scene change or camera cut: the previous surfaces are invalid.
    pub history_valid: u32,
    pub light_count: u32,
    pub punctual_count: u32,
    /// The previous frame's jitter: reprojection lands on the pixel whose (jittered)
    /// sample was nearest to the point.
    pub prev_jitter: [f32; 2],
    /// The pixel inspector's pixel (y · width + x), or `NO_INSPECT_PIXEL`: the PT passes
    /// write that pixel's path into the path probe.
    pub inspect_pixel: u32,
    /// Σ select_pdf over the lights with a position: the light BVH's share of a light
    /// sample (docs/src/light-samplers.md, "The light BVH").
    pub finite_light_share: f32,
}

/// Pipeline parameters as the shaders see them (built from `Settings::gpu_params`): the
/// fields no one technique owns, then each technique's struct, declared in its folder
/// (`di::params`, …). A struct member of a uniform starts on 16 bytes: the shared part is
/// 48 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuParams {
    pub normal_threshold: f32,
    pub depth_threshold: f32,
    /// `REJECT_*` bits of the enabled validation checks.
    pub checks: u32,
    /// `PARAM_FLAG_*` bits (each technique's in its `constants.rs`).
    pub flags: u32,
    pub reference_spp: u32,
    /// Path vertices the reference shades, 1..=MAX_BOUNCES (1 = direct light only).
    pub max_bounces: u32,
    /// ReGIR (settings `regir_*`; docs/src/light-samplers.md): cells per side, slots per
    /// cell (as used), cell side as a fraction of `scene_scale`, build samples, jitter.
    pub regir_grid: u32,
    pub regir_slots: u32,
    pub regir_cell_size: f32,
    pub regir_build_samples: u32,
    pub regir_jitter: f32,
    /// Light samples per vertex of the reference (≥ 1), each weighed by the multi-sample
    /// balance heuristic against the vertex's one BSDF sample.
    pub reference_light_samples: u32,
    pub di: GpuDiParams,
    pub gi: GpuGiParams,
    pub pt: GpuPtParams,
    pub denoise: GpuDenoiseParams,
}

/// What the display pass shows and how (view settings, not pipeline parameters).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuDisplay {
    /// Multiplies the image buffer: 1/N for an accumulation of N frames.
    pub scale: f32,
    /// Linear exposure multiplier (2^EV).
    pub exposure: f32,
    /// One of `TONEMAP_*`.
    pub tonemapper: u32,
    /// One of `VIEW_*`.
    pub view: u32,
    /// Which temporal rejection reasons the rejection view shows (bits 0..8).
    pub reason_mask: u32,
    /// M value drawn at the top of the M heatmap (the M cap).
    pub m_scale: f32,
    /// Reference radiance scale for the error view (1/N of the reference accumulation).
    pub reference_scale: f32,
    /// Spatial neighbours tried per pixel this frame (K × passes): the top of the rejection
    /// view's spatial count; 0 hides it.
    pub spatial_tries: u32,
    /// Radiance scale of the comparison image (the difference view's B side).
    pub comparison_scale: f32,
    /// The reference's own per-pixel noise (luma RMSE), added to the bias view's noise.
    pub reference_noise: f32,
    pub _pad: [u32; 2],
}

/// Uniform of one spatial pass: which pass it is (for decorrelated random numbers).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuPassInfo {
    pub pass_index: u32,
    pub is_last: u32,
    pub _pad: [u32; 2],
}

/// Distance between the `GpuPassInfo` slots of the pass-info buffer (the uniform offset
/// alignment), and how many slots it has.
pub const PASS_INFO_STRIDE: u32 = 256;
pub const PASS_INFO_SLOTS: u32 = 256;

/// One entry of the environment's sampling table (environment/distribution.rs): W·H
/// conditional entries (alias within the row) then H marginal entries (alias over rows).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuEnvTexel {
    pub alias_threshold: f32,
    pub alias_index: u32,
    /// Conditional entries: the density of the texel's directions per steradian;
    /// marginal entries: the row's probability.
    pub pdf: f32,
}

/// The environment's uniform (scene group, binding 10).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuEnvironment {
    pub size: [u32; 2],
    /// The environment's index in the light table, `NO_LIGHT` when it does not emit.
    pub light: u32,
    pub strength: f32,
    /// (cos, sin) of the rotation about +Y.
    pub rotation: [f32; 2],
    pub _pad: [u32; 2],
}

/// A ReSTIR GI reservoir (docs/src/restir-gi.md; the math is gi/model.rs, the WGSL
/// functions gi/reservoir.wgsl): the sample point, its normal and the radiance cached toward
/// the pixel that drew it, and the reservoir's weights, in 48 bytes. The visible point it
/// belongs to is the pixel's `GpuSurface`. The sample's source pdf is not stored: after
/// initial resampling `weight` (W) stands for it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuGiReservoir {
    /// x_s, the secondary hit.
    pub position: [f32; 3],
    /// Octahedral n_s (`oct_encode`), either orientation.
    pub normal: u32,
    /// L_o(x_s → x_v), linear rgb (f32: emitters seen directly exceed half floats).
    pub radiance: [f32; 3],
    pub w_sum: f32,
    /// W: 0 for the null sample.
    pub weight: f32,
    /// Confidence M (capped by `gi_m_cap`).
    pub m: f32,
    /// p̂ of the sample at the pixel that selected it (finalisation divides by it).
    pub p_hat: f32,
    /// `SOURCE_*` (bits 0..4) | GI rejection bits of the stage that wrote it (bits 4..16) |
    /// age in frames (bits 16..32): see [`GpuGiReservoir::pack`].
    pub packed: u32,
}

impl GpuGiReservoir {
    /// `packed` from its parts; flags beyond 12 bits are dropped, the age saturates.
    pub fn pack(source: u32, flags: u32, age: u32) -> u32 {
        use crate::gi::constants::*;
        (source & GI_SOURCE_MASK)
            | ((flags & GI_FLAGS_MASK) << GI_FLAGS_SHIFT)
            | (age.min(GI_AGE_MAX) << GI_AGE_SHIFT)
    }

    pub fn source(&self) -> u32 {
        self.packed & crate::gi::constants::GI_SOURCE_MASK
    }

    /// The GI rejection bits (`REJECT_*` 0..5, `GI_REJECT_*`) of the stage that wrote it.
    pub fn flags(&self) -> u32 {
        use crate::gi::constants::*;
        (self.packed >> GI_FLAGS_SHIFT) & GI_FLAGS_MASK
    }

    pub fn age(&self) -> u32 {
        self.packed >> crate::gi::constants::GI_AGE_SHIFT
    }
}

/// A ReSTIR PT path reservoir (`PtReservoir` in types.wgsl, which documents each field):
/// the sample is a path from the pixel's visible point, stored as what its shifts need.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuPtReservoir {
    pub value: [f32; 3],
    pub p_hat: f32,
    pub w_sum: f32,
    pub weight: f32,
    pub m: f32,
    pub seed: u32,
    pub packed: u32,
    pub rc_triangle: u32,
    pub rc_u: f32,
    pub rc_v: f32,
    pub rc_out: u32,
    pub light: u32,
    pub light_u: f32,
    pub light_v: f32,
    pub rc_suffix: [f32; 3],
    pub replay_pdf: f32,
    pub rc_from_d2: f32,
    pub rc_from_cos: f32,
    pub jacobian: f32,
    pub _pad: u32,
}

/// Per-pixel ReSTIR GI debug record (the GI views and the stats): the stages' rejection
/// masks (GI_REJECT_* bits), accepted spatial neighbours, the |J| of the survivor's last
/// shift (1 for the pixel's own sample) and M after each stage.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuGiPixelDebug {
    pub temporal_mask: u32,
    pub spatial_mask: u32,
    pub spatial_accepted: u32,
    pub jacobian: f32,
    pub m_initial: f32,
    pub m_temporal: f32,
    pub m_spatial: f32,
    pub _pad: u32,
}

/// Per-pixel ReSTIR PT debug record (the PT views, the inspector): how the shifts into the
/// pixel went this frame and M after each stage.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuPtPixelDebug {
    /// `REJECT_*` bits of the previous pixel's G-buffer checks (0: the history was merged).
    pub temporal_mask: u32,
    /// `PT_FAIL_*` of the previous path's shift to this pixel, `PT_FAIL_NOT_TRIED` when
    /// there was none.
    pub temporal_failure: u32,
    /// Four bits per `PT_FAIL_*` value (bits 4f..4f+4): how many neighbours' shifts to this
    /// pixel ended that way (`PT_FAIL_NONE`: moved).
    pub spatial_outcomes: u32,
    /// Neighbours that passed the G-buffer checks with a path to shift.
    pub spatial_tried: u32,
    /// |J| of the survivor's last shift (1 for the pixel's own path).
    pub jacobian: f32,
    pub m_initial: f32,
    pub m_temporal: f32,
    pub m_spatial: f32,
}

impl GpuPtPixelDebug {
    /// Neighbours whose shift to this pixel ended with `failure` (`PT_FAIL_*`).
    pub fn spatial_count(&self, failure: u32) -> u32 {
        (self.spatial_outcomes >> (4 * failure)) & 0xf
    }
}

/// One PT stage's path at the inspected pixel (shaders/pt/probe.wgsl): the reservoir it kept and
/// the path's vertices x_1 … x_n and z, rebuilt on the GPU from the record.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuPtProbeStage {
    /// 1 when the stage ran this frame (the probe is cleared before each frame).
    pub written: u32,
    pub vertex_count: u32,
    pub _pad: [u32; 2],
    pub reservoir: GpuPtReservoir,
    /// xyz; w holds `PT_VERTEX_*` bits (as f32 bits).
    pub vertices: [[f32; 4]; crate::pt::constants::PT_PROBE_VERTICES as usize],
}

/// One pixel's temporal window (the `temporal window` pass, passes/temporal_window.rs):
/// its luminance over the last `TEMPORAL_WINDOW_FRAMES` frames (a ring) and which of them
/// changed the survivor's light, with the two figures the boiling and survivor-change
/// views paint, computed when the frame was pushed.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuWindowPixel {
    /// Frame n's luminance is in slot n % TEMPORAL_WINDOW_FRAMES.
    pub luma: [f32; crate::shader_constants::TEMPORAL_WINDOW_FRAMES as usize],
    /// Frames pushed since the window restarted.
    pub count: u32,
    /// The survivor's light in the last real-time frame (`NO_LIGHT` for the null sample).
    pub last_light: u32,
    /// Bit s: the survivor's light changed in the frame held in slot s.
    pub changes: u32,
    /// σ / mean of the luminance over the filled slots (sample σ; 0 below two frames or
    /// for a black pixel).
    pub rel_std: f32,
    /// Changes of the survivor's light / transitions inside the window.
    pub change_fraction: f32,
    pub _pad: [u32; 3],
}

/// One pixel of the denoiser's temporal history (shaders/denoise/temporal.wgsl writes it,
/// `denoise::model::temporal` mirrors it): the accumulated demodulated illumination, how
/// many frames it holds, and the first two moments of its luminance.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuDenoiseHistory {
    pub illumination: [f32; 3],
    /// Frames accumulated (0: no surface), capped at `denoise_history_cap`.
    pub length: f32,
    /// (E[l], E[l²]) of the luminance, exponentially averaged.
    pub moments: [f32; 2],
    pub _pad: [f32; 2],
}

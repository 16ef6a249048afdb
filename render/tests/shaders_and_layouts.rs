//! Every pass shader composes, parses and validates with naga for the general effect set,
//! for no optional effect at all and for each effect alone; and every host struct in
//! gpu_types.rs has the size and field offsets of its WGSL twin (checked with naga's
//! layouter on the composed source). No GPU needed.

use std::collections::BTreeSet;

use restir_render::effects::{Effect, EffectSet};
use restir_render::gpu_types::*;
use restir_render::shader_source::compose;

const PASSES: [&str; 9] = [
    "presample_lights.wgsl",
    "gbuffer_raster.wgsl",
    "gbuffer_resolve.wgsl",
    "initial.wgsl",
    "temporal.wgsl",
    "spatial.wgsl",
    "shade.wgsl",
    "reference.wgsl",
    "display.wgsl",
];

fn parse_and_validate(name: &str, defines: &BTreeSet<String>) -> naga::Module {
    let source = compose(name, defines).unwrap_or_else(|e| panic!("{name}: {e}"));
    let module = naga::front::wgsl::parse_str(&source)
        .unwrap_or_else(|e| panic!("{name} with {defines:?}:\n{}", e.emit_to_string(&source)));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{name} with {defines:?}: {}", e.emit_to_string(&source)));
    module
}

#[test]
fn every_pass_validates_for_every_effect_set() {
    let mut sets = vec![EffectSet::all().defines(), BTreeSet::new()];
    for e in Effect::ALL {
        sets.push(
            EffectSet {
                enabled: [e].into_iter().collect(),
                reasons: vec![],
                planted: BTreeSet::new(),
            }
            .defines(),
        );
    }
    for defines in &sets {
        for pass in PASSES {
            parse_and_validate(pass, defines);
        }
    }
    // The furnace test's planted errors must keep compiling (render/tests/multi_bounce.rs).
    for planted in ["PLANTED_NO_BSDF_MIS", "PLANTED_NO_THROUGHPUT_PDF"] {
        let mut defines = EffectSet::all().defines();
        defines.insert(planted.to_string());
        parse_and_validate("reference.wgsl", &defines);
        let mut bare = BTreeSet::new();
        bare.insert(planted.to_string());
        parse_and_validate("reference.wgsl", &bare);
    }
}

/// (size, [(member name, offset)]) of a WGSL struct.
fn wgsl_layout(module: &naga::Module, name: &str) -> (u32, Vec<(String, u32)>) {
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).unwrap();
    let (handle, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("struct {name} not found in WGSL"));
    match &ty.inner {
        naga::TypeInner::Struct { members, span } => {
            assert_eq!(*span, layouter[handle].size);
            (
                *span,
                members
                    .iter()
                    .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
                    .collect(),
            )
        }
        _ => panic!("{name} is not a struct"),
    }
}

macro_rules! check_struct {
    ($module:expr, $wgsl:literal, $rust:ty, [$($field:ident),* $(,)?]) => {{
        let (size, members) = wgsl_layout($module, $wgsl);
        assert_eq!(size as usize, std::mem::size_of::<$rust>(), "size of {}", $wgsl);
        $(
            let offset = members
                .iter()
                .find(|(n, _)| n == stringify!($field))
                .unwrap_or_else(|| panic!("{}.{} missing in WGSL", $wgsl, stringify!($field)))
                .1;
            assert_eq!(offset as usize, std::mem::offset_of!($rust, $field), "{}.{}", $wgsl, stringify!($field));
        )*
        // Every named WGSL member that is not padding must have been listed above.
        let listed: &[&str] = &[$(stringify!($field)),*];
        for (name, _) in &members {
            assert!(name.starts_with('_') || listed.contains(&name.as_str()), "{}.{name} not checked", $wgsl);
        }
    }};
}

#[test]
fn host_structs_match_wgsl_layouts() {
    // All shared structs live in types.wgsl; compose it with the constants prelude.
    let module = parse_and_validate("common/types.wgsl", &BTreeSet::new());
    let m = &module;
    check_struct!(
        m,
        "Triangle",
        GpuTriangle,
        [p0, material, p1, light, p2, source_index]
    );
    check_struct!(
        m,
        "TriangleShading",
        GpuTriangleShading,
        [normals, has_normals, uvs]
    );
    check_struct!(
        m,
        "Material",
        GpuMaterial,
        [
            base_color,
            emission,
            metallic,
            roughness,
            specular,
            alpha_cutoff,
            flags,
            base_color_texture,
            metallic_roughness_texture,
            emissive_texture
        ]
    );
    check_struct!(m, "Texture", GpuTexture, [offset, width, height, wrap]);
    check_struct!(
        m,
        "Light",
        GpuLight,
        [kind_prim, select_pdf, alias_threshold, alias_index]
    );
    check_struct!(
        m,
        "PunctualLight",
        GpuPunctualLight,
        [
            position, kind, direction, range, intensity, cos_outer, cos_inner
        ]
    );
    check_struct!(m, "BvhNode", GpuBvhNode, [min, first, max, count]);
    check_struct!(
        m,
        "TileSample",
        GpuTileSample,
        [position, source_pdf, radiance, light, uv, normal, flags]
    );
    check_struct!(
        m,
        "Reservoir",
        GpuReservoir,
        [light, p_hat, uv, w_sum, weight, m, source]
    );
    check_struct!(
        m,
        "Surface",
        GpuSurface,
        [
            position,
            depth,
            normal,
            geo_normal,
            material,
            base_color_metallic,
            roughness,
            specular,
            motion,
            emission
        ]
    );
    check_struct!(
        m,
        "PixelDebug",
        GpuPixelDebug,
        [
            source,
            temporal_mask,
            spatial_mask,
            flags,
            m_initial,
            m_temporal,
            m_spatial,
            weight,
            p_hat,
            spatial_accepted
        ]
    );
    check_struct!(
        m,
        "Frame",
        GpuFrame,
        [
            view_proj,
            inv_view_proj,
            prev_view_proj,
            camera_position,
            frame_index,
            prev_camera_position,
            seed,
            jitter,
            size,
            scene_scale,
            history_valid,
            light_count,
            punctual_count,
            prev_jitter
        ]
    );
    check_struct!(
        m,
        "Params",
        GpuParams,
        [
            light_candidates,
            bsdf_candidates,
            m_cap,
            normal_threshold,
            depth_threshold,
            target_ratio_clamp,
            checks,
            flags,
            spatial_neighbours,
            spatial_radius,
            reference_spp,
            boiling_filter,
            max_bounces
        ]
    );
    check_struct!(
        m,
        "Display",
        GpuDisplay,
        [
            scale,
            exposure,
            tonemapper,
            view,
            reason_mask,
            m_scale,
            reference_scale,
            spatial_tries,
            comparison_scale
        ]
    );
    check_struct!(m, "PassInfo", GpuPassInfo, [pass_index, is_last]);
    check_struct!(
        m,
        "EnvTexel",
        GpuEnvTexel,
        [alias_threshold, alias_index, pdf]
    );
    check_struct!(
        m,
        "Environment",
        GpuEnvironment,
        [size, light, strength, rotation]
    );
}

//! Every pass shader composes, parses, validates and compiles to SPIR-V with naga (the
//! backend wgpu uses on Vulkan) for the general effect set, for no optional effect at all
//! and for each effect alone; every pass declaration
//! (`PassDef`) matches its shader's group-2 bindings; and every host struct in
//! gpu_types.rs has the size and field offsets of its WGSL twin (checked with naga's
//! layouter on the composed source). No GPU needed.

use std::collections::BTreeSet;

use restir_render::denoise::params::GpuDenoiseParams;
use restir_render::di::params::GpuDiParams;
use restir_render::effects::{Effect, EffectSet};
use restir_render::gi::params::GpuGiParams;
use restir_render::gpu_types::*;
use restir_render::pt::params::GpuPtParams;
use restir_render::shader_source::compose;

use restir_render::passes::pass::Access;
use restir_render::passes::resources::Resource;

fn parse_and_validate(name: &str, defines: &BTreeSet<String>) -> naga::Module {
    let source = compose(name, defines).unwrap_or_else(|e| panic!("{name}: {e}"));
    validate_source(&format!("{name} with {defines:?}"), &source)
}

/// Parses, validates and compiles composed WGSL to SPIR-V; `what` names it in the panic
/// message. The SPIR-V step catches what validation lets through and the driver never sees:
/// naga's SPIR-V writer panics on some valid shapes (a pointer to a member of a pointee
/// passed to a function: "Expression [n] is not cached!"), which a GPU test meets only when
/// a scene with that effect set is opened.
fn validate_source(what: &str, source: &str) -> naga::Module {
    let module = naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{what}:\n{}", e.emit_to_string(source)));
    // Ray queries are a capability wgpu grants with EXPERIMENTAL_RAY_QUERY; the software
    // variants do not use it, so validating them with it loses nothing.
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default() | naga::valid::Capabilities::RAY_QUERY,
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{what}: {}", e.emit_to_string(source)));
    let spirv = std::panic::catch_unwind(|| {
        naga::back::spv::write_vec(&module, &info, &naga::back::spv::Options::default(), None)
    });
    match spirv {
        Ok(Ok(_)) => {}
        Ok(Err(e)) => panic!("{what}: SPIR-V: {e}"),
        Err(_) => panic!("{what}: naga's SPIR-V writer panicked (see above)"),
    }
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
    // Each set with either tracing backend behind trace.wgsl.
    let ray_query: Vec<BTreeSet<String>> = sets
        .iter()
        .map(|d| {
            let mut d = d.clone();
            d.insert(restir_render::tracing::RAY_QUERY_DEFINE.to_string());
            d
        })
        .collect();
    sets.extend(ray_query);
    for defines in &sets {
        for pass in restir_render::passes::ALL {
            parse_and_validate(pass.shader, defines);
        }
    }
}

/// Every planted-bug switch the shaders have is in the registry (render/src/planted.rs) and
/// every entry is in some shader; each named test file plants it; and its twin of every
/// pass shader it changes (with either tracing backend) validates, so a planted test never
/// fails for a shader that does not compile.
#[test]
fn every_planted_switch_is_registered_and_its_twins_validate() {
    use restir_render::planted::PLANTED;
    use restir_render::shader_source::{all_shader_files, shader_file};
    let mut in_shaders = BTreeSet::new();
    for file in all_shader_files() {
        let text = shader_file(file).unwrap();
        for line in text.lines() {
            let line = line.trim();
            let name = line
                .strip_prefix("#ifdef ")
                .or_else(|| line.strip_prefix("#ifndef "))
                .map(str::trim);
            if let Some(name) = name.filter(|n| n.starts_with("PLANTED_") || n.starts_with("TEST_"))
            {
                in_shaders.insert(name.to_string());
            }
        }
    }
    let registered: BTreeSet<String> = PLANTED.iter().map(|p| p.name.to_string()).collect();
    assert_eq!(
        in_shaders, registered,
        "the shaders' planted switches and render/src/planted.rs disagree"
    );
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for p in PLANTED {
        if p.tests.is_empty() {
            assert!(
                p.breaks.contains("no GPU test plants it"),
                "{}: name the test that plants it, or say that none does and what does instead",
                p.name
            );
        }
        for test in p.tests {
            let text = std::fs::read_to_string(root.join(test))
                .unwrap_or_else(|e| panic!("{}: {test}: {e}", p.name));
            assert!(text.contains(p.name), "{test} does not plant {}", p.name);
        }
        let mut changed = 0;
        // Every effect with either backend, no optional effect at all, and the general set
        // with each light sampler that `EffectSet::all` leaves out (a planted ReGIR or tree
        // error lives behind its sampler's define).
        let with_sampler = |sampler: &[&str]| {
            let mut set = EffectSet::all().defines();
            set.remove("LIGHT_TILES");
            set.extend(sampler.iter().map(|d| d.to_string()));
            set
        };
        for base_set in 0..5 {
            let mut base = match base_set {
                2 => BTreeSet::new(),
                3 => with_sampler(&["REGIR", "REGIR_FROM_BVH"]),
                4 => with_sampler(&["LIGHT_BVH", "VERTEX_LIGHT_BVH"]),
                _ => EffectSet::all().defines(),
            };
            if base_set == 1 {
                base.insert(restir_render::tracing::RAY_QUERY_DEFINE.to_string());
            }
            let mut planted = base.clone();
            planted.insert(p.name.to_string());
            for pass in restir_render::passes::ALL {
                let plain = compose(pass.shader, &base).unwrap();
                if compose(pass.shader, &planted).unwrap() != plain {
                    parse_and_validate(pass.shader, &planted);
                    changed += 1;
                }
            }
        }
        assert!(changed > 0, "{} changes no pass shader", p.name);
    }
}

/// The SPIR-V step has power: the shape that once reached lavapipe as a panic while the WGSL
/// validated (layer_walk.wgsl passing `&(*p).walk` on) fails here. Should a naga release
/// fix its writer, this test says so; then find another planted shape or drop the step.
#[test]
fn the_spirv_step_catches_what_validation_lets_through() {
    let planted = r#"
struct Inner { w: vec3<f32>, t: f32 }
struct Outer { a: Inner, b: u32 }
fn zero(x: ptr<function, Inner>) { (*x).w = vec3<f32>(0.0); }
fn advance(p: ptr<function, Outer>) -> bool {
    zero(&(*p).a);
    return (*p).b > 0u;
}
@compute @workgroup_size(1)
fn main() { var o: Outer; _ = advance(&o); }
"#;
    let caught = std::panic::catch_unwind(|| validate_source("planted", planted));
    assert!(
        caught.is_err(),
        "the SPIR-V writer no longer panics on the planted shape"
    );
    // The same shape with a local copy (what layer_walk.wgsl does now) compiles.
    let fixed = planted.replace("zero(&(*p).a);", "var a = (*p).a; zero(&a); (*p).a = a;");
    validate_source("fixed", &fixed);
}

/// Calls every function of the GI reservoir library (no pass uses it yet), so the library
/// is checked the way a pass will use it: pointers to function-scope reservoirs, a storage
/// array of `GiReservoir`, the generated constants.
const GI_LIBRARY_ENTRY: &str = r#"
@group(0) @binding(0) var<storage, read_write> gi_check: array<GiReservoir>;

@compute @workgroup_size(64)
fn gi_library_check(@builtin(global_invocation_id) id: vec3<u32>) {
    let other = gi_check[id.x];
    let here = vec3<f32>(0.0);
    let n_here = vec3<f32>(0.0, 0.0, 1.0);
    let j = gi_reconnection_jacobian(other.position, oct_decode(other.normal), vec3<f32>(1.0), here);
    var flags = gi_shift_rejection(j, 10.0);
    if !gi_jacobian_in_window(j, 10.0) || gi_reservoir_is_corrupt(other) {
        flags |= GI_REJECT_JACOBIAN;
    }
    let p = gi_target(vec3<f32>(0.25), other.radiance, gi_receiver_cosine(here, n_here, other.position));
    var r = gi_reservoir_empty();
    gi_reservoir_update(&r, other.position, other.normal, other.radiance, gi_initial_weight(p, 0.5, 1.0), p, gi_pack(SOURCE_INITIAL, 0u, 0u), 0.5);
    gi_reservoir_finalize(&r, 1.0);
    r.m = 1.0;
    var s = gi_reservoir_empty();
    let m_i = shifted_pairwise_noncanonical(3.0, 1.0, 2.0, p, p, j);
    let m_c = confidence_share(1.0, 3.0) + shifted_pairwise_canonical_term(3.0, 1.0, 2.0, p, p, j);
    gi_reservoir_merge_mis(&s, r, p, 1.0, m_c, gi_pack(gi_source(r), 0u, gi_age(r)), 0.25);
    gi_reservoir_merge_mis(&s, other, p, j, m_i, gi_pack(SOURCE_SPATIAL, 0u, gi_age(other)), 0.75);
    gi_reservoir_merge(&s, other, p, j, min(other.m, 10.0), gi_pack(SOURCE_TEMPORAL, 0u, gi_age(other) + 1u), 0.5);
    s.m = 3.0;
    gi_reservoir_finalize(&s, 1.0);
    gi_cap_confidence(&s, 10.0);
    gi_set_flags(&s, flags | gi_flags(other));
    if !gi_reservoir_is_null(s) {
        gi_check[id.x] = s;
    }
}
"#;

#[test]
fn gi_reservoir_library_validates_in_a_compute_entry_point() {
    for defines in [BTreeSet::new(), EffectSet::all().defines()] {
        let mut source = compose("gi/reservoir.wgsl", &defines).unwrap();
        source.push_str(GI_LIBRARY_ENTRY);
        let module = validate_source("gi/reservoir.wgsl in a compute entry point", &source);
        assert_eq!(module.entry_points.len(), 1);
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
            emissive_texture,
            transmission_texture,
            transmission
        ]
    );
    check_struct!(m, "Texture", GpuTexture, [placement, uv_transform]);
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
        "LightBvhNode",
        GpuLightBvhNode,
        [
            min,
            phi,
            max,
            child_or_light,
            axis,
            cos_theta_o,
            cos_theta_e
        ]
    );
    check_struct!(m, "LightBvhTrail", GpuLightBvhTrail, [bits, depth]);
    check_struct!(
        m,
        "LightBounds",
        GpuLightBounds,
        [min, phi, max, cos_theta_o, w, cos_theta_e]
    );
    check_struct!(m, "RefitLevel", GpuRefitLevel, [first, count, leaves]);
    check_struct!(
        m,
        "PresampledLight",
        GpuPresampledLight,
        [
            position, source_pdf, radiance, light, uv, normal, flags, weight
        ]
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
            emission,
            transparent_first,
            throughput
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
            spatial_accepted,
            gradient,
            proposer,
            useful_candidates
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
            prev_jitter,
            inspect_pixel,
            finite_light_share
        ]
    );
    check_struct!(
        m,
        "Params",
        GpuParams,
        [
            normal_threshold,
            depth_threshold,
            checks,
            flags,
            reference_spp,
            max_bounces,
            regir_grid,
            regir_slots,
            regir_cell_size,
            regir_build_samples,
            regir_jitter,
            reference_light_samples,
            di,
            gi,
            pt,
            denoise
        ]
    );
    check_struct!(
        m,
        "DiParams",
        GpuDiParams,
        [
            light_candidates,
            bsdf_candidates,
            m_cap,
            target_ratio_clamp,
            spatial_neighbours,
            spatial_radius,
            boiling_filter,
            mutations,
            mutation_step
        ]
    );
    check_struct!(
        m,
        "GiParams",
        GpuGiParams,
        [
            m_cap,
            spatial_neighbours,
            spatial_radius,
            jacobian_max,
            light_candidates
        ]
    );
    check_struct!(
        m,
        "PtParams",
        GpuPtParams,
        [
            shift,
            rough_threshold,
            min_distance,
            spatial_neighbours,
            spatial_radius,
            m_cap,
            jacobian_clamp
        ]
    );
    check_struct!(
        m,
        "DenoiseParams",
        GpuDenoiseParams,
        [
            alpha,
            moments_alpha,
            phi_luminance,
            phi_normal,
            phi_depth,
            history_cap
        ]
    );
    check_struct!(
        m,
        "PtReservoir",
        GpuPtReservoir,
        [
            value,
            p_hat,
            w_sum,
            weight,
            m,
            seed,
            packed,
            rc_triangle,
            rc_u,
            rc_v,
            rc_out,
            light,
            light_u,
            light_v,
            rc_suffix,
            replay_pdf,
            rc_from_d2,
            rc_from_cos,
            jacobian
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
            comparison_scale,
            reference_noise
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
    check_struct!(
        m,
        "GiReservoir",
        GpuGiReservoir,
        [position, normal, radiance, w_sum, weight, m, p_hat, packed]
    );
    check_struct!(
        m,
        "PtPixelDebug",
        GpuPtPixelDebug,
        [
            temporal_mask,
            temporal_failure,
            spatial_outcomes,
            spatial_tried,
            jacobian,
            m_initial,
            m_temporal,
            m_spatial
        ]
    );
    check_struct!(
        m,
        "PtProbeStage",
        GpuPtProbeStage,
        [written, vertex_count, reservoir, vertices]
    );
    check_struct!(
        m,
        "GiPixelDebug",
        GpuGiPixelDebug,
        [
            temporal_mask,
            spatial_mask,
            spatial_accepted,
            jacobian,
            m_initial,
            m_temporal,
            m_spatial
        ]
    );
    check_struct!(
        m,
        "DenoiseHistory",
        GpuDenoiseHistory,
        [illumination, length, moments]
    );
    check_struct!(
        m,
        "WindowPixel",
        GpuWindowPixel,
        [luma, count, last_light, changes, rel_std, change_fraction]
    );
}

/// What the shader declares at a group-2 binding, as the declaration should name it.
fn declared_kind(module: &naga::Module, var: &naga::GlobalVariable) -> String {
    match var.space {
        naga::AddressSpace::Uniform => "uniform".into(),
        naga::AddressSpace::Storage { access } => {
            let written = access.contains(naga::StorageAccess::STORE);
            let stride = match module.types[var.ty].inner {
                naga::TypeInner::Array { stride, .. } => format!(" stride {stride}"),
                _ => String::new(),
            };
            format!(
                "storage {}{stride}",
                if written { "read_write" } else { "read" }
            )
        }
        naga::AddressSpace::Handle => match module.types[var.ty].inner {
            naga::TypeInner::Image {
                class: naga::ImageClass::Storage { .. },
                ..
            } => "storage texture".into(),
            naga::TypeInner::Image { .. } => "texture".into(),
            ref other => format!("{other:?}"),
        },
        other => format!("{other:?}"),
    }
}

/// What a `PassDef` binding implies the shader declares.
fn expected_kind(binding: &restir_render::passes::pass::Binding) -> String {
    let access = match binding.access {
        Access::Read => "read",
        Access::ReadWrite => "read_write",
    };
    let stride = |s: usize| format!("storage {access} stride {s}");
    match binding.resource {
        Resource::PassInfo | Resource::DisplayUniform => "uniform".into(),
        Resource::Visibility => "texture".into(),
        Resource::Output => "storage texture".into(),
        Resource::Surfaces | Resource::PrevSurfaces => stride(std::mem::size_of::<GpuSurface>()),
        Resource::Pixels(p) => stride(p.stride),
        Resource::Chain(c, _) => stride(c.stride),
        Resource::ShownImage => stride(16),
        Resource::Lights(data) => stride(data.stride()),
    }
}

/// A pass's declaration is the only description of its bindings the host has (layouts and
/// bind groups are derived from it), so it must say exactly what the shader declares:
/// the same bindings, read or written as the shader does, with the element size of the
/// buffer the renderer binds there.
#[test]
fn every_pass_declaration_matches_its_shader_bindings() {
    let defines = EffectSet::all().defines();
    for pass in restir_render::passes::ALL {
        let module = parse_and_validate(pass.shader, &defines);
        let mut declared: Vec<(u32, String)> = module
            .global_variables
            .iter()
            .filter_map(|(_, var)| {
                let binding = var.binding.as_ref()?;
                (binding.group == 2).then(|| (binding.binding, declared_kind(&module, var)))
            })
            .collect();
        declared.sort();
        let expected: Vec<(u32, String)> =
            (0..).zip(pass.group.iter().map(expected_kind)).collect();
        assert_eq!(declared, expected, "{} ({})", pass.name, pass.shader);
    }
}

// Material and texture evaluation at a point of a triangle. Each texture slot sits in its
// own #ifdef so a scene without textures compiles none of this (docs/src/specialisation.md).
#include "common/scene_bindings.wgsl"
#include "common/math.wgsl"
#include "common/brdf.wgsl"

struct MaterialSample {
    base_color: vec3<f32>,
    alpha: f32,
    metallic: f32,
    roughness: f32,
    specular: f32,
}

fn triangle_uv(tri_index: u32, u: f32, v: f32) -> vec2<f32> {
    let s = shading[tri_index];
    return s.uvs[0] * (1.0 - u - v) + s.uvs[1] * u + s.uvs[2] * v;
}

#ifdef ANY_TEXTURES
// Texel coordinates of a footprint's two columns (or rows), wrapped by the sampler's mode.
fn wrap_texel_pair(i: vec2<i32>, size: i32, mode: u32) -> vec2<i32> {
    if mode == 1u {
        return clamp(i, vec2<i32>(0), vec2<i32>(size - 1));
    }
    if mode == 2u {
        let period = 2 * size;
        let m = ((i % period) + period) % period;
        return select(m, period - 1 - m, m >= vec2<i32>(size));
    }
    return ((i % size) + size) % size;
}

// Bilinear filtering of the base level (no mips: every pass reads the same value, which
// keeps the raster and ray-traced paths consistent).
// The record's KHR_texture_transform moves the uv first (only in scenes that have one).
fn sample_texture(index: u32, uv: vec2<f32>, srgb: bool) -> vec4<f32> {
    let t = textures[index];
    let first = t.placement.x & ((1u << TEXEL_OFFSET_BITS) - 1u);
    let wrap = t.placement.x >> TEXEL_OFFSET_BITS;
    let size = vec2<u32>(t.placement.y & 0xffffu, t.placement.y >> 16u);
#ifdef TEXTURE_TRANSFORM
#ifdef PLANTED_NO_UV_TRANSFORM
    let st = uv;
#else
    let st = t.uv_transform * vec3<f32>(uv, 1.0);
#endif
#else
    let st = uv;
#endif
    let p = st * vec2<f32>(size) - 0.5;
    let base = floor(p);
    let f = p - base;
    let xs = wrap_texel_pair(vec2<i32>(i32(base.x)) + vec2<i32>(0, 1), i32(size.x), wrap & 3u);
    let ys = wrap_texel_pair(vec2<i32>(i32(base.y)) + vec2<i32>(0, 1), i32(size.y), wrap >> 2u);
    // The corners that carry weight (bit k: corner k, x-major), fetched by one loop so the
    // fetch and the sRGB decode are compiled once per call site, not four times (shader
    // size is compile time on a CPU driver: docs/src/compile-time.md). A lookup on a texel
    // centre reads one texel.
    var corners = 1u | select(0u, 2u, f.x > 0.0) | select(0u, 4u, f.y > 0.0) | select(0u, 8u, f.x > 0.0 && f.y > 0.0);
    var sum = vec4<f32>(0.0);
    while corners != 0u {
        let corner = firstTrailingBit(corners);
        corners &= corners - 1u;
        let right = (corner & 1u) != 0u;
        let below = corner >= 2u;
        let x = select(xs.x, xs.y, right);
        let y = select(ys.x, ys.y, below);
        var c = unpack4x8unorm(texels[first + u32(y) * size.x + u32(x)]);
        if srgb {
            c = vec4<f32>(srgb_to_linear(c.rgb), c.a);
        }
        sum += c * (select(1.0 - f.x, f.x, right) * select(1.0 - f.y, f.y, below));
    }
    return sum;
}
#endif

// Base colour factor × base colour texture (rgb linear, a coverage).
fn base_color_at(material_index: u32, uv: vec2<f32>) -> vec4<f32> {
    let m = materials[material_index];
    var c = m.base_color;
#ifdef BASE_COLOR_TEXTURES
    if m.base_color_texture != NO_TEXTURE {
        c *= sample_texture(m.base_color_texture, uv, true);
    }
#endif
    return c;
}

fn material_alpha(material_index: u32, uv: vec2<f32>) -> f32 {
    return base_color_at(material_index, uv).a;
}

fn eval_material(material_index: u32, uv: vec2<f32>) -> MaterialSample {
    let m = materials[material_index];
    let base = base_color_at(material_index, uv);
    var out = MaterialSample(base.rgb, base.a, m.metallic, m.roughness, m.specular);
#ifdef METALLIC_ROUGHNESS_TEXTURES
    if m.metallic_roughness_texture != NO_TEXTURE {
        let mr = sample_texture(m.metallic_roughness_texture, uv, false);
        out.roughness *= mr.g;
        out.metallic *= mr.b;
    }
#endif
#ifndef METALLIC
    out.metallic = 0.0;
#endif
#ifdef UNLIT
#ifndef PLANTED_UNLIT_AS_LIT
    // Unlit: the look is radiance (material_unlit_color); nothing is reflected.
    // (The planted twin, test only, shades it as a lit surface: the old loader.)
    if (m.flags & MATERIAL_UNLIT) != 0u {
        out.base_color = vec3<f32>(0.0);
        out.metallic = 0.0;
        out.specular = 0.0;
    }
#endif
#endif
#ifndef SPECULAR
    out.specular = 0.0;
#endif
    return out;
}

// Emitted radiance of a material at uv, before the front-face rule.
fn material_emission(material_index: u32, uv: vec2<f32>) -> vec3<f32> {
    return material_emission_of(materials[material_index], uv);
}

// The same for a material record (last frame's, for a light point made with `previous`).
fn material_emission_of(m: Material, uv: vec2<f32>) -> vec3<f32> {
    var e = m.emission;
#ifdef EMISSIVE_TEXTURES
    if m.emissive_texture != NO_TEXTURE {
        e *= sample_texture(m.emissive_texture, uv, true).rgb;
    }
#endif
    return e;
}

#ifdef UNLIT
// KHR_materials_unlit: base colour × texture, seen directly as radiance (docs/src/scenes.md,
// "Emitters and materials"). Not a light: no light table entry, so nothing else receives it.
// Blended, it covers the share alpha (glTF's α·colour + (1 − α)·behind: the layer passes the rest).
fn material_unlit_color(material_index: u32, uv: vec2<f32>) -> vec3<f32> {
    let c = base_color_at(material_index, uv);
    var blended = (materials[material_index].flags & MATERIAL_ALPHA_BLEND) != 0u;
#ifdef PLANTED_UNLIT_UNBLENDED
    blended = false;  // test only: the colour at full strength whatever its alpha (before)
#endif
    return c.rgb * select(1.0, clamp(c.a, 0.0, 1.0), blended);
}
#endif

#ifdef TRANSPARENCY
// A transparent surface as a thin layer (docs/src/transparency.md, "The thin-layer model"). With
// coverage a (alpha BLEND, else 1) and transmission t (KHR_materials_transmission × its texture, of
// the dielectric share: × (1 − metallic)), of the light reaching it
//   * `solid` = a·(1 − t) meets the surface as if it were opaque: shaded with its BRDF, blocked;
//   * `glass` = a·t meets a smooth dielectric interface (glTF's thin-walled transmission):
//     the share F(θ) is reflected (the specular lobe of the layer's roughness: layer_walk.wgsl
//     adds it to camera rays) and (1 − F(θ))·baseColour goes straight on, unrefracted;
//   * the rest, 1 − a, goes straight on untouched.
// pass_through = (1 − a) + glass·(1 − F(θ))·baseColour, θ between the ray and the layer's
// normal. Shadow rays multiply pass_through along the segment; camera and path rays go
// through the layers by layer_walk.wgsl's two walks, which estimate the same transport.
struct Layer {
    solid: f32,
    glass: f32,
    pass_through: vec3<f32>,
}

fn opaque_layer() -> Layer {
    return Layer(1.0, 0.0, vec3<f32>(0.0));
}

// The layer of a material at uv for a ray crossing it at cos_theta to its normal.
fn material_layer(material_index: u32, uv: vec2<f32>, cos_theta: f32) -> Layer {
    let m = materials[material_index];
    if (m.flags & MATERIAL_TRANSPARENT) == 0u {
        return opaque_layer();
    }
#ifdef PLANTED_OPAQUE_GLASS
    return opaque_layer();  // test only: glass and BLEND as opaque (the old loader)
#endif
    let ms = eval_material(material_index, uv);
    var coverage = 1.0;
    if (m.flags & MATERIAL_ALPHA_BLEND) != 0u {
        coverage = clamp(ms.alpha, 0.0, 1.0);
    }
    var t = m.transmission;
    if m.transmission_texture != NO_TEXTURE {
        t *= sample_texture(m.transmission_texture, uv, false).r;
    }
    t = clamp(t, 0.0, 1.0) * (1.0 - ms.metallic);
    let glass = coverage * t;
    var reflected = 0.0;
#ifdef SPECULAR
#ifndef PLANTED_NO_FRESNEL
    // (The planted twin, test only: the layer before Fresnel, all of `glass` passing.)
    reflected = clamp(dielectric_fresnel(ms.specular, cos_theta), 0.0, 1.0);
#endif
#endif
    let tint = clamp(ms.base_color, vec3<f32>(0.0), vec3<f32>(1.0));
    return Layer(coverage * (1.0 - t), glass, vec3<f32>(1.0 - coverage) + glass * (1.0 - reflected) * tint);
}

// The layer a ray along `dir` (any length: shadow rays span their segment) meets at a
// point of a triangle, θ from the shading normal (the one camera rays shade with).
fn triangle_layer(tri_index: u32, u: f32, v: f32, dir: vec3<f32>) -> Layer {
    let cos_theta = abs(dot(shading_normal_at(tri_index, u, v), safe_normalize(dir, vec3<f32>(0.0))));
    return material_layer(triangles[tri_index].material, triangle_uv(tri_index, u, v), cos_theta);
}
#endif

// Geometric normal of a triangle by its counter-clockwise winding (the emitting side).
fn triangle_normal(tri: Triangle) -> vec3<f32> {
    return safe_normalize(cross(tri.p1 - tri.p0, tri.p2 - tri.p0), vec3<f32>(0.0, 1.0, 0.0));
}

// The interpolated vertex normal at barycentrics (u, v), or the geometric one without
// normals (either side: callers orient it).
fn shading_normal_at(tri_index: u32, u: f32, v: f32) -> vec3<f32> {
    let ng = triangle_normal(triangles[tri_index]);
    let s = shading[tri_index];
    if s.has_normals == 0u {
        return ng;
    }
    return safe_normalize(oct_decode(s.normals[0]) * (1.0 - u - v) + oct_decode(s.normals[1]) * u + oct_decode(s.normals[2]) * v, ng);
}

// Everything a shading point needs from a hit (G-buffer resolve and reference renderer).
struct HitSurface {
    position: vec3<f32>,
    normal: vec3<f32>,      // shading normal, on the viewer's side
    geo_normal: vec3<f32>,  // geometric normal, on the viewer's side
    front_facing: bool,     // the viewer sees the counter-clockwise (emitting) side
    uv: vec2<f32>,
    material: u32,
}

fn hit_surface(tri_index: u32, u: f32, v: f32, viewer: vec3<f32>) -> HitSurface {
    let tri = triangles[tri_index];
    let w = 1.0 - u - v;
    let position = tri.p0 * w + tri.p1 * u + tri.p2 * v;
    let ng = triangle_normal(tri);
    let to_viewer = viewer - position;
    let front = dot(ng, to_viewer) >= 0.0;
    let ng_f = select(-ng, ng, front);
    var ns = shading_normal_at(tri_index, u, v);
    ns = select(-ns, ns, front);
    // An interpolated normal that faces away from the viewer would make the BRDF
    // undefined; fall back to the geometric one (the usual "normal flip" fix).
    if dot(ns, to_viewer) <= 0.0 {
        ns = ng_f;
    }
    return HitSurface(position, ns, ng_f, front, triangle_uv(tri_index, u, v), tri.material);
}

// The BRDF of the material at a hit.
fn hit_brdf(hs: HitSurface) -> Brdf {
    let m = eval_material(hs.material, hs.uv);
    return make_brdf(m.base_color, m.metallic, m.roughness, m.specular);
}

// Radiance leaving a hit toward the viewer: emitters shine from their front face only,
// from both faces when double-sided (docs/src/scenes.md, "Emitters and materials").
fn emission_toward_viewer(hs: HitSurface) -> vec3<f32> {
    let m = materials[hs.material];
    if !hs.front_facing && (m.flags & MATERIAL_DOUBLE_SIDED) == 0u {
        return vec3<f32>(0.0);
    }
#ifdef UNLIT
#ifndef PLANTED_UNLIT_AS_LIT
    if (m.flags & MATERIAL_UNLIT) != 0u {
        return material_unlit_color(hs.material, hs.uv) + material_emission(hs.material, hs.uv);
    }
#endif
#endif
    return material_emission(hs.material, hs.uv);
}

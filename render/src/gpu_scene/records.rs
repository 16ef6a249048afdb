//! The GPU records of a scene, built on upload and rebuilt by `update.rs`: triangles and
//! their shading data in BVH order, materials, light-table slots and light geometry.

use glam::Vec3;

use crate::gpu_types::*;
use crate::scene::lights::LightTable;
use crate::scene::{AlphaMode, Scene, TextureRef, UvTransform, Wrap};

/// Octahedral encoding into two snorm16, bit-identical to `oct_encode` in math.wgsl.
pub fn oct_encode(n: Vec3) -> u32 {
    let l1 = n.x.abs() + n.y.abs() + n.z.abs();
    let mut p = glam::Vec2::new(n.x, n.y) / l1.max(1e-20);
    if n.z < 0.0 {
        let s = glam::Vec2::new(
            if p.x >= 0.0 { 1.0 } else { -1.0 },
            if p.y >= 0.0 { 1.0 } else { -1.0 },
        );
        p = (glam::Vec2::ONE - glam::Vec2::new(p.y.abs(), p.x.abs())) * s;
    }
    let snorm = |x: f32| ((x.clamp(-1.0, 1.0) * 32767.0).round() as i16) as u16 as u32;
    snorm(p.x) | (snorm(p.y) << 16)
}

pub(super) fn wrap_code(w: Wrap) -> u32 {
    match w {
        Wrap::Repeat => 0,
        Wrap::ClampToEdge => 1,
        Wrap::MirroredRepeat => 2,
    }
}

/// Which light-table slots a scene keeps at zero power: for a dynamic scene every material
/// that emits now or is animated, and every punctual light; nothing for a static scene.
pub(super) fn light_slots(scene: &Scene) -> (Vec<bool>, bool) {
    let Some(anim) = &scene.animation else {
        return (Vec::new(), false);
    };
    let mut kept: Vec<bool> = scene.materials.iter().map(|m| m.is_emissive()).collect();
    for binding in &anim.materials {
        if let Some(k) = kept.get_mut(binding.material) {
            *k = true;
        }
    }
    (kept, true)
}

/// Triangles and their shading data in BVH order.
pub(super) fn triangle_records(
    scene: &Scene,
    order: &[u32],
    positions: &[[Vec3; 3]],
    triangle_light: &[u32],
) -> (Vec<GpuTriangle>, Vec<GpuTriangleShading>) {
    order
        .iter()
        .enumerate()
        .map(|(bvh_index, &source)| {
            triangle_record(
                scene,
                source,
                positions[source as usize],
                triangle_light[bvh_index],
            )
        })
        .unzip()
}

/// Scene triangle `source` at `positions`, holding light entry `light` (or `NO_LIGHT`).
pub(super) fn triangle_record(
    scene: &Scene,
    source: u32,
    [p0, p1, p2]: [Vec3; 3],
    light: u32,
) -> (GpuTriangle, GpuTriangleShading) {
    let tri = &scene.triangles[source as usize];
    let verts = tri.indices.map(|i| scene.vertices[i as usize]);
    let has_normals = verts.iter().all(|v| v.normal.length_squared() > 0.0);
    let triangle = GpuTriangle {
        p0: p0.into(),
        material: tri.material,
        p1: p1.into(),
        light,
        p2: p2.into(),
        source_index: source,
    };
    let shading = GpuTriangleShading {
        normals: verts.map(|v| {
            if has_normals {
                oct_encode(v.normal.normalize())
            } else {
                0
            }
        }),
        has_normals: has_normals as u32,
        uvs: verts.map(|v| v.uv.into()),
    };
    (triangle, shading)
}

/// The texture records and the shared texel buffer: record `i` is scene texture `i`
/// untransformed, then one record per distinct (texture, transform) pair of
/// [`transformed_slots`], over the same texels with that transform.
pub(super) fn texture_records(scene: &Scene) -> (Vec<GpuTexture>, Vec<u32>) {
    let mut texels: Vec<u32> = Vec::new();
    let mut records = Vec::with_capacity(scene.textures.len());
    for t in &scene.textures {
        let wrap = wrap_code(t.wrap_u) | (wrap_code(t.wrap_v) << 2);
        records.push(GpuTexture {
            placement: [
                texels.len() as u32 | (wrap << TEXEL_OFFSET_BITS),
                t.width | (t.height << 16),
            ],
            uv_transform: UvTransform::IDENTITY.columns,
        });
        texels.extend(t.texels.iter().map(|c| u32::from_le_bytes(*c)));
    }
    for r in transformed_slots(scene) {
        if let Some(&base) = records.get(r.texture as usize) {
            records.push(GpuTexture {
                uv_transform: r.transform.columns,
                ..base
            });
        }
    }
    (records, texels)
}

/// Every distinct (texture, non-identity transform) of the materials' slots, in material
/// and slot order: the same list on upload and on every material update.
fn transformed_slots(scene: &Scene) -> Vec<TextureRef> {
    let mut slots: Vec<TextureRef> = Vec::new();
    for m in &scene.materials {
        for (_, r) in m.texture_slots() {
            let Some(r) = r.filter(|r| !r.transform.is_identity()) else {
                continue;
            };
            if !slots.iter().any(|s| same_record(s, &r)) {
                slots.push(r);
            }
        }
    }
    slots
}

fn same_record(a: &TextureRef, b: &TextureRef) -> bool {
    a.texture == b.texture && a.transform == b.transform
}

/// The record a slot samples (see [`texture_records`]).
fn record_index(scene: &Scene, transformed: &[TextureRef], r: TextureRef) -> u32 {
    if r.transform.is_identity() {
        return r.texture;
    }
    transformed
        .iter()
        .position(|s| same_record(s, &r))
        .map_or(r.texture, |i| (scene.textures.len() + i) as u32)
}

pub(super) fn gpu_materials(scene: &Scene) -> Vec<GpuMaterial> {
    let transformed = transformed_slots(scene);
    let tex_index =
        |r: Option<TextureRef>| r.map_or(NO_TEXTURE, |r| record_index(scene, &transformed, r));
    scene
        .materials
        .iter()
        .map(|m| {
            let mut flags = 0;
            if m.double_sided {
                flags |= MATERIAL_DOUBLE_SIDED;
            }
            let mut alpha_cutoff = 0.0;
            if let AlphaMode::Mask(cutoff) = m.alpha_mode {
                flags |= MATERIAL_ALPHA_MASK;
                alpha_cutoff = cutoff;
            }
            if m.alpha_mode == AlphaMode::Blend {
                flags |= MATERIAL_ALPHA_BLEND;
            }
            if m.is_transparent() {
                flags |= MATERIAL_TRANSPARENT;
            }
            if m.unlit {
                flags |= MATERIAL_UNLIT;
            }
            GpuMaterial {
                base_color: m.base_color.into(),
                emission: m.emission.into(),
                metallic: m.metallic,
                roughness: m.roughness,
                specular: m.specular,
                alpha_cutoff,
                flags,
                base_color_texture: tex_index(m.base_color_texture),
                metallic_roughness_texture: tex_index(m.metallic_roughness_texture),
                emissive_texture: tex_index(m.emissive_texture),
                transmission_texture: tex_index(m.transmission_texture),
                transmission: m.transmission,
                _pad: [0; 3],
            }
        })
        .collect()
}

/// (source triangle, area) of every triangle entry of `table`.
pub(super) fn light_areas(
    scene: &Scene,
    order: &[u32],
    table: &LightTable,
) -> Vec<Option<(u32, f32)>> {
    table
        .lights
        .iter()
        .map(|l| {
            (l.kind_prim >> LIGHT_KIND_SHIFT == LIGHT_KIND_TRIANGLE).then(|| {
                let source = order[(l.kind_prim & LIGHT_PRIM_MASK) as usize];
                let [a, b, c] = scene.triangle_positions(source as usize);
                (source, 0.5 * (b - a).cross(c - a).length())
            })
        })
        .collect()
}

/// Per light entry: (is a triangle, BVH triangle or punctual index), `None` for the
/// environment (a direction, no point).
pub(super) fn geometry_kind(l: &GpuLight) -> Option<(bool, u32)> {
    let index = l.kind_prim & LIGHT_PRIM_MASK;
    match l.kind_prim >> LIGHT_KIND_SHIFT {
        LIGHT_KIND_TRIANGLE => Some((true, index)),
        LIGHT_KIND_PUNCTUAL => Some((false, index)),
        _ => None,
    }
}

/// Per light entry: its triangle's corners, a punctual light's position three times, or
/// `None` for the environment.
pub(super) fn light_geometry(
    lights: &LightTable,
    triangles: &[GpuTriangle],
) -> Vec<Option<[Vec3; 3]>> {
    lights
        .lights
        .iter()
        .map(|l| {
            geometry_kind(l).map(|(is_triangle, index)| {
                if is_triangle {
                    let t = &triangles[index as usize];
                    [t.p0, t.p1, t.p2].map(Vec3::from)
                } else {
                    [Vec3::from(lights.punctual[index as usize].position); 3]
                }
            })
        })
        .collect()
}

/// How a light entry emits, for the light samplers (`light_sampler.rs`): a one- or
/// two-sided triangle or a punctual light (emits all around: two-sided), or a light with
/// no position (the environment, a directional light).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightShape {
    OneSided,
    TwoSided,
    Infinite,
}

pub(super) fn light_shapes(
    lights: &LightTable,
    triangles: &[GpuTriangle],
    materials: &[GpuMaterial],
) -> Vec<LightShape> {
    lights
        .lights
        .iter()
        .map(|l| match geometry_kind(l) {
            None => LightShape::Infinite,
            Some((true, index)) => {
                let material = materials.get(triangles[index as usize].material as usize);
                if material.is_some_and(|m| m.flags & MATERIAL_DOUBLE_SIDED != 0) {
                    LightShape::TwoSided
                } else {
                    LightShape::OneSided
                }
            }
            Some((false, index)) => {
                if lights.punctual[index as usize].kind == PUNCTUAL_DIRECTIONAL {
                    LightShape::Infinite
                } else {
                    LightShape::TwoSided
                }
            }
        })
        .collect()
}

//! The power-proportional light table (docs/src/ris.md, "Light sampling"): one entry per emissive
//! triangle and per punctual light (and one for the environment), picked with probability power /
//! total through an alias table (Vose's method) so the shader samples a light in O(1) with two
//! random numbers.
//!
//! Entries with zero, negative or non-finite (in f32) power or area never enter the table: a light that can
//! be picked but contributes nothing only wastes candidates, and a degenerate triangle has
//! no area to put the 1/area source pdf on.

use glam::{DVec3, Vec3};

use super::{Material, PunctualKind, PunctualLight, Scene, Texture};
use crate::alias::alias_slots;
use crate::gpu_types::{
    GpuLight, GpuPunctualLight, LIGHT_KIND_ENVIRONMENT, LIGHT_KIND_PUNCTUAL, LIGHT_KIND_SHIFT,
    LIGHT_KIND_TRIANGLE, LIGHT_PRIM_MASK, NO_LIGHT, PUNCTUAL_DIRECTIONAL, PUNCTUAL_POINT,
    PUNCTUAL_SPOT,
};
use crate::image::luminance;

pub struct LightTable {
    /// Table entries: emissive triangles in BVH order, then punctual lights in scene order.
    pub lights: Vec<GpuLight>,
    /// Per triangle in BVH order: its index in `lights`, or `NO_LIGHT`.
    pub triangle_light: Vec<u32>,
    /// Every punctual light of the scene, in scene order (entries of `lights` point here).
    pub punctual: Vec<GpuPunctualLight>,
    /// Sum of the entries' powers (W for physical units).
    pub total_power: f64,
    /// Smallest and largest entry power, `None` for an empty table (for the UI and logs).
    pub power_range: Option<(f32, f32)>,
    /// The environment's entry, `NO_LIGHT` without an environment or when it is black.
    pub environment_light: u32,
    /// `(kind_prim, power)` of every entry, to rebuild the table with another
    /// environment share (`with_environment_share`).
    pub entries: Vec<(u32, f64)>,
}

impl LightTable {
    /// `triangle_order[i]` is the scene triangle at BVH position `i` (see `Bvh`).
    pub fn build(scene: &Scene, triangle_order: &[u32]) -> LightTable {
        Self::build_with_slots(scene, triangle_order, &[], false)
    }

    /// As `build`, but every triangle of a material with `kept_materials[m]` (and, with
    /// `keep_punctual`, every punctual light) keeps its entry even at zero power, with
    /// select_pdf 0 and no alias slot pointing at it. Dynamic scenes keep every light that
    /// can ever emit, so an entry's index is the light's identity for the whole animation:
    /// a stored (light, uv) sample still names the same light after others switched off.
    pub fn build_with_slots(
        scene: &Scene,
        triangle_order: &[u32],
        kept_materials: &[bool],
        keep_punctual: bool,
    ) -> LightTable {
        let kept = |m: usize| kept_materials.get(m).copied().unwrap_or(false);
        let radiance: Vec<Option<Vec3>> = scene
            .materials
            .iter()
            .map(|m| emitted_radiance(m, &scene.textures))
            .collect();
        let mut entries: Vec<(u32, f64)> = Vec::new();
        let mut triangle_light = vec![NO_LIGHT; triangle_order.len()];
        for (bvh_index, &source) in triangle_order.iter().enumerate() {
            let material = scene.triangles[source as usize].material as usize;
            let le = match radiance[material] {
                Some(le) => le,
                None if kept(material) => Vec3::ZERO,
                None => continue,
            };
            let sides = if scene.materials[material].double_sided {
                2.0
            } else {
                1.0
            };
            let area = triangle_area(scene.triangle_positions(source as usize));
            let power = area * luminance(le.to_array()) as f64 * std::f64::consts::PI * sides;
            // The shader divides by the f32 area, so that must be usable too.
            let usable = is_usable(area) && is_usable(power);
            if usable || kept(material) {
                assert!(
                    bvh_index as u32 <= LIGHT_PRIM_MASK,
                    "too many triangles for a light index"
                );
                triangle_light[bvh_index] = entries.len() as u32;
                entries.push((
                    LIGHT_KIND_TRIANGLE << LIGHT_KIND_SHIFT | bvh_index as u32,
                    if usable { power } else { 0.0 },
                ));
            }
        }
        // Directional lights are aimed at the scene: their power is what crosses a disc the
        // size of the scene (R = half the bounds' diagonal), as in PBRT's DistantLight.
        let scene_radius = 0.5 * scene.bounds().extent().length() as f64;
        for (i, light) in scene.punctual_lights.iter().enumerate() {
            let power = punctual_power(light, scene_radius);
            if is_usable(power) || keep_punctual {
                let power = if is_usable(power) { power } else { 0.0 };
                entries.push((LIGHT_KIND_PUNCTUAL << LIGHT_KIND_SHIFT | i as u32, power));
            }
        }
        // The environment's share (docs/src/environment.md, "Split with the other lights"): its
        // power is π R² ∫ L dω, what crosses a disc the size of the scene from every direction
        // (PBRT-v4's ImageInfiniteLight::Phi), the same measure as a directional light's.
        let mut environment_light = NO_LIGHT;
        if let Some(env) = &scene.environment {
            let power =
                std::f64::consts::PI * scene_radius * scene_radius * env.luminance_integral();
            if is_usable(power) {
                environment_light = entries.len() as u32;
                entries.push((LIGHT_KIND_ENVIRONMENT << LIGHT_KIND_SHIFT, power));
            }
        }
        let power_range = entries.iter().filter(|e| e.1 > 0.0).fold(
            None,
            |range: Option<(f32, f32)>, &(_, p)| {
                let p = p as f32;
                Some(range.map_or((p, p), |(lo, hi)| (lo.min(p), hi.max(p))))
            },
        );
        let (lights, total_power) = alias_table(&entries);
        LightTable {
            lights,
            triangle_light,
            punctual: scene.punctual_lights.iter().map(gpu_punctual).collect(),
            total_power,
            power_range,
            environment_light,
            entries,
        }
    }

    /// Entries that can be picked (zero-power kept slots cannot): the shader samples the
    /// table only when this is positive.
    pub fn sampleable(&self) -> bool {
        self.total_power > 0.0
    }

    /// Picks an entry exactly as the shader does: `(index, select_pdf)` from two uniform
    /// numbers in [0, 1); `(NO_LIGHT, 0)` for an empty table.
    pub fn sample(&self, u_slot: f32, u_alias: f32) -> (u32, f32) {
        let n = self.lights.len() as u32;
        if n == 0 {
            return (NO_LIGHT, 0.0);
        }
        let slot = ((u_slot * n as f32) as u32).min(n - 1);
        let entry = &self.lights[slot as usize];
        let index = if u_alias < entry.alias_threshold {
            slot
        } else {
            entry.alias_index
        };
        (index, self.lights[index as usize].select_pdf)
    }
}

/// Positive and finite as the f32 the GPU will see.
fn is_usable(x: f64) -> bool {
    let x = x as f32;
    x > 0.0 && x.is_finite()
}

/// Emitted radiance of a material, averaged over its emissive texture; `None` when it
/// cannot emit.
fn emitted_radiance(material: &Material, textures: &[Texture]) -> Option<Vec3> {
    if !material.is_emissive() {
        return None;
    }
    let mean = material
        .emissive_texture
        .and_then(|t| textures.get(t.texture as usize))
        .map_or(Vec3::ONE, mean_linear_colour);
    Some(material.emission * mean)
}

/// Per-channel mean of a texture's sRGB-decoded texels (alpha ignored). The mean keeps the
/// colour, so the luminance of `emission × mean` is the texture-averaged luminance.
fn mean_linear_colour(texture: &Texture) -> Vec3 {
    if texture.texels.is_empty() {
        return Vec3::ZERO;
    }
    // A 256-entry table: `powf` per channel of a 2048² texture was most of a model's
    // light-table time (docs/src/load-time.md, "What was slow, and what changed"); the table
    // holds the same f64 values.
    let linear: [f64; 256] = std::array::from_fn(|c| srgb_to_linear(c as u8));
    let sum = texture.texels.iter().fold(DVec3::ZERO, |acc, t| {
        acc + DVec3::new(
            linear[t[0] as usize],
            linear[t[1] as usize],
            linear[t[2] as usize],
        )
    });
    (sum / texture.texels.len() as f64).as_vec3()
}

/// The sRGB transfer function (IEC 61966-2-1), as the GPU's `*Srgb` texture formats apply it.
fn srgb_to_linear(c: u8) -> f64 {
    let c = c as f64 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Area in f64, so thin triangles of a large scene do not round to zero power.
fn triangle_area(p: [Vec3; 3]) -> f64 {
    let [a, b, c] = p.map(|v| v.as_dvec3());
    0.5 * (b - a).cross(c - a).length()
}

/// Emitted power, the same measure as a triangle's area · luminance(Le) · π.
fn punctual_power(light: &PunctualLight, scene_radius: f64) -> f64 {
    use std::f64::consts::PI;
    let lum = luminance(light.intensity.to_array()) as f64;
    match light.kind {
        PunctualKind::Point => 4.0 * PI * lum,
        PunctualKind::Spot { outer_cone, .. } => 2.0 * PI * (1.0 - (outer_cone as f64).cos()) * lum,
        PunctualKind::Directional => lum * PI * scene_radius * scene_radius,
    }
}

/// Point and directional lights get an all-accepting cone (cos = −1); shaders branch on
/// `kind` anyway.
pub(crate) fn gpu_punctual(light: &PunctualLight) -> GpuPunctualLight {
    let (kind, cos_outer, cos_inner) = match light.kind {
        PunctualKind::Point => (PUNCTUAL_POINT, -1.0, -1.0),
        PunctualKind::Spot {
            inner_cone,
            outer_cone,
        } => (PUNCTUAL_SPOT, outer_cone.cos(), inner_cone.cos()),
        PunctualKind::Directional => (PUNCTUAL_DIRECTIONAL, -1.0, -1.0),
    };
    GpuPunctualLight {
        position: light.position.to_array(),
        kind,
        // glTF lights point down their local −Z when nothing else is known.
        direction: light.direction.normalize_or(Vec3::NEG_Z).to_array(),
        range: light.range.unwrap_or(0.0),
        intensity: light.intensity.to_array(),
        cos_outer,
        cos_inner,
        _pad: [0.0; 3],
    }
}

/// The table of `entries` with the environment (entry `environment_light`) picked with
/// probability `share` and the other entries sharing 1 − share in proportion to their
/// power. `share` 0, no environment or nothing else to share with: the power-proportional
/// table. Rebuilding costs one alias pass, so the setting can change between frames.
pub fn with_environment_share(
    entries: &[(u32, f64)],
    environment_light: u32,
    share: f32,
) -> Vec<GpuLight> {
    let env = environment_light as usize;
    let others: f64 = entries
        .iter()
        .enumerate()
        .filter(|(i, _)| *i != env)
        .map(|(_, e)| e.1)
        .sum();
    if env >= entries.len() || !(share > 0.0 && share < 1.0) || others <= 0.0 {
        return alias_table(entries).0;
    }
    let share = share as f64;
    let mut weighted = entries.to_vec();
    // env / (env + others) = share.
    weighted[env].1 = others * share / (1.0 - share);
    alias_table(&weighted).0
}

/// The light entries of `(kind_prim, power)` pairs with their alias slots (see
/// `alias.rs`). Returns the entries and the total power.
fn alias_table(entries: &[(u32, f64)]) -> (Vec<GpuLight>, f64) {
    let powers: Vec<f64> = entries.iter().map(|e| e.1).collect();
    let (slots, total) = alias_slots(&powers);
    // Only kept zero-power slots (every light of a dynamic scene off): nothing can be
    // picked (the renderer then samples no light at all), and no 0/0 reaches a select_pdf.
    let sampleable = total > 0.0;
    let lights = entries
        .iter()
        .zip(slots)
        .map(|(&(kind_prim, power), slot)| GpuLight {
            kind_prim,
            select_pdf: if sampleable {
                (power / total) as f32
            } else {
                0.0
            },
            alias_threshold: slot.threshold,
            alias_index: slot.alias,
        })
        .collect();
    (lights, total)
}

#[cfg(test)]
mod tests;

//! Which effects a scene (and the current settings) call for. Each effect is a WGSL
//! `#ifdef` name: pipelines are compiled with exactly the set in use, so a Lambertian
//! Cornell box never compiles GGX, punctual-light or texture code
//! (docs/src/specialisation.md). Chosen over WGSL `override` constants because overrides leave the
//! dead code in the module (and in the lavapipe/driver compile), and over naga_oil
//! because one 100-line preprocessor is easier to read than a composition framework.

use std::collections::BTreeSet;
use std::fmt;

use crate::light_probe::{self, LightProbe};
use crate::scene::{AlphaMode, Scene};
use crate::settings::{LightSampler, Settings};
use crate::shader_constants::{LIGHT_TILE_COUNT, LIGHT_TILE_SIZE};

/// The light count from which `light_sampler=auto` presamples light tiles. Below it the
/// fixed cost of presampling LIGHT_TILE_COUNT × LIGHT_TILE_SIZE lights every frame exceeds
/// what the smaller working set saves; measured by the tiles on/off sweep over
/// `builtin:many-lights:N` (docs/src/measured/many-lights.md, "Light tiles: where they pay").
pub const LIGHT_TILES_BREAK_EVEN: usize = 16384;

/// `light_sampler=auto` takes the light BVH where the load-time probe (`light_probe.rs`)
/// finds that a sampler by distance would need at least this many times fewer samples than
/// the power table, and the scene has at least `LIGHT_BVH_MIN_LIGHTS` lights. The walk
/// made the initial pass 2.7–5.9× the table's at 2^20 (docs/src/measured/many-lights.md, "Light
/// samplers at scale"): a gain of this size is what it must bring. Calibrated on the probe's
/// figures for the measured scenes (docs/src/light-samplers.md, "Choosing"): the lowest where the
/// BVH won at equal time is 24 (`city:1024`; 24–36 over `city:N`), the highest where it lost
/// 6.2 (`many-lights:65536`; `concourse` 4.5); the threshold is their geometric mean.
pub const LIGHT_BVH_MIN_LOCALITY: f32 = 12.0;
/// Light candidates per pixel when `auto` takes the BVH (at most: `light_candidates` caps
/// it). Chosen by equal-time gain over the tiles under ReSTIR, over 12 seeds, on `city:N` at
/// 2^14, 2^17 and 2^20 (docs/src/measured/many-lights.md, "How many candidates auto draws"):
/// 8 beat 4 in every cell and had the highest geometric mean over them, 16 level with it at
/// twice the walk. The one-seed figures it was first chosen on (4, at "≥ 5×") did not hold
/// over seeds.
pub const AUTO_BVH_CANDIDATES: u32 = 8;
/// Below this many lights the BVH was not measured against the table; `auto` keeps the
/// table or the tiles there.
pub const LIGHT_BVH_MIN_LIGHTS: usize = 1024;

/// Whether `light_sampler=auto` takes the light BVH for a scene with features `f`: its
/// probe finds the lights local and there are enough of them. Cheap: the renderer asks
/// every frame (`Renderer::effective_settings` caps the candidates then).
pub fn auto_takes_bvh(f: &SceneFeatures) -> bool {
    f.emissive_triangles + f.punctual_lights >= LIGHT_BVH_MIN_LIGHTS
        && f.light_probe
            .is_some_and(|p| p.locality() >= LIGHT_BVH_MIN_LOCALITY)
}

/// The sampler `choice` means for a scene, and why: `auto` by the measurements
/// (docs/src/measured/many-lights.md, "Light tiles: where they pay" and "Light samplers at scale")
/// and the scene's probe.
pub fn resolve_light_sampler(f: &SceneFeatures, choice: LightSampler) -> (LightSampler, String) {
    let lights = f.emissive_triangles + f.punctual_lights;
    let probe = match f.light_probe {
        Some(p) => format!(
            "the probe at {} points: sampling by distance would need {:.1}× fewer samples than by power",
            p.points,
            p.locality()
        ),
        None => "no probe (no lights with a position, or no surfaces)".to_string(),
    };
    match choice {
        LightSampler::Auto if auto_takes_bvh(f) => (
            LightSampler::Bvh,
            format!(
                "auto: {lights} lights; {probe} (≥ {LIGHT_BVH_MIN_LOCALITY} pays for the walk)"
            ),
        ),
        LightSampler::Auto if lights >= LIGHT_TILES_BREAK_EVEN => (
            LightSampler::Tiles,
            format!(
                "auto: {lights} lights ≥ {LIGHT_TILES_BREAK_EVEN}, where presampling pays; {probe} (< {LIGHT_BVH_MIN_LOCALITY}: not worth the walk)"
            ),
        ),
        LightSampler::Auto => (
            LightSampler::Power,
            format!(
                "auto: {lights} lights < {LIGHT_TILES_BREAK_EVEN}: presampling would cost more than it saves; {probe}"
            ),
        ),
        other => (other, format!("light_sampler={}", other.name())),
    }
}

/// The light samplers' effects, alternatives of which a frame uses at most one; the tiles
/// first (the general pipeline's).
const LIGHT_SAMPLER_EFFECTS: [Effect; 3] = [Effect::LightTiles, Effect::Regir, Effect::LightBvh];

/// What effect detection needs to know about a scene, counted once at load time.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SceneFeatures {
    pub emissive_triangles: usize,
    pub emissive_textured_materials: usize,
    pub punctual_lights: usize,
    pub specular_materials: usize,
    pub metallic_materials: usize,
    pub base_color_textured_materials: usize,
    pub metallic_roughness_textured_materials: usize,
    /// Materials with a KHR_texture_transform other than the identity on some slot.
    pub texture_transformed_materials: usize,
    pub alpha_masked_materials: usize,
    /// Materials light passes through (alpha BLEND or transmission).
    pub transparent_materials: usize,
    /// KHR_materials_unlit materials.
    pub unlit_materials: usize,
    /// False only when occlusion is provably impossible (see `can_occlude`).
    pub can_occlude: bool,
    /// An environment lights the scene and shows where camera rays miss
    /// (docs/src/environment.md).
    pub environment: bool,
    /// The scene has an animation (moving geometry or changing lights).
    pub animated: bool,
    /// What a sampler by distance would gain over the power table here (`light_probe.rs`;
    /// `None` without lights with a position): `auto`'s choice of the light BVH.
    pub light_probe: Option<LightProbe>,
}

impl SceneFeatures {
    /// Counts over the materials that some triangle actually uses.
    pub fn of(scene: &Scene) -> SceneFeatures {
        let mut used = vec![false; scene.materials.len()];
        for t in &scene.triangles {
            if let Some(u) = used.get_mut(t.material as usize) {
                *u = true;
            }
        }
        let mats: Vec<_> = scene
            .materials
            .iter()
            .zip(&used)
            .filter(|(_, u)| **u)
            .map(|(m, _)| m)
            .collect();
        let count =
            |f: &dyn Fn(&crate::scene::Material) -> bool| mats.iter().filter(|m| f(m)).count();
        let specular = |m: &crate::scene::Material| m.metallic > 0.0 || m.specular > 0.0;
        SceneFeatures {
            emissive_triangles: potential_emitters(scene),
            emissive_textured_materials: count(&|m| {
                m.is_emissive() && m.emissive_texture.is_some()
            }),
            punctual_lights: scene.punctual_lights.len(),
            specular_materials: count(&specular),
            metallic_materials: count(&|m| m.metallic > 0.0),
            base_color_textured_materials: count(&|m| m.base_color_texture.is_some()),
            metallic_roughness_textured_materials: count(&|m| {
                m.metallic_roughness_texture.is_some() && specular(m)
            }),
            texture_transformed_materials: count(&|m| {
                m.texture_slots()
                    .iter()
                    .any(|(_, r)| r.is_some_and(|r| !r.transform.is_identity()))
            }),
            alpha_masked_materials: count(&|m| matches!(m.alpha_mode, AlphaMode::Mask(_))),
            transparent_materials: count(&|m| m.is_transparent()),
            unlit_materials: count(&|m| m.unlit),
            can_occlude: can_occlude(scene),
            environment: scene.environment.is_some(),
            animated: scene.animation.is_some(),
            light_probe: probe_light_locality(scene),
        }
    }
}

/// `light_probe::probe` over the scene's lights with a position (emissive triangles, point
/// and spot lights, each with its power) seen from its other triangles.
fn probe_light_locality(scene: &Scene) -> Option<LightProbe> {
    use glam::Vec3;
    let pi = std::f32::consts::PI;
    let luminance = |c: Vec3| 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
    let emitter = |t: usize| {
        scene
            .materials
            .get(scene.triangles[t].material as usize)
            .filter(|m| m.is_emissive())
    };
    let mut lights: Vec<(Vec3, f32)> = Vec::new();
    for t in 0..scene.triangles.len() {
        if let Some(m) = emitter(t) {
            let [a, b, c] = scene.triangle_positions(t);
            let area = 0.5 * (b - a).cross(c - a).length();
            let sides = if m.double_sided { 2.0 } else { 1.0 };
            lights.push(((a + b + c) / 3.0, luminance(m.emission) * area * sides * pi));
        }
    }
    for p in &scene.punctual_lights {
        if p.kind != crate::scene::PunctualKind::Directional {
            lights.push((p.position, luminance(p.intensity) * 4.0 * pi));
        }
    }
    light_probe::probe(
        &lights,
        scene.triangles.len(),
        |t| emitter(t).is_none().then(|| scene.triangle_positions(t)),
        light_probe::PROBE_SEED,
    )
}

/// Emissive triangles, counting those of animated materials dark at load time: a light
/// that switches on later needs the area-light code compiled in from the start.
fn potential_emitters(scene: &Scene) -> usize {
    let Some(anim) = &scene.animation else {
        return scene.emissive_triangle_count();
    };
    let mut emits: Vec<bool> = scene.materials.iter().map(|m| m.is_emissive()).collect();
    for b in &anim.materials {
        if let Some(e) = emits.get_mut(b.material) {
            *e = true;
        }
    }
    scene
        .triangles
        .iter()
        .filter(|t| emits.get(t.material as usize).copied().unwrap_or(false))
        .count()
}

/// Above this many triangles the convexity proof is not attempted (it is O(T·V)).
const CONVEXITY_PROOF_LIMIT: usize = 4096;

/// Whether any triangle can block a segment between two surface points. It cannot when
/// every vertex lies on the inner side of every triangle's plane (normal by winding): the
/// scene is then the boundary of one convex region seen from inside (an empty room, a
/// plane under a light), and a segment between two boundary points never crosses the
/// boundary. Anything else, or a scene too large to check, counts as occluding.
fn can_occlude(scene: &Scene) -> bool {
    if scene.triangles.len() > CONVEXITY_PROOF_LIMIT {
        return true;
    }
    let bounds = scene.bounds();
    let eps = bounds.extent().length() * 1e-5;
    for t in 0..scene.triangles.len() {
        let [a, b, c] = scene.triangle_positions(t);
        let n = (b - a).cross(c - a);
        if n.length_squared() <= 0.0 {
            continue; // zero area: blocks nothing
        }
        let n = n.normalize();
        if scene.vertices.iter().any(|v| n.dot(v.position - a) < -eps) {
            return true;
        }
    }
    false
}

/// One row per effect: its variant, its WGSL define (an `#ifdef` name in the shaders) and
/// its name on the command line (`--effects`) and in `--stats`. Why a scene turns it on is
/// `EffectSet::detect`.
macro_rules! effect_table {
    ($( $(#[$meta:meta])* $variant:ident => $define:literal, $name:literal; )*) => {
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub enum Effect {
            $( $(#[$meta])* $variant, )*
        }

        impl Effect {
            pub const ALL: [Effect; [$( Effect::$variant ),*].len()] = [$( Effect::$variant ),*];

            /// The WGSL define.
            pub fn define(self) -> &'static str {
                match self { $( Effect::$variant => $define, )* }
            }

            /// Lower-case name used on the command line (`--effects`) and in stats.
            pub fn name(self) -> &'static str {
                match self { $( Effect::$variant => $name, )* }
            }
        }
    };
}

effect_table! {
    AreaLights => "AREA_LIGHTS", "area-lights";
    EmissiveTextures => "EMISSIVE_TEXTURES", "emissive-textures";
    PunctualLights => "PUNCTUAL_LIGHTS", "punctual-lights";
    /// The GGX lobe (some material has specularFactor > 0 or metallic > 0).
    Specular => "SPECULAR", "specular";
    Metallic => "METALLIC", "metallic";
    BaseColorTextures => "BASE_COLOR_TEXTURES", "base-color-textures";
    MetallicRoughnessTextures => "METALLIC_ROUGHNESS_TEXTURES", "metallic-roughness-textures";
    /// A KHR_texture_transform other than the identity: only then does a lookup read its
    /// matrix (docs/src/compile-time.md).
    TextureTransform => "TEXTURE_TRANSFORM", "texture-transform";
    AlphaMask => "ALPHA_MASK", "alpha-mask";
    Transparency => "TRANSPARENCY", "transparency";
    Unlit => "UNLIT", "unlit";
    Shadows => "SHADOWS", "shadows";
    Motion => "MOTION", "motion";
    BsdfCandidates => "BSDF_CANDIDATES", "bsdf-candidates";
    LightTiles => "LIGHT_TILES", "light-tiles";
    /// ReGIR's cells of presampled lights (docs/src/light-samplers.md).
    Regir => "REGIR", "regir";
    /// ReGIR's build samples drawn from the light BVH at each cell's centre.
    RegirFromBvh => "REGIR_FROM_BVH", "regir-from-bvh";
    /// The light BVH (docs/src/light-samplers.md).
    LightBvh => "LIGHT_BVH", "light-bvh";
    /// The light BVH at every light-sampling site past DI's candidates: GI and PT vertices,
    /// transparent layers, the reference (common/vertex_light.wgsl).
    VertexLightBvh => "VERTEX_LIGHT_BVH", "vertex-light-bvh";
    Environment => "ENVIRONMENT", "environment";
    Animation => "ANIMATION", "animation";
}

impl Effect {
    pub fn from_name(name: &str) -> Option<Effect> {
        Effect::ALL.into_iter().find(|e| e.name() == name)
    }
}

/// A set of effects plus, for each, why it is on or off.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EffectSet {
    pub enabled: BTreeSet<Effect>,
    pub reasons: Vec<(Effect, String)>,
    /// `PLANTED_*` defines that break an estimator on purpose, so a test can show that its
    /// detector fires (render/tests/multi_bounce.rs). Empty everywhere else.
    pub planted: BTreeSet<String>,
}

impl fmt::Display for EffectSet {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<_> = self.enabled.iter().map(|e| e.name()).collect();
        write!(f, "{}", names.join(","))?;
        for p in &self.planted {
            write!(f, ",planted:{p}")?;
        }
        Ok(())
    }
}

impl EffectSet {
    /// The general pipeline: every code path compiled in. The light samplers are
    /// alternatives (one draws a frame's candidates), so it keeps the tiles and leaves
    /// ReGIR and the light BVH (at the first vertex and at the others) out.
    pub fn all() -> EffectSet {
        EffectSet {
            enabled: Effect::ALL
                .into_iter()
                .filter(|e| {
                    !LIGHT_SAMPLER_EFFECTS[1..].contains(e)
                        && ![Effect::VertexLightBvh, Effect::RegirFromBvh].contains(e)
                })
                .collect(),
            reasons: Effect::ALL
                .iter()
                .map(|e| (*e, "forced (--effects all)".to_string()))
                .collect(),
            planted: BTreeSet::new(),
        }
    }

    pub fn contains(&self, e: Effect) -> bool {
        self.enabled.contains(&e)
    }

    /// The defines to compile with. `ANY_TEXTURES` guards the shared texture sampler.
    pub fn defines(&self) -> BTreeSet<String> {
        let mut d: BTreeSet<String> = self
            .enabled
            .iter()
            .map(|e| e.define().to_string())
            .collect();
        d.extend(self.planted.iter().cloned());
        if self.contains(Effect::BaseColorTextures)
            || self.contains(Effect::MetallicRoughnessTextures)
            || self.contains(Effect::EmissiveTextures)
            || self.contains(Effect::Transparency)
        {
            d.insert("ANY_TEXTURES".to_string());
        }
        d
    }

    /// Derives what a scene needs under `settings`; `camera_moves` is false while the
    /// camera (and scene) stay still, which drops motion-vector work.
    pub fn detect(scene: &SceneFeatures, settings: &Settings, camera_moves: bool) -> EffectSet {
        let mut set = EffectSet {
            enabled: BTreeSet::new(),
            reasons: Vec::new(),
            planted: BTreeSet::new(),
        };
        let mut decide = |e: Effect, on: bool, yes: String, no: String| {
            if on {
                set.enabled.insert(e);
            }
            set.reasons.push((e, if on { yes } else { no }));
        };
        let f = scene;
        decide(
            Effect::AreaLights,
            f.emissive_triangles > 0,
            format!("{} emissive triangles", f.emissive_triangles),
            "no material emits".into(),
        );
        decide(
            Effect::EmissiveTextures,
            f.emissive_textured_materials > 0,
            format!(
                "{} emissive materials have an emissive texture",
                f.emissive_textured_materials
            ),
            "no emissive texture".into(),
        );
        decide(
            Effect::PunctualLights,
            f.punctual_lights > 0,
            format!("{} KHR_lights_punctual lights", f.punctual_lights),
            "no punctual lights".into(),
        );
        decide(
            Effect::Specular,
            f.specular_materials > 0,
            format!(
                "{} materials have a GGX lobe (specularFactor > 0 or metallic > 0)",
                f.specular_materials
            ),
            "every material has specularFactor 0 and metallic 0 (Lambertian)".into(),
        );
        decide(
            Effect::Metallic,
            f.metallic_materials > 0,
            format!("{} materials are (partly) metallic", f.metallic_materials),
            "no material has metallic > 0".into(),
        );
        decide(
            Effect::BaseColorTextures,
            f.base_color_textured_materials > 0,
            format!(
                "{} materials have a base-colour texture",
                f.base_color_textured_materials
            ),
            "no base-colour texture".into(),
        );
        decide(
            Effect::MetallicRoughnessTextures,
            f.metallic_roughness_textured_materials > 0,
            format!(
                "{} specular materials have a metallic-roughness texture",
                f.metallic_roughness_textured_materials
            ),
            "no metallic-roughness texture on a specular material".into(),
        );
        decide(
            Effect::TextureTransform,
            f.texture_transformed_materials > 0,
            format!(
                "{} materials move a texture's uvs (KHR_texture_transform)",
                f.texture_transformed_materials
            ),
            "no texture transform".into(),
        );
        decide(
            Effect::AlphaMask,
            f.alpha_masked_materials > 0,
            format!("{} materials use alphaMode MASK", f.alpha_masked_materials),
            "no alpha-masked material".into(),
        );
        decide(
            Effect::Transparency,
            f.transparent_materials > 0,
            format!(
                "{} materials let light through (alphaMode BLEND or KHR_materials_transmission)",
                f.transparent_materials
            ),
            "every material is opaque".into(),
        );
        decide(
            Effect::Unlit,
            f.unlit_materials > 0,
            format!(
                "{} materials are unlit (KHR_materials_unlit)",
                f.unlit_materials
            ),
            "no unlit material".into(),
        );
        let has_lights = f.emissive_triangles > 0 || f.punctual_lights > 0 || f.environment;
        // The convexity proof covers segments between surface points; a ray toward the
        // environment leaves the scene and may well cross it, so an environment needs rays.
        decide(
            Effect::Shadows,
            has_lights && (f.can_occlude || f.environment),
            if f.environment && !f.can_occlude {
                "rays toward the environment can be blocked by the scene itself".into()
            } else {
                "occlusion cannot be ruled out, so every light sample gets a shadow ray".into()
            },
            if has_lights {
                "the scene is one convex region seen from inside: nothing can occlude".into()
            } else {
                "no lights: nothing to shadow".into()
            },
        );
        decide(
            Effect::Motion,
            camera_moves || f.animated,
            if camera_moves {
                "the camera moved: motion vectors reproject history".into()
            } else {
                "objects move: motion vectors follow them".into()
            },
            "static camera and scene: a point stays in its pixel".into(),
        );
        decide(
            Effect::Animation,
            f.animated,
            "the scene is animated: object motion, light identity checks".into(),
            "static scene".into(),
        );
        decide(
            Effect::BsdfCandidates,
            settings.bsdf_candidates > 0 && (f.emissive_triangles > 0 || f.environment),
            format!("{} BSDF candidates per pixel", settings.bsdf_candidates),
            if settings.bsdf_candidates == 0 {
                "BSDF candidates set to 0".into()
            } else {
                "no emissive triangles or environment for BSDF rays to hit".into()
            },
        );
        let (sampler, why) = resolve_light_sampler(f, settings.light_sampler);
        let (sampler, why) = if has_lights {
            (sampler, why)
        } else {
            (LightSampler::Power, "no lights to sample".to_string())
        };
        let tile_shape =
            format!("{LIGHT_TILE_COUNT} × {LIGHT_TILE_SIZE} presampled lights per frame");
        let other = format!("the light sampler is {}: {why}", sampler.name());
        decide(
            Effect::LightTiles,
            sampler == LightSampler::Tiles,
            format!("light tiles ({tile_shape}): {why}"),
            other.clone(),
        );
        decide(
            Effect::Regir,
            sampler == LightSampler::Regir,
            format!("ReGIR cells around the camera: {why}"),
            other.clone(),
        );
        decide(
            Effect::RegirFromBvh,
            sampler == LightSampler::Regir && settings.regir_build_from_bvh,
            "ReGIR's cells filled from the light BVH walked at their centres".into(),
            if sampler == LightSampler::Regir {
                "ReGIR's cells filled from the power table (regir_build_from_bvh off)".into()
            } else {
                other.clone()
            },
        );
        decide(
            Effect::LightBvh,
            sampler == LightSampler::Bvh,
            format!("a light BVH: {why}"),
            other.clone(),
        );
        decide(
            Effect::VertexLightBvh,
            sampler == LightSampler::Bvh && settings.bvh_at_vertices,
            "the light BVH at path vertices, transparent layers and the reference's vertices too"
                .into(),
            if sampler == LightSampler::Bvh {
                "path vertices draw lights from the power table (bvh_at_vertices off)".into()
            } else {
                other
            },
        );
        decide(
            Effect::Environment,
            f.environment,
            "an environment lights the scene and fills the background".into(),
            "no environment (--env)".into(),
        );
        set
    }

    /// Parses `--effects`: `all`, or a comma-separated list of effect names.
    pub fn parse_list(text: &str) -> Result<EffectSet, String> {
        if text == "all" {
            return Ok(EffectSet::all());
        }
        let mut enabled = BTreeSet::new();
        for name in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let e = Effect::from_name(name).ok_or_else(|| {
                let known: Vec<_> = Effect::ALL.iter().map(|e| e.name()).collect();
                format!("unknown effect '{name}' (known: {})", known.join(", "))
            })?;
            enabled.insert(e);
        }
        if LIGHT_SAMPLER_EFFECTS
            .iter()
            .filter(|e| enabled.contains(e))
            .count()
            > 1
        {
            return Err(
                "light-tiles, regir and light-bvh are alternative light samplers: name at most one"
                    .into(),
            );
        }
        if enabled.contains(&Effect::RegirFromBvh) && !enabled.contains(&Effect::Regir) {
            return Err(
                "regir-from-bvh fills ReGIR's cells from the light BVH: name regir too".into(),
            );
        }
        if enabled.contains(&Effect::VertexLightBvh) && !enabled.contains(&Effect::LightBvh) {
            return Err(
                "vertex-light-bvh samples path vertices with the light BVH: name light-bvh too"
                    .into(),
            );
        }
        let reasons = Effect::ALL
            .iter()
            .map(|e| {
                (
                    *e,
                    format!(
                        "forced by --effects ({})",
                        if enabled.contains(e) { "on" } else { "off" }
                    ),
                )
            })
            .collect();
        Ok(EffectSet {
            enabled,
            reasons,
            planted: BTreeSet::new(),
        })
    }
}

//! Scenes on the CPU: what a glTF file or a built-in generator produces, before anything
//! is uploaded. Everything is in world space and linear units; see docs/src/scenes.md,
//! "Units and images".

pub mod animation;
pub mod builtin;
pub mod bvh;
pub mod camera;
pub mod gltf_loader;
pub mod lights;
pub mod load;
mod uv_transform;
pub mod validate;

pub use camera::Camera;
pub use gltf_loader::extensions::{ExtensionStatus, ExtensionUse};
pub use load::{load_scene, load_scene_watched};

use glam::{Vec2, Vec3, Vec4};

/// A triangle soup with materials, textures, punctual lights and an optional camera.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// Human-readable name: the file name or `builtin:NAME`.
    pub name: String,
    pub vertices: Vec<Vertex>,
    pub triangles: Vec<Triangle>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    pub punctual_lights: Vec<PunctualLight>,
    /// The file's first perspective camera, if it has one.
    pub camera: Option<Camera>,
    /// The sky around the scene (`--env`); glTF files carry none.
    pub environment: Option<std::sync::Arc<crate::environment::Environment>>,
    /// What moves and changes with scene time; `None` for a static scene.
    pub animation: Option<animation::SceneAnimation>,
    /// The world matrix of each of `animation`'s mesh bindings as last placed (by the
    /// loader, then by `SceneAnimation::pose`), in step with the vertices it produced: the
    /// ray-query backend places each moving mesh's BLAS with it (gpu_scene/accel.rs).
    pub mesh_transforms: Vec<glam::Mat4>,
    /// What the loader did with each extension the file lists (empty for built-ins).
    pub extensions: Vec<ExtensionUse>,
    /// How long the loader's phases took (`load_phases.rs`; the upload adds its own).
    pub load_phases: crate::load_phases::LoadPhases,
}

/// A world-space vertex. `normal` is zero when the source had none: shaders then use the
/// geometric normal of the triangle.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vertex {
    pub position: Vec3,
    pub normal: Vec3,
    pub uv: Vec2,
}

/// Three vertex indices in counter-clockwise order (the front face, see docs/src/scenes.md,
/// "Emitters and materials") and a material index.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Triangle {
    pub indices: [u32; 3],
    pub material: u32,
}

/// glTF metallic-roughness material with the extensions this project reads.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    /// Linear RGBA base colour factor.
    pub base_color: Vec4,
    pub base_color_texture: Option<TextureRef>,
    pub metallic: f32,
    pub roughness: f32,
    /// glTF metallicRoughness texture: G = roughness, B = metallic (linear).
    pub metallic_roughness_texture: Option<TextureRef>,
    /// Emitted radiance = emissiveFactor × KHR_materials_emissive_strength.
    pub emission: Vec3,
    pub emissive_texture: Option<TextureRef>,
    /// KHR_materials_specular `specularFactor` (1 when absent). 0 makes the dielectric
    /// part exactly Lambertian.
    pub specular: f32,
    pub double_sided: bool,
    pub alpha_mode: AlphaMode,
    /// KHR_materials_transmission `transmissionFactor` (0 when absent): the share of the
    /// covered surface that is thin glass, passing light straight through tinted by the
    /// base colour (docs/src/transparency.md, "The thin-layer model").
    pub transmission: f32,
    /// KHR_materials_transmission `transmissionTexture` (R channel, linear).
    pub transmission_texture: Option<TextureRef>,
    /// KHR_materials_unlit: the camera sees the base colour as radiance; the surface neither
    /// reflects nor emits light for anything else.
    pub unlit: bool,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            name: String::from("default"),
            base_color: Vec4::new(0.8, 0.8, 0.8, 1.0),
            base_color_texture: None,
            metallic: 0.0,
            roughness: 1.0,
            metallic_roughness_texture: None,
            emission: Vec3::ZERO,
            emissive_texture: None,
            specular: 1.0,
            double_sided: false,
            alpha_mode: AlphaMode::Opaque,
            transmission: 0.0,
            transmission_texture: None,
            unlit: false,
        }
    }
}

impl Material {
    /// Every texture slot by its glTF name: the one list the loader, validation and the
    /// uv-set choice go through (a new slot is added here).
    pub fn texture_slots(&self) -> [(&'static str, Option<TextureRef>); 4] {
        [
            ("baseColorTexture", self.base_color_texture),
            ("metallicRoughnessTexture", self.metallic_roughness_texture),
            ("emissiveTexture", self.emissive_texture),
            ("transmissionTexture", self.transmission_texture),
        ]
    }

    /// The uv set the vertices of this material's primitives carry: the one every slot
    /// reads, else the base colour slot's (the loader warns), else the first slot's, else 0.
    pub fn uv_set(&self) -> u32 {
        let slots = self.texture_slots();
        self.base_color_texture
            .or_else(|| slots.iter().find_map(|(_, r)| *r))
            .map_or(0, |r| r.tex_coord)
    }

    /// A matte Lambertian material (specular lobe off).
    pub fn diffuse(name: &str, base_color: Vec3) -> Self {
        Self {
            name: name.to_string(),
            base_color: base_color.extend(1.0),
            specular: 0.0,
            ..Self::default()
        }
    }

    /// An emitter: black diffuse surface with the given radiance.
    pub fn emitter(name: &str, radiance: Vec3, double_sided: bool) -> Self {
        Self {
            name: name.to_string(),
            base_color: Vec4::new(0.0, 0.0, 0.0, 1.0),
            specular: 0.0,
            emission: radiance,
            double_sided,
            ..Self::default()
        }
    }

    /// True when this material can emit light at all.
    pub fn is_emissive(&self) -> bool {
        self.emission.max_element() > 0.0
    }

    /// True when light can pass through the surface: alpha blending (coverage below 1
    /// somewhere) or transmission. Alpha MASK is not transparency: its texels are either
    /// surface or hole.
    pub fn is_transparent(&self) -> bool {
        self.alpha_mode == AlphaMode::Blend || self.transmission > 0.0
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AlphaMode {
    Opaque,
    /// Texels with alpha below the cutoff are holes (for camera and shadow rays).
    Mask(f32),
    /// Coverage by alpha: a fraction 1 − alpha of the light passes untouched (camera,
    /// path and shadow rays alike; docs/src/transparency.md, "The thin-layer model").
    Blend,
}

/// A texture slot of a material: the texture, the uv set the file names for it and its
/// `KHR_texture_transform` (identity without one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureRef {
    pub texture: u32,
    /// The TEXCOORD_n set this slot reads (the transform's `texCoord` override applied).
    /// Vertices store one uv set: the loader reads the one the material's slots agree on.
    pub tex_coord: u32,
    pub transform: UvTransform,
}

impl TextureRef {
    /// Texture `texture` read through TEXCOORD_0, untransformed.
    pub fn new(texture: u32) -> TextureRef {
        TextureRef {
            texture,
            tex_coord: 0,
            transform: UvTransform::IDENTITY,
        }
    }
}

pub use uv_transform::UvTransform;

/// RGBA8 texels as stored in the file (colour textures stay sRGB-encoded; the shader
/// decodes them according to the slot that reads them).
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    pub name: String,
    pub width: u32,
    pub height: u32,
    pub texels: Vec<[u8; 4]>,
    pub wrap_u: Wrap,
    pub wrap_v: Wrap,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wrap {
    Repeat,
    ClampToEdge,
    MirroredRepeat,
}

/// KHR_lights_punctual light, in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PunctualLight {
    pub kind: PunctualKind,
    pub position: Vec3,
    /// Direction the light points to (spot and directional), unit length.
    pub direction: Vec3,
    /// colour × intensity: candela for point and spot, lux for directional.
    pub intensity: Vec3,
    /// Distance where the light's influence ends (KHR_lights_punctual `range`).
    pub range: Option<f32>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PunctualKind {
    Point,
    /// Cone angles in radians, 0 ≤ inner < outer ≤ π/2.
    Spot {
        inner_cone: f32,
        outer_cone: f32,
    },
    Directional,
}

/// Axis-aligned bounds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    pub fn grow(&mut self, p: Vec3) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }

    pub fn union(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x
    }

    pub fn extent(&self) -> Vec3 {
        if self.is_empty() {
            Vec3::ZERO
        } else {
            self.max - self.min
        }
    }

    pub fn center(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    /// The eight corners (bit 0 of the index picks max x, bit 1 max y, bit 2 max z).
    pub fn corners(&self) -> [Vec3; 8] {
        std::array::from_fn(|i| {
            Vec3::new(
                if i & 1 == 0 { self.min.x } else { self.max.x },
                if i & 2 == 0 { self.min.y } else { self.max.y },
                if i & 4 == 0 { self.min.z } else { self.max.z },
            )
        })
    }

    /// Half the surface area (enough for SAH ratios).
    pub fn half_area(&self) -> f32 {
        let e = self.extent();
        e.x * e.y + e.y * e.z + e.z * e.x
    }
}

impl Scene {
    /// The rectangle `center ± u ± v` (half-extents), front face along `u × v`, flat-shaded:
    /// the built-ins' building block, and the tests'.
    pub fn push_rect(&mut self, center: Vec3, u: Vec3, v: Vec3, material: u32) {
        let corners = [
            center - u - v,
            center + u - v,
            center + u + v,
            center - u + v,
        ];
        let uvs = [Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y];
        let normal = u.cross(v).normalize_or_zero();
        self.push_flat(&corners, &uvs, normal, &[[0, 1, 2], [0, 2, 3]], material);
    }

    /// Vertices `p` with texture coordinates `uv` and one shared `normal`, and the triangles
    /// `tris` (indices into `p`), all with `material`.
    pub fn push_flat(
        &mut self,
        p: &[Vec3],
        uv: &[Vec2],
        normal: Vec3,
        tris: &[[u32; 3]],
        material: u32,
    ) {
        let base = self.vertices.len() as u32;
        self.vertices
            .extend(p.iter().zip(uv).map(|(&position, &uv)| Vertex {
                position,
                normal,
                uv,
            }));
        self.triangles.extend(tris.iter().map(|t| Triangle {
            indices: t.map(|i| base + i),
            material,
        }));
    }

    pub fn bounds(&self) -> Aabb {
        let mut b = Aabb::EMPTY;
        for v in &self.vertices {
            b.grow(v.position);
        }
        b
    }

    /// The three world positions of triangle `t`.
    pub fn triangle_positions(&self, t: usize) -> [Vec3; 3] {
        let tri = &self.triangles[t];
        tri.indices.map(|i| self.vertices[i as usize].position)
    }

    /// Per triangle, whether it belongs to a moving mesh of the animation (what the BVH keeps
    /// apart, `bvh::split`); empty for a scene without animation.
    pub fn moving_triangles(&self) -> Vec<bool> {
        self.animation.as_ref().map_or_else(Vec::new, |a| {
            let bindings = a.triangle_bindings(&self.triangles);
            bindings.iter().map(Option::is_some).collect()
        })
    }

    /// True when the scene has no camera of its own (a file without one): the start
    /// camera is then [`Camera::framing`] of the bounds.
    pub fn camera_is_automatic(&self) -> bool {
        self.camera.is_none()
    }

    /// The camera to start with: the file's, else one framing the scene bounds.
    pub fn default_camera(&self) -> Camera {
        self.camera
            .unwrap_or_else(|| Camera::framing(self.bounds()))
    }

    /// Poses the scene at `time` with its own animation (nothing for a static scene).
    pub fn pose(&mut self, time: f32, choice: animation::ClipChoice) -> animation::SceneChange {
        let Some(mut anim) = self.animation.take() else {
            return animation::SceneChange::default();
        };
        let change = anim.pose(self, time, choice);
        anim.posed_at = time;
        self.animation = Some(anim);
        change
    }

    /// Number of triangles whose material emits.
    pub fn emissive_triangle_count(&self) -> usize {
        self.triangles
            .iter()
            .filter(|t| self.materials[t.material as usize].is_emissive())
            .count()
    }
}

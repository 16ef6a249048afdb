// Group 1: the uploaded scene, all in BVH triangle order (render/src/gpu_scene/layout.rs
// numbers the bindings).
#include "common/types.wgsl"

@group(1) @binding(0) var<storage, read> triangles: array<Triangle>;
@group(1) @binding(1) var<storage, read> shading: array<TriangleShading>;
@group(1) @binding(2) var<storage, read> materials: array<Material>;
@group(1) @binding(3) var<storage, read> textures: array<Texture>;
@group(1) @binding(4) var<storage, read> texels: array<u32>;
@group(1) @binding(5) var<storage, read> lights: array<Light>;
@group(1) @binding(6) var<storage, read> punctual_lights: array<PunctualLight>;
@group(1) @binding(7) var<storage, read> bvh_nodes: array<BvhNode>;
#ifdef ANIMATION
// Last frame's triangles, materials and punctual lights, same slots as the current ones
// (render/src/gpu_scene/update.rs): object motion vectors (gbuffer_resolve.wgsl) and the
// pairwise MIS canonical term at the previous pixel (di/temporal.wgsl). A static scene binds
// the current buffers here.
@group(1) @binding(8) var<storage, read> prev_triangles: array<Triangle>;
@group(1) @binding(9) var<storage, read> prev_materials: array<Material>;
@group(1) @binding(10) var<storage, read> prev_punctual_lights: array<PunctualLight>;
// Last frame's BVH boxes: the same tree as bvh_nodes refitted to last frame's triangles
// (temporal visibility at the previous pixel, trace_bvh.wgsl).
@group(1) @binding(14) var<storage, read> prev_bvh_nodes: array<BvhNode>;
#endif
#ifdef ENVIRONMENT
// The environment (render/src/gpu_scene/environment.rs): sampling table, radiance, uniform.
@group(1) @binding(11) var<storage, read> env_table: array<EnvTexel>;
@group(1) @binding(12) var env_radiance: texture_2d<f32>;
@group(1) @binding(13) var<uniform> env: Environment;
#endif
#ifdef RAY_QUERY
// The hardware's acceleration structures (render/src/gpu_scene/accel.rs) and the map from
// (instance, geometry, primitive) to a triangle slot (trace_ray_query.wgsl).
@group(1) @binding(15) var scene_tlas: acceleration_structure;
@group(1) @binding(17) var<storage, read> accel_map: array<u32>;
#ifdef ANIMATION
// Last frame's TLAS: the same BLASes at last frame's instance transforms.
@group(1) @binding(16) var prev_scene_tlas: acceleration_structure;
#endif
#endif

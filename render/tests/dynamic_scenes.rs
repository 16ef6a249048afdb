//! Reuse that stays correct while the scene changes (docs/src/dynamic-scenes.md). Each estimator
//! test has a planted-error twin that runs the same detector on a renderer with one part of the
//! per-frame update left out, and asserts that the detector fires.
//!
//! Sizes are tiny (lavapipe on two cores); tolerances are justified where they are set.

use crate::common;

use restir_render::di::constants::*;
use restir_render::effects::Effect;
use restir_render::gpu_types::NO_LIGHT;
use restir_render::scene::animation::{ClipChoice, SceneChange};
use restir_render::shader_constants::*;
use restir_render::timeline::AnimatedScene;
use restir_render::{LinearImage, Mode, Renderer, Settings, load_scene};

fn animated(name: &str, time: f32) -> AnimatedScene {
    let mut scene = AnimatedScene::new(load_scene(name).unwrap_or_else(|e| panic!("{e}")));
    scene.pose_only(time);
    scene
}

fn renderer_for(scene: &AnimatedScene, w: u32, h: u32, settings: Settings) -> Renderer {
    Renderer::new(common::gpu(), scene.scene(), w, h, settings).unwrap_or_else(|e| panic!("{e:#}"))
}

/// Which part of the per-frame update a twin leaves out.
#[derive(Clone, Copy, PartialEq)]
enum Plant {
    None,
    /// Lights switch on the CPU but the GPU keeps the old emission and light table.
    SkipLightUpdate,
    /// The GPU keeps the old geometry: targets use the previous light position.
    SkipGeometryUpdate,
}

/// Poses `scene` at `time` and updates `r`, minus what `plant` leaves out.
fn step(scene: &mut AnimatedScene, r: &mut Renderer, time: f32, plant: Plant) {
    if plant == Plant::None {
        scene.set_time(r, time);
        return;
    }
    let mut change: SceneChange = scene.pose_only(time);
    match plant {
        Plant::SkipLightUpdate => change.lights = false,
        Plant::SkipGeometryUpdate => {
            change.geometry = false;
            change.lights = false;
        }
        Plant::None => {}
    }
    r.update_scene(scene.scene(), change);
}

fn frame(r: &mut Renderer) {
    r.render_frame().unwrap_or_else(|e| panic!("{e}"));
}

/// Motion-vector error (pixels) of every blade pixel against the blade's known transforms.
fn blade_motion_errors(plant_no_object_motion: bool) -> (Vec<f32>, usize) {
    let (w, h) = (64u32, 48u32);
    let (t0, t1) = (0.0f32, 0.1f32);
    let mut scene = animated("builtin:dynamic:moving-occluder", t0);
    let mut r = renderer_for(&scene, w, h, common::settings(&["jitter=false"]));
    r.set_mode(Mode::Restir);
    frame(&mut r);
    if plant_no_object_motion {
        let mut set = r.last_effects().expect("a frame ran").clone();
        assert!(set.enabled.remove(&Effect::Animation));
        r.force_effects(Some(set));
    }
    scene.set_time(&mut r, t1);
    frame(&mut r);
    let anim = scene.scene().animation.clone().unwrap();
    let blade_node = anim.meshes[0].node;
    let blade = scene
        .scene()
        .materials
        .iter()
        .position(|m| m.name == "blade")
        .unwrap() as u32;
    let (before, after) = (
        anim.world_matrices(t0, ClipChoice::All)[blade_node],
        anim.world_matrices(t1, ClipChoice::All)[blade_node],
    );
    let camera = r.camera();
    let aspect = w as f32 / h as f32;
    let near = (r.scene_scale() * 1e-5).max(1e-30);
    let view_proj = camera.projection_matrix(aspect, near) * camera.view_matrix();
    let surfaces = r.read_surfaces();
    let errors: Vec<f32> = surfaces
        .iter()
        .filter(|s| s.depth > 0.0 && s.material == blade)
        .map(|s| {
            let was = before.transform_point3(after.inverse().transform_point3(s.position.into()));
            let clip = view_proj * was.extend(1.0);
            let ndc = clip.truncate().truncate() / clip.w;
            let expected = glam::Vec2::new(
                (ndc.x * 0.5 + 0.5) * w as f32,
                (0.5 - ndc.y * 0.5) * h as f32,
            );
            (glam::Vec2::from(s.motion) - expected).length()
        })
        .collect();
    // Floor pixels the blade uncovered: their previous pixel showed the blade.
    let disoccluded = r
        .read_debug()
        .iter()
        .zip(&surfaces)
        .filter(|(_, s)| s.depth > 0.0 && s.material != blade)
        .filter(|(d, _)| d.temporal_mask & REJECT_MATERIAL != 0)
        .count();
    (errors, disoccluded)
}

#[test]
fn a_moving_blade_reprojects_to_where_it_was() {
    let (errors, disoccluded) = blade_motion_errors(false);
    assert!(errors.len() > 50, "only {} blade pixels", errors.len());
    let worst = errors.iter().cloned().fold(0.0f32, f32::max);
    // f32 barycentrics on the GPU against a CPU matrix inverse: well under 1/100 pixel.
    assert!(worst < 0.01, "worst motion error {worst} px");
    // The floor the blade uncovered is rejected (material differs), visible in the view.
    assert!(disoccluded > 0, "no disocclusion rejected");
}

#[test]
fn planted_ignoring_object_motion_is_detected() {
    let (errors, _) = blade_motion_errors(true);
    // In 0.1 s the blade turns 9°: its tip moves ~0.3 m, several pixels at 64×48.
    let off = errors.iter().filter(|&&e| e > 0.5).count();
    assert!(
        off > errors.len() / 2,
        "{off} of {} blade pixels off by > 0.5 px",
        errors.len()
    );
}

fn mean_luma(img: &LinearImage, pixels: &[usize]) -> f64 {
    let luma = |p: [f32; 4]| 0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64;
    pixels.iter().map(|&i| luma(img.pixels[i])).sum::<f64>() / pixels.len().max(1) as f64
}

/// A reference of one moment: `--fps 0` accumulation of the reference mode.
fn reference_at(scene: &mut AnimatedScene, r: &mut Renderer, time: f32) -> LinearImage {
    scene.set_time(r, time);
    common::reference(r, 8, 64)
}

const BLINK_SIZE: (u32, u32) = (48, 32);
/// M cap of the switching test: the stale share of a pixel's history after k frames is
/// at most (M_cap / (M_cap + 1))^k (each frame adds one fresh M to a history capped at
/// M_cap); with M cap 5 that is 5 % after 16 frames.
const BLINK_M_CAP: &str = "m_cap=5";
const SETTLE_FRAMES: u32 = 16;

struct BlinkOutcome {
    /// Final reservoirs holding a light the renderer has off, per frame after the switch.
    stale: Vec<usize>,
    /// Mean luminance of the changed region over frames SETTLE..SETTLE+8 after the switch,
    /// and the reference's.
    settled: f64,
    reference: f64,
    changed_pixels: usize,
    /// Temporal `light_gone` rejections in the first frame after the switch.
    light_gone: usize,
}

fn blink_settings() -> Settings {
    common::settings(&["jitter=false", BLINK_M_CAP, "spatial_radius=4"])
}

/// References of `blinking-lights` with every light on (0.9 s) and half off (1.5 s),
/// rendered once for the test and its twin.
fn blink_references() -> &'static (LinearImage, LinearImage) {
    static REFS: std::sync::OnceLock<(LinearImage, LinearImage)> = std::sync::OnceLock::new();
    REFS.get_or_init(|| {
        let mut scene = animated("builtin:dynamic:blinking-lights", 0.9);
        let mut r = renderer_for(&scene, BLINK_SIZE.0, BLINK_SIZE.1, blink_settings());
        let before = reference_at(&mut scene, &mut r, 0.9);
        let after = reference_at(&mut scene, &mut r, 1.5);
        (before, after)
    })
}

fn blink(plant: Plant) -> BlinkOutcome {
    let fps = 30.0;
    let mut scene = animated("builtin:dynamic:blinking-lights", 0.5);
    let mut r = renderer_for(&scene, BLINK_SIZE.0, BLINK_SIZE.1, blink_settings());
    let (before, after) = blink_references();
    let changed = common::changed_pixels(before, after);
    // 15 frames of history with every light on (0.5 s → 0.97 s), then across the switch.
    r.set_mode(Mode::Restir);
    r.request_cut();
    let mut t = 0.5f32;
    for _ in 0..15 {
        step(&mut scene, &mut r, t, plant);
        frame(&mut r);
        t += 1.0 / fps;
    }
    let mut stale = Vec::new();
    let mut settled = 0.0;
    let mut light_gone = 0;
    let first_after = 1.0 + 1.0 / fps;
    for k in 0..SETTLE_FRAMES + 8 {
        let time = first_after + k as f32 / fps;
        assert!(time < 2.0, "still inside the off interval");
        step(&mut scene, &mut r, time, plant);
        frame(&mut r);
        let off = r
            .read_final_reservoirs()
            .iter()
            .filter(|res| res.light != NO_LIGHT)
            .filter(|res| r.light_select_pdf(res.light) == Some(0.0))
            .count();
        stale.push(off);
        if k == 0 {
            light_gone = r
                .read_debug()
                .iter()
                .filter(|d| d.temporal_mask & REJECT_LIGHT_GONE != 0)
                .count();
        }
        if k >= SETTLE_FRAMES {
            settled += mean_luma(&r.read_radiance(), &changed) / 8.0;
        }
    }
    BlinkOutcome {
        stale,
        settled,
        reference: mean_luma(after, &changed),
        changed_pixels: changed.len(),
        light_gone,
    }
}

#[test]
fn switched_off_lights_leave_no_samples_and_the_image_settles() {
    let o = blink(Plant::None);
    eprintln!(
        "stale per frame {:?}; changed region {} px, settled {:.4} vs reference {:.4}; light_gone {}",
        o.stale, o.changed_pixels, o.settled, o.reference, o.light_gone
    );
    assert!(o.changed_pixels > 50, "{} changed pixels", o.changed_pixels);
    // A sample of a light that is off is rejected the first frame it is read (its target
    // is re-evaluated with current emission, 0): no pixel keeps one, from frame 0 on.
    assert!(o.stale.iter().all(|&n| n == 0), "{:?}", o.stale);
    // Those samples are rejected as `light_gone` (its own bit), in the first frame.
    assert!(o.light_gone > 20, "{} light_gone rejections", o.light_gone);
    // Measured 0.94: the 1/M estimator's own darkening (0.96 on many-lights:
    // docs/src/mis-and-bias.md, "Measured bias") plus the noise of 8 frames over ~1000
    // pixels; 10 % holds both and still catches a lag (the changed region differs by more
    // than 10 % per pixel by construction).
    let ratio = o.settled / o.reference;
    assert!((ratio - 1.0).abs() < 0.1, "settled/reference {ratio:.3}");
}

#[test]
fn planted_skipped_light_update_is_detected() {
    let o = blink(Plant::SkipLightUpdate);
    let ratio = o.settled / o.reference;
    eprintln!("planted: settled/reference {ratio:.3}");
    assert!((ratio - 1.0).abs() > 0.1, "detector silent: {ratio:.3}");
    // light_gone follows the renderer's lights: with the update skipped nothing is gone.
    assert_eq!(o.light_gone, 0);
}

const SWEEP_SIZE: (u32, u32) = (48, 32);
const SWEEP_FRAMES: u32 = 24;

/// The average over SWEEP_FRAMES frames (t = 0.3 s + i/30) of `mode` with the light
/// sweeping, and the fraction of surface pixels whose temporal candidate merged in the
/// last frame.
fn sweep(mode: Mode, seed: u32, plant: Plant) -> (LinearImage, f64) {
    let mut scene = animated("builtin:dynamic:moving-light", 0.3);
    let mut settings = common::settings(&["jitter=false", "spatial_radius=4"]);
    settings.reference_spp = 32;
    let mut r = renderer_for(&scene, SWEEP_SIZE.0, SWEEP_SIZE.1, settings);
    r.set_mode(mode);
    r.set_seed(seed);
    r.reset_accumulation();
    for i in 0..SWEEP_FRAMES {
        step(&mut scene, &mut r, 0.3 + i as f32 / 30.0, plant);
        frame(&mut r);
    }
    let debug = r.read_debug();
    let surfaces = r.read_surfaces();
    let on_surface = surfaces.iter().filter(|s| s.depth > 0.0).count();
    let merged = debug
        .iter()
        .zip(&surfaces)
        .filter(|(d, s)| s.depth > 0.0 && d.flags & DEBUG_FLAG_TEMPORAL_MERGED != 0)
        .count();
    (
        r.read_accumulated(),
        merged as f64 / on_surface.max(1) as f64,
    )
}

/// (restir mean / reference mean, relative RMSE of the restir average, merged fraction),
/// the restir numbers averaged over two seeds.
fn sweep_bias(plant: Plant) -> (f64, f64, f64) {
    static REFERENCE: std::sync::OnceLock<LinearImage> = std::sync::OnceLock::new();
    let reference = REFERENCE.get_or_init(|| sweep(Mode::Reference, 0, Plant::None).0);
    let all: Vec<usize> = (0..reference.pixels.len()).collect();
    let ref_mean = mean_luma(reference, &all);
    let (mut ratio, mut rel_rmse, mut merged) = (0.0, 0.0, 0.0);
    for seed in [1, 2] {
        let (img, m) = sweep(Mode::Restir, seed, plant);
        ratio += mean_luma(&img, &all) / ref_mean / 2.0;
        rel_rmse += restir_render::metrics::luma_rmse(&img, reference).unwrap() / ref_mean / 2.0;
        merged += m / 2.0;
    }
    (ratio, rel_rmse, merged)
}

#[test]
fn a_moving_light_keeps_reuse_and_stays_unbiased_enough() {
    let (ratio, rel_rmse, merged) = sweep_bias(Plant::None);
    eprintln!(
        "moving light: mean ratio {ratio:.3}, relative RMSE {rel_rmse:.3}, merged {merged:.2}"
    );
    // Temporal reuse keeps merging while the light moves (the floor does not move).
    assert!(merged > 0.5, "only {merged:.2} of surface pixels merged");
    // 1/M darkens by a few % (docs/src/mis-and-bias.md, "Measured bias"); the sweep's time
    // average over 24 frames at 32 spp for the reference adds noise well under that.
    assert!(
        (ratio - 1.0).abs() < 0.08,
        "accumulated mean / reference {ratio:.3}"
    );
    assert!(rel_rmse < 0.25, "relative RMSE {rel_rmse:.3}");
}

#[test]
fn planted_stale_light_position_is_detected() {
    let (ratio, rel_rmse, _) = sweep_bias(Plant::SkipGeometryUpdate);
    eprintln!("planted: mean ratio {ratio:.3}, relative RMSE {rel_rmse:.3}");
    assert!(
        rel_rmse >= 0.25 || (ratio - 1.0).abs() >= 0.08,
        "detector silent: ratio {ratio:.3}, relative RMSE {rel_rmse:.3}"
    );
}

#[test]
fn the_light_table_is_rebuilt_only_when_powers_can_change() {
    // Rigid motion of an emitter: same areas, same powers, same table.
    let mut scene = animated("builtin:dynamic:moving-light", 0.0);
    let mut r = renderer_for(&scene, 8, 8, Settings::default());
    let (change, times) = scene.set_time(&mut r, 0.5);
    assert!(change.geometry && change.lights && !change.emission);
    assert!(!times.light_table_rebuilt);
    // Switching lights changes emission: rebuilt, and the switched lights get pdf 0.
    let mut scene = animated("builtin:dynamic:blinking-lights", 0.5);
    let mut r = renderer_for(&scene, 8, 8, Settings::default());
    let (change, times) = scene.set_time(&mut r, 1.5);
    assert!(change.emission && times.light_table_rebuilt);
    assert!(r.light_select_pdf(0).is_some());
}

/// How an update reaches the GPU in the change-list test below.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Update {
    /// As posing said: only the moved meshes' triangles and the lights it names.
    ChangeList,
    /// As a full upload: the change without its list (every triangle, every light).
    Everything,
    /// Planted: the change list loses one moved mesh.
    LostMesh,
    /// Planted: the light BVH's refit loses one light of the scene's change list.
    LostLight,
}

/// The city with traffic stepped through cars driving and signs blinking (across t = 1 s),
/// a frame rendered after each step so the light BVH refits.
fn traffic_buffers(
    update: Update,
    refit_on_gpu: bool,
) -> (restir_render::gpu_scene::SceneBufferContents, usize) {
    let mut scene = animated("builtin:city-traffic:4096", 0.5);
    let refit = format!("light_bvh_gpu_refit={refit_on_gpu}");
    let settings = common::settings(&["light_sampler=bvh", "spatial=false", &refit]);
    let mut r = renderer_for(&scene, 32, 24, settings);
    frame(&mut r);
    if update == Update::LostLight {
        r.lose_light_change_for_tests();
    }
    let mut rewritten = 0;
    for time in [0.6, 0.9, 1.05, 1.4] {
        let mut change: SceneChange = scene.pose_only(time);
        match update {
            Update::Everything => change.moved_vertices = None,
            Update::LostMesh => {
                change.moved_vertices.as_mut().unwrap().pop();
            }
            Update::ChangeList | Update::LostLight => {}
        }
        rewritten += r.update_scene(scene.scene(), change).triangles_rewritten;
        frame(&mut r);
    }
    (r.scene_buffers_for_tests(), rewritten)
}

/// An update that rewrites only what posing moved leaves the GPU with the same triangles,
/// shading, BVH nodes and light-BVH nodes (refitted on the CPU), bit for bit, as one that
/// rewrites everything (boxes are minima and maxima: exact in any order). Planted: a moved
/// mesh left out of the list, and a light left out of the light BVH's refit, each leave a
/// difference.
#[test]
fn a_change_list_update_equals_a_full_one_bit_for_bit() {
    let (full, all) = traffic_buffers(Update::Everything, false);
    let (partial, moved) = traffic_buffers(Update::ChangeList, false);
    assert!(
        moved * 4 < all,
        "the change list rewrote {moved} triangles of {all}"
    );
    assert!(partial.triangles == full.triangles, "triangles differ");
    assert!(partial.shading == full.shading, "shading differs");
    assert!(partial.bvh_nodes == full.bvh_nodes, "BVH nodes differ");
    assert!(
        partial.light_bvh_nodes == full.light_bvh_nodes,
        "light BVH nodes differ"
    );
    let (lost_mesh, _) = traffic_buffers(Update::LostMesh, false);
    assert!(
        lost_mesh.triangles != full.triangles,
        "a lost mesh went unseen"
    );
    assert!(
        lost_mesh.bvh_nodes != full.bvh_nodes,
        "a lost mesh's boxes went unseen"
    );
    let (lost_light, _) = traffic_buffers(Update::LostLight, false);
    assert!(lost_light.triangles == full.triangles);
    assert!(
        lost_light.light_bvh_nodes != full.light_bvh_nodes,
        "a light left out of the light BVH's refit went unseen"
    );
}

/// The octahedral decoding of math.wgsl.
fn oct_decode(e: u32) -> glam::Vec3 {
    let x = (e & 0xffff) as u16 as i16 as f32 / 32767.0;
    let y = (e >> 16) as u16 as i16 as f32 / 32767.0;
    let mut n = glam::Vec3::new(x, y, 1.0 - x.abs() - y.abs());
    let t = (-n.z).max(0.0);
    n.x += if n.x >= 0.0 { -t } else { t };
    n.y += if n.y >= 0.0 { -t } else { t };
    n.normalize()
}

/// The most by which a node's normals cone, as the walk reads it (axis decoded, cos θ_o
/// widened by the records' slack), misses the axis of a one-sided light below it
/// (radians; ≤ 0: every such light is inside every cone above it).
fn worst_cone_miss(nodes: &[restir_render::gpu_types::GpuLightBvhNode]) -> f32 {
    use restir_render::shader_constants::LIGHT_BVH_LEAF;
    let mut worst = f32::NEG_INFINITY;
    let mut stack = vec![(0usize, Vec::<usize>::new())];
    while let Some((i, mut above)) = stack.pop() {
        let node = nodes[i];
        if node.child_or_light & LIGHT_BVH_LEAF != 0 {
            if node.cos_theta_o > -1.0 && node.phi > 0.0 {
                let light = oct_decode(node.axis);
                for &a in &above {
                    let cone = nodes[a];
                    if cone.cos_theta_o > -1.0 {
                        let angle = oct_decode(cone.axis).dot(light).clamp(-1.0, 1.0).acos();
                        worst = worst.max(angle - cone.cos_theta_o.clamp(-1.0, 1.0).acos());
                    }
                }
            }
            continue;
        }
        above.push(i);
        stack.push((i + 1, above.clone()));
        stack.push((node.child_or_light as usize, above));
    }
    worst
}

/// How far apart two light-BVH node records are: the largest difference of the exact
/// fields (box, power, links, cos θ_e: all the same operations on both sides, so 0 unless
/// something is wrong), of cos θ_o, and the angle between their decoded axes (radians).
fn light_node_gaps(
    a: &[restir_render::gpu_types::GpuLightBvhNode],
    b: &[restir_render::gpu_types::GpuLightBvhNode],
) -> (f32, f32, f32) {
    let decode = oct_decode;
    let mut gaps = (0.0f32, 0.0f32, 0.0f32);
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        let exact = (glam::Vec3::from(x.min) - glam::Vec3::from(y.min))
            .abs()
            .max_element()
            .max(
                (glam::Vec3::from(x.max) - glam::Vec3::from(y.max))
                    .abs()
                    .max_element(),
            )
            .max((x.phi - y.phi).abs())
            .max((x.cos_theta_e - y.cos_theta_e).abs())
            .max(if x.child_or_light == y.child_or_light {
                0.0
            } else {
                f32::INFINITY
            });
        gaps.0 = gaps.0.max(exact);
        gaps.1 = gaps.1.max((x.cos_theta_o - y.cos_theta_o).abs());
        if x.cos_theta_o > -1.0 {
            let angle = decode(x.axis).dot(decode(y.axis)).clamp(-1.0, 1.0).acos();
            gaps.2 = gaps.2.max(angle);
        }
    }
    gaps
}

/// The light BVH refitted on the GPU (lights/light_bvh_refit.wgsl) equals the CPU's refit: boxes,
/// powers and links bit for bit, the normals' cones within float rounding (tolerances
/// below). Planted: a light left out of the change list shows in the boxes.
#[test]
fn the_gpu_refit_equals_the_cpu_refit() {
    let (cpu, _) = traffic_buffers(Update::ChangeList, false);
    let (gpu, _) = traffic_buffers(Update::ChangeList, true);
    let (exact, cos_theta_o, axis) = light_node_gaps(&gpu.light_bvh_nodes, &cpu.light_bvh_nodes);
    let (miss_gpu, miss_cpu) = (
        worst_cone_miss(&gpu.light_bvh_nodes),
        worst_cone_miss(&cpu.light_bvh_nodes),
    );
    eprintln!(
        "GPU against CPU refit: exact fields {exact}, cos θ_o {cos_theta_o:e}, axis {axis:e} rad; \
         worst cone miss {miss_gpu:e} (GPU), {miss_cpu:e} (CPU) rad"
    );
    assert_eq!(exact, 0.0, "boxes, powers or links differ");
    // The cones go through acos, cos, sin and atan2 on both sides, whose GPU versions are
    // not correctly rounded, and each level unions its children's: measured 2.9e-4 in
    // cos θ_o and 4.9e-4 rad between axes (11 steps of the axis's encoding) after 12
    // levels. Both stay inside what the records' slack (LIGHT_BVH_CONE_SLACK, 1e-3 rad)
    // absorbs, which the containment check below confirms.
    assert!(cos_theta_o < 5e-4, "cos θ_o differs by {cos_theta_o}");
    assert!(axis < 1e-3, "axes differ by {axis} rad");
    // What keeps the tree's PDF unbiased: every light's normal inside every cone above it.
    assert!(
        miss_gpu < 0.0,
        "a GPU cone misses a light's normal by {miss_gpu} rad"
    );
    // Planted: cones narrowed by 2e-3 rad (twice the slack) must fail that check.
    let mut narrowed = gpu.light_bvh_nodes.clone();
    for n in narrowed.iter_mut().filter(|n| n.cos_theta_o > -1.0) {
        n.cos_theta_o = (n.cos_theta_o.clamp(-1.0, 1.0).acos() - 2e-3)
            .max(0.0)
            .cos();
    }
    assert!(
        worst_cone_miss(&narrowed) > 0.0,
        "narrowed cones went unseen"
    );
    let (lost, _) = traffic_buffers(Update::LostLight, true);
    let (exact, _, _) = light_node_gaps(&lost.light_bvh_nodes, &cpu.light_bvh_nodes);
    assert!(
        exact > 0.1,
        "a light left out of the GPU refit went unseen ({exact})"
    );
}

//! `bench-bvh`: the per-frame ray-tracing structure of an animated scene, four ways
//! (docs/src/measured/dynamic-scenes.md, "BVH: refit, rebuild or two levels"): a single tree
//! built at the first time and refitted, a full rebuild every frame, the renderer's split tree
//! (`scene::bvh::split`: the moving triangles' subtree apart from the static one, only it
//! refitted, and the price of rebuilding only it), and a two-level BVH
//! (`scene::bvh::two_level`: BLAS per instance built once, TLAS rebuilt every frame). For each
//! scene time: the CPU time of the per-frame work, the SAH cost, and the nodes visited and
//! triangles tested by a fixed set of rays — primary rays from the scene camera and one shadow
//! ray per hit to a point on an emitter — which measures traversal cost independently of the
//! machine. Prints a Markdown table; never a timing assertion.

use std::time::Instant;

use clap::Args;
use glam::{Mat4, Vec3};
use restir_render::load_scene;
use restir_render::scene::Scene;
use restir_render::scene::animation::ClipChoice;
use restir_render::scene::bvh::split::MovingPart;
use restir_render::scene::bvh::two_level::TwoLevelBvh;
use restir_render::scene::bvh::{Bvh, Ray, RefitLinks, Visits};
use restir_render::scene::camera::Camera;

use crate::cli::setup::parse_size;

#[derive(Args, Debug)]
pub struct BvhCostArgs {
    /// An animated scene (`builtin:dynamic:...` or a glTF file with animations).
    #[arg(long)]
    pub scene: String,
    /// Scene times to measure, in seconds; the refitted tree is built at the first.
    #[arg(long, value_delimiter = ',', default_value = "0,0.25,0.5,1,2")]
    pub times: Vec<f32>,
    /// Primary rays, WxH through the scene camera (one shadow ray per hit).
    #[arg(long, default_value = "64x40")]
    pub rays: String,
    /// Timed repetitions of each build / refit; the median is reported.
    #[arg(long, default_value_t = 3)]
    pub repeats: u32,
}

/// Rays traced through every structure: primary (closest hit) and shadow (any hit).
struct RaySet {
    primary: Vec<Ray>,
    shadow: Vec<Ray>,
}

/// Mean nodes visited and triangles tested per ray, primary and shadow together.
fn per_ray(v: Visits, rays: usize) -> (f64, f64) {
    let n = rays.max(1) as f64;
    (v.nodes as f64 / n, v.primitives as f64 / n)
}

fn median_ms(repeats: u32, mut f: impl FnMut()) -> f64 {
    median(
        (0..repeats.max(1))
            .map(|_| {
                let t = Instant::now();
                f();
                t.elapsed().as_secs_f64() * 1e3
            })
            .collect(),
    )
}

fn median(mut times: Vec<f64>) -> f64 {
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

fn positions(scene: &Scene) -> Vec<[Vec3; 3]> {
    (0..scene.triangles.len())
        .map(|t| scene.triangle_positions(t))
        .collect()
}

fn in_order(bvh: &Bvh, positions: &[[Vec3; 3]]) -> Vec<[Vec3; 3]> {
    bvh.triangle_order
        .iter()
        .map(|&i| positions[i as usize])
        .collect()
}

/// Primary rays through pixel centres, and from each hit (found with `bvh`) one shadow ray
/// to a point on an emitter picked by a hash of the pixel (the same for every structure).
fn ray_set(scene: &Scene, bvh: &Bvh, ordered: &[[Vec3; 3]], (w, h): (u32, u32)) -> RaySet {
    let camera = scene
        .camera
        .unwrap_or_else(|| Camera::framing(scene.bounds()));
    let tan = (camera.yfov * 0.5).tan();
    let aspect = w as f32 / h as f32;
    let emitters: Vec<usize> = (0..scene.triangles.len())
        .filter(|&t| scene.materials[scene.triangles[t].material as usize].is_emissive())
        .collect();
    let scale = scene.bounds().extent().length().max(1e-30);
    let mut set = RaySet {
        primary: Vec::new(),
        shadow: Vec::new(),
    };
    for y in 0..h {
        for x in 0..w {
            let sx = (2.0 * (x as f32 + 0.5) / w as f32 - 1.0) * tan * aspect;
            let sy = (1.0 - 2.0 * (y as f32 + 0.5) / h as f32) * tan;
            let dir = (camera.forward() + camera.right() * sx + camera.up() * sy).normalize();
            let ray = Ray {
                origin: camera.position,
                dir,
                t_max: f32::INFINITY,
            };
            set.primary.push(ray);
            let (Some(hit), false) = (bvh.closest_hit(ordered, &ray), emitters.is_empty()) else {
                continue;
            };
            let k = hash_u32(x * 7919 + y * 104_729);
            let tri = scene.triangle_positions(emitters[k as usize % emitters.len()]);
            let (a, b) = (
                (k >> 8 & 255) as f32 / 255.0,
                (k >> 16 & 255) as f32 / 255.0,
            );
            let (a, b) = if a + b > 1.0 {
                (1.0 - a, 1.0 - b)
            } else {
                (a, b)
            };
            let target = tri[0] * (1.0 - a - b) + tri[1] * a + tri[2] * b;
            // Off the surface toward the camera, and stop just short of the light.
            let origin = ray.origin + dir * hit.t - dir * (1e-5 * scale);
            set.shadow.push(Ray {
                origin,
                dir: target - origin,
                t_max: 0.999,
            });
        }
    }
    set
}

/// PCG's output hash (as `pcg_hash` in rng.wgsl): a fixed pseudo-random u32 per pixel.
fn hash_u32(v: u32) -> u32 {
    let state = v.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

fn trace_single(bvh: &Bvh, ordered: &[[Vec3; 3]], rays: &RaySet) -> Visits {
    let mut v = Visits::default();
    for r in &rays.primary {
        bvh.closest_hit_counted(ordered, r, &mut v);
    }
    for r in &rays.shadow {
        bvh.any_hit_counted(ordered, r, &mut v);
    }
    v
}

/// What rebuilding only the moving part costs (median), each time on a copy made before the
/// clock starts: the split column stays refitted, as the renderer's tree between rebuilds.
fn moving_part_rebuild_ms(
    split: &Bvh,
    part: MovingPart,
    positions: &[[Vec3; 3]],
    repeats: u32,
) -> f64 {
    median(
        (0..repeats.max(1))
            .map(|_| {
                let mut copy = Bvh {
                    nodes: split.nodes.clone(),
                    triangle_order: split.triangle_order.clone(),
                };
                let t = Instant::now();
                copy.rebuild_moving(part, positions);
                t.elapsed().as_secs_f64() * 1e3
            })
            .collect(),
    )
}

fn trace_two_level(two: &TwoLevelBvh, rays: &RaySet) -> Visits {
    let mut v = Visits::default();
    for r in &rays.primary {
        two.closest_hit_counted(r, &mut v);
    }
    for r in &rays.shadow {
        two.any_hit_counted(r, &mut v);
    }
    v
}

pub fn run(args: BvhCostArgs) -> anyhow::Result<()> {
    let size = parse_size(&args.rays)?;
    let mut scene = load_scene(&args.scene)?;
    let Some(anim) = scene.animation.clone() else {
        anyhow::bail!("{}: not an animated scene (nothing to refit)", args.scene);
    };
    let Some(&first) = args.times.first() else {
        anyhow::bail!("--times: give at least one scene time");
    };
    anim.pose(&mut scene, first, ClipChoice::All);
    let mut trees = Trees::build(&scene, &args.scene)?;
    print_header(&args.scene, &scene, &trees, size);
    for &t in &args.times {
        anim.pose(&mut scene, t, ClipChoice::All);
        let world: Vec<Mat4> = anim.world_matrices(t, ClipChoice::All);
        trees.print_row(t, &scene, &world, size, args.repeats);
    }
    Ok(())
}

/// The four structures, built at the first scene time, with what refitting them needs.
struct Trees {
    refit: Bvh,
    refit_links: RefitLinks,
    /// The single tree's slots of the moving triangles.
    refit_moving: Vec<usize>,
    split: Bvh,
    split_links: RefitLinks,
    part: MovingPart,
    /// What the renderer's rebuild policy compares with `BVH_REBUILD_FACTOR`.
    built_moving_sah: f64,
    two: TwoLevelBvh,
    /// The two-level BVH's BLASes, built once.
    blas_ms: f64,
}

impl Trees {
    fn build(scene: &Scene, name: &str) -> anyhow::Result<Trees> {
        let refit = Bvh::build(&positions(scene));
        let moving = scene.moving_triangles();
        let (split, part) = Bvh::build_split(&positions(scene), &moving);
        let Some(part) = part else {
            anyhow::bail!("{name}: no moving triangles beside static ones (nothing to keep apart)");
        };
        let split_links = split.refit_links();
        let built_moving_sah = split.moving_sah_cost(part).max(f64::MIN_POSITIVE);
        let refit_links = refit.refit_links();
        let refit_moving: Vec<usize> = (0..refit.triangle_order.len())
            .filter(|&p| moving[refit.triangle_order[p] as usize])
            .collect();
        let started = Instant::now();
        let two = TwoLevelBvh::new(scene);
        let blas_ms = started.elapsed().as_secs_f64() * 1e3;
        Ok(Trees {
            refit,
            refit_links,
            refit_moving,
            split,
            split_links,
            part,
            built_moving_sah,
            two,
            blas_ms,
        })
    }

    /// One scene time's row: each structure's per-frame work timed, then its SAH cost and
    /// the nodes and triangles the rays visit.
    fn print_row(&mut self, t: f32, scene: &Scene, world: &[Mat4], size: (u32, u32), repeats: u32) {
        let pos = positions(scene);
        // As `GpuScene::update` does it: the moved triangles' leaves and the nodes above
        // them (with a split tree, the moving part and the root).
        let refit_ms = median_ms(repeats, || {
            self.refit
                .refit_moved(&self.refit_links, &self.refit_moving, |s| pos[s as usize]);
        });
        let moved_slots: Vec<usize> =
            (self.part.first_slot..self.split.triangle_order.len()).collect();
        let split_refit_ms = median_ms(repeats, || {
            self.split
                .refit_moved(&self.split_links, &moved_slots, |s| pos[s as usize]);
        });
        let split_rebuild_ms = moving_part_rebuild_ms(&self.split, self.part, &pos, repeats);
        let mut rebuilt = None;
        let rebuild_ms = median_ms(repeats, || rebuilt = Some(Bvh::build(&pos)));
        let rebuilt = rebuilt.expect("built at least once");
        let tlas_ms = median_ms(repeats, || self.two.update(world));
        let refit_order = in_order(&self.refit, &pos);
        let rebuilt_order = in_order(&rebuilt, &pos);
        let rays = ray_set(scene, &rebuilt, &rebuilt_order, size);
        let n = rays.primary.len() + rays.shadow.len();
        let v_refit = per_ray(trace_single(&self.refit, &refit_order, &rays), n);
        let v_rebuild = per_ray(trace_single(&rebuilt, &rebuilt_order, &rays), n);
        let split_order = in_order(&self.split, &pos);
        let v_split = per_ray(trace_single(&self.split, &split_order, &rays), n);
        let v_two = per_ray(trace_two_level(&self.two, &rays), n);
        println!(
            "| {t} s | {refit_ms:.3} ms | {rebuild_ms:.3} ms | {split_refit_ms:.3} ms | {split_rebuild_ms:.3} ms | {tlas_ms:.3} ms | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.2} |",
            self.refit.sah_cost(),
            rebuilt.sah_cost(),
            self.split.sah_cost(),
            self.two.sah_cost(),
            v_refit.0,
            v_rebuild.0,
            v_split.0,
            v_two.0,
            v_refit.1,
            v_rebuild.1,
            v_split.1,
            v_two.1,
            self.split.moving_sah_cost(self.part) / self.built_moving_sah,
        );
    }
}

/// What is measured, and the table's header.
fn print_header(name: &str, scene: &Scene, trees: &Trees, size: (u32, u32)) {
    println!(
        "{}: {} triangles, {} instances (BLASes built once in {:.0} ms); {}×{} primary rays + a shadow ray per hit",
        name,
        scene.triangles.len(),
        trees.two.instance_count(),
        trees.blas_ms,
        size.0,
        size.1
    );
    println!();
    println!(
        "split tree: {} static and {} moving triangles",
        trees.part.first_slot,
        scene.triangles.len() - trees.part.first_slot
    );
    println!();
    println!(
        "| time | refit | rebuild | split refit | split rebuild | TLAS | SAH refit | SAH rebuild | SAH split | SAH two-level | nodes/ray refit | rebuild | split | two-level | triangles/ray refit | rebuild | split | two-level | split: moving part's SAH ÷ built |"
    );
    println!(
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
    );
}

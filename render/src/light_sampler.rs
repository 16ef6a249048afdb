//! The light samplers' GPU data beside the power table (docs/src/light-samplers.md): the
//! presampled lights (the light tiles' entries or ReGIR's slots) and the light BVH. The
//! renderer owns them and allocates each on the first frame that uses it (a one-element
//! placeholder before), so a scene that never asks for a structure pays nothing for it.
//! The BVH is the plain-Rust `LightBvh` (the model its tests check) uploaded as it is:
//! built on a scene's first frame that uses it, refitted when lights move or change power,
//! on the GPU by default (`light_sampler/gpu_refit.rs`). A scene's lights keep their slots,
//! so none is ever added or removed: a light switched off stays in the tree with no power.

mod gpu_refit;

use std::time::Instant;

use glam::Vec3;

use crate::gpu::{Gpu, write_runs};
use crate::gpu_scene::{GpuScene, oct_encode};
use crate::gpu_types::{GpuLightBvhNode, GpuLightBvhTrail, GpuPresampledLight};
use crate::light_bvh::{EmissiveTriangle, LightBvh, Node};
use crate::shader_constants::{LIGHT_BVH_CONE_SLACK, LIGHT_BVH_LEAF, LIGHT_BVH_NOT_IN_TREE};

/// Rewritten nodes closer than this are uploaded in one write with the nodes between them.
const UPLOAD_GAP: usize = 64;

/// What the light samplers cost, for `--stats`, the viewer and docs/src/measured/many-lights.md.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct LightSamplerStats {
    /// Lights in the BVH, its nodes, its bytes on the GPU (nodes and trails).
    pub bvh_lights: usize,
    pub bvh_nodes: usize,
    pub bvh_bytes: u64,
    /// The last build and the last refit on the CPU, upload included (ms).
    pub bvh_build_ms: f64,
    pub bvh_refit_ms: f64,
    pub bvh_refits: u64,
    /// Nodes the last refit rewrote (the changed lights' leaves and everything above them).
    pub bvh_refit_nodes: usize,
    /// The last refit ran on the GPU (`light_bvh_gpu_refit`); its time then is the CPU's
    /// share (finding the nodes, uploading the work) plus, when the frame is timed, the
    /// GPU's, waited for.
    pub bvh_refit_on_gpu: bool,
    /// The presampled lights' bytes (the tiles' entries or ReGIR's slots, 64 each).
    pub presampled_bytes: u64,
}

/// A light's selection probability at a shading point under each sampler, for the
/// inspector: the power table's (the tiles draw from it too), and the light BVH's when it
/// is built (`None` before the first frame that samples with it). ReGIR has none to show:
/// its slots carry contribution weights W, unbiased estimates of 1 / p, not a PDF.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SelectionPdfs {
    pub light: u32,
    pub power: f32,
    pub bvh: Option<f32>,
}

/// The BVH of the scene's lights as built, with what it was built from.
struct SceneLightBvh {
    tree: LightBvh,
    /// Its nodes as uploaded (a refit rewrites the changed ones).
    records: Vec<GpuLightBvhNode>,
    /// The lights it holds (those with a position) and their light-table entries.
    lights: Vec<EmissiveTriangle>,
    entries: Vec<u32>,
    power_generation: u64,
    motion_generation: u64,
    /// The scene's `light_changes` generation it has caught up with.
    change_generation: u64,
    /// The refit on the GPU, made on its first use (`light_bvh_gpu_refit`).
    gpu_refit: Option<gpu_refit::GpuRefit>,
    /// The GPU has refitted the tree since `tree` and `records` were last brought up to
    /// date: only `lights` is current on the CPU.
    refitted_on_gpu: bool,
}

pub struct LightSamplerBuffers {
    /// The light tiles' entries or ReGIR's slots (the frame uses one or the other).
    pub presampled: wgpu::Buffer,
    pub bvh_nodes: wgpu::Buffer,
    pub bvh_trails: wgpu::Buffer,
    bvh: Option<SceneLightBvh>,
    pub stats: LightSamplerStats,
    /// Test-only: the BVH is neither refitted nor rebuilt (a planted stale tree).
    pub frozen: bool,
    /// Test-only: each refit loses one light of the scene's change list (planted).
    pub planted_lost_change: bool,
    /// Wait for a GPU refit and count its time in `bvh_refit_ms` (frames that are timed).
    pub wait_for_gpu_refit: bool,
    /// The refit's pipeline failed to compile on this device: the CPU refits.
    gpu_refit_failed: bool,
}

fn storage(gpu: &Gpu, label: &str, bytes: u64) -> wgpu::Buffer {
    gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: bytes.max(16),
        // COPY_SRC: the tests read the tree back.
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_DST
            | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    })
}

fn size_of<T>(count: u64) -> u64 {
    count * std::mem::size_of::<T>() as u64
}

impl LightSamplerBuffers {
    /// One-element placeholders for every structure.
    pub fn new(gpu: &Gpu) -> LightSamplerBuffers {
        LightSamplerBuffers {
            presampled: storage(gpu, "presampled lights", size_of::<GpuPresampledLight>(1)),
            bvh_nodes: storage(gpu, "light bvh nodes", size_of::<GpuLightBvhNode>(1)),
            bvh_trails: storage(gpu, "light bvh trails", size_of::<GpuLightBvhTrail>(1)),
            bvh: None,
            stats: LightSamplerStats::default(),
            frozen: false,
            planted_lost_change: false,
            wait_for_gpu_refit: false,
            gpu_refit_failed: false,
        }
    }

    /// Room for `count` presampled lights (the tiles' entries, or ReGIR's cells × slots);
    /// true if it replaced the buffer (bind groups holding the old one must be rebuilt).
    pub fn ensure_presampled(&mut self, gpu: &Gpu, count: u32) -> bool {
        let bytes = size_of::<GpuPresampledLight>(count as u64);
        let replace = self.presampled.size() < bytes;
        if replace {
            self.presampled = storage(gpu, "presampled lights", bytes);
        }
        self.stats.presampled_bytes = bytes;
        replace
    }

    /// The light BVH of `scene` as it is now: built on first use, refitted after its
    /// lights moved or changed power, on the GPU if `on_gpu`. True if the buffers were
    /// replaced.
    pub fn ensure_bvh(&mut self, gpu: &Gpu, scene: &GpuScene, on_gpu: bool) -> bool {
        let power = scene.light_power_generation;
        let motion = scene.light_motion_generation;
        match &mut self.bvh {
            Some(_) if self.frozen => false,
            Some(b) if b.power_generation == power && b.motion_generation == motion => false,
            Some(b) => {
                let start = Instant::now();
                let mut changed = Vec::new();
                match scene.light_changes.since(b.change_generation) {
                    // The scene's log names the entries that changed: only those are read.
                    Some(mut entries) => {
                        if self.planted_lost_change {
                            entries.pop();
                        }
                        for entry in entries {
                            let Ok(i) = b.entries.binary_search(&entry) else {
                                continue; // the environment or a directional light
                            };
                            if let Some(now) = scene.light_sampler_light(entry)
                                && now != b.lights[i]
                            {
                                b.lights[i] = now;
                                changed.push(i);
                            }
                        }
                    }
                    // The log no longer reaches back: every light compared.
                    None => {
                        let now = scene.light_sampler_lights();
                        for (i, (light, &entry)) in b.lights.iter_mut().zip(&b.entries).enumerate()
                        {
                            if let Some(Some(t)) =
                                now.get(entry as usize).filter(|t| **t != Some(*light))
                            {
                                *light = *t;
                                changed.push(i);
                            }
                        }
                    }
                }
                b.change_generation = scene.light_changes.generation();
                b.power_generation = power;
                b.motion_generation = motion;
                if on_gpu && b.gpu_refit.is_none() && !self.gpu_refit_failed {
                    match gpu_refit::GpuRefit::new(gpu, &b.tree) {
                        Ok(g) => b.gpu_refit = Some(g),
                        Err(e) => {
                            // Said once: every later refit runs on the CPU.
                            log::error!(
                                "light BVH refit on the GPU unavailable ({e}); refitting on the CPU"
                            );
                            self.gpu_refit_failed = true;
                        }
                    }
                }
                match b.gpu_refit.as_mut().filter(|_| on_gpu) {
                    Some(g) => {
                        self.stats.bvh_refit_nodes =
                            g.refit(gpu, &b.tree, &b.lights, &changed, &self.bvh_nodes);
                        b.refitted_on_gpu = true;
                        if self.wait_for_gpu_refit {
                            gpu.wait_idle();
                        }
                    }
                    None => {
                        // The GPU's bounds would go stale: a later GPU refit starts anew.
                        b.gpu_refit = None;
                        self.stats.bvh_refit_nodes = cpu_refit(gpu, b, &changed, &self.bvh_nodes);
                    }
                }
                self.stats.bvh_refit_on_gpu = on_gpu && b.gpu_refit.is_some();
                self.stats.bvh_refit_ms = start.elapsed().as_secs_f64() * 1e3;
                self.stats.bvh_refits += 1;
                false
            }
            None => {
                self.build_bvh(gpu, scene);
                true
            }
        }
    }

    fn build_bvh(&mut self, gpu: &Gpu, scene: &GpuScene) {
        let start = Instant::now();
        let all = scene.light_sampler_lights();
        let (entries, lights): (Vec<u32>, Vec<EmissiveTriangle>) = all
            .iter()
            .enumerate()
            .filter_map(|(i, l)| l.map(|l| (i as u32, l)))
            .unzip();
        let tree = LightBvh::build(&lights);
        let nodes = node_records(&tree, &entries);
        let trails = trail_records(&tree, &entries, all.len());
        self.bvh_nodes = storage(
            gpu,
            "light bvh nodes",
            size_of::<GpuLightBvhNode>(nodes.len() as u64),
        );
        self.bvh_trails = storage(
            gpu,
            "light bvh trails",
            size_of::<GpuLightBvhTrail>(trails.len() as u64),
        );
        gpu.queue
            .write_buffer(&self.bvh_nodes, 0, bytemuck::cast_slice(&nodes));
        gpu.queue
            .write_buffer(&self.bvh_trails, 0, bytemuck::cast_slice(&trails));
        self.stats.bvh_lights = tree.in_tree.iter().filter(|&&t| t).count();
        self.stats.bvh_nodes = tree.nodes.len();
        self.stats.bvh_bytes = self.bvh_nodes.size() + self.bvh_trails.size();
        self.stats.bvh_build_ms = start.elapsed().as_secs_f64() * 1e3;
        self.bvh = Some(SceneLightBvh {
            tree,
            records: nodes,
            lights,
            entries,
            power_generation: scene.light_power_generation,
            motion_generation: scene.light_motion_generation,
            change_generation: scene.light_changes.generation(),
            gpu_refit: None,
            refitted_on_gpu: false,
        });
    }

    /// `light`'s selection probability at point `p` with normal `n` under each sampler
    /// (light_bvh.wgsl's `light_bvh_selection`, by the plain-Rust tree it was uploaded from).
    pub fn selection_pdfs(
        &mut self,
        scene: &GpuScene,
        light: u32,
        p: Vec3,
        n: Vec3,
    ) -> SelectionPdfs {
        let power = scene.light_select_pdf(light).unwrap_or(0.0);
        if let Some(b) = self.bvh.as_mut().filter(|b| b.refitted_on_gpu) {
            // The tree the GPU refitted, on the CPU (its records stay as they were).
            b.tree.refit(&b.lights);
        }
        let bvh = self
            .bvh
            .as_ref()
            .map(|b| match b.entries.binary_search(&light) {
                Ok(index) => scene.finite_light_share() * b.tree.pdf(index, p, n, true),
                // No position (the environment, a directional light): the table's.
                Err(_) => power,
            });
        SelectionPdfs { light, power, bvh }
    }

    /// Drops the BVH (a new scene): the next frame that samples with it builds it again.
    pub fn forget_scene(&mut self) {
        self.bvh = None;
    }
}

/// The refit on the CPU of the `changed` lights (already in `b.lights`): their nodes
/// recomputed and uploaded in runs; after refits on the GPU, every node (the CPU's tree
/// and records are older than the GPU's). Returns the nodes it rewrote.
fn cpu_refit(gpu: &Gpu, b: &mut SceneLightBvh, changed: &[usize], nodes: &wgpu::Buffer) -> usize {
    if b.refitted_on_gpu {
        b.tree.refit(&b.lights);
        b.records = node_records(&b.tree, &b.entries);
        gpu.queue
            .write_buffer(nodes, 0, bytemuck::cast_slice(&b.records));
        b.refitted_on_gpu = false;
        return b.records.len();
    }
    let rewritten = b.tree.refit_changed(&b.lights, changed);
    for &index in &rewritten {
        b.records[index] = node_record(&b.tree, index, &b.entries);
    }
    write_runs(gpu, nodes, &b.records, &rewritten, UPLOAD_GAP);
    rewritten.len()
}

/// The tree's nodes as the GPU reads them (at least one, a placeholder for an empty tree:
/// the shader never walks it, `finite_light_share` is then 0).
pub fn node_records(tree: &LightBvh, entries: &[u32]) -> Vec<GpuLightBvhNode> {
    let mut nodes: Vec<GpuLightBvhNode> = (0..tree.nodes.len())
        .map(|index| node_record(tree, index, entries))
        .collect();
    if nodes.is_empty() {
        nodes.push(GpuLightBvhNode::default());
    }
    nodes
}

/// Node `index` as the GPU reads it.
fn node_record(tree: &LightBvh, index: usize, entries: &[u32]) -> GpuLightBvhNode {
    let node = &tree.nodes[index];
    let b = node.bounds();
    let child_or_light = match node {
        Node::Leaf { light, .. } => LIGHT_BVH_LEAF | entries[*light],
        Node::Interior { children, .. } => {
            debug_assert_eq!(children[0], index + 1, "first child follows its parent");
            children[1] as u32
        }
    };
    let cos_theta_o = if b.normals.cos_theta <= -1.0 {
        -1.0
    } else {
        (b.normals.cos_theta.clamp(-1.0, 1.0).acos() + LIGHT_BVH_CONE_SLACK)
            .min(std::f32::consts::PI)
            .cos()
    };
    GpuLightBvhNode {
        min: b.min.into(),
        phi: b.phi,
        max: b.max.into(),
        child_or_light,
        axis: oct_encode(b.normals.w.normalize_or(Vec3::Z)),
        cos_theta_o,
        cos_theta_e: b.cos_theta_e,
        _pad: 0,
    }
}

/// Per light-table entry, its trail (`LIGHT_BVH_NOT_IN_TREE` for entries outside the tree).
pub fn trail_records(
    tree: &LightBvh,
    entries: &[u32],
    entry_count: usize,
) -> Vec<GpuLightBvhTrail> {
    let mut trails = vec![
        GpuLightBvhTrail {
            bits: [0, 0],
            depth: LIGHT_BVH_NOT_IN_TREE,
            _pad: 0,
        };
        entry_count.max(1)
    ];
    for (light, &entry) in entries.iter().enumerate() {
        if tree.in_tree[light] {
            let (bits, depth) = tree.trails[light];
            trails[entry as usize] = GpuLightBvhTrail {
                bits: [bits as u32, (bits >> 32) as u32],
                depth,
                _pad: 0,
            };
        }
    }
    trails
}

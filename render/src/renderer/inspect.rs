//! The pixel inspector: while a pixel is selected, every frame copies that pixel's
//! reservoir after each stage, its surface and its debug record into a small buffer that
//! comes back asynchronously with the frame's report.

use super::inspect_pt::PtInspection;
use crate::gi::constants::*;
use crate::gpu::readback::ReadbackRing;
use crate::gpu_types::{
    GpuDenoiseHistory, GpuGiPixelDebug, GpuGiReservoir, GpuPixelDebug, GpuPtPixelDebug,
    GpuPtProbeStage, GpuReservoir, GpuSurface, NO_LIGHT,
};
use crate::pt::constants::*;
use crate::shader_constants::*;

/// DI's stages: initial, temporal and up to 8 spatial passes.
const MAX_STAGES: usize = 10;
/// GI's stages: gi initial, temporal, spatial.
const MAX_GI_STAGES: usize = 3;

/// The staging record a capture fills, one field per thing it copies: each copy lands at
/// its field's offset and the readback is one read, so no offset is summed by hand.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct InspectRecord {
    surface: GpuSurface,
    debug: GpuPixelDebug,
    reservoirs: [GpuReservoir; MAX_STAGES],
    gi_debug: GpuGiPixelDebug,
    gi_reservoirs: [GpuGiReservoir; MAX_GI_STAGES],
    /// The pixel's radiance this frame (what the image shows there before tonemapping).
    radiance: [f32; 4],
    /// ReSTIR PT's debug record and path probe (inspect_pt.rs).
    pt_debug: GpuPtPixelDebug,
    pt_probe: [GpuPtProbeStage; PT_PROBE_STAGES as usize],
    /// The denoiser's history record and temporal gradient (gradient, before, now, -).
    denoise_history: GpuDenoiseHistory,
    gradient: [f32; 4],
}

pub const INSPECT_BYTES: u64 = size_of::<InspectRecord>() as u64;

/// Where `field` of the staging record starts, in bytes.
macro_rules! at {
    ($field:ident) => {
        std::mem::offset_of!(InspectRecord, $field) as u64
    };
}
/// The size of one `T` in bytes: what a copy of one pixel's record moves.
const fn bytes<T>() -> u64 {
    size_of::<T>() as u64
}

/// One stage's reservoir at the inspected pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct StageReservoir {
    /// "initial", "temporal", "spatial 1", ...
    pub stage: String,
    pub reservoir: GpuReservoir,
    /// World position of the reservoir's light sample (None for the null sample and for
    /// environment samples, which have no position).
    pub sample_point: Option<[f32; 3]>,
    /// The world direction toward the sky when the sample is an environment direction.
    pub environment_direction: Option<[f32; 3]>,
}

/// One GI stage's reservoir at the inspected pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct GiStageReservoir {
    /// "gi initial", "gi temporal", "gi spatial".
    pub stage: String,
    pub reservoir: GpuGiReservoir,
}

impl GiStageReservoir {
    pub fn is_null(&self) -> bool {
        // A NaN weight counts as null too.
        let usable = self.reservoir.weight > 0.0;
        (self.reservoir.packed & GI_SOURCE_MASK) == SOURCE_NULL || !usable
    }

    pub fn source_name(&self) -> &'static str {
        let source = self.reservoir.packed & GI_SOURCE_MASK;
        SOURCE_NAMES.get(source as usize).copied().unwrap_or("?")
    }

    pub fn age(&self) -> u32 {
        self.reservoir.packed >> GI_AGE_SHIFT
    }

    /// The GI rejection bits the stage that wrote it recorded, by name.
    pub fn rejections(&self) -> Vec<&'static str> {
        gi_bit_names((self.reservoir.packed >> GI_FLAGS_SHIFT) & GI_FLAGS_MASK)
    }
}

/// The ReSTIR GI part of an inspection (present when GI ran that frame).
#[derive(Clone, Debug, PartialEq)]
pub struct GiInspection {
    pub debug: GpuGiPixelDebug,
    pub stages: Vec<GiStageReservoir>,
}

impl GiInspection {
    pub fn temporal_rejections(&self) -> Vec<&'static str> {
        gi_bit_names(self.debug.temporal_mask)
    }

    pub fn spatial_rejections(&self) -> Vec<&'static str> {
        gi_bit_names(self.debug.spatial_mask)
    }
}

fn gi_bit_names(mask: u32) -> Vec<&'static str> {
    GI_REJECT_REASON_NAMES
        .iter()
        .enumerate()
        .filter(|(i, _)| mask & (1 << i) != 0)
        .map(|(_, n)| *n)
        .collect()
}

/// The denoiser at the inspected pixel (present when it ran that frame).
#[derive(Clone, Debug, PartialEq)]
pub struct DenoiseInspection {
    /// The temporal history after this frame: its length, the accumulated illumination and
    /// the luminance moments.
    pub history: GpuDenoiseHistory,
    /// λ, the share of the neighbourhood's lighting that changed (0 with gradients off),
    /// and the neighbourhood's shading before and now that it came from.
    pub gradient: f32,
    pub gradient_before: f32,
    pub gradient_now: f32,
}

impl DenoiseInspection {
    /// The standard deviation of the luminance over its mean, from the moments.
    pub fn relative_sigma(&self) -> f32 {
        let [m1, m2] = self.history.moments;
        (m2 - m1 * m1).max(0.0).sqrt() / m1.max(1e-6)
    }
}

/// Everything the inspector shows about one pixel in one frame.
#[derive(Clone, Debug, PartialEq)]
pub struct PixelInspection {
    pub frame: u64,
    pub pixel: (u32, u32),
    pub surface: GpuSurface,
    pub debug: GpuPixelDebug,
    pub stages: Vec<StageReservoir>,
    pub gi: Option<GiInspection>,
    /// ReSTIR PT's paths, per stage (present when PT ran that frame).
    pub pt: Option<PtInspection>,
    /// The pixel's linear radiance this frame (the value the pixel history plots; after
    /// the denoiser when it runs).
    pub radiance: [f32; 3],
    pub denoise: Option<DenoiseInspection>,
    /// The final survivor's light under each light sampler (docs/src/light-samplers.md);
    /// `None` without a survivor.
    pub light_pdfs: Option<crate::light_sampler::SelectionPdfs>,
}

fn bit_names(mask: u32) -> Vec<&'static str> {
    REJECT_REASON_NAMES
        .iter()
        .enumerate()
        .filter(|(i, _)| mask & (1 << i) != 0)
        .map(|(_, n)| *n)
        .collect()
}

impl PixelInspection {
    /// Why the temporal candidate was rejected (empty when it was merged or no
    /// temporal pass ran).
    pub fn temporal_rejections(&self) -> Vec<&'static str> {
        bit_names(self.debug.temporal_mask)
    }

    /// Reasons any spatial neighbour was rejected.
    pub fn spatial_rejections(&self) -> Vec<&'static str> {
        bit_names(self.debug.spatial_mask)
    }

    pub fn source_name(&self) -> &'static str {
        SOURCE_NAMES
            .get(self.debug.source as usize)
            .copied()
            .unwrap_or("?")
    }
}

/// The copies recorded for one frame.
pub struct InspectCapture {
    pixel: (u32, u32),
    index: u64,
    /// The renderer's persistent staging buffer (allocated once, reused every frame: the
    /// ring copies out of it before the next frame's copies land in queue order).
    staging: wgpu::Buffer,
    stages: Vec<String>,
    gi_stages: Vec<String>,
    gi: bool,
    pt: bool,
    denoise: bool,
}

/// A capture in flight: the stage names, waiting for its bytes.
pub struct PendingInspection {
    pub pixel: (u32, u32),
    pub stages: Vec<String>,
    pub gi_stages: Vec<String>,
    pub gi: bool,
    pub pt: bool,
    pub denoise: bool,
}

impl InspectCapture {
    pub fn new(pixel: (u32, u32), size: (u32, u32), staging: wgpu::Buffer) -> InspectCapture {
        let (x, y) = (pixel.0.min(size.0 - 1), pixel.1.min(size.1 - 1));
        InspectCapture {
            pixel: (x, y),
            index: (y * size.0 + x) as u64,
            staging,
            stages: Vec::new(),
            gi_stages: Vec::new(),
            gi: false,
            pt: false,
            denoise: false,
        }
    }

    /// The staging buffer every capture writes into.
    pub fn staging_buffer(device: &wgpu::Device) -> wgpu::Buffer {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("inspect"),
            size: INSPECT_BYTES,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        })
    }

    /// Copies the pixel's reservoir from `reservoirs` as the next stage.
    pub fn copy_reservoir(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        reservoirs: &wgpu::Buffer,
        stage: &str,
    ) {
        let slot = self.stages.len();
        if slot >= MAX_STAGES {
            return;
        }
        let name = if stage == "spatial" {
            format!(
                "spatial {}",
                self.stages
                    .iter()
                    .filter(|s| s.starts_with("spatial"))
                    .count()
                    + 1
            )
        } else {
            stage.to_string()
        };
        self.stages.push(name);
        let size = bytes::<GpuReservoir>();
        let to = at!(reservoirs) + slot as u64 * size;
        encoder.copy_buffer_to_buffer(reservoirs, self.index * size, &self.staging, to, size);
    }

    /// Copies the pixel's GI reservoir from `reservoirs` as the next GI stage.
    pub fn copy_gi_reservoir(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        reservoirs: &wgpu::Buffer,
        stage: &str,
    ) {
        let slot = self.gi_stages.len();
        if slot >= MAX_GI_STAGES {
            return;
        }
        self.gi_stages.push(stage.to_string());
        let size = bytes::<GpuGiReservoir>();
        let to = at!(gi_reservoirs) + slot as u64 * size;
        encoder.copy_buffer_to_buffer(reservoirs, self.index * size, &self.staging, to, size);
    }

    /// Copies the pixel's GI debug record (frames where GI ran).
    pub fn copy_gi_debug(&mut self, encoder: &mut wgpu::CommandEncoder, gi_debug: &wgpu::Buffer) {
        self.gi = true;
        let size = bytes::<GpuGiPixelDebug>();
        encoder.copy_buffer_to_buffer(
            gi_debug,
            self.index * size,
            &self.staging,
            at!(gi_debug),
            size,
        );
    }

    /// Copies the pixel's PT debug record and the PT path probe (frames where PT ran; the
    /// probe was cleared before the frame, so a stage that did not run reads as absent).
    pub fn copy_pt(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        pt_debug: &wgpu::Buffer,
        pt_probe: &wgpu::Buffer,
    ) {
        self.pt = true;
        let size = bytes::<GpuPtPixelDebug>();
        encoder.copy_buffer_to_buffer(
            pt_debug,
            self.index * size,
            &self.staging,
            at!(pt_debug),
            size,
        );
        let size = PT_PROBE_STAGES as u64 * bytes::<GpuPtProbeStage>();
        encoder.copy_buffer_to_buffer(pt_probe, 0, &self.staging, at!(pt_probe), size);
    }

    /// Copies the pixel's surface, final debug record and radiance.
    /// The inspected pixel's records at the end of a frame: its surface, debug record and
    /// radiance, and the indirect technique's debug records while GI or PT runs.
    pub fn copy_frame_records(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        targets: &crate::frame_targets::FrameTargets,
        surfaces: usize,
        gi: bool,
        pt: bool,
        denoise_history: Option<usize>,
    ) {
        use crate::gi::passes::initial::GI_DEBUG;
        use crate::passes::resources::{DEBUG, RADIANCE};
        use crate::pt::passes::initial::{PT_DEBUG, PT_PROBE};
        self.copy_pixel_records(
            encoder,
            &targets.surfaces[surfaces],
            targets.pixels(&DEBUG),
            targets.pixels(&RADIANCE),
        );
        if gi {
            self.copy_gi_debug(encoder, targets.pixels(&GI_DEBUG));
        }
        if pt {
            self.copy_pt(
                encoder,
                targets.pixels(&PT_DEBUG),
                targets.pixels(&PT_PROBE),
            );
        }
        if let Some(buffer) = denoise_history {
            use crate::denoise::passes::{GRADIENT, HISTORY};
            self.denoise = true;
            let history = targets.chain(&HISTORY, buffer);
            let size = bytes::<GpuDenoiseHistory>();
            let to = at!(denoise_history);
            encoder.copy_buffer_to_buffer(history, self.index * size, &self.staging, to, size);
            let gradient = targets.pixels(&GRADIENT);
            let size = bytes::<[f32; 4]>();
            let to = at!(gradient);
            encoder.copy_buffer_to_buffer(gradient, self.index * size, &self.staging, to, size);
        }
    }

    pub fn copy_pixel_records(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        surfaces: &wgpu::Buffer,
        debug: &wgpu::Buffer,
        radiance: &wgpu::Buffer,
    ) {
        let copy = |encoder: &mut wgpu::CommandEncoder, from: &wgpu::Buffer, to: u64, size: u64| {
            encoder.copy_buffer_to_buffer(from, self.index * size, &self.staging, to, size)
        };
        copy(encoder, radiance, at!(radiance), bytes::<[f32; 4]>());
        copy(encoder, surfaces, at!(surface), bytes::<GpuSurface>());
        copy(encoder, debug, at!(debug), bytes::<GpuPixelDebug>());
    }

    /// Queues the readback of everything copied this frame.
    pub fn submit_copy(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        ring: &mut ReadbackRing,
        frame: u64,
    ) {
        ring.copy_from(device, encoder, &self.staging, INSPECT_BYTES, frame);
    }

    pub fn into_pending(self) -> PendingInspection {
        PendingInspection {
            pixel: self.pixel,
            stages: self.stages,
            gi_stages: self.gi_stages,
            gi: self.gi,
            pt: self.pt,
            denoise: self.denoise,
        }
    }
}

impl PendingInspection {
    /// Decodes the bytes read back; `sample_point` maps (light, uv) to a world position,
    /// `environment_direction` to a direction when the light is the environment.
    pub fn finish(
        self,
        frame: u64,
        bytes: &[u8],
        sample_point: impl Fn(u32, [f32; 2]) -> Option<[f32; 3]>,
        environment_direction: impl Fn(u32, [f32; 2]) -> Option<[f32; 3]>,
    ) -> Option<PixelInspection> {
        if (bytes.len() as u64) < INSPECT_BYTES {
            return None;
        }
        let record: InspectRecord = bytemuck::pod_read_unaligned(&bytes[..INSPECT_BYTES as usize]);
        let gi = self.gi.then(|| GiInspection {
            debug: record.gi_debug,
            stages: self
                .gi_stages
                .iter()
                .zip(record.gi_reservoirs)
                .map(|(stage, reservoir)| GiStageReservoir {
                    stage: stage.clone(),
                    reservoir,
                })
                .collect(),
        });
        let stages = self
            .stages
            .into_iter()
            .zip(record.reservoirs)
            .map(|(stage, reservoir)| {
                let sample_point = (reservoir.light != NO_LIGHT)
                    .then(|| sample_point(reservoir.light, reservoir.uv))
                    .flatten();
                StageReservoir {
                    stage,
                    reservoir,
                    sample_point,
                    environment_direction: environment_direction(reservoir.light, reservoir.uv),
                }
            })
            .collect();
        let radiance = record.radiance;
        Some(PixelInspection {
            frame,
            pixel: self.pixel,
            surface: record.surface,
            debug: record.debug,
            stages,
            gi,
            pt: self
                .pt
                .then(|| PtInspection::decode(&record.pt_debug, &record.pt_probe)),
            radiance: [radiance[0], radiance[1], radiance[2]],
            light_pdfs: None,
            denoise: self.denoise.then(|| DenoiseInspection {
                history: record.denoise_history,
                gradient: record.gradient[0],
                gradient_before: record.gradient[1],
                gradient_now: record.gradient[2],
            }),
        })
    }
}

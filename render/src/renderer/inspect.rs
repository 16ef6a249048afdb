//! The pixel inspector: while a pixel is selected, every frame copies that pixel's
//! reservoir after each stage, its surface and its debug record into a small buffer that
//! comes back asynchronously with the frame's report.

use super::inspect_pt::{PT_BYTES, PT_DEBUG_BYTES, PtInspection};
use crate::gpu::readback::ReadbackRing;
use crate::gpu_types::{
    GpuDenoiseHistory, GpuGiPixelDebug, GpuGiReservoir, GpuPixelDebug, GpuReservoir, GpuSurface,
    NO_LIGHT,
};
use crate::shader_constants::*;

const SURFACE_BYTES: u64 = std::mem::size_of::<GpuSurface>() as u64;
const DEBUG_BYTES: u64 = std::mem::size_of::<GpuPixelDebug>() as u64;
const RESERVOIR_BYTES: u64 = std::mem::size_of::<GpuReservoir>() as u64;
/// initial, temporal and up to 8 spatial passes.
const MAX_STAGES: u64 = 10;
const DI_BYTES: u64 = SURFACE_BYTES + DEBUG_BYTES + MAX_STAGES * RESERVOIR_BYTES;
/// ReSTIR GI, after the DI part: its debug record, then gi initial, temporal, spatial.
const GI_DEBUG_BYTES: u64 = std::mem::size_of::<GpuGiPixelDebug>() as u64;
const GI_RESERVOIR_BYTES: u64 = std::mem::size_of::<GpuGiReservoir>() as u64;
const MAX_GI_STAGES: u64 = 3;
const GI_BYTES: u64 = GI_DEBUG_BYTES + MAX_GI_STAGES * GI_RESERVOIR_BYTES;
/// Last, the pixel's radiance this frame (what the image shows there before tonemapping).
const RADIANCE_BYTES: u64 = 16;
/// Then ReSTIR PT's debug record and path probe (inspect_pt.rs).
const PT_AT: u64 = DI_BYTES + GI_BYTES + RADIANCE_BYTES;
/// Then the denoiser's history record and temporal gradient.
const DENOISE_AT: u64 = PT_AT + PT_BYTES;
const DENOISE_HISTORY_BYTES: u64 = std::mem::size_of::<GpuDenoiseHistory>() as u64;
const GRADIENT_BYTES: u64 = 16;
pub const INSPECT_BYTES: u64 = DENOISE_AT + DENOISE_HISTORY_BYTES + GRADIENT_BYTES;

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
        let slot = self.stages.len() as u64;
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
        encoder.copy_buffer_to_buffer(
            reservoirs,
            self.index * RESERVOIR_BYTES,
            &self.staging,
            SURFACE_BYTES + DEBUG_BYTES + slot * RESERVOIR_BYTES,
            RESERVOIR_BYTES,
        );
    }

    /// Copies the pixel's GI reservoir from `reservoirs` as the next GI stage.
    pub fn copy_gi_reservoir(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        reservoirs: &wgpu::Buffer,
        stage: &str,
    ) {
        let slot = self.gi_stages.len() as u64;
        if slot >= MAX_GI_STAGES {
            return;
        }
        self.gi_stages.push(stage.to_string());
        encoder.copy_buffer_to_buffer(
            reservoirs,
            self.index * GI_RESERVOIR_BYTES,
            &self.staging,
            DI_BYTES + GI_DEBUG_BYTES + slot * GI_RESERVOIR_BYTES,
            GI_RESERVOIR_BYTES,
        );
    }

    /// Copies the pixel's GI debug record (frames where GI ran).
    pub fn copy_gi_debug(&mut self, encoder: &mut wgpu::CommandEncoder, gi_debug: &wgpu::Buffer) {
        self.gi = true;
        encoder.copy_buffer_to_buffer(
            gi_debug,
            self.index * GI_DEBUG_BYTES,
            &self.staging,
            DI_BYTES,
            GI_DEBUG_BYTES,
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
        encoder.copy_buffer_to_buffer(
            pt_debug,
            self.index * PT_DEBUG_BYTES,
            &self.staging,
            PT_AT,
            PT_DEBUG_BYTES,
        );
        encoder.copy_buffer_to_buffer(
            pt_probe,
            0,
            &self.staging,
            PT_AT + PT_DEBUG_BYTES,
            PT_BYTES - PT_DEBUG_BYTES,
        );
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
        use crate::passes::gi::initial::GI_DEBUG;
        use crate::passes::pt::initial::{PT_DEBUG, PT_PROBE};
        use crate::passes::resources::{DEBUG, RADIANCE};
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
            use crate::passes::denoise::{GRADIENT, HISTORY};
            self.denoise = true;
            let history = targets.chain(&HISTORY, buffer);
            let at = self.index * DENOISE_HISTORY_BYTES;
            let to = DENOISE_AT;
            encoder.copy_buffer_to_buffer(history, at, &self.staging, to, DENOISE_HISTORY_BYTES);
            let at = self.index * GRADIENT_BYTES;
            let to = DENOISE_AT + DENOISE_HISTORY_BYTES;
            let gradient = targets.pixels(&GRADIENT);
            encoder.copy_buffer_to_buffer(gradient, at, &self.staging, to, GRADIENT_BYTES);
        }
    }

    pub fn copy_pixel_records(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        surfaces: &wgpu::Buffer,
        debug: &wgpu::Buffer,
        radiance: &wgpu::Buffer,
    ) {
        let index = self.index;
        encoder.copy_buffer_to_buffer(
            radiance,
            index * RADIANCE_BYTES,
            &self.staging,
            DI_BYTES + GI_BYTES,
            RADIANCE_BYTES,
        );
        encoder.copy_buffer_to_buffer(
            surfaces,
            index * SURFACE_BYTES,
            &self.staging,
            0,
            SURFACE_BYTES,
        );
        encoder.copy_buffer_to_buffer(
            debug,
            index * DEBUG_BYTES,
            &self.staging,
            SURFACE_BYTES,
            DEBUG_BYTES,
        );
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
        let surface: GpuSurface = bytemuck::pod_read_unaligned(&bytes[..SURFACE_BYTES as usize]);
        let debug: GpuPixelDebug = bytemuck::pod_read_unaligned(
            &bytes[SURFACE_BYTES as usize..(SURFACE_BYTES + DEBUG_BYTES) as usize],
        );
        let gi = self.gi.then(|| {
            let at = DI_BYTES as usize;
            let debug: GpuGiPixelDebug =
                bytemuck::pod_read_unaligned(&bytes[at..at + GI_DEBUG_BYTES as usize]);
            let stages = self
                .gi_stages
                .iter()
                .enumerate()
                .map(|(slot, stage)| {
                    let start =
                        (DI_BYTES + GI_DEBUG_BYTES + slot as u64 * GI_RESERVOIR_BYTES) as usize;
                    GiStageReservoir {
                        stage: stage.clone(),
                        reservoir: bytemuck::pod_read_unaligned(
                            &bytes[start..start + GI_RESERVOIR_BYTES as usize],
                        ),
                    }
                })
                .collect();
            GiInspection { debug, stages }
        });
        let stages = self
            .stages
            .into_iter()
            .enumerate()
            .map(|(slot, stage)| {
                let start = (SURFACE_BYTES + DEBUG_BYTES + slot as u64 * RESERVOIR_BYTES) as usize;
                let reservoir: GpuReservoir =
                    bytemuck::pod_read_unaligned(&bytes[start..start + RESERVOIR_BYTES as usize]);
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
        let at = (DI_BYTES + GI_BYTES) as usize;
        let radiance: [f32; 4] =
            bytemuck::pod_read_unaligned(&bytes[at..at + RADIANCE_BYTES as usize]);
        Some(PixelInspection {
            frame,
            pixel: self.pixel,
            surface,
            debug,
            stages,
            gi,
            pt: self
                .pt
                .then(|| PtInspection::decode(&bytes[PT_AT as usize..]))
                .flatten(),
            radiance: [radiance[0], radiance[1], radiance[2]],
            light_pdfs: None,
            denoise: self.denoise.then(|| {
                let at = DENOISE_AT as usize;
                let history =
                    bytemuck::pod_read_unaligned(&bytes[at..at + DENOISE_HISTORY_BYTES as usize]);
                let at = (DENOISE_AT + DENOISE_HISTORY_BYTES) as usize;
                let g: [f32; 4] = bytemuck::pod_read_unaligned(&bytes[at..at + 16]);
                DenoiseInspection {
                    history,
                    gradient: g[0],
                    gradient_before: g[1],
                    gradient_now: g[2],
                }
            }),
        })
    }
}

//! The pixel inspector: while a pixel is selected, every frame copies that pixel's
//! reservoir after each stage, its surface and its debug record into a small buffer that
//! comes back asynchronously with the frame's report.

use crate::gpu::readback::ReadbackRing;
use crate::gpu_types::{GpuPixelDebug, GpuReservoir, GpuSurface, NO_LIGHT};
use crate::shader_constants::*;

const SURFACE_BYTES: u64 = std::mem::size_of::<GpuSurface>() as u64;
const DEBUG_BYTES: u64 = std::mem::size_of::<GpuPixelDebug>() as u64;
const RESERVOIR_BYTES: u64 = std::mem::size_of::<GpuReservoir>() as u64;
/// initial, temporal and up to 8 spatial passes.
const MAX_STAGES: u64 = 10;
pub const INSPECT_BYTES: u64 = SURFACE_BYTES + DEBUG_BYTES + MAX_STAGES * RESERVOIR_BYTES;

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

/// Everything the inspector shows about one pixel in one frame.
#[derive(Clone, Debug, PartialEq)]
pub struct PixelInspection {
    pub frame: u64,
    pub pixel: (u32, u32),
    pub surface: GpuSurface,
    pub debug: GpuPixelDebug,
    pub stages: Vec<StageReservoir>,
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
}

/// A capture in flight: the stage names, waiting for its bytes.
pub struct PendingInspection {
    pub pixel: (u32, u32),
    pub stages: Vec<String>,
}

impl InspectCapture {
    pub fn new(pixel: (u32, u32), size: (u32, u32), staging: wgpu::Buffer) -> InspectCapture {
        let (x, y) = (pixel.0.min(size.0 - 1), pixel.1.min(size.1 - 1));
        InspectCapture {
            pixel: (x, y),
            index: (y * size.0 + x) as u64,
            staging,
            stages: Vec::new(),
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

    /// Copies the pixel's surface and final debug record.
    pub fn copy_pixel_records(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        surfaces: &wgpu::Buffer,
        debug: &wgpu::Buffer,
    ) {
        let index = self.index;
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
        Some(PixelInspection {
            frame,
            pixel: self.pixel,
            surface,
            debug,
            stages,
        })
    }
}

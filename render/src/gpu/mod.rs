//! Device set-up and small GPU helpers shared by the passes.

pub mod bindings;
pub mod context;
pub mod readback;
pub mod timing;

pub use context::{Gpu, GpuError, NO_RAY_QUERY_ENV, RayQueryUnavailable};

/// A single-sampled, single-mip 2-D texture (render targets, storage images, captures).
pub fn texture_2d(
    gpu: &Gpu,
    label: &str,
    width: u32,
    height: u32,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
    view_formats: &[wgpu::TextureFormat],
) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats,
    })
}

/// Writes `records[i]` for the ascending `indices` into `buffer` (which holds `records`
/// as uploaded before), as runs: indices closer than `gap` go in one write with the
/// records between them, so a few scattered changes cost a few writes, not one each.
pub fn write_runs<T: bytemuck::Pod>(
    gpu: &Gpu,
    buffer: &wgpu::Buffer,
    records: &[T],
    indices: &[usize],
    gap: usize,
) {
    for run in runs(indices, gap) {
        let offset = (run.start * std::mem::size_of::<T>()) as u64;
        gpu.queue
            .write_buffer(buffer, offset, bytemuck::cast_slice(&records[run]));
    }
}

/// Ascending `indices` as ranges, joined where fewer than `gap` indices lie between them.
fn runs(indices: &[usize], gap: usize) -> Vec<std::ops::Range<usize>> {
    let mut out: Vec<std::ops::Range<usize>> = Vec::new();
    for &i in indices {
        match out.last_mut() {
            Some(run) if i < run.end + gap => run.end = i + 1,
            _ => out.push(i..i + 1),
        }
    }
    out
}

//! The environment on the GPU (scene group bindings 11–13 after the scene's storage
//! buffers, scene_bindings.wgsl): the sampling table as a storage buffer, the radiance as an
//! unfilterable RGBA32F texture (a texture, not another storage buffer: the temporal pass
//! already binds 21, gpu/context.rs) and the
//! uniform with size, strength, rotation and light index. Without an environment all
//! three are one-texel placeholders the shaders never read (their code is not compiled).

use wgpu::util::DeviceExt;

use crate::environment::Environment;
use crate::gpu::{Gpu, texture_2d};
use crate::gpu_types::{GpuEnvTexel, GpuEnvironment, NO_LIGHT};

pub struct EnvironmentResources {
    pub table: wgpu::Buffer,
    pub radiance: wgpu::TextureView,
    pub uniform: wgpu::Buffer,
}

impl EnvironmentResources {
    pub fn upload(gpu: &Gpu, env: Option<&Environment>, light: u32) -> EnvironmentResources {
        let placeholder_table = [GpuEnvTexel::default()];
        let placeholder_texel = [[0.0f32; 3]];
        let (width, height, table, texels) = match env {
            Some(e) => (e.width, e.height, &e.distribution.table[..], &e.texels[..]),
            None => (1, 1, &placeholder_table[..], &placeholder_texel[..]),
        };
        let table = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("environment table"),
                contents: bytemuck::cast_slice(table),
                usage: wgpu::BufferUsages::STORAGE,
            });
        let rgba: Vec<[f32; 4]> = texels.iter().map(|t| [t[0], t[1], t[2], 0.0]).collect();
        let texture = texture_2d(
            gpu,
            "environment radiance",
            width,
            height,
            wgpu::TextureFormat::Rgba32Float,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            &[],
        );
        gpu.queue.write_texture(
            texture.as_image_copy(),
            bytemuck::cast_slice(&rgba),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(width * 16),
                rows_per_image: Some(height),
            },
            texture.size(),
        );
        let params = GpuEnvironment {
            size: [width, height],
            light: if env.is_some() { light } else { NO_LIGHT },
            strength: env.map_or(0.0, |e| e.strength),
            rotation: env.map_or([1.0, 0.0], |e| e.rotation_cos_sin()),
            _pad: [0; 2],
        };
        let uniform = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("environment"),
                contents: bytemuck::bytes_of(&params),
                usage: wgpu::BufferUsages::UNIFORM,
            });
        EnvironmentResources {
            table,
            radiance: texture.create_view(&Default::default()),
            uniform,
        }
    }
}

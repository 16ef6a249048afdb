//! G-buffer: rasterise a visibility buffer (triangle id + barycentrics, depth-tested),
//! then resolve it in a compute pass into per-pixel `Surface` records. Rasterising ids
//! instead of attributes keeps the colour targets within the 32-bytes-per-sample limit
//! and lets the raster and ray-traced paths share `hit_surface` in material.wgsl.

use std::collections::BTreeSet;

use super::compile::{PassLayouts, shader_module};
use super::pass::{Dispatch, PassDef, read, write};
use super::resources::{LightData, Resource::*};
use crate::gpu::timing::FrameRecorder;
use crate::gpu::{Gpu, GpuError};

pub const VISIBILITY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Uint;
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Rasterises every triangle into the visibility and depth targets (groups 0 and 1 only).
pub const RASTER: PassDef = PassDef {
    name: "gbuffer raster",
    shader: "gbuffer_raster.wgsl",
    group: &[],
    dispatch: Dispatch::Raster,
};

/// Turns the visibility buffer into `Surface` records (object motion comes from the
/// scene group's previous-frame triangles).
pub const RESOLVE: PassDef = PassDef {
    name: "gbuffer resolve",
    shader: "gbuffer_resolve.wgsl",
    group: &[
        read(Visibility),
        write(Surfaces),
        read(Lights(LightData::BvhNodes)),
        read(Lights(LightData::BvhTrails)),
    ],
    dispatch: Dispatch::Pixels,
};

pub struct RasterPass {
    pipeline: wgpu::RenderPipeline,
}

impl RasterPass {
    pub fn new(
        gpu: &Gpu,
        layouts: &PassLayouts,
        defines: &BTreeSet<String>,
    ) -> Result<RasterPass, GpuError> {
        let module = shader_module(gpu, RASTER.shader, defines)?;
        let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let layout = gpu
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("gbuffer raster"),
                bind_group_layouts: &layouts.frame_and_scene(defines),
                immediate_size: 0,
            });
        let raster = gpu
            .device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("gbuffer raster"),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_main"),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: wgpu::PrimitiveState {
                    // Culling of single-sided back faces happens in the fragment shader, per
                    // material; double-sided ones must survive the rasteriser.
                    cull_mode: None,
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(true),
                    // Reverse-Z: nearer is greater.
                    depth_compare: Some(wgpu::CompareFunction::Greater),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs_main"),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: VISIBILITY_FORMAT,
                        blend: None,
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            });
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Validation(format!("gbuffer raster: {e}")));
        }
        Ok(RasterPass { pipeline: raster })
    }

    /// Rasterises `triangle_count` triangles into the visibility and depth targets.
    pub fn record(
        &self,
        rec: &mut FrameRecorder,
        groups: [&wgpu::BindGroup; 2],
        visibility: &wgpu::TextureView,
        depth: &wgpu::TextureView,
        triangle_count: u32,
    ) {
        rec.render_pass(RASTER.name, |encoder, timestamp_writes| {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(RASTER.name),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: visibility,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: depth,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(0.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, groups[0], &[]);
            pass.set_bind_group(1, groups[1], &[]);
            pass.draw(0..triangle_count * 3, 0..1);
        });
    }
}

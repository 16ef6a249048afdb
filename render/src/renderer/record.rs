//! One frame, in order: uniforms → G-buffer → initial → temporal → spatial × P → shade →
//! display (or reference → display). Passes the settings switch off are not dispatched.

use glam::Vec2;

use super::bind_groups::{Key, Uniforms};
use super::{PingPong, PipelineVariant, Renderer};
use crate::effects::EffectSet;
use crate::gpu::GpuError;
use crate::gpu_types::{GpuDisplay, GpuFrame};
use crate::passes::{
    ComputePass, PASS_INFO_SLOTS, PASS_INFO_STRIDE, display, gbuffer::GBufferPass, initial,
    reference, shade, spatial, temporal,
};
use crate::settings::Settings;
use crate::shader_constants::REFERENCE_SAMPLES_PER_DISPATCH;
use crate::view::{DebugView, Mode};

/// Radical inverse in base b (Halton sequence) for sub-pixel jitter.
fn halton(mut index: u32, base: u32) -> f32 {
    let mut f = 1.0;
    let mut r = 0.0;
    while index > 0 {
        f /= base as f32;
        r += f * (index % base) as f32;
        index /= base;
    }
    r
}

impl Renderer {
    /// The settings as the current mode applies them (`nee` is RIS with one light
    /// candidate and no BSDF candidate; `ris` has no reuse).
    pub fn effective_settings(&self) -> Settings {
        let mut s = self.settings.clone();
        match self.mode {
            Mode::Nee => {
                s.light_candidates = 1;
                s.bsdf_candidates = 0;
                s.temporal = false;
                s.spatial = false;
            }
            Mode::Ris => {
                s.temporal = false;
                s.spatial = false;
            }
            Mode::Restir | Mode::Reference => {}
        }
        s
    }

    fn pass<'a>(
        variant: &'a mut PipelineVariant,
        gpu: &crate::gpu::Gpu,
        layouts: &crate::passes::PassLayouts,
        defines: &std::collections::BTreeSet<String>,
        name: &'static str,
    ) -> Result<&'a ComputePass, GpuError> {
        if !variant.passes.contains_key(name) {
            let (shader, layout) = match name {
                "initial" => (initial::SHADER, &layouts.initial),
                "temporal" => (temporal::SHADER, &layouts.temporal),
                "spatial" => (spatial::SHADER, &layouts.spatial),
                "shade" => (shade::SHADER, &layouts.shade),
                "reference" => (reference::SHADER, &layouts.reference),
                _ => (display::SHADER, &layouts.display),
            };
            let pass = ComputePass::new(gpu, layouts, name, shader, defines, layout)?;
            variant.passes.insert(name, pass);
        }
        Ok(&variant.passes[name])
    }

    /// Renders one frame with the current camera, mode, settings and view, and submits it.
    pub fn render_frame(&mut self) -> Result<(), GpuError> {
        let settings = self.effective_settings();
        let (width, height) = self.size();
        let camera = self.camera;
        let moved = self.prev_camera.is_some_and(|p| p != camera);
        let jump = self
            .prev_camera
            .map_or(0.0, |p| (p.position - camera.position).length());
        if self.cut_requested || jump > settings.camera_cut * self.scene.scale {
            self.history_valid = false;
        }
        self.cut_requested = false;

        let effects = match &self.forced_effects {
            Some(forced) => forced.clone(),
            None => EffectSet::detect(&self.features, &settings, moved),
        };
        let defines = effects.defines();
        let variant_key = defines.iter().cloned().collect::<Vec<_>>().join(",");

        // Uniforms.
        let aspect = width as f32 / height as f32;
        let near = (self.scene.scale * 1e-5).max(1e-30);
        let view_proj = camera.projection_matrix(aspect, near) * camera.view_matrix();
        let prev_view_proj = self.prev_view_proj.unwrap_or(view_proj);
        let jitter = if settings.jitter && self.mode != Mode::Reference {
            let i = (self.frame_index % 64) as u32 + 1;
            Vec2::new(halton(i, 2), halton(i, 3)) - 0.5
        } else {
            Vec2::ZERO
        };
        let prev_jitter = self.prev_jitter;
        let frame = GpuFrame {
            view_proj: view_proj.to_cols_array_2d(),
            inv_view_proj: view_proj.inverse().to_cols_array_2d(),
            prev_view_proj: prev_view_proj.to_cols_array_2d(),
            camera_position: camera.position.into(),
            frame_index: self.frame_index as u32,
            prev_camera_position: self
                .prev_camera
                .map_or(camera.position, |c| c.position)
                .into(),
            seed: self.seed,
            jitter: jitter.into(),
            size: [width, height],
            scene_scale: self.scene.scale,
            history_valid: self.history_valid as u32,
            light_count: self.scene.light_count,
            punctual_count: self.scene.punctual_count,
            prev_jitter: prev_jitter.into(),
            _pad: [0; 2],
        };
        self.gpu
            .queue
            .write_buffer(&self.frame_uniform, 0, bytemuck::bytes_of(&frame));
        self.gpu.queue.write_buffer(
            &self.params_uniform,
            0,
            bytemuck::bytes_of(&settings.gpu_params()),
        );

        // The reference traces its own camera rays, except with jitter off, where it shades
        // the rasterised surfaces (see reference.wgsl).
        let needs_gbuffer = self.mode != Mode::Reference || !settings.jitter;
        let variant = self.variants.entry(variant_key).or_default();
        if variant.gbuffer.is_none() && needs_gbuffer {
            variant.gbuffer = Some(GBufferPass::new(&self.gpu, &self.layouts, &defines)?);
        }
        let mut names: Vec<&'static str> = match self.mode {
            Mode::Reference => vec!["reference"],
            _ => {
                let mut v = vec!["initial"];
                if settings.temporal {
                    v.push("temporal");
                }
                if settings.spatial && settings.spatial_neighbours > 0 {
                    v.push("spatial");
                }
                v.push("shade");
                v
            }
        };
        names.push("display");
        for name in &names {
            Self::pass(variant, &self.gpu, &self.layouts, &defines, name)?;
        }

        let mut encoder = self
            .gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("frame"),
            });
        encoder.clear_buffer(&self.stats_buffer, 0, None);
        let uniforms = Uniforms {
            pass_info: &self.pass_info,
            display: &self.display_uniform,
        };
        let frame_group = self.frame_bind_group.clone();
        let scene_group = self.scene.bind_group.clone();
        let surfaces = 1 - self.ping_pong.surfaces;
        let size = (width, height);
        let mut dispatched: Vec<&'static str> = Vec::new();
        self.last_effects = Some(effects);
        let mut final_reservoirs = self.ping_pong.history;

        if needs_gbuffer {
            let gb = variant.gbuffer.as_ref().expect("built above");
            gb.record_raster(
                &mut encoder,
                &mut self.timer,
                &frame_group,
                &scene_group,
                &self.targets.visibility,
                &self.targets.depth,
                self.scene.triangle_count,
            );
            let group = self.bind_groups.get(
                &self.gpu,
                &self.layouts,
                &self.targets,
                &uniforms,
                Key::Resolve { surfaces },
            );
            gb.resolve.record(
                &mut encoder,
                &mut self.timer,
                [&frame_group, &scene_group, &group],
                size,
            );
            dispatched.extend(["gbuffer raster", "gbuffer resolve"]);
        }
        if self.mode == Mode::Reference {
            let group = self.bind_groups.get(
                &self.gpu,
                &self.layouts,
                &self.targets,
                &uniforms,
                Key::Reference { surfaces },
            );
            // Samples in chunks, one dispatch each (see REFERENCE_SAMPLES_PER_DISPATCH).
            let chunks = settings
                .reference_spp
                .max(1)
                .div_ceil(REFERENCE_SAMPLES_PER_DISPATCH)
                .min(PASS_INFO_SLOTS);
            let offsets: Vec<u32> = (0..chunks).map(|c| c * PASS_INFO_STRIDE).collect();
            variant.passes["reference"].record_repeated(
                &mut encoder,
                &mut self.timer,
                [&frame_group, &scene_group, &group],
                &offsets,
                size,
            );
            dispatched.push("reference");
        } else {
            // Reservoir buffers: `history` holds last frame's result until temporal reuse
            // has read it; every stage writes a buffer its inputs do not occupy.
            let history = self.ping_pong.history;
            let other =
                |a: usize, b: usize| (0..3).find(|&i| i != a && i != b).expect("three buffers");
            let mut current = other(history, history);
            let group = self.bind_groups.get(
                &self.gpu,
                &self.layouts,
                &self.targets,
                &uniforms,
                Key::Initial {
                    surfaces,
                    out: current,
                },
            );
            variant.passes["initial"].record(
                &mut encoder,
                &mut self.timer,
                [&frame_group, &scene_group, &group],
                size,
            );
            dispatched.push("initial");

            if settings.temporal {
                let out = other(current, history);
                let key = Key::Temporal {
                    surfaces,
                    input: current,
                    prev: history,
                    out,
                };
                let group =
                    self.bind_groups
                        .get(&self.gpu, &self.layouts, &self.targets, &uniforms, key);
                variant.passes["temporal"].record(
                    &mut encoder,
                    &mut self.timer,
                    [&frame_group, &scene_group, &group],
                    size,
                );
                dispatched.push("temporal");
                current = out;
            }
            if names.contains(&"spatial") {
                // Each pass reads the previous pass's output: one compute pass per spatial
                // pass (a bind group per buffer pair), timed together as "spatial".
                for p in 0..settings.spatial_passes.min(8) {
                    let out = other(current, current);
                    let key = Key::Spatial {
                        surfaces,
                        input: current,
                        out,
                    };
                    let group = self.bind_groups.get(
                        &self.gpu,
                        &self.layouts,
                        &self.targets,
                        &uniforms,
                        key,
                    );
                    let groups = [&frame_group, &scene_group, &group];
                    variant.passes["spatial"].record_repeated(
                        &mut encoder,
                        &mut self.timer,
                        groups,
                        &[p * PASS_INFO_STRIDE],
                        size,
                    );
                    current = out;
                }
                dispatched.push("spatial");
            }
            let group = self.bind_groups.get(
                &self.gpu,
                &self.layouts,
                &self.targets,
                &uniforms,
                Key::Shade {
                    surfaces,
                    input: current,
                },
            );
            variant.passes["shade"].record(
                &mut encoder,
                &mut self.timer,
                [&frame_group, &scene_group, &group],
                size,
            );
            dispatched.push("shade");
            final_reservoirs = current;
        }
        self.accumulated_frames += 1;

        self.record_display(&mut encoder, surfaces, final_reservoirs, &settings)?;
        dispatched.push("display");

        self.timer.resolve(&mut encoder, self.frame_index);
        self.stats_ring.copy_from(
            &mut encoder,
            &self.stats_buffer,
            self.stats_buffer.size(),
            self.frame_index,
        );
        self.gpu.queue.submit([encoder.finish()]);
        self.timer.after_submit();
        self.stats_ring.after_submit();
        self.gpu.check()?;

        // Hand over to the next frame.
        self.ping_pong = PingPong {
            history: final_reservoirs,
            surfaces,
        };
        self.history_valid = self.mode != Mode::Reference;
        self.last_final = (self.mode != Mode::Reference).then_some(final_reservoirs);
        self.prev_camera = Some(camera);
        self.prev_view_proj = Some(view_proj);
        self.prev_jitter = jitter;
        self.frame_index += 1;
        self.last_passes = dispatched;
        Ok(())
    }

    /// Records the display pass (tonemapped image or debug view) for the given buffers.
    fn record_display(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        surfaces: usize,
        reservoirs: usize,
        settings: &Settings,
    ) -> Result<(), GpuError> {
        // The reference is always shown as its running average.
        let accumulated = self.view.accumulate || self.mode == Mode::Reference;
        let display_data = GpuDisplay {
            scale: if accumulated {
                1.0 / self.accumulated_frames.max(1) as f32
            } else {
                1.0
            },
            exposure: 2f32.powf(self.view.exposure_ev.clamp(-60.0, 60.0)),
            tonemapper: self.view.tonemapper.gpu_code(),
            view: self.view.view.gpu_code(),
            reason_mask: self.view.reason_mask,
            m_scale: settings.m_cap,
            // The uploaded reference is already an average.
            reference_scale: 1.0,
            _pad: 0,
        };
        self.gpu
            .queue
            .write_buffer(&self.display_uniform, 0, bytemuck::bytes_of(&display_data));
        let size = self.size();
        let defines = self
            .last_effects
            .as_ref()
            .map(|e| e.defines())
            .unwrap_or_default();
        let key = defines.iter().cloned().collect::<Vec<_>>().join(",");
        let variant = self.variants.entry(key).or_default();
        let pass = Self::pass(variant, &self.gpu, &self.layouts, &defines, "display")?;
        let uniforms = Uniforms {
            pass_info: &self.pass_info,
            display: &self.display_uniform,
        };
        let group = self.bind_groups.get(
            &self.gpu,
            &self.layouts,
            &self.targets,
            &uniforms,
            Key::Display {
                surfaces,
                reservoirs,
                accumulated,
            },
        );
        pass.record(
            encoder,
            &mut self.timer,
            [&self.frame_bind_group, &self.scene.bind_group, &group],
            size,
        );
        Ok(())
    }

    /// Re-runs only the display pass on the last frame's buffers (after a change of view,
    /// exposure or debug view) without rendering a new frame.
    pub fn redisplay(&mut self) -> Result<(), GpuError> {
        let settings = self.effective_settings();
        let mut encoder = self.gpu.device.create_command_encoder(&Default::default());
        let (surfaces, reservoirs) = (self.ping_pong.surfaces, self.ping_pong.history);
        self.record_display(&mut encoder, surfaces, reservoirs, &settings)?;
        // Timestamps of a lone display pass are not a frame: drop them.
        self.timer.discard();
        self.gpu.queue.submit([encoder.finish()]);
        self.gpu.check()
    }

    /// True when the view shows a debug buffer rather than the image.
    pub fn showing_debug_view(&self) -> bool {
        self.view.view != DebugView::Final
    }
}

#[cfg(test)]
mod tests {
    use super::halton;

    #[test]
    fn halton_is_in_unit_interval_and_low_discrepancy() {
        let xs: Vec<f32> = (1..=64).map(|i| halton(i, 2)).collect();
        assert!(xs.iter().all(|x| (0.0..1.0).contains(x)));
        let mean = xs.iter().sum::<f32>() / 64.0;
        assert!((mean - 0.5).abs() < 0.02);
        assert_eq!(halton(1, 2), 0.5);
        assert_eq!(halton(2, 3), 2.0 / 3.0);
    }
}

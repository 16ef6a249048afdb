//! One frame, in order: uniforms → G-buffer → initial → temporal → spatial × P → shade →
//! display (or reference → display). Passes the settings switch off are not dispatched.

use std::collections::BTreeSet;

use super::bind_groups::{Key, Uniforms};
use super::inspect::InspectCapture;
use super::{PingPong, PipelineVariant, Renderer};
use std::sync::Arc;

use crate::effects::{Effect, EffectSet};
use crate::gpu::timing::FrameRecorder;
use crate::gpu::{Gpu, GpuError};
use crate::passes::{
    ComputePass, PASS_INFO_SLOTS, PASS_INFO_STRIDE, PassLayouts, display, gbuffer::GBufferPass,
    initial, presample, reference, shade, spatial, temporal,
};
use crate::settings::Settings;
use crate::shader_constants::{
    LIGHT_TILE_COUNT, LIGHT_TILE_SIZE, MAX_SPATIAL_PASSES, REFERENCE_SAMPLES_PER_DISPATCH,
};
use crate::view::Mode;

/// The first of `count` reservoir buffers that is neither `a` nor `b`.
fn other(count: usize, a: usize, b: usize) -> usize {
    (0..count)
        .find(|&i| i != a && i != b)
        .expect("enough reservoir buffers")
}

/// The effect set of a frame, its WGSL defines and the key of its pipeline variant,
/// computed when the inputs change and shared until they change again.
pub(super) struct ActiveEffects {
    pub set: EffectSet,
    pub defines: BTreeSet<String>,
    pub key: String,
    /// What it was derived from (`None` settings when forced by `--effects`).
    inputs: Option<(Settings, bool)>,
}

impl Renderer {
    /// The effect set for this frame: forced, or derived from the scene and settings
    /// (cached: the common frame allocates nothing here).
    fn active_effects(&mut self, settings: &Settings, moved: bool) -> Arc<ActiveEffects> {
        let inputs = self
            .forced_effects
            .is_none()
            .then(|| (settings.clone(), moved));
        let unchanged = |last: &ActiveEffects| {
            last.inputs == inputs
                && (inputs.is_some() || Some(&last.set) == self.forced_effects.as_ref())
        };
        if let Some(last) = self.last_effects.as_ref().filter(|l| unchanged(l)) {
            return last.clone();
        }
        let set = match &self.forced_effects {
            Some(forced) => forced.clone(),
            None => EffectSet::detect(&self.features, settings, moved),
        };
        let defines = set.defines();
        let key = defines.iter().cloned().collect::<Vec<_>>().join(",");
        Arc::new(ActiveEffects {
            set,
            defines,
            key,
            inputs,
        })
    }
}

/// The compiled pass `name` of `variant`, compiling it on first use.
fn pass<'a>(
    variant: &'a mut PipelineVariant,
    gpu: &Gpu,
    layouts: &PassLayouts,
    defines: &BTreeSet<String>,
    name: &'static str,
) -> Result<&'a ComputePass, GpuError> {
    if !variant.passes.contains_key(name) {
        let (shader, layout) = match name {
            "initial" => (initial::SHADER, &layouts.initial),
            "presample lights" => (presample::SHADER, &layouts.presample),
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

    /// Renders one frame with the current camera, mode, settings and view, and submits it.
    pub fn render_frame(&mut self) -> Result<(), GpuError> {
        self.scene.begin_frame(&self.gpu);
        let settings = self.effective_settings();
        let camera = self.camera;
        let moved = self.prev_camera.is_some_and(|p| p != camera);
        let jump = self
            .prev_camera
            .map_or(0.0, |p| (p.position - camera.position).length());
        if self.cut_requested || jump > settings.camera_cut * self.scene.scale {
            self.history_valid = false;
        }
        self.cut_requested = false;

        self.scene
            .set_environment_share(&self.gpu, settings.environment_share);
        let active = self.active_effects(&settings, moved);
        let (effects, defines, key) = (&active.set, &active.defines, active.key.as_str());
        let (view_proj, jitter) = self.write_frame_uniform(&settings);
        self.gpu.queue.write_buffer(
            &self.params_uniform,
            0,
            bytemuck::bytes_of(&settings.gpu_params(self.targets.height)),
        );

        // Which passes run. The reference traces its own camera rays, except with jitter
        // off, where it shades the rasterised surfaces (see reference.wgsl).
        let realtime = self.mode != Mode::Reference;
        let needs_gbuffer = realtime || !settings.jitter;
        let temporal_on = realtime && settings.temporal;
        let spatial_on = realtime && settings.spatial && settings.spatial_neighbours > 0;
        let tiles_on = realtime && effects.contains(Effect::LightTiles);
        let mut names = vec!["display"];
        if realtime {
            names.extend(["initial", "shade"]);
        } else {
            names.push("reference");
        }
        if temporal_on {
            names.push("temporal");
        }
        if spatial_on {
            names.push("spatial");
        }
        if tiles_on {
            names.push("presample lights");
            super::setup::ensure_light_tiles(&self.gpu, &mut self.light_tiles);
        }
        let variant = self.variants.entry(key.to_string()).or_default();
        if variant.gbuffer.is_none() && needs_gbuffer {
            variant.gbuffer = Some(GBufferPass::new(&self.gpu, &self.layouts, defines)?);
        }
        for name in &names {
            pass(variant, &self.gpu, &self.layouts, defines, name)?;
        }
        let variant = &self.variants[key];

        self.accumulated_frames += 1;
        let show_accumulation = self.shows_accumulation();
        self.write_display_uniform(&settings);

        let frame_group = self.frame_bind_group.clone();
        let scene_group = self.scene.bind_group.clone();
        if temporal_on {
            self.targets.ensure_history(&self.gpu);
        }
        // Surfaces alternate once there are two buffers (the previous one is the history).
        let surfaces = if self.targets.surfaces.len() == 2 {
            1 - self.ping_pong.surfaces
        } else {
            0
        };
        let buffers = self.targets.reservoirs.len();
        let size = self.size();
        let mut dispatched: Vec<&'static str> = Vec::new();
        let mut capture = self
            .inspected_pixel
            .map(|p| InspectCapture::new(p, size, self.inspect_staging.clone()));
        let mut rec = FrameRecorder::new(&self.gpu, &mut self.timer, self.timing_mode);
        rec.encoder().clear_buffer(&self.stats_buffer, 0, None);
        let uniforms = Uniforms {
            pass_info: &self.pass_info,
            display: &self.display_uniform,
            light_tiles: &self.light_tiles,
            prev_triangles: &self.scene.prev_triangles,
        };
        let tiles =
            self.light_tiles.size() > std::mem::size_of::<crate::gpu_types::GpuTileSample>() as u64;
        let mut group = |key: Key| {
            self.bind_groups
                .get(&self.gpu, &self.layouts, &self.targets, &uniforms, key)
        };
        let mut final_reservoirs = self.ping_pong.history;

        if needs_gbuffer {
            let gb = variant.gbuffer.as_ref().expect("built above");
            gb.record_raster(
                &mut rec,
                [&frame_group, &scene_group],
                &self.targets.visibility,
                &self.targets.depth,
                self.scene.triangle_count,
            );
            gb.resolve.record(
                &mut rec,
                [
                    &frame_group,
                    &scene_group,
                    &group(Key::Resolve { surfaces }),
                ],
                size,
            );
            dispatched.extend(["gbuffer raster", "gbuffer resolve"]);
        }
        if realtime {
            // Reservoir buffers: `history` holds last frame's result until temporal reuse
            // has read it; every stage writes a buffer its inputs do not occupy.
            let history = self.ping_pong.history;
            let mut current = other(buffers, history, history);
            if tiles_on {
                let workgroups =
                    (LIGHT_TILE_COUNT * LIGHT_TILE_SIZE).div_ceil(presample::WORKGROUP_SIZE);
                variant.passes["presample lights"].record_workgroups(
                    &mut rec,
                    [&frame_group, &scene_group, &group(Key::Presample)],
                    (workgroups, 1),
                );
                dispatched.push("presample lights");
            }
            let g = group(Key::Initial {
                surfaces,
                out: current,
                tiles,
            });
            variant.passes["initial"].record(&mut rec, [&frame_group, &scene_group, &g], size);
            dispatched.push("initial");
            if let Some(c) = &mut capture {
                c.copy_reservoir(rec.encoder(), &self.targets, current, "initial");
            }
            if temporal_on {
                let out = other(buffers, current, history);
                let g = group(Key::Temporal {
                    surfaces,
                    input: current,
                    prev: history,
                    out,
                });
                variant.passes["temporal"].record(&mut rec, [&frame_group, &scene_group, &g], size);
                dispatched.push("temporal");
                current = out;
                if let Some(c) = &mut capture {
                    c.copy_reservoir(rec.encoder(), &self.targets, current, "temporal");
                }
            }
            if spatial_on {
                // Each pass reads the previous pass's output (its own bind group); the
                // pass index picks its PassInfo slot for decorrelated random numbers.
                for p in 0..settings.spatial_passes.min(MAX_SPATIAL_PASSES) {
                    let out = other(buffers, current, current);
                    let g = group(Key::Spatial {
                        surfaces,
                        input: current,
                        out,
                    });
                    variant.passes["spatial"].record_repeated(
                        &mut rec,
                        [&frame_group, &scene_group, &g],
                        &[p * PASS_INFO_STRIDE],
                        size,
                    );
                    current = out;
                    if let Some(c) = &mut capture {
                        c.copy_reservoir(rec.encoder(), &self.targets, current, "spatial");
                    }
                }
                dispatched.push("spatial");
            }
            let g = group(Key::Shade {
                surfaces,
                input: current,
            });
            variant.passes["shade"].record(&mut rec, [&frame_group, &scene_group, &g], size);
            dispatched.push("shade");
            final_reservoirs = current;
        } else {
            // Samples in chunks, one dispatch each (see REFERENCE_SAMPLES_PER_DISPATCH).
            let chunks = settings
                .reference_spp
                .max(1)
                .div_ceil(REFERENCE_SAMPLES_PER_DISPATCH)
                .min(PASS_INFO_SLOTS);
            let offsets: Vec<u32> = (0..chunks).map(|c| c * PASS_INFO_STRIDE).collect();
            let g = group(Key::Reference { surfaces });
            variant.passes["reference"].record_repeated(
                &mut rec,
                [&frame_group, &scene_group, &g],
                &offsets,
                size,
            );
            dispatched.push("reference");
        }
        let display_group = group(Key::Display {
            surfaces,
            reservoirs: final_reservoirs,
            accumulated: show_accumulation,
        });
        variant.passes["display"].record(
            &mut rec,
            [&frame_group, &scene_group, &display_group],
            size,
        );
        dispatched.push("display");
        if let Some(c) = &mut capture {
            c.copy_pixel_records(rec.encoder(), &self.targets, surfaces);
        }

        let frame = self.frame_index;
        let stats_ring = &mut self.stats_ring;
        let stats_buffer = &self.stats_buffer;
        let inspect_ring = &mut self.inspect_ring;
        let device = self.gpu.device.clone();
        let wall_times = rec.submit(frame, |encoder| {
            stats_ring.copy_from(&device, encoder, stats_buffer, stats_buffer.size(), frame);
            if let Some(c) = &capture {
                c.submit_copy(&device, encoder, inspect_ring, frame);
            }
        });
        self.stats_ring.after_submit();
        self.inspect_ring.after_submit();
        if !wall_times.is_empty() {
            self.pending_times.insert(frame, wall_times);
        }
        if let Some(c) = capture {
            self.pending_inspections.insert(frame, c.into_pending());
        }
        self.gpu.check()?;

        // Hand over to the next frame.
        self.ping_pong = PingPong {
            history: final_reservoirs,
            surfaces,
        };
        self.history_valid = realtime;
        self.last_final = realtime.then_some(final_reservoirs);
        self.prev_camera = Some(camera);
        self.prev_view_proj = Some(view_proj);
        self.prev_jitter = jitter;
        self.frame_index += 1;
        self.last_effects = Some(active.clone());
        self.last_passes = dispatched;
        Ok(())
    }

    /// Whether the display shows the running average (the reference always does).
    pub(super) fn shows_accumulation(&self) -> bool {
        self.view.accumulate || self.mode == Mode::Reference
    }

    /// Re-runs only the display pass on the last frame's buffers (after a change of view,
    /// exposure or debug view) without rendering a new frame.
    pub fn redisplay(&mut self) -> Result<(), GpuError> {
        let settings = self.effective_settings();
        self.write_display_uniform(&settings);
        // The display pass of the last frame's variant (any variant's would do).
        let Some(active) = self.last_effects.clone() else {
            return Ok(());
        };
        let variant = self.variants.entry(active.key.clone()).or_default();
        let display_pass = pass(
            variant,
            &self.gpu,
            &self.layouts,
            &active.defines,
            "display",
        )?;
        let uniforms = Uniforms {
            pass_info: &self.pass_info,
            display: &self.display_uniform,
            light_tiles: &self.light_tiles,
            prev_triangles: &self.scene.prev_triangles,
        };
        let key = Key::Display {
            surfaces: self.ping_pong.surfaces,
            reservoirs: self.ping_pong.history,
            accumulated: self.view.accumulate || self.mode == Mode::Reference,
        };
        let group = self
            .bind_groups
            .get(&self.gpu, &self.layouts, &self.targets, &uniforms, key);
        let size = (self.targets.width, self.targets.height);
        let mut rec = FrameRecorder::new(
            &self.gpu,
            &mut self.timer,
            crate::gpu::timing::TimingMode::Off,
        );
        display_pass.record(
            &mut rec,
            [&self.frame_bind_group, &self.scene.bind_group, &group],
            size,
        );
        rec.submit(self.frame_index, |_| {});
        self.gpu.check()
    }
}

#[cfg(test)]
mod tests {
    use super::other;

    #[test]
    fn stages_never_write_a_buffer_they_read() {
        for history in 0..3 {
            let initial = other(3, history, history);
            assert_ne!(initial, history);
            let temporal = other(3, initial, history);
            assert!(temporal != initial && temporal != history);
            let spatial = other(3, temporal, temporal);
            assert_ne!(spatial, temporal);
        }
    }
}

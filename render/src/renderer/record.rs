//! Records one frame: the uniforms, then the frame plan (`frame_plan.rs`) step by step,
//! each step's bindings resolved to buffers (`resolve.rs`) and bound through the cache.

use std::collections::BTreeSet;

use std::sync::Arc;

use super::bind_groups::Uniforms;
use super::frame_plan::{self, FrameSwitches, Step, frame_plan};
use super::inspect::InspectCapture;
use super::resolve::resolve;
use super::{PipelineVariant, Renderer};

use crate::denoise::constants::MAX_DENOISE_ITERATIONS;
use crate::denoise::passes as denoise;
use crate::effects::{Effect, EffectSet};
use crate::gi::passes::initial::GI_RESERVOIRS;
use crate::gpu::timing::FrameRecorder;
use crate::gpu::{Gpu, GpuError};
use crate::passes::gbuffer::RasterPass;
use crate::passes::pass::Dispatch;
use crate::passes::resources::RESERVOIRS;
use crate::passes::{ComputePass, PASS_INFO_SLOTS, PASS_INFO_STRIDE, PassDef, PassLayouts};
use crate::pt::passes::initial::{PT_PROBE, PT_RESERVOIRS};
use crate::settings::{LightSampler, Settings};
use crate::shader_constants::{
    LIGHT_TILE_COUNT, LIGHT_TILE_SIZE, MAX_SPATIAL_PASSES, REFERENCE_SAMPLES_PER_DISPATCH,
};
use crate::tracing::RayBackend;
use crate::view::{DebugView, Mode};

/// What recording one step needs besides the bind group cache and the recorder (shared by
/// a frame and a redisplay).
struct StepContext<'a> {
    gpu: &'a Gpu,
    layouts: &'a PassLayouts,
    targets: &'a crate::frame_targets::FrameTargets,
    uniforms: &'a Uniforms<'a>,
    variant: &'a PipelineVariant,
    /// Groups 0 (frame) and 1 (scene).
    groups: [&'a wgpu::BindGroup; 2],
    triangle_count: u32,
}

/// A `StepContext` over a renderer's fields. A macro rather than a method, so that it
/// borrows the fields one by one and the recorder can borrow `bind_groups` mutably beside it.
macro_rules! step_context {
    ($renderer:expr, $uniforms:expr, $variant:expr, $groups:expr) => {
        StepContext {
            gpu: &$renderer.gpu,
            layouts: &$renderer.layouts,
            targets: &$renderer.targets,
            uniforms: $uniforms,
            variant: $variant,
            groups: $groups,
            triangle_count: $renderer.scene.triangle_count,
        }
    };
}

impl StepContext<'_> {
    /// Records `step` with its resolved bindings: the raster draw, or the compute pass
    /// with its group 2 and one dispatch per `PassInfo` slot.
    fn record(
        &self,
        bind_groups: &mut super::bind_groups::BindGroupCache,
        rec: &mut FrameRecorder,
        step: &Step,
        bound: &[super::resolve::Bound],
    ) {
        let [frame, scene] = self.groups;
        if step.pass.dispatch == Dispatch::Raster {
            let raster = self
                .variant
                .raster
                .as_ref()
                .expect("compiled with the plan");
            raster.record(
                rec,
                [frame, scene],
                &self.targets.visibility,
                &self.targets.depth,
                self.triangle_count,
            );
            return;
        }
        let t = self.targets;
        let group = bind_groups.get(self.gpu, self.layouts, t, self.uniforms, step.pass, bound);
        let size = (t.width, t.height);
        self.variant.passes[step.pass.name].record(
            rec,
            [frame, scene, &group],
            &dynamic_offsets(step),
            size,
            step.threads,
        );
    }
}

/// The `PassInfo` dynamic offsets of a step's dispatches (slot 0 for a pass that reads
/// `PassInfo` but names no slots).
fn dynamic_offsets(step: &Step) -> Vec<u32> {
    let slots = if step.slots.is_empty() && step.pass.reads_pass_info() {
        0..1
    } else {
        step.slots.clone()
    };
    slots.map(|slot| slot * PASS_INFO_STRIDE).collect()
}

/// The effect set of a frame, its WGSL defines and the key of its pipeline variant,
/// computed when the inputs change and shared until they change again.
pub(super) struct ActiveEffects {
    pub set: EffectSet,
    /// What traces the frame's rays (its define is among `defines`).
    pub backend: RayBackend,
    pub defines: BTreeSet<String>,
    pub key: String,
    /// What it was derived from (`None` settings when forced by `--effects`).
    inputs: Option<(Settings, bool)>,
}

impl Renderer {
    /// The effect set for this frame: forced, or derived from the scene and settings
    /// (cached: the common frame allocates nothing here).
    fn active_effects(
        &mut self,
        settings: &Settings,
        moved: bool,
    ) -> Result<Arc<ActiveEffects>, GpuError> {
        let inputs = self
            .pipelines
            .forced_effects
            .is_none()
            .then(|| (settings.clone(), moved));
        let unchanged = |last: &ActiveEffects| {
            last.inputs == inputs
                && (inputs.is_some() || Some(&last.set) == self.pipelines.forced_effects.as_ref())
        };
        if let Some(last) = self
            .pipelines
            .last_effects
            .as_ref()
            .filter(|l| unchanged(l))
        {
            return Ok(last.clone());
        }
        let backend = crate::tracing::resolve_for(&self.gpu, settings.ray_backend)?;
        let mut set = match &self.pipelines.forced_effects {
            Some(forced) => forced.clone(),
            None => EffectSet::detect(&self.features, settings, moved),
        };
        set.planted.extend(self.pipelines.planted.iter().cloned());
        let mut defines = set.defines();
        defines.extend(backend.define().map(str::to_string));
        let key = defines.iter().cloned().collect::<Vec<_>>().join(",");
        Ok(Arc::new(ActiveEffects {
            set,
            backend,
            defines,
            key,
            inputs,
        }))
    }
}

impl PipelineVariant {
    /// Compiles `pass` for this variant's defines on first use.
    pub(super) fn compile(
        &mut self,
        gpu: &Gpu,
        layouts: &PassLayouts,
        defines: &BTreeSet<String>,
        pass: &'static PassDef,
    ) -> Result<(), GpuError> {
        if pass.dispatch == Dispatch::Raster {
            if self.raster.is_none() {
                self.raster = Some(RasterPass::new(gpu, layouts, defines)?);
            }
        } else if !self.passes.contains_key(pass.name) {
            let compiled = ComputePass::new(gpu, layouts, pass, defines)?;
            self.passes.insert(pass.name, compiled);
        }
        Ok(())
    }
}

impl Renderer {
    /// The settings as the current mode applies them (`nee` is RIS with one light
    /// candidate and no BSDF candidate; `ris` has no reuse).
    pub fn effective_settings(&self) -> Settings {
        let mut settings = self.mode.settings(&self.settings);
        // `auto`'s light BVH draws the candidate count measured to pay within a tenth of
        // the frame (`effects::AUTO_BVH_CANDIDATES`); `light_sampler=bvh` draws them all.
        if settings.light_sampler == LightSampler::Auto
            && crate::effects::auto_takes_bvh(&self.features)
        {
            settings.light_candidates = settings
                .light_candidates
                .min(crate::effects::AUTO_BVH_CANDIDATES);
        }
        self.apply_depth_choice(&mut settings);
        settings
    }

    /// Which passes this frame runs. The reference traces its own camera rays, except with
    /// jitter off, where it shades the rasterised surfaces (see reference.wgsl).
    fn frame_switches(&self, settings: &Settings, effects: &EffectSet) -> FrameSwitches {
        let realtime = self.mode != Mode::Reference;
        let spatial_on = realtime && settings.spatial && settings.spatial_neighbours > 0;
        FrameSwitches {
            realtime,
            gbuffer: realtime || !settings.jitter,
            light_tiles: realtime && effects.contains(Effect::LightTiles),
            regir_slots: if realtime && effects.contains(Effect::Regir) {
                settings
                    .regir_grid
                    .clamp(1, crate::shader_constants::MAX_REGIR_GRID)
                    .pow(3)
                    * settings.regir_slots_in_use()
            } else {
                0
            },
            // DI's temporal pass also makes the denoiser's gradient samples.
            temporal: realtime && (settings.temporal || settings.denoise_gradients_on()),
            spatial_passes: if spatial_on {
                settings.spatial_passes.min(MAX_SPATIAL_PASSES)
            } else {
                0
            },
            // Mutation decorrelates reused samples: it runs where reuse does.
            mutation: realtime && settings.mutations > 0 && (settings.temporal || spatial_on),
            // Samples in chunks, one dispatch each (see REFERENCE_SAMPLES_PER_DISPATCH).
            reference_chunks: settings
                .reference_spp
                .max(1)
                .div_ceil(REFERENCE_SAMPLES_PER_DISPATCH)
                .min(PASS_INFO_SLOTS),
            gi: realtime && settings.gi && !settings.pt,
            pt: realtime && settings.pt,
            pt_temporal: settings.pt_temporal && self.history.carried.has_history(&PT_RESERVOIRS),
            pt_spatial: settings.pt_spatial && settings.pt_spatial_neighbours > 0,
            pt_view: self.view.view.is_path_view() || self.view.view == DebugView::Indirect,
            // A chain has a history only if last frame used it (GI switched on again, or
            // back from the reference, starts fresh).
            gi_temporal: settings.gi_temporal && self.history.carried.has_history(&GI_RESERVOIRS),
            gi_spatial: settings.gi_spatial && settings.gi_spatial_neighbours > 0,
            gi_view: self.view.view.is_indirect(),
            bias_view: self.view.view == DebugView::Bias,
            temporal_window: self.view.view.uses_temporal_window(),
            denoise: realtime && settings.denoise,
            denoise_gradients: settings.denoise_gradients_on(),
            denoise_iterations: settings.denoise_iterations.clamp(1, MAX_DENOISE_ITERATIONS),
            // A history only if last frame denoised, and nothing since invalidated it.
            denoise_history: self.history.history_valid
                && self.history.carried.has_history(&denoise::HISTORY),
            denoise_view: self.view.view.is_denoise_view(),
        }
    }

    /// The effect set of the next `render_frame` if that frame would compile pipelines
    /// (`None`: its variant is ready). The viewer warms them beside the window first where
    /// compiling on its thread would freeze it (a CPU driver compiles at the first
    /// dispatch): `ScenePreparer::warm_effects`.
    pub fn effects_to_compile(&mut self) -> Result<Option<EffectSet>, GpuError> {
        let settings = self.effective_settings();
        let moved = self.history.prev_camera.is_some_and(|p| p != self.camera);
        let active = self.active_effects(&settings, moved)?;
        let plan = frame_plan(&self.frame_switches(&settings, &active.set));
        let empty = PipelineVariant::default();
        let variant = self.pipelines.variants.get(&active.key).unwrap_or(&empty);
        let missing = super::pipelines::missing(variant, plan.iter().map(|s| s.pass));
        Ok((!missing.is_empty()).then(|| active.set.clone()))
    }

    /// Renders one frame with the current camera, mode, settings and view, and submits it.
    pub fn render_frame(&mut self) -> Result<(), GpuError> {
        let frame_start = std::time::Instant::now();
        self.scene.begin_frame(&self.gpu);
        let settings = self.effective_settings();
        let camera = self.camera;
        let moved = self.history.prev_camera.is_some_and(|p| p != camera);
        if self
            .history
            .take_cut(camera, settings.camera_cut * self.scene.scale)
        {
            self.window.restart();
        }

        self.scene
            .set_environment_share(&self.gpu, settings.environment_share);
        let active = self.active_effects(&settings, moved)?;
        let (effects, key) = (&active.set, active.key.as_str());
        let (view_proj, jitter) = self.write_frame_uniform(&settings);
        self.gpu.queue.write_buffer(
            &self.buffers.params_uniform,
            0,
            bytemuck::bytes_of(&settings.gpu_params(self.targets.height)),
        );

        let switches = self.frame_switches(&settings, effects);
        let plan = frame_plan(&switches);
        if self.ensure_light_sampler(&switches, effects, settings.light_bvh_gpu_refit) {
            self.bind_groups.clear();
        }
        self.compile_frame_pipelines(&active, &plan)?;
        let variant = &self.pipelines.variants[key];

        self.accumulated_frames += 1;
        let show_accumulation = self.shows_accumulation();
        self.write_display_uniform(&settings);
        let resolved = resolve(&plan, &self.history.carried, true, show_accumulation);
        self.targets.ensure(&self.gpu, &resolved.needs);
        super::window::begin_window_frame(
            &mut self.window,
            &self.gpu,
            &self.targets,
            switches.temporal_window,
        );

        let frame_group = self.buffers.frame_bind_group.clone();
        let scene_group = self.scene.bind_group(active.backend).clone();
        let size = self.size();
        let mut dispatched: Vec<&'static str> = Vec::new();
        let mut capture = self
            .inspected_pixel
            .map(|p| InspectCapture::new(p, size, self.readbacks.inspect_staging.clone()));
        // A frame with first dispatches is timed pass by pass, whatever the timing mode:
        // that is where a CPU driver compiles (pipelines.rs, first_dispatch_ms).
        let first_dispatches = super::pipelines::awaits_first_dispatch(
            &self.pipelines.pipeline_compiles,
            key,
            plan.iter().map(|s| s.pass.name),
        );
        let timing = if first_dispatches {
            crate::gpu::timing::TimingMode::WallClock
        } else {
            self.readbacks.timing_mode
        };
        let mut rec = FrameRecorder::new(&self.gpu, &mut self.readbacks.timer, timing);
        rec.encoder()
            .clear_buffer(&self.buffers.stats_buffer, 0, None);
        if capture.is_some() && switches.pt {
            rec.encoder()
                .clear_buffer(self.targets.pixels(&PT_PROBE), 0, None);
        }
        let uniforms = self.buffers.uniforms();
        let steps = step_context!(self, &uniforms, variant, [&frame_group, &scene_group]);
        for (step, r) in plan.iter().zip(&resolved.steps) {
            steps.record(&mut self.bind_groups, &mut rec, step, &r.bound);
            // Repeated passes (spatial × P) are listed once.
            if dispatched.last() != Some(&step.pass.name) {
                dispatched.push(step.pass.name);
            }
            if let (Some(c), Some((chain, stage, buffer))) = (&mut capture, r.inspect) {
                let reservoirs = self.targets.chain(chain, buffer);
                if chain.name == RESERVOIRS.name {
                    c.copy_reservoir(rec.encoder(), reservoirs, stage);
                } else {
                    c.copy_gi_reservoir(rec.encoder(), reservoirs, stage);
                }
            }
        }
        if let Some(c) = &mut capture {
            c.copy_frame_records(
                rec.encoder(),
                &self.targets,
                resolved.surfaces,
                switches.gi,
                switches.pt,
                switches
                    .denoise
                    .then(|| resolved.finals.get(denoise::HISTORY.name).copied())
                    .flatten(),
            );
        }

        let frame = self.frame_index;
        let stats_ring = &mut self.readbacks.stats_ring;
        let stats_buffer = &self.buffers.stats_buffer;
        let inspect_ring = &mut self.readbacks.inspect_ring;
        let device = self.gpu.device.clone();
        let wall_times = rec.submit(frame, |encoder| {
            stats_ring.copy_from(&device, encoder, stats_buffer, stats_buffer.size(), frame);
            if let Some(c) = &capture {
                c.submit_copy(&device, encoder, inspect_ring, frame);
            }
        });
        self.file_frame(
            wall_times,
            capture,
            &active.key,
            first_dispatches,
            frame_start,
        )?;

        self.history.hand_over(
            resolved,
            self.targets.surfaces.len(),
            switches.realtime,
            camera,
            view_proj,
            jitter,
        );
        self.frame_index += 1;
        self.pipelines.last_effects = Some(active.clone());
        self.last_passes = dispatched;
        self.after_frame_depth_probe(switches.denoise && switches.denoise_history);
        Ok(())
    }

    /// Compiles the pipelines of `plan` that the frame's variant lacks (on every core),
    /// recording each compile and, for the scene's first frame, the "pipelines" phase.
    fn compile_frame_pipelines(
        &mut self,
        active: &ActiveEffects,
        plan: &[Step],
    ) -> Result<(), GpuError> {
        let variant = self
            .pipelines
            .variants
            .entry(active.key.clone())
            .or_default();
        let missing = super::pipelines::missing(variant, plan.iter().map(|s| s.pass));
        let compile_start = std::time::Instant::now();
        let watch = self.pipelines.compile_watcher.clone();
        let compiled = super::pipelines::compile_all(
            &self.gpu,
            &self.layouts,
            &active.defines,
            variant,
            &missing,
            &|e| watch.as_ref().map_or((), |w| w(e)),
        )?;
        if self.pipelines.first_frame_pipelines.is_none() && !compiled.is_empty() {
            let wall = compile_start.elapsed().as_secs_f64() * 1e3;
            self.pipelines.first_frame_pipelines = Some(super::pipelines::phase(&compiled, wall));
        }
        self.pipelines.pipeline_compiles.extend(compiled);
        Ok(())
    }

    /// Files what a submitted frame sends back, by frame index: its pass times, its first
    /// dispatches, the pending inspection. The scene's first frame is waited for (a CPU
    /// driver compiles its shaders there) and becomes the "first frame" phase.
    fn file_frame(
        &mut self,
        wall_times: Vec<(&'static str, f64)>,
        capture: Option<InspectCapture>,
        variant: &str,
        first_dispatches: bool,
        frame_start: std::time::Instant,
    ) -> Result<(), GpuError> {
        let frame = self.frame_index;
        self.readbacks.stats_ring.after_submit();
        self.readbacks.inspect_ring.after_submit();
        if first_dispatches {
            super::pipelines::record_first_dispatches(
                &mut self.pipelines.pipeline_compiles,
                variant,
                &wall_times,
            );
        }
        if !wall_times.is_empty() {
            self.readbacks.pending_times.insert(frame, wall_times);
        }
        if let Some(c) = capture {
            self.readbacks
                .pending_inspections
                .insert(frame, c.into_pending());
        }
        self.gpu.check()?;
        if self.pipelines.first_frame.is_none() {
            // The scene's first frame, waited for: a CPU driver (lavapipe) compiles its
            // shaders at the first dispatch, not at pipeline creation, so on a cold shader
            // cache this is where the compile time shows.
            self.gpu.wait_idle();
            let compiled_ms = self
                .pipelines
                .first_frame_pipelines
                .as_ref()
                .map_or(0.0, |p| p.ms);
            let ms = frame_start.elapsed().as_secs_f64() * 1e3 - compiled_ms;
            self.pipelines.first_frame = Some(crate::load_phases::Phase {
                name: "first frame",
                ms,
                detail: "recorded, run and waited for (lavapipe compiles its shaders here)".into(),
            });
        }
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
        let Some(active) = self.pipelines.last_effects.clone() else {
            return Ok(());
        };
        let shown_accumulation = self.shows_accumulation();
        let variant = self
            .pipelines
            .variants
            .entry(active.key.clone())
            .or_default();
        let gi_view = settings.gi
            && !settings.pt
            && self.mode != Mode::Reference
            && self.view.view.is_indirect();
        let pt_view = settings.pt
            && self.mode != Mode::Reference
            && (self.view.view.is_path_view() || self.view.view == DebugView::Indirect);
        let denoise_view = settings.denoise
            && self.mode != Mode::Reference
            && self.view.view.is_denoise_view()
            && self.history.carried.has_history(&denoise::HISTORY);
        let plan = frame_plan::display_only(
            gi_view,
            pt_view,
            denoise_view,
            self.view.view == DebugView::Bias,
            self.view.view.uses_temporal_window(),
        );
        for step in &plan {
            variant.compile(&self.gpu, &self.layouts, &active.defines, step.pass)?;
        }
        let resolved = resolve(&plan, &self.history.carried, false, shown_accumulation);
        // Normally there already (a GI view right after GI was switched on shows zeros).
        self.targets.ensure(&self.gpu, &resolved.needs);
        let variant = &self.pipelines.variants[&active.key];
        let uniforms = self.buffers.uniforms();
        let mut rec = FrameRecorder::new(
            &self.gpu,
            &mut self.readbacks.timer,
            crate::gpu::timing::TimingMode::Off,
        );
        let groups = [
            &self.buffers.frame_bind_group,
            self.scene.bind_group(active.backend),
        ];
        let steps = step_context!(self, &uniforms, variant, groups);
        for (step, r) in plan.iter().zip(&resolved.steps) {
            steps.record(&mut self.bind_groups, &mut rec, step, &r.bound);
        }
        rec.submit(self.frame_index, |_| {});
        self.gpu.check()
    }
}

impl Renderer {
    /// The light samplers' data this frame needs, allocated or brought up to date (the BVH
    /// rebuilt or refitted after the lights changed); true if a buffer was replaced.
    fn ensure_light_sampler(
        &mut self,
        switches: &FrameSwitches,
        effects: &EffectSet,
        refit_on_gpu: bool,
    ) -> bool {
        let lights = &mut self.buffers.light_sampler;
        lights.wait_for_gpu_refit =
            self.readbacks.timing_mode != crate::gpu::timing::TimingMode::Off;
        let mut replaced = false;
        if switches.light_tiles {
            replaced |= lights.ensure_presampled(&self.gpu, LIGHT_TILE_COUNT * LIGHT_TILE_SIZE);
        }
        if switches.regir_slots > 0 {
            replaced |= lights.ensure_presampled(&self.gpu, switches.regir_slots);
        }
        // The reference's vertices may sample with the tree too (`Settings::for_reference`),
        // and ReGIR's fill may draw from it.
        let tree = [
            Effect::LightBvh,
            Effect::VertexLightBvh,
            Effect::RegirFromBvh,
        ];
        if tree.iter().any(|e| effects.contains(*e)) {
            replaced |= lights.ensure_bvh(&self.gpu, &self.scene, refit_on_gpu);
        }
        replaced
    }
}

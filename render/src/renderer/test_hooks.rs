//! What only tests may do to a renderer: plant a known error in the shaders, freeze the
//! light samplers, poison the history. Compiled only with the `test-hooks` feature, which
//! the crate's own tests turn on (render/Cargo.toml's dev-dependency on itself), so the
//! shipped API has none of it.

use super::*;
use crate::gpu_types::{GpuGiReservoir, GpuReservoir};
use crate::passes::resources::RESERVOIRS;

impl Renderer {
    /// Test-only: the light samplers' structures stay as they are now, whatever the scene
    /// does (the planted twin of the BVH's refit).
    pub fn freeze_light_sampler_for_tests(&mut self) {
        self.buffers.light_sampler.frozen = true;
    }

    /// Test-only: each light-BVH refit loses one light of the scene's change list (the
    /// planted twin of the change list's test).
    pub fn lose_light_change_for_tests(&mut self) {
        self.buffers.light_sampler.planted_lost_change = true;
    }

    /// Test-only: the scene's and the light BVH's GPU buffers as they are now (the
    /// partial update's test compares them with a full upload's).
    pub fn scene_buffers_for_tests(&self) -> crate::gpu_scene::SceneBufferContents {
        let mut contents = self.scene.buffer_contents_for_tests(&self.gpu);
        let nodes = &self.buffers.light_sampler.bvh_nodes;
        contents.light_bvh_nodes =
            crate::gpu::readback::read_buffer(&self.gpu, nodes, 0, nodes.size());
        contents
    }

    /// Test-only: compiles the `PLANTED_*` defines `defines` into every pass from the next
    /// frame on (on top of the derived or forced effect set), so that a test can show that
    /// its detector fires on a known error.
    pub fn plant_for_tests(&mut self, defines: &[&str]) {
        for d in defines {
            assert!(
                crate::planted::find(d).is_some(),
                "{d} is not a planted switch (render/src/planted.rs lists them)"
            );
        }
        self.pipelines.planted = defines.iter().map(|d| d.to_string()).collect();
        self.pipelines.last_effects = None;
    }

    /// Fault injection for tests of the non-finite guard: overwrites the history
    /// reservoirs with NaN and infinite weights, as a driver bug or a bad upload might.
    /// The next frame's temporal pass must count them and treat them as null.
    pub fn poison_history_for_tests(&mut self) {
        let poisoned = GpuReservoir {
            light: 0,
            p_hat: f32::NAN,
            uv: [0.3, 0.3],
            w_sum: f32::INFINITY,
            weight: f32::NAN,
            m: f32::NAN,
            source: 1,
        };
        let data = vec![poisoned; self.targets.pixel_count() as usize];
        self.gpu.queue.write_buffer(
            self.targets
                .chain(&RESERVOIRS, self.history.carried.history(&RESERVOIRS)),
            0,
            bytemuck::cast_slice(&data),
        );
    }

    /// The same for the ReSTIR GI history (after a frame with GI): NaN and infinite
    /// weights and positions, which the next GI temporal pass must count and drop.
    pub fn poison_gi_history_for_tests(&mut self) {
        use crate::gi::passes::initial::GI_RESERVOIRS;
        if !self.history.carried.has_history(&GI_RESERVOIRS) {
            return;
        }
        let poisoned = GpuGiReservoir {
            position: [f32::NAN, 0.0, f32::INFINITY],
            normal: 0,
            radiance: [f32::INFINITY; 3],
            w_sum: f32::NAN,
            weight: f32::INFINITY,
            m: f32::NAN,
            p_hat: 1.0,
            packed: GpuGiReservoir::pack(crate::shader_constants::SOURCE_TEMPORAL, 0, 0),
        };
        let data = vec![poisoned; self.targets.pixel_count() as usize];
        let history = self.history.carried.history(&GI_RESERVOIRS);
        self.gpu.queue.write_buffer(
            self.targets.chain(&GI_RESERVOIRS, history),
            0,
            bytemuck::cast_slice(&data),
        );
    }

    /// The same for the ReSTIR PT history (after a frame with PT): NaN and infinite values,
    /// weights and geometry, which the next PT temporal pass must count and drop.
    pub fn poison_pt_history_for_tests(&mut self) {
        use crate::pt::passes::initial::PT_RESERVOIRS;
        if !self.history.carried.has_history(&PT_RESERVOIRS) {
            return;
        }
        let poisoned = crate::gpu_types::GpuPtReservoir {
            value: [f32::INFINITY, 0.0, f32::NAN],
            p_hat: 1.0,
            w_sum: f32::NAN,
            weight: f32::INFINITY,
            m: f32::NAN,
            packed: crate::shader_constants::SOURCE_TEMPORAL | (2 << 4) | (1 << 9),
            rc_from_d2: f32::NAN,
            replay_pdf: f32::INFINITY,
            jacobian: 1.0,
            ..Default::default()
        };
        let data = vec![poisoned; self.targets.pixel_count() as usize];
        let history = self.history.carried.history(&PT_RESERVOIRS);
        self.gpu.queue.write_buffer(
            self.targets.chain(&PT_RESERVOIRS, history),
            0,
            bytemuck::cast_slice(&data),
        );
    }
}

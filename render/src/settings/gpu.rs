//! The `Params` uniform the shaders read, from the settings: the fields no one technique
//! owns here, each technique's part from its folder (`di::settings::gpu_params`, …).

use super::{Settings, flag_bits};
use crate::gpu_types::{GpuParams, PASS_INFO_SLOTS};
use crate::shader_constants::*;
use crate::{denoise, di, gi, pt};

impl Settings {
    /// The uniform block the shaders read, for an image `height` pixels high (pixel-unit
    /// parameters follow the height, see `pixel_units`).
    pub fn gpu_params(&self, height: u32) -> GpuParams {
        let checks = flag_bits(&[
            (self.check_offscreen, REJECT_OFFSCREEN),
            (self.check_surface, REJECT_SURFACE),
            (self.check_material, REJECT_MATERIAL),
            (self.check_normal, REJECT_NORMAL),
            (self.check_depth, REJECT_DEPTH),
            (self.check_reservoir, REJECT_RESERVOIR),
            (self.check_target, REJECT_TARGET),
            (self.check_target_ratio, REJECT_TARGET_RATIO),
        ]);
        let shared_flags = flag_bits(&[(self.jitter, PARAM_FLAG_JITTER)]);
        GpuParams {
            normal_threshold: self.normal_threshold,
            depth_threshold: self.depth_threshold,
            checks,
            flags: shared_flags
                | di::settings::flags(self)
                | gi::settings::flags(self)
                | denoise::settings::flags(self),
            // One frame renders at most PASS_INFO_SLOTS chunks of samples; the shader divides
            // by this count, so it must be the count actually rendered (4096 used to render
            // 2048 and halve the image).
            reference_spp: self
                .reference_spp
                .clamp(1, REFERENCE_SAMPLES_PER_DISPATCH * PASS_INFO_SLOTS),
            max_bounces: self.reference_bounces(),
            regir_grid: self.regir_grid.clamp(1, MAX_REGIR_GRID),
            regir_slots: self.regir_slots_in_use(),
            regir_cell_size: self.regir_cell_size,
            regir_build_samples: self.regir_build_samples.max(1),
            regir_jitter: self.regir_jitter,
            reference_light_samples: self.reference_light_samples_in_use(),
            di: di::settings::gpu_params(self, height),
            gi: gi::settings::gpu_params(self, height),
            pt: pt::settings::gpu_params(self, height),
            denoise: denoise::settings::gpu_params(self),
        }
    }
}

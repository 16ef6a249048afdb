//! The denoiser's companion preset: switching the denoiser on in the Pipeline panel
//! switches to `restir-denoised` (render/src/settings/preset.rs), the ReSTIR that the
//! crossover map found cheapest through the denoiser (docs/src/measured/denoiser.md, "The crossover
//! map at 384×256"), and opens the split screen with denoised RIS as B, so both errors stand on the
//! image. Switching the denoiser off again brings back the settings, mode and split screen of
//! before. The Pipeline panel's "Denoiser on: switch to restir-denoised" box turns this off.

use restir_render::settings::preset;
use restir_render::{Mode, Settings};

use super::state::{BeforePreset, CompareState, ViewerState};

/// B of the split screen while the preset is on.
pub const COMPARE_WITH: &str = "ris+denoise";

/// Call after the Pipeline panel ran, with the denoiser's state before it: a switch of the
/// denoiser applies or undoes the preset.
pub fn follow_denoiser(state: &mut ViewerState, was_on: bool) {
    let on = state.settings.denoise;
    if on == was_on || !state.denoised_preset.follow {
        return;
    }
    if on {
        let Some(assignments) = preset::builtin("restir-denoised") else {
            return;
        };
        let mut settings = state.settings.clone();
        if let Err(e) = settings.apply_assignments(assignments.iter().copied()) {
            state.preset_message = Some(format!("error: restir-denoised: {e}"));
            return;
        }
        state.denoised_preset.saved = Some(BeforePreset {
            settings: state.settings.clone(),
            mode: state.mode,
            compare: state.compare.clone(),
        });
        state.settings = settings;
        state.mode = Mode::Restir;
        state.compare = CompareState {
            enabled: true,
            spec: COMPARE_WITH.to_string(),
            ..state.compare.clone()
        };
        state.compare.target = None;
        state.compare.error = None;
        state.preset_message = Some(format!(
            "Denoiser on: restir-denoised (temporal reuse, M cap 4, no spatial reuse), \
             B = {COMPARE_WITH} (docs/src/measured/denoiser.md, \"The crossover map at 384×256\")"
        ));
    } else if let Some(saved) = state.denoised_preset.saved.take() {
        state.settings = Settings {
            denoise: false,
            ..saved.settings
        };
        state.mode = saved.mode;
        state.compare = saved.compare;
        state.preset_message = Some("Denoiser off: the settings of before".to_string());
    }
}

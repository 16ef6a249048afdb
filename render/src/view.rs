//! What is shown and how: the rendering mode, the debug view, exposure and tonemapper.
//! These are view settings, not pipeline parameters (they never change the estimate).

use crate::shader_constants::*;

/// Which estimator renders the frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum Mode {
    /// Unbiased progressive ground truth (ray-traced camera rays, light + BSDF MIS).
    Reference,
    /// One power-sampled light sample per pixel per frame.
    Nee,
    /// Initial RIS without reuse.
    Ris,
    /// RIS + temporal + spatial reuse, as the settings say.
    Restir,
}

impl Mode {
    pub const ALL: [Mode; 4] = [Mode::Reference, Mode::Nee, Mode::Ris, Mode::Restir];

    pub fn name(self) -> &'static str {
        match self {
            Mode::Reference => "reference",
            Mode::Nee => "nee",
            Mode::Ris => "ris",
            Mode::Restir => "restir",
        }
    }

    pub fn from_name(s: &str) -> Option<Mode> {
        Mode::ALL.into_iter().find(|m| m.name() == s)
    }

    /// The settings this mode renders with: nee and ris turn every reuse stage off
    /// (`Settings::without_reuse`), nee also draws one light candidate and no BSDF one; the
    /// reference samples lights its own way (`Settings::for_reference`).
    pub fn settings(self, settings: &crate::settings::Settings) -> crate::settings::Settings {
        match self {
            Mode::Nee => {
                let mut s = settings.without_reuse();
                s.light_candidates = 1;
                s.bsdf_candidates = 0;
                s
            }
            Mode::Ris => settings.without_reuse(),
            Mode::Restir => settings.clone(),
            Mode::Reference => settings.for_reference(),
        }
    }
}

/// Which pass draws a debug view (the frame plan dispatches it only while it is shown).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DrawnBy {
    /// display.wgsl, from the frame's buffers.
    Display,
    /// ReSTIR GI's view pass (gi/view.wgsl), only while GI runs.
    GiView,
    /// The indirect light alone: GI's view pass, or PT's while PT runs.
    IndirectView,
    /// ReSTIR PT's view pass (pt/view.wgsl), only while PT runs.
    PtView,
    /// bias_view.wgsl: the running average against the Accuracy reference.
    BiasView,
    /// window_view.wgsl, from the temporal window (kept only while such a view is shown).
    WindowView,
    /// The denoiser's view pass (denoise/view.wgsl), only while the denoiser runs.
    DenoiseView,
}

/// One row per debug view: its variant, its name on the command line
/// (`--debug-view NAME`), its code (the WGSL constant `VIEW_*` the passes switch on), the
/// pass that draws it and whether it compares with the Accuracy reference (which must then
/// be fetched). Adding a view is a row here, a branch in the WGSL of the pass named and a
/// legend in the View panel (docs/src/adding-a-debug-view.md).
macro_rules! debug_views {
    ($( $(#[$meta:meta])* $variant:ident, $name:literal, $code:ident = $value:literal, $drawn_by:ident, $reference:literal; )*) => {
        /// The debug views (names as on the command line: `--debug-view NAME`).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum DebugView {
            $( $(#[$meta])* $variant, )*
        }

        $( pub const $code: u32 = $value; )*

        /// The views' codes, for the WGSL prelude (shader_constants.rs).
        pub(crate) fn view_codes() -> Vec<(&'static str, crate::wgsl_constants::WgslValue)> {
            vec![$( (stringify!($code), crate::wgsl_constants::WgslValue::from($code)) ),*]
        }

        impl DebugView {
            pub const ALL: [DebugView; [$( DebugView::$variant ),*].len()] = [$( DebugView::$variant ),*];

            pub fn name(self) -> &'static str {
                match self { $( DebugView::$variant => $name, )* }
            }

            pub fn gpu_code(self) -> u32 {
                match self { $( DebugView::$variant => $code, )* }
            }

            /// The pass that draws the view.
            pub fn drawn_by(self) -> DrawnBy {
                match self { $( DebugView::$variant => DrawnBy::$drawn_by, )* }
            }

            /// Whether the view compares with the Accuracy reference (which must be fetched).
            pub fn needs_reference(self) -> bool {
                match self { $( DebugView::$variant => $reference, )* }
            }
        }
    };
}

debug_views! {
    Final, "final", VIEW_FINAL = 0, Display, false;
    Source, "source", VIEW_SOURCE = 1, Display, false;
    M, "m", VIEW_M = 2, Display, false;
    Rejection, "rejection", VIEW_REJECTION = 3, Display, false;
    Weight, "w", VIEW_WEIGHT = 4, Display, false;
    Normals, "normals", VIEW_NORMALS = 5, Display, false;
    Albedo, "albedo", VIEW_ALBEDO = 6, Display, false;
    Depth, "depth", VIEW_DEPTH = 7, Display, false;
    Motion, "motion", VIEW_MOTION = 8, Display, false;
    Error, "error", VIEW_ERROR = 9, Display, true;
    /// |A − B| against the other side of a split-screen comparison.
    Difference, "difference", VIEW_DIFFERENCE = 10, Display, false;
    /// The running average minus the reference, signed, where it exceeds the noise.
    Bias, "bias", VIEW_BIAS = 17, BiasView, true;
    Age, "age", VIEW_AGE = 11, Display, false;
    /// The indirect radiance alone (ReSTIR GI or PT).
    Indirect, "indirect", VIEW_INDIRECT = 12, IndirectView, false;
    /// ReSTIR GI's reservoirs.
    GiSource, "gi-source", VIEW_GI_SOURCE = 13, GiView, false;
    GiM, "gi-m", VIEW_GI_M = 14, GiView, false;
    GiRejection, "gi-rejection", VIEW_GI_REJECTION = 15, GiView, false;
    GiJacobian, "gi-jacobian", VIEW_GI_JACOBIAN = 16, GiView, false;
    /// ReSTIR PT: the survivor's path length, the depth of its reconnection vertex, why
    /// shifts to the pixel failed, log2 |J| of its last shift.
    PtLength, "pt-length", VIEW_PT_LENGTH = 20, PtView, false;
    PtReconnection, "pt-reconnection", VIEW_PT_RECONNECTION = 21, PtView, false;
    PtFailure, "pt-failure", VIEW_PT_FAILURE = 22, PtView, false;
    PtJacobian, "pt-jacobian", VIEW_PT_JACOBIAN = 23, PtView, false;
    /// The denoiser: the frame before it, each pixel's history length, the relative
    /// standard deviation its luminance gate is scaled by.
    DenoiseInput, "denoise-input", VIEW_DENOISE_INPUT = 24, DenoiseView, false;
    HistoryLength, "history-length", VIEW_HISTORY_LENGTH = 25, DenoiseView, false;
    DenoiseVariance, "denoise-variance", VIEW_DENOISE_VARIANCE = 26, DenoiseView, false;
    /// λ, the share of the lighting that changed since last frame (temporal gradients).
    TemporalGradient, "temporal-gradient", VIEW_TEMPORAL_GRADIENT = 27, DenoiseView, false;
    /// The light samplers (docs/src/light-samplers.md): which strategy proposed the initial
    /// survivor, the share of light candidates that could contribute (p̂ > 0, unshadowed),
    /// and the ReGIR cell each pixel lies in.
    Proposer, "proposer", VIEW_PROPOSER = 28, Display, false;
    UsefulCandidates, "useful-candidates", VIEW_USEFUL_CANDIDATES = 29, Display, false;
    RegirCell, "regir-cell", VIEW_REGIR_CELL = 30, Display, false;
    /// σ/mean of each pixel's luminance over the temporal window: where the image flickers.
    Boiling, "boiling", VIEW_BOILING = 18, WindowView, false;
    /// How often the survivor's light changed within the temporal window.
    SurvivorChange, "survivor-change", VIEW_SURVIVOR_CHANGE = 19, WindowView, false;
}

impl DebugView {
    pub fn from_name(s: &str) -> Option<DebugView> {
        DebugView::ALL.into_iter().find(|v| v.name() == s)
    }

    /// Whether the view shows ReSTIR GI data (drawn by the gi_view pass, only when GI runs).
    pub fn is_indirect(self) -> bool {
        matches!(self.drawn_by(), DrawnBy::GiView | DrawnBy::IndirectView)
    }

    /// Whether the view shows ReSTIR PT's path reservoirs (drawn by the pt_view pass, only
    /// when PT runs; `Indirect` is drawn there too while PT is on).
    pub fn is_path_view(self) -> bool {
        self.drawn_by() == DrawnBy::PtView
    }

    /// Whether the view shows the denoiser's buffers (drawn only while it runs).
    pub fn is_denoise_view(self) -> bool {
        self.drawn_by() == DrawnBy::DenoiseView
    }

    /// Whether the view reads the temporal window (kept only while such a view is shown).
    pub fn uses_temporal_window(self) -> bool {
        self.drawn_by() == DrawnBy::WindowView
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tonemapper {
    Aces,
    Reinhard,
    Clamp,
}

impl Tonemapper {
    pub const ALL: [Tonemapper; 3] = [Tonemapper::Aces, Tonemapper::Reinhard, Tonemapper::Clamp];

    pub fn name(self) -> &'static str {
        match self {
            Tonemapper::Aces => "aces",
            Tonemapper::Reinhard => "reinhard",
            Tonemapper::Clamp => "clamp",
        }
    }

    pub fn gpu_code(self) -> u32 {
        match self {
            Tonemapper::Aces => TONEMAP_ACES,
            Tonemapper::Reinhard => TONEMAP_REINHARD,
            Tonemapper::Clamp => TONEMAP_CLAMP,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewSettings {
    pub view: DebugView,
    /// Exposure in stops (the image is multiplied by 2^exposure_ev before tonemapping).
    pub exposure_ev: f32,
    pub tonemapper: Tonemapper,
    /// Show the running average instead of the last frame.
    pub accumulate: bool,
    /// Temporal rejection reasons the rejection view shows (bits 0..8).
    pub reason_mask: u32,
    /// The rejection view shows, where the temporal candidate was not rejected, how many
    /// spatial neighbours were.
    pub spatial_count: bool,
}

impl Default for ViewSettings {
    fn default() -> Self {
        ViewSettings {
            view: DebugView::Final,
            exposure_ev: 0.0,
            tonemapper: Tonemapper::Aces,
            accumulate: false,
            reason_mask: crate::shader_constants::REJECT_TEMPORAL_REASONS,
            spatial_count: true,
        }
    }
}

/// Exposure (in EV) that maps the image's log-average luminance to middle grey (0.18),
/// the usual automatic exposure; 0 for a black image.
pub fn auto_exposure_ev(image: &crate::image::LinearImage) -> f32 {
    let mut sum = 0.0f64;
    let mut n = 0usize;
    for p in &image.pixels {
        let l = crate::image::luminance([p[0], p[1], p[2]]);
        if l.is_finite() && l > 0.0 {
            sum += (l as f64).ln();
            n += 1;
        }
    }
    if n == 0 {
        return 0.0;
    }
    let log_avg = (sum / n as f64).exp();
    (0.18 / log_avg).log2().clamp(-40.0, 40.0) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every view has its own name and code, and a code the passes can switch on.
    #[test]
    fn each_debug_view_row_is_its_own() {
        let mut names: Vec<_> = DebugView::ALL.iter().map(|v| v.name()).collect();
        let mut codes: Vec<_> = DebugView::ALL.iter().map(|v| v.gpu_code()).collect();
        names.sort();
        names.dedup();
        codes.sort();
        codes.dedup();
        assert_eq!(names.len(), DebugView::ALL.len());
        assert_eq!(codes.len(), DebugView::ALL.len());
        let prelude = crate::shader_source::wgsl_prelude();
        for v in DebugView::ALL {
            assert_eq!(DebugView::from_name(v.name()), Some(v));
            assert!(prelude.contains(&format!("= {}u;", v.gpu_code())));
        }
        assert!(prelude.contains("const VIEW_PT_JACOBIAN: u32 = 23u;"));
        assert_eq!(DebugView::Indirect.drawn_by(), DrawnBy::IndirectView);
        assert!(DebugView::Bias.needs_reference() && !DebugView::Boiling.needs_reference());
    }
}

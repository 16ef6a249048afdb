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
    /// (`Settings::without_reuse`), nee also draws one light candidate and no BSDF one.
    pub fn settings(self, settings: &crate::settings::Settings) -> crate::settings::Settings {
        match self {
            Mode::Nee => {
                let mut s = settings.without_reuse();
                s.light_candidates = 1;
                s.bsdf_candidates = 0;
                s
            }
            Mode::Ris => settings.without_reuse(),
            Mode::Restir | Mode::Reference => settings.clone(),
        }
    }
}

/// The debug views (names as on the command line: `--debug-view NAME`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DebugView {
    Final,
    Source,
    M,
    Rejection,
    Weight,
    Normals,
    Albedo,
    Depth,
    Motion,
    Error,
    /// |A − B| against the other side of a split-screen comparison.
    Difference,
    /// The running average minus the reference, signed, where it exceeds the noise.
    Bias,
    Age,
    /// ReSTIR GI: the indirect radiance alone, and the GI reservoirs (drawn by gi_view).
    Indirect,
    GiSource,
    GiM,
    GiRejection,
    GiJacobian,
    /// ReSTIR PT (drawn by pt_view): the survivor's path length, the depth of its
    /// reconnection vertex, why shifts to the pixel failed, log2 |J| of its last shift.
    PtLength,
    PtReconnection,
    PtFailure,
    PtJacobian,
    /// σ/mean of each pixel's luminance over the temporal window: where the image flickers.
    Boiling,
    /// How often the survivor's light changed within the temporal window.
    SurvivorChange,
}

impl DebugView {
    pub const ALL: [DebugView; 24] = [
        DebugView::Final,
        DebugView::Source,
        DebugView::M,
        DebugView::Rejection,
        DebugView::Weight,
        DebugView::Normals,
        DebugView::Albedo,
        DebugView::Depth,
        DebugView::Motion,
        DebugView::Error,
        DebugView::Difference,
        DebugView::Bias,
        DebugView::Age,
        DebugView::Indirect,
        DebugView::GiSource,
        DebugView::GiM,
        DebugView::GiRejection,
        DebugView::GiJacobian,
        DebugView::PtLength,
        DebugView::PtReconnection,
        DebugView::PtFailure,
        DebugView::PtJacobian,
        DebugView::Boiling,
        DebugView::SurvivorChange,
    ];

    pub fn name(self) -> &'static str {
        match self {
            DebugView::Final => "final",
            DebugView::Source => "source",
            DebugView::M => "m",
            DebugView::Rejection => "rejection",
            DebugView::Weight => "w",
            DebugView::Normals => "normals",
            DebugView::Albedo => "albedo",
            DebugView::Depth => "depth",
            DebugView::Motion => "motion",
            DebugView::Error => "error",
            DebugView::Difference => "difference",
            DebugView::Bias => "bias",
            DebugView::Age => "age",
            DebugView::Indirect => "indirect",
            DebugView::GiSource => "gi-source",
            DebugView::GiM => "gi-m",
            DebugView::GiRejection => "gi-rejection",
            DebugView::GiJacobian => "gi-jacobian",
            DebugView::PtLength => "pt-length",
            DebugView::PtReconnection => "pt-reconnection",
            DebugView::PtFailure => "pt-failure",
            DebugView::PtJacobian => "pt-jacobian",
            DebugView::Boiling => "boiling",
            DebugView::SurvivorChange => "survivor-change",
        }
    }

    pub fn from_name(s: &str) -> Option<DebugView> {
        DebugView::ALL.into_iter().find(|v| v.name() == s)
    }

    pub fn gpu_code(self) -> u32 {
        match self {
            DebugView::Final => VIEW_FINAL,
            DebugView::Source => VIEW_SOURCE,
            DebugView::M => VIEW_M,
            DebugView::Rejection => VIEW_REJECTION,
            DebugView::Weight => VIEW_WEIGHT,
            DebugView::Normals => VIEW_NORMALS,
            DebugView::Albedo => VIEW_ALBEDO,
            DebugView::Depth => VIEW_DEPTH,
            DebugView::Motion => VIEW_MOTION,
            DebugView::Error => VIEW_ERROR,
            DebugView::Difference => VIEW_DIFFERENCE,
            DebugView::Bias => VIEW_BIAS,
            DebugView::Age => VIEW_AGE,
            DebugView::Indirect => VIEW_INDIRECT,
            DebugView::GiSource => VIEW_GI_SOURCE,
            DebugView::GiM => VIEW_GI_M,
            DebugView::GiRejection => VIEW_GI_REJECTION,
            DebugView::GiJacobian => VIEW_GI_JACOBIAN,
            DebugView::PtLength => VIEW_PT_LENGTH,
            DebugView::PtReconnection => VIEW_PT_RECONNECTION,
            DebugView::PtFailure => VIEW_PT_FAILURE,
            DebugView::PtJacobian => VIEW_PT_JACOBIAN,
            DebugView::Boiling => VIEW_BOILING,
            DebugView::SurvivorChange => VIEW_SURVIVOR_CHANGE,
        }
    }

    /// Whether the view compares with the Accuracy reference (which must be fetched).
    pub fn needs_reference(self) -> bool {
        matches!(self, DebugView::Error | DebugView::Bias)
    }

    /// Whether the view shows ReSTIR GI data (drawn by the gi_view pass, only when GI runs).
    pub fn is_indirect(self) -> bool {
        matches!(
            self,
            DebugView::Indirect
                | DebugView::GiSource
                | DebugView::GiM
                | DebugView::GiRejection
                | DebugView::GiJacobian
        )
    }

    /// Whether the view shows ReSTIR PT's path reservoirs (drawn by the pt_view pass, only
    /// when PT runs; `Indirect` is drawn there too while PT is on).
    pub fn is_path_view(self) -> bool {
        matches!(
            self,
            DebugView::PtLength
                | DebugView::PtReconnection
                | DebugView::PtFailure
                | DebugView::PtJacobian
        )
    }

    /// Whether the view reads the temporal window (kept only while such a view is shown).
    pub fn uses_temporal_window(self) -> bool {
        matches!(self, DebugView::Boiling | DebugView::SurvivorChange)
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

//! The Pipeline panel: the estimator (mode) and every parameter of the `PARAMS` table,
//! grouped by stage, with the table's documentation as tooltips. Nothing here names a
//! parameter: a new row in render/src/settings.rs shows up on its own.

use std::path::Path;

use egui::{RichText, Ui};
use restir_render::effects::{AUTO_BVH_CANDIDATES, Effect};
use restir_render::settings::{
    LightSampler, PARAMS, ParamDef, ParamKind, ParamValue, RayBackendChoice, Stage, preset,
};
use restir_render::tracing::RayBackend;
use restir_render::{Mode, Settings};

use crate::viewer::state::ViewerState;

pub fn ui(ui: &mut Ui, state: &mut ViewerState) {
    let denoiser_was_on = state.settings.denoise;
    mode_selector(ui, &mut state.mode);
    let context = Context {
        height: state.render_size.1,
        ray_query: state.device.ray_query,
        ray_backend: state.device.ray_backend,
        auto_took_bvh: state.settings.light_sampler == LightSampler::Auto
            && state
                .scene
                .effects
                .as_ref()
                .is_some_and(|e| e.contains(Effect::LightBvh)),
    };
    for stage in stages() {
        stage_ui(ui, &mut state.settings, stage, &context);
    }
    ui.checkbox(
        &mut state.denoised_preset.follow,
        "Denoiser on: switch to restir-denoised",
    )
    .on_hover_text(
        "Switching the denoiser on applies the restir-denoised preset (temporal reuse, M cap 4, \
         no spatial reuse: what the crossover map found pays through the denoiser, \
         docs/src/measured/denoiser.md) and shows denoised RIS beside it; switching it off brings \
         back the settings of before.",
    );
    crate::viewer::denoised_preset::follow_denoiser(state, denoiser_was_on);
    ui.horizontal(|ui| {
        if ui
            .button("Reset to defaults")
            .on_hover_text("Every parameter back to its default (docs/src/parameters.md)")
            .clicked()
        {
            state.settings = Settings::default();
        }
    });
    presets_ui(ui, state);
}

/// The stages in the order the table first names them.
fn stages() -> Vec<Stage> {
    let mut out: Vec<Stage> = Vec::new();
    for p in PARAMS {
        if !out.contains(&p.stage) {
            out.push(p.stage);
        }
    }
    out
}

fn mode_selector(ui: &mut Ui, mode: &mut Mode) {
    ui.horizontal(|ui| {
        ui.label("Mode").on_hover_text(
            "reference: progressive ground truth · nee: one light sample · ris: initial RIS, no reuse · restir: RIS with the reuse the settings enable",
        );
        for m in Mode::ALL {
            ui.selectable_value(mode, m, m.name());
        }
    });
    match *mode {
        Mode::Nee => ui.weak("nee: 1 light candidate, no BSDF candidate, no reuse"),
        Mode::Ris => ui.weak("ris: temporal and spatial reuse are off"),
        Mode::Reference => ui.weak("reference: the pipeline parameters below do not apply"),
        Mode::Restir => ui.weak("restir: as configured below"),
    };
}

/// What the notes under the parameters need to know about the device and the last frame.
struct Context {
    height: u32,
    ray_query: bool,
    ray_backend: Option<RayBackend>,
    /// `light_sampler=auto` took the light BVH for this scene (it then caps the candidates).
    auto_took_bvh: bool,
}

/// A stage as a collapsible group. A stage with an on/off switch (`temporal`,
/// `spatial`) shows it in the group's header, so it stays reachable while the group is
/// closed, and greys out the rest of the stage while it is off; a technique's switch
/// (`gi`, `pt`) greys out that technique's parameters.
fn stage_ui(ui: &mut Ui, settings: &mut Settings, stage: Stage, context: &Context) {
    let switch = PARAMS
        .iter()
        .find(|p| p.stage == stage && is_stage_switch(p));
    let id = ui.make_persistent_id(("stage", stage.label()));
    let load = |ui: &Ui| {
        egui::collapsing_header::CollapsingState::load_with_default_open(
            ui.ctx(),
            id,
            stage == Stage::Initial,
        )
    };
    // A stage without a switch opens from its name too, not only from the small arrow
    // (clicking the name and seeing nothing happen is the first thing a new user tries).
    let mut name_clicked = false;
    load(ui)
        .show_header(ui, |ui| match switch {
            Some(def) => param_widget(ui, settings, def),
            None => {
                name_clicked = ui
                    .add(egui::Label::new(stage.label()).sense(egui::Sense::click()))
                    .clicked();
            }
        })
        .body(|ui| {
            ui.add_enabled_ui(switch.is_none_or(|s| is_on(settings, s)), |ui| {
                for def in PARAMS
                    .iter()
                    .filter(|p| p.stage == stage && !is_stage_switch(p))
                {
                    let enabled = technique_switch(def).is_none_or(|s| is_on(settings, s))
                        && chosen_by(def).is_none_or(|(choice, value)| {
                            settings.get(choice.name) == Some(ParamValue::Choice(value.to_string()))
                        });
                    ui.add_enabled_ui(enabled, |ui| {
                        param_widget(ui, settings, def);
                        effective_value(ui, settings, def, context);
                    });
                }
            });
        });
    if name_clicked {
        let mut state = load(ui);
        state.toggle(ui);
        state.store(ui.ctx());
    }
}

/// The choice whose value `def`'s name starts with, and that value: `regir_grid` belongs
/// to `light_sampler=regir` and is greyed out while another sampler draws the candidates.
fn chosen_by(def: &ParamDef) -> Option<(&'static ParamDef, &'static str)> {
    let (prefix, _) = def.name.split_once('_')?;
    PARAMS.iter().find_map(|p| match p.kind {
        ParamKind::Choice(values) if p.stage == def.stage && p.name != def.name => {
            values.iter().find(|v| **v == prefix).map(|v| (p, *v))
        }
        _ => None,
    })
}

fn is_on(settings: &Settings, switch: &ParamDef) -> bool {
    settings.get(switch.name) == Some(ParamValue::Bool(true))
}

/// `temporal` and `spatial` switch their whole stage off (no pass is dispatched).
fn is_stage_switch(def: &ParamDef) -> bool {
    matches!(
        (def.stage, def.name),
        (Stage::Temporal, "temporal") | (Stage::Spatial, "spatial")
    )
}

/// The switch of the technique `def` belongs to: the on/off parameter of its stage that
/// its name starts with (`gi` for `gi_m_cap`, `pt` for `pt_shift`). The Indirect stage
/// holds two techniques, ReSTIR GI and PT, each with its own switch: one stage switch
/// would grey out PT's while GI is off, though PT runs without GI (it replaces it).
fn technique_switch(def: &ParamDef) -> Option<&'static ParamDef> {
    let (prefix, _) = def.name.split_once('_')?;
    PARAMS
        .iter()
        .find(|p| p.stage == def.stage && p.name == prefix && matches!(p.kind, ParamKind::Bool))
}

/// One parameter's widget, chosen by its kind; the label is strong when the value
/// differs from the default; hovering shows the table's documentation.
pub fn param_widget(ui: &mut Ui, settings: &mut Settings, def: &ParamDef) {
    let Some(value) = settings.get(def.name) else {
        return;
    };
    let mut label = RichText::new(def.label);
    if value != def.default_value() {
        label = label.strong();
    }
    let doc = format!(
        "{}\n\n`{}` · default {}",
        def.doc,
        def.name,
        def.default_value()
    );
    let new_value = match (def.kind, value) {
        (ParamKind::Bool, ParamValue::Bool(mut b)) => ui
            .checkbox(&mut b, label)
            .on_hover_text(doc)
            .changed()
            .then_some(ParamValue::Bool(b)),
        (ParamKind::Int { min, max }, ParamValue::Int(mut i)) => {
            slider(ui, &mut i, min..=max, label, doc).then_some(ParamValue::Int(i))
        }
        (ParamKind::Float { min, max }, ParamValue::Float(mut x)) => {
            slider(ui, &mut x, min..=max, label, doc).then_some(ParamValue::Float(x))
        }
        (ParamKind::Choice(options), ParamValue::Choice(current)) => {
            let mut chosen = current.clone();
            egui::ComboBox::from_label(label)
                .selected_text(&current)
                .show_ui(ui, |ui| {
                    for option in options {
                        ui.selectable_value(&mut chosen, option.to_string(), *option);
                    }
                })
                .response
                .on_hover_text(doc);
            (chosen != current).then_some(ParamValue::Choice(chosen))
        }
        (_, other) => {
            ui.label(format!("{}: {other}", def.label));
            None
        }
    };
    if let Some(v) = new_value
        && let Err(e) = settings.set(def.name, v)
    {
        log::warn!("{e}");
    }
}

/// Under a pixel-unit parameter (defined at 1080p): what it is at the render height; under a
/// switch another one overrides: what runs.
fn effective_value(ui: &mut Ui, settings: &Settings, def: &ParamDef, context: &Context) {
    let height = context.height;
    if def.name == "ray_backend" {
        ray_backend_note(ui, settings, context);
    }
    if def.name == "light_candidates"
        && context.auto_took_bvh
        && settings.light_candidates > AUTO_BVH_CANDIDATES
    {
        ui.weak(format!(
            "= {AUTO_BVH_CANDIDATES} here: auto's light BVH (light_sampler=bvh draws all)"
        ));
    }
    if def.name == "initial_visibility"
        && !settings.initial_visibility
        && settings.traces_initial_visibility()
    {
        ui.weak("traced anyway: MIS visibility needs this pixel's own V");
    }
    if let Some(px) = settings
        .effective_pixels(def.name, height)
        .filter(|_| height > 0)
    {
        ui.weak(format!("= {px:.1} px at this {height}-pixel-high image"));
    }
}

/// Under `ray_backend`: what runs, or why ray-query cannot.
fn ray_backend_note(ui: &mut Ui, settings: &Settings, context: &Context) {
    if settings.ray_backend == RayBackendChoice::RayQuery && !context.ray_query {
        let device = restir_render::tracing::Device {
            ray_query: false,
            is_cpu: false,
            adapter: "this adapter",
        };
        let line = restir_render::tracing::resolve(settings.ray_backend, device)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        ui.colored_label(
            ui.visuals().error_fg_color,
            format!("{line} — rendering with software"),
        );
    } else if let Some(backend) = context.ray_backend {
        ui.weak(format!("= {} here", backend.name()));
    }
}

/// A slider over the parameter's range; true when moved. Ranges wider than a thousand
/// get a logarithmic scale (M cap goes to 1e6, and 20 must stay reachable).
fn slider<T: egui::emath::Numeric>(
    ui: &mut Ui,
    value: &mut T,
    range: std::ops::RangeInclusive<T>,
    label: RichText,
    doc: String,
) -> bool {
    let wide = range.end().to_f64() - range.start().to_f64() >= 1000.0;
    let slider = egui::Slider::new(value, range)
        .text(label)
        .logarithmic(wide)
        .max_decimals(4);
    ui.add(slider).on_hover_text(doc).changed()
}

fn presets_ui(ui: &mut Ui, state: &mut ViewerState) {
    ui.horizontal(|ui| {
        ui.label("Preset");
        ui.add(
            egui::TextEdit::singleline(&mut state.preset_path)
                .desired_width(140.0)
                .hint_text("file.toml"),
        )
        .on_hover_text(
            "A preset file: one `name = value` line per parameter (the same files as --preset)",
        );
        if ui.button("Load").clicked() {
            state.preset_message = Some(load_preset(state));
        }
        if ui.button("Save").clicked() {
            let path = Path::new(&state.preset_path);
            state.preset_message = Some(match preset::save(path, &state.settings) {
                Ok(()) => format!("saved {}", path.display()),
                Err(e) => format!("error: {e:#}"),
            });
        }
    });
    if let Some(message) = &state.preset_message {
        let color = if message.starts_with("error") {
            ui.visuals().error_fg_color
        } else {
            ui.visuals().weak_text_color()
        };
        ui.colored_label(color, message);
    }
}

/// Loads the preset on top of the defaults (a preset names what it changes).
fn load_preset(state: &mut ViewerState) -> String {
    let path = Path::new(&state.preset_path);
    match preset::load(path, &Settings::default()) {
        Ok((settings, warnings)) => {
            state.settings = settings;
            if warnings.is_empty() {
                format!("loaded {}", path.display())
            } else {
                format!("loaded {} ({})", path.display(), warnings.join("; "))
            }
        }
        Err(e) => format!("error: {e:#}"),
    }
}

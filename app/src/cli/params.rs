//! `params` and `scenes`: what can be set and what can be loaded.

use restir_render::Settings;
use restir_render::scene::builtin::{DEFAULT_SCENE, builtin_names};
use restir_render::settings::{PARAMS, ParamKind};

pub fn print_params() {
    let mut stage = None;
    for p in PARAMS {
        if stage != Some(p.stage) {
            println!("# {}", p.stage.label());
            stage = Some(p.stage);
        }
        let range = match p.kind {
            ParamKind::Bool => "true|false".to_string(),
            ParamKind::Int { min, max } => format!("{min}..={max}"),
            ParamKind::Float { min, max } => format!("{min}..={max}"),
            ParamKind::Choice(options) => options.join("|"),
        };
        println!(
            "{} = {}  [{}]  {}: {}",
            p.name,
            p.default_value(),
            range,
            p.label,
            p.doc
        );
        let defaults = Settings::default();
        if defaults.effective_pixels(p.name, 1080).is_some() {
            let at: Vec<String> = [96, 180, 360, 720, 1080, 2160]
                .iter()
                .filter_map(|&h| {
                    Some(format!(
                        "{:.1} px at {h}p",
                        defaults.effective_pixels(p.name, h)?
                    ))
                })
                .collect();
            println!("    default, effective: {}", at.join(", "));
        }
    }
}

/// One `builtin:NAME` per line; the viewer's default is marked ` (default)`.
pub fn print_scenes() {
    for name in builtin_names() {
        let mark = if name == DEFAULT_SCENE {
            " (default)"
        } else {
            ""
        };
        println!("{name}{mark}");
    }
}

//! `params` and `scenes`: what can be set and what can be loaded.

use restir_render::scene::builtin::builtin_names;
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
    }
}

pub fn print_scenes() {
    for name in builtin_names() {
        println!("{name}");
    }
}

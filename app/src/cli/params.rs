//! `params` and `scenes`: what can be set and what can be loaded.

use std::fmt::Write as _;

use restir_render::Settings;
use restir_render::scene::builtin::DEFAULT_SCENE;
use restir_render::settings::pixel_units::{MIN_SPATIAL_RADIUS_PX, REFERENCE_HEIGHT};
use restir_render::settings::{PARAMS, ParamDef, ParamKind, Stage};

/// `restir-viewer params [--markdown]`.
#[derive(clap::Args, Debug, Default)]
pub struct ParamsArgs {
    /// Print the book's parameters page (Markdown) instead of the plain listing:
    /// `restir-viewer params --markdown > docs/src/parameters.md`.
    #[arg(long)]
    pub markdown: bool,
}

pub fn run(args: ParamsArgs) {
    if args.markdown {
        print!("{}", params_markdown());
    } else {
        print_params();
    }
}

/// Image heights at which a pixel-unit parameter's default is shown in effect.
const EFFECTIVE_HEIGHTS: [u32; 6] = [96, 180, 360, 720, 1080, 2160];

/// `2.7 px at 96p, 5.0 px at 180p, …` for a pixel-unit parameter (defaults), else `None`.
fn effective_pixels(name: &str) -> Option<String> {
    let defaults = Settings::default();
    defaults.effective_pixels(name, 1080)?;
    let at: Vec<String> = EFFECTIVE_HEIGHTS
        .iter()
        .filter_map(|&h| {
            Some(format!(
                "{:.1} px at {h}p",
                defaults.effective_pixels(name, h)?
            ))
        })
        .collect();
    Some(at.join(", "))
}

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
        if let Some(at) = effective_pixels(p.name) {
            println!("    default, effective: {at}");
        }
    }
}

/// The range or choices of a parameter, as Markdown.
fn markdown_range(kind: ParamKind) -> String {
    match kind {
        ParamKind::Bool => "`true`, `false`".to_string(),
        ParamKind::Int { min, max } => format!("`{min}` to `{max}` (integer)"),
        ParamKind::Float { min, max } => format!("`{min}` to `{max}`"),
        ParamKind::Choice(options) => {
            let quoted: Vec<String> = options.iter().map(|o| format!("`{o}`")).collect();
            quoted.join(", ")
        }
    }
}

/// The stages in table order, each once.
fn stages() -> Vec<Stage> {
    let mut stages: Vec<Stage> = Vec::new();
    for p in PARAMS {
        if !stages.contains(&p.stage) {
            stages.push(p.stage);
        }
    }
    stages
}

/// The book's parameters page (docs/src/parameters.md): every row of the settings table,
/// grouped by stage, with its default, range or choices and meaning. Generated, so the page
/// cannot drift from the table; app/tests/params_markdown.rs fails when the file is stale.
pub fn params_markdown() -> String {
    let mut out = String::new();
    let w = &mut out;
    let _ = writeln!(w, "# Parameters");
    let _ = writeln!(w);
    let _ = writeln!(
        w,
        "<!-- Generated from the settings table (render/src/settings.rs) by \
         `cargo run -p restir-viewer -- params --markdown > docs/src/parameters.md`. \
         Do not edit by hand: app/tests/params_markdown.rs fails when this file is stale. -->"
    );
    let _ = writeln!(w);
    let _ = writeln!(
        w,
        "Every pipeline parameter, from the one table the viewer's Pipeline panel, `--set \
         name=value`, preset files, tour steps and `restir-viewer params` all read. A preset \
         is a TOML file of `name = value` lines applied on top of the defaults. A number \
         outside its range is clamped, with a warning; a wrong type, an unknown name or a \
         choice that is not listed is an error that names the parameter."
    );
    let _ = writeln!(w);
    let _ = writeln!(
        w,
        "Parameters in pixels are defined at {REFERENCE_HEIGHT}p: an image `h` pixels high uses \
         value × h / {REFERENCE_HEIGHT}, at least {MIN_SPATIAL_RADIUS_PX} px (or the value \
         itself if smaller), for the viewer at any render scale, `render` and `bench` alike."
    );
    let _ = writeln!(w);
    let _ = writeln!(w, "## Overview");
    let _ = writeln!(w);
    let _ = writeln!(w, "| parameter | stage | default | range or choices |");
    let _ = writeln!(w, "| --- | --- | --- | --- |");
    for p in PARAMS {
        let _ = writeln!(
            w,
            "| [`{name}`](#{name}) | {stage} | `{default}` | {range} |",
            name = p.name,
            stage = p.stage.label(),
            default = p.default_value(),
            range = markdown_range(p.kind),
        );
    }
    for stage in stages() {
        let _ = writeln!(w);
        let _ = writeln!(w, "## {}", stage.label());
        for p in PARAMS.iter().filter(|p| p.stage == stage) {
            write_param(w, p);
        }
    }
    out
}

fn write_param(w: &mut String, p: &ParamDef) {
    let _ = writeln!(w);
    let _ = writeln!(w, "### {}", p.name);
    let _ = writeln!(w);
    let _ = writeln!(
        w,
        "**{}**: default `{}`; {}.",
        p.label,
        p.default_value(),
        markdown_range(p.kind)
    );
    if let Some(at) = effective_pixels(p.name) {
        let _ = writeln!(w, "The default in effect: {at}.");
    }
    let _ = writeln!(w);
    let _ = writeln!(w, "{}", p.doc);
}

/// One `builtin:NAME` per line with what it is, the viewer's default marked ` (default)`;
/// then the families, `builtin:NAME:N` with the range of N.
pub fn print_scenes() {
    let catalogue = restir_render::scene::builtin::catalogue();
    let max = restir_render::scene::builtin::MAX_LIGHT_COUNT;
    let label = |name: &str| {
        if name == DEFAULT_SCENE {
            format!("{name} (default)")
        } else if name.ends_with(":N") {
            format!("{name} (N lights, 1 to {max})")
        } else {
            name.to_string()
        }
    };
    let width = catalogue
        .iter()
        .map(|(n, _)| label(n).len())
        .max()
        .unwrap_or(0);
    for (name, line) in &catalogue {
        println!("{:width$}  {line}", label(name));
    }
}

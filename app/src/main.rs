//! restir-viewer: the ReSTIR lab's viewer and its headless commands.
//!
//! `restir-viewer` (or `view`) opens the interactive viewer; `render` renders frames
//! headless to EXR/PNG with statistics; `params` lists every pipeline parameter;
//! `scenes` lists the built-in scenes.

mod cli;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "restir-viewer",
    version,
    about = "The ReSTIR lab: watch, tune and measure ReSTIR direct lighting"
)]
struct Args {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Render frames headless and write an image (and statistics).
    Render(cli::render::RenderArgs),
    /// List every pipeline parameter with its stage, default, range and meaning.
    Params,
    /// List the built-in scenes (one `builtin:...` name per line).
    Scenes,
}

fn main() {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).init();
    let args = Args::parse();
    let result = match args.command {
        Some(Command::Render(a)) => cli::render::run(a),
        Some(Command::Params) => {
            cli::params::print_params();
            Ok(())
        }
        Some(Command::Scenes) => {
            cli::params::print_scenes();
            Ok(())
        }
        None => Err(anyhow::anyhow!(
            "the interactive viewer is not built yet; use `render`"
        )),
    };
    if let Err(e) = result {
        // One line, naming the file or argument and the problem.
        let msg = format!("{e:#}").replace('\n', " ");
        eprintln!("error: {msg}");
        std::process::exit(1);
    }
}

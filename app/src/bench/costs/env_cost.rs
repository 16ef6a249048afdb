//! `bench-env`: what building an environment's sampling distribution costs
//! (docs/src/environment.md, "As a light"),
//! by default for a 4K (4096×2048) HDRI: the built-in sky rendered at that size, or the
//! image `--env` names. Prints one Markdown table row; never a timing assertion.

use std::time::Instant;

use clap::Args;
use restir_render::environment::{EnvDistribution, clear_sky_texels};
use restir_render::load_environment;

use crate::cli::setup::parse_size;

#[derive(Args, Debug)]
pub struct EnvCostArgs {
    /// Time this .hdr/.exr instead of the built-in sky (its own size; --size is ignored).
    #[arg(long)]
    pub env: Option<String>,
    /// Size of the built-in sky to time, WxH.
    #[arg(long, default_value = "4096x2048")]
    pub size: String,
    /// Builds to time; the median is reported.
    #[arg(long, default_value_t = 5)]
    pub repeats: u32,
}

pub fn run(args: EnvCostArgs) -> anyhow::Result<()> {
    let started = Instant::now();
    let (name, width, height, texels) = match &args.env {
        Some(spec) => {
            let env = load_environment(spec)?;
            (spec.clone(), env.width, env.height, env.texels)
        }
        None => {
            let (w, h) = parse_size(&args.size)?;
            ("builtin:sky".to_string(), w, h, clear_sky_texels(w, h))
        }
    };
    let prepare_s = started.elapsed().as_secs_f64();
    let mut times: Vec<f64> = (0..args.repeats.max(1))
        .map(|_| {
            let t = Instant::now();
            let d = EnvDistribution::build(width, height, &texels);
            std::hint::black_box(&d);
            t.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    let texel_count = width as f64 * height as f64;
    let table_mib = (texel_count + height as f64) * 12.0 / (1024.0 * 1024.0);
    println!(
        "| image | texels | table | build (median of {}) | per Mtexel |",
        times.len()
    );
    println!("| --- | --- | --- | --- | --- |");
    println!(
        "| {name} {width}×{height} | {:.1} M | {table_mib:.0} MiB | {median:.0} ms | {:.0} ms |",
        texel_count / 1e6,
        median / (texel_count / 1e6)
    );
    eprintln!(
        "prepared the image in {prepare_s:.1} s; builds: {}",
        times
            .iter()
            .map(|t| format!("{t:.0} ms"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(())
}

//! `--sweep-lights N,N,...`: the light-count benchmark (docs/src/measured/many-lights.md,
//! "Light count: does light selection stay flat?"). For each N it times the generation of
//! `builtin:many-lights:N`, its upload (BVH build, light table) and the per-frame and per-pass
//! times of every configuration. Light selection draws from an alias table, so the cost of
//! selection should not grow with N; the table reports the ratio between the largest and the
//! smallest N. Writes sweep.csv, sweep.md and sweep.png.

use std::fmt::Write;
use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context, bail};
use restir_render::environment::Environment;
use restir_render::{Gpu, Renderer, load_scene};

use crate::bench::plan::Plan;
use crate::bench::plan::args::BenchArgs;
use crate::bench::plan::camera_path::CameraPath;
use crate::bench::run::run_loop::{ConfigRun, RunPlan, run_interleaved};
use crate::bench::run::shot::Shot;
use crate::bench::score::result::ConfigResult;
use crate::bench::score::scoring::Scoring;
use crate::bench::write::info::timing_note;
use crate::bench::write::markdown::{ms, pass_table, ratio, table, time_footnote};
use crate::bench::write::passes::{pass_cells, pass_columns, pass_names};
use crate::bench::write::plots::canvas::{color, render_png, with_footnote};
use crate::bench::write::plots::line_chart::{LineChart, Series, line_chart};
use crate::bench::write::table::{Table, num};

/// Frames per configuration and light count when `--frames` is not given.
const DEFAULT_FRAMES: u32 = 16;

struct SweepRow {
    lights: usize,
    triangles: usize,
    generate_ms: f64,
    upload_ms: f64,
    bvh_build_ms: f64,
    results: Vec<ConfigResult>,
}

fn parse_counts(list: &str) -> anyhow::Result<Vec<usize>> {
    let counts: Vec<usize> = list
        .split(',')
        .map(|s| {
            s.trim()
                .parse::<usize>()
                .with_context(|| format!("--sweep-lights: '{s}' is not a light count"))
        })
        .collect::<Result<_, _>>()?;
    if counts.is_empty() {
        bail!("--sweep-lights: no light count given");
    }
    Ok(counts)
}

pub fn run(args: &BenchArgs, list: &str, plan: &Plan) -> anyhow::Result<()> {
    if !args.scene.starts_with("builtin:many-lights") {
        bail!(
            "--sweep-lights varies the light count of builtin:many-lights; --scene is '{}'",
            args.scene
        );
    }
    let counts = parse_counts(list)?;
    let environment = args.env.load()?;
    let gpu = Gpu::new_headless()?;
    let device = gpu.adapter_name();
    let note = timing_note(gpu.is_cpu());
    let rows = measure(args, plan, &gpu, &counts, &environment)?;
    write(&args.out, plan, &rows, &device, note)
}

/// Every (N, configuration) on its own renderer, all interleaved (see run_loop.rs), so
/// the ratios across N are taken under the same background load.
fn measure(
    args: &BenchArgs,
    plan: &Plan,
    gpu: &Gpu,
    counts: &[usize],
    environment: &Option<Arc<Environment>>,
) -> anyhow::Result<Vec<SweepRow>> {
    let (size, configs) = (plan.size, &plan.configs);
    let mut rows = Vec::new();
    let mut runs = Vec::new();
    let mut run_plan = None;
    for &lights in counts {
        let spec = format!("builtin:many-lights:{lights}");
        let t = Instant::now();
        let mut scene = load_scene(&spec)?;
        scene.environment = environment.clone();
        let generate_ms = t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let renderer = Renderer::new(
            gpu.clone(),
            &scene,
            size.0,
            size.1,
            configs[0].settings.clone(),
        )?;
        let upload_ms = t.elapsed().as_secs_f64() * 1e3;
        eprintln!(
            "{spec}: {} triangles, generated in {generate_ms:.0} ms, uploaded in {upload_ms:.0} ms",
            scene.triangles.len()
        );
        let bvh_build_ms = renderer.scene_info().bvh_build_ms;
        let this_plan = run_plan.get_or_insert_with(|| RunPlan {
            frames: args.frames.unwrap_or(DEFAULT_FRAMES),
            warmup: 0,
            budget: None,
            shot: Shot::of(
                renderer.camera(),
                renderer.scene_bounds().center(),
                CameraPath::Static,
            ),
            seed: args.pipeline.seed,
            effects: plan.effects.clone(),
        });
        let mut renderer = Some(renderer);
        for config in configs {
            let r = match renderer.take() {
                Some(r) => r,
                None => {
                    Renderer::new(gpu.clone(), &scene, size.0, size.1, config.settings.clone())?
                }
            };
            runs.push((
                format!("{lights}/{}", config.name),
                ConfigRun::start(r, config, this_plan, Scoring::Off, None, None)?,
            ));
        }
        rows.push(SweepRow {
            lights,
            triangles: scene.triangles.len(),
            generate_ms,
            upload_ms,
            bvh_build_ms,
            results: Vec::new(),
        });
    }
    let run_plan = run_plan.expect("at least one light count");
    let mut results = run_interleaved(runs, &run_plan)?
        .into_iter()
        .map(|(r, _)| r);
    for row in &mut rows {
        row.results = results.by_ref().take(configs.len()).collect();
    }
    Ok(rows)
}

/// sweep.csv, sweep.md (printed) and sweep.png.
fn write(
    out: &Path,
    plan: &Plan,
    rows: &[SweepRow],
    device: &str,
    note: &str,
) -> anyhow::Result<()> {
    let (size, configs) = (plan.size, &plan.configs);
    write_csv(&out.join("sweep.csv"), rows, device, note)?;
    let md = markdown(rows, size, device, note);
    std::fs::write(out.join("sweep.md"), &md)
        .with_context(|| format!("{}: cannot write", out.display()))?;
    let subtitle = format!("builtin:many-lights:N {}×{} · {note}", size.0, size.1);
    render_png(&out.join("sweep.png"), (1200, 800), |area| {
        area.fill(&plotters::style::WHITE)?;
        let area = with_footnote(area, &subtitle)?;
        let series: Vec<Series> = configs
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let points = rows
                    .iter()
                    .filter_map(|r| Some((r.lights as f64, r.results[i].median_frame_ms()?)))
                    .collect();
                Series::new(c.name.clone(), color(i), points)
            })
            .collect();
        line_chart(
            &area,
            &LineChart {
                title: "Time per frame vs number of lights",
                x_desc: "emissive quads N (log)",
                y_desc: "median time per frame (ms; see note below)",
                log_x: true,
                log_y: false,
                markers_x: &[],
            },
            &series,
        )
    })?;
    println!("{md}");
    eprintln!("wrote {}/sweep.csv, sweep.md, sweep.png", out.display());
    Ok(())
}

fn write_csv(path: &Path, rows: &[SweepRow], device: &str, note: &str) -> anyhow::Result<()> {
    let passes = pass_names(rows.iter().flat_map(|r| &r.results));
    let pass_headers = pass_columns(&passes);
    let mut header = vec![
        "lights",
        "triangles",
        "generate_ms",
        "upload_ms",
        "bvh_build_ms",
        "config",
        "median_frame_ms",
    ];
    header.extend(pass_headers.iter().map(String::as_str));
    header.extend(["device", "timing"]);
    let mut table = Table::new(&header);
    for r in rows {
        for c in &r.results {
            let mut cells = vec![
                r.lights.to_string(),
                r.triangles.to_string(),
                r.generate_ms.to_string(),
                r.upload_ms.to_string(),
                r.bvh_build_ms.to_string(),
                c.config.name.clone(),
                num(c.median_frame_ms()),
            ];
            cells.extend(pass_cells(&passes, c));
            cells.extend([device.to_string(), note.to_string()]);
            table.row(cells);
        }
    }
    table.write(path)
}

fn markdown(rows: &[SweepRow], size: (u32, u32), device: &str, note: &str) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "# Light-count sweep: builtin:many-lights:N at {}×{}\n",
        size.0, size.1
    );
    let _ = writeln!(md, "- Device: **{device}** — {note}.");
    let _ = writeln!(
        md,
        "- Scene load = generating the scene on the CPU; upload = BVH build + light table + GPU buffers.\n"
    );
    let names: Vec<String> = rows
        .first()
        .map(|r| r.results.iter().map(|c| c.config.name.clone()).collect())
        .unwrap_or_default();
    let mut header: Vec<String> = [
        "lights N",
        "triangles",
        "scene load (ms)[^t]",
        "upload (ms)[^t]",
        "BVH build (ms)[^t]",
    ]
    .map(String::from)
    .to_vec();
    for n in &names {
        header.push(format!("`{n}` ms/frame[^t]"));
        header.push(format!("`{n}` initial pass (ms)[^t]"));
    }
    let body: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            let mut row = vec![
                r.lights.to_string(),
                r.triangles.to_string(),
                format!("{:.0}", r.generate_ms),
                format!("{:.0}", r.upload_ms),
                format!("{:.0}", r.bvh_build_ms),
            ];
            for c in &r.results {
                row.push(ms(c.median_frame_ms()));
                row.push(ms(c.times.pass_ms_median.get("initial").copied()));
            }
            row
        })
        .collect();
    table(&mut md, &header, &body);
    growth(&mut md, rows, &names);
    relative_times(&mut md, rows, &names);
    let _ = writeln!(md, "\n## Median time per pass (ms)[^t]\n");
    let labelled: Vec<(String, &ConfigResult)> = rows
        .iter()
        .flat_map(|r| {
            r.results
                .iter()
                .map(move |c| (format!("{} `{}`", r.lights, c.config.name), c))
        })
        .collect();
    pass_table(&mut md, "lights, configuration", &labelled);
    let _ = writeln!(md, "\n{}", time_footnote(note));
    md
}

/// Each configuration's times at the largest N over those at the smallest.
fn growth(md: &mut String, rows: &[SweepRow], names: &[String]) {
    let (Some(first), Some(last)) = (rows.first(), rows.last()) else {
        return;
    };
    let _ = writeln!(
        md,
        "\nGrowth from N = {} to N = {} (ratios of times measured in this run):\n",
        first.lights, last.lights
    );
    for (i, n) in names.iter().enumerate() {
        let grow = |f: &dyn Fn(&ConfigResult) -> Option<f64>| match (
            f(&first.results[i]),
            f(&last.results[i]),
        ) {
            (Some(a), Some(b)) if a > 0.0 => Some(b / a),
            _ => None,
        };
        let frame = grow(&|c| c.median_frame_ms());
        let initial = grow(&|c| c.times.pass_ms_median.get("initial").copied());
        let _ = writeln!(
            md,
            "- `{n}`: time per frame {}, initial (light selection) pass {}",
            ratio(frame),
            ratio(initial)
        );
    }
}

/// Time per frame of every configuration relative to the first, per light count, and the
/// smallest N from which each is faster and stays faster: the break-even of a pair such as
/// `tiles-on,tiles-off`.
fn relative_times(md: &mut String, rows: &[SweepRow], names: &[String]) {
    if names.len() < 2 {
        return;
    }
    let _ = writeln!(
        md,
        "\n## Time per frame relative to `{}` (ratios within this run)\n",
        names[0]
    );
    let ratios: Vec<Vec<Option<f64>>> = rows
        .iter()
        .map(|r| {
            let base = r.results[0].median_frame_ms();
            r.results[1..]
                .iter()
                .map(|c| match (c.median_frame_ms(), base) {
                    (Some(t), Some(b)) if b > 0.0 => Some(t / b),
                    _ => None,
                })
                .collect()
        })
        .collect();
    let mut header = vec!["lights N".to_string()];
    header.extend(names[1..].iter().map(|n| format!("`{n}` / `{}`", names[0])));
    let body: Vec<Vec<String>> = rows
        .iter()
        .zip(&ratios)
        .map(|(r, q)| {
            let mut row = vec![r.lights.to_string()];
            row.extend(q.iter().map(|x| ratio(*x)));
            row
        })
        .collect();
    table(md, &header, &body);
    for (i, n) in names[1..].iter().enumerate() {
        // The first N from which one side is faster at every larger N too.
        let from = |wins: &dyn Fn(f64) -> bool| {
            (0..rows.len()).find(|&k| ratios[k..].iter().all(|q| q[i].is_some_and(wins)))
        };
        let first = &names[0];
        let line = match (from(&|x| x < 1.0), from(&|x| x > 1.0)) {
            (Some(k), _) => format!(
                "- `{n}` is faster than `{first}` from N = {} on",
                rows[k].lights
            ),
            (_, Some(k)) => format!(
                "- `{first}` is faster than `{n}` from N = {} on",
                rows[k].lights
            ),
            _ => format!("- neither `{n}` nor `{first}` is faster at the largest N measured"),
        };
        let _ = writeln!(md, "{line}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_sweep_counts_parse() {
        assert_eq!(parse_counts("1024, 65536").unwrap(), vec![1024, 65536]);
        assert!(parse_counts("12k").is_err());
    }
}

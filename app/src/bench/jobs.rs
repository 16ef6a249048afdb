//! A bench as independent jobs (docs/src/headless.md, "Sweeps as independent jobs"):
//! `--list-jobs` prints one `bench` command per configuration, each writing its own folder
//! under `OUT/jobs/`, and `--merge` (the same command line otherwise) gathers their
//! `figures.json` into the output folder's `figures.md` and `figures.csv`. The figures hold no time or
//! path, so the merged table is the one a single process writes; times from separate jobs
//! are not comparable (each ran under its own load), which is why the merge leaves them out.

use std::fmt::Write;
use std::path::{Path, PathBuf};

use anyhow::bail;

use super::configs::Config;
use super::csv::Table;
use super::seed_figures::{self, FIGURES_FILE, FigureRow};

/// The folder of configuration `name`'s job under `out`.
pub fn job_dir(out: &Path, name: &str) -> PathBuf {
    out.join("jobs").join(slug(name))
}

/// This process's `bench` arguments with `--list-jobs` left out and `--configs` and `--out`
/// replaced: one job's command line.
pub fn job_argv(args: &[String], config: &str, out: &Path) -> Vec<String> {
    let mut kept = Vec::new();
    let mut skip_value = false;
    for a in args {
        if skip_value {
            skip_value = false;
            continue;
        }
        match a.as_str() {
            "--list-jobs" | "--merge" => {}
            // A job runs one configuration, a `--knob` point already named in it.
            "--configs" | "--out" | "--knob" => skip_value = true,
            _ if a.starts_with("--configs=")
                || a.starts_with("--out=")
                || a.starts_with("--knob=") => {}
            _ => kept.push(a.clone()),
        }
    }
    kept.extend([
        "--configs".to_string(),
        config.to_string(),
        "--out".to_string(),
        job_dir(out, config).to_string_lossy().into_owned(),
    ]);
    kept
}

/// Prints one command per configuration.
pub fn list(configs: &[Config], out: &Path) -> anyhow::Result<()> {
    let exe = std::env::current_exe()?;
    // The arguments after `bench`.
    let argv: Vec<String> = std::env::args()
        .skip_while(|a| a != "bench")
        .skip(1)
        .collect();
    for c in configs {
        let job = job_argv(&argv, &c.name, out);
        println!("{}", shell_line(&exe.to_string_lossy(), &job));
    }
    Ok(())
}

/// Gathers the jobs' figures into `figures.md` and `figures.csv` under `out`.
pub fn merge(configs: &[Config], out: &Path) -> anyhow::Result<()> {
    let mut rows: Vec<FigureRow> = Vec::new();
    let mut missing = Vec::new();
    for c in configs {
        let path = job_dir(out, &c.name).join(FIGURES_FILE);
        if !path.is_file() {
            missing.push(c.name.clone());
            continue;
        }
        let found = seed_figures::read_rows(&path)?;
        rows.extend(found.into_iter().filter(|r| r.config == c.name));
    }
    if !missing.is_empty() {
        bail!(
            "no figures yet for {} under {}",
            missing.join(", "),
            out.join("jobs").display()
        );
    }
    let mut md = String::new();
    if let Some(first) = rows.first() {
        let _ = writeln!(
            md,
            "# Bench jobs merged: {}, {}×{}, {} camera, {} seeds × {} frames\n",
            first.scene,
            first.size.0,
            first.size.1,
            first.camera,
            first.figures.seeds,
            first.figures.frames
        );
    }
    let named: Vec<(&str, &seed_figures::SeedFigures)> = rows
        .iter()
        .map(|r| (r.config.as_str(), &r.figures))
        .collect();
    super::markdown::seed_figures_table(&mut md, &named);
    std::fs::write(out.join("figures.md"), &md)?;
    let mut csv_header = vec!["config"];
    csv_header.extend(seed_figures::CSV_COLUMNS);
    let mut csv = Table::new(&csv_header);
    for r in &rows {
        let mut cells = vec![r.config.clone()];
        cells.extend(seed_figures::csv_cells(Some(&r.figures)));
        csv.row(cells);
    }
    csv.write(&out.join("figures.csv"))?;
    println!("{md}");
    Ok(())
}

/// Letters, digits, `-`, `.` and `_` kept, anything else `_`.
pub fn slug(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '-' | '.' | '_') {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// A command line a POSIX shell reads back as `program` and `args`.
pub fn shell_line(program: &str, args: &[String]) -> String {
    let quote = |s: &str| {
        if !s.is_empty()
            && s.chars()
                .all(|c| c.is_ascii_alphanumeric() || "-_./:=@+,".contains(c))
        {
            s.to_string()
        } else {
            format!("'{}'", s.replace('\'', r"'\''"))
        }
    };
    std::iter::once(quote(program))
        .chain(std::iter::once("bench".to_string()))
        .chain(args.iter().map(|a| quote(a)))
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_job_keeps_every_argument_but_its_configs_and_out() {
        let args: Vec<String> = [
            "--scene",
            "builtin:cornell",
            "--configs",
            "ris,nee",
            "--list-jobs",
            "--out=x",
            "--seeds",
            "4",
        ]
        .map(String::from)
        .to_vec();
        let job = job_argv(&args, "ris+denoise", Path::new("o"));
        assert_eq!(
            job.join(" "),
            "--scene builtin:cornell --seeds 4 --configs ris+denoise --out o/jobs/ris_denoise"
        );
    }
}

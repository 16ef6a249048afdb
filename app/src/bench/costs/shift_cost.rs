//! `bench-shifts`: the path shifts of ReSTIR PT (docs/src/restir-pt.md, "The CPU model") on
//! the CPU toy scene of
//! `restir_render::pt::model`: for each place and shift, the mean of one pairwise spatial
//! step against the place's path-traced reference, its standard error (and variance
//! against reconnection's), and how the neighbours' paths fared when shifted (moved, moved
//! but carrying under 1 % of their target, or why not) with their mean |log2 |J||. A Markdown table; `--csv` writes the rows.

use std::path::PathBuf;

use clap::Args;
use restir_render::pt::model::experiment::{
    HYBRID, PLACES, Trials, glossy_scene, pixel, reference, spatial_trials,
};
use restir_render::pt::model::pairwise::Planted;
use restir_render::pt::model::shift::Shift;

#[derive(Args, Debug)]
pub struct ShiftCostArgs {
    /// Independent spatial steps per place and shift.
    #[arg(long, default_value_t = 20_000)]
    pub trials: usize,
    /// Paths of each place's reference.
    #[arg(long, default_value_t = 8_000_000)]
    pub reference_paths: usize,
    /// Also write the rows as CSV here.
    #[arg(long, value_name = "FILE.csv")]
    pub csv: Option<PathBuf>,
}

const SHIFTS: [(&str, Shift); 3] = [
    ("reconnection", Shift::Reconnection),
    ("random replay", Shift::RandomReplay),
    ("hybrid", HYBRID),
];

pub fn run(args: ShiftCostArgs) -> anyhow::Result<()> {
    anyhow::ensure!(args.trials >= 2, "--trials must be at least 2");
    anyhow::ensure!(
        args.reference_paths >= 2,
        "--reference-paths must be at least 2"
    );
    let scene = glossy_scene();
    let mut md = String::from(
        "| place | shift | mean ± SE | reference | z | variance × reconnection | moved | of those useless | replay left | undefined | occluded | reconnects elsewhere | mean \\|log2 J\\| |\n\
         | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n",
    );
    let mut csv = String::from(
        "place,shift,mean,se,reference,reference_se,moved,moved_useless,replay_left,undefined,occluded,elsewhere,mean_abs_log2_j\n",
    );
    for (p, place) in PLACES.iter().enumerate() {
        let (truth, truth_se) = reference(&scene, &pixel(place.at), args.reference_paths);
        let mut reconnection_var = None;
        for (s, (name, shift)) in SHIFTS.iter().enumerate() {
            let seed = 1 + (p * SHIFTS.len() + s) as u64;
            let t = spatial_trials(&scene, place, *shift, Planted::None, args.trials, seed);
            let var = t.se * t.se;
            let ratio = var / *reconnection_var.get_or_insert(var);
            md.push_str(&row_md(place.name, name, &t, truth, truth_se, ratio));
            csv.push_str(&row_csv(place.name, name, &t, truth, truth_se));
            eprintln!("{} / {name}: done", place.name);
        }
    }
    println!(
        "Path shifts on the CPU toy scene (render/src/pt/model): one pairwise spatial step, \
         4 neighbours, {} trials each; references {} paths.\n\n{md}",
        args.trials, args.reference_paths
    );
    if let Some(path) = &args.csv {
        std::fs::write(path, csv)?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

fn share(n: u64, total: u64) -> String {
    format!("{:.1} %", 100.0 * n as f64 / total.max(1) as f64)
}

fn row_md(
    place: &str,
    shift: &str,
    t: &Trials,
    truth: f64,
    truth_se: f64,
    var_ratio: f64,
) -> String {
    let o = &t.outcomes;
    let total = o.total();
    let z = (t.mean - truth) / (t.se * t.se + truth_se * truth_se).sqrt();
    format!(
        "| {place} | {shift} | {:.5} ± {:.5} | {truth:.5} ± {truth_se:.5} | {z:.2} | {var_ratio:.2} | {} | {} | {} | {} | {} | {} | {:.3} |\n",
        t.mean,
        t.se,
        share(o.moved, total),
        share(o.moved_useless, o.moved),
        share(o.replay_left, total),
        share(o.undefined, total),
        share(o.occluded, total),
        share(o.elsewhere, total),
        o.abs_log2_jacobian / o.moved.max(1) as f64,
    )
}

fn row_csv(place: &str, shift: &str, t: &Trials, truth: f64, truth_se: f64) -> String {
    let o = &t.outcomes;
    format!(
        "\"{place}\",{shift},{:.6},{:.6},{truth:.6},{truth_se:.6},{},{},{},{},{},{},{:.4}\n",
        t.mean,
        t.se,
        o.moved,
        o.moved_useless,
        o.replay_left,
        o.undefined,
        o.occluded,
        o.elsewhere,
        o.abs_log2_jacobian / o.moved.max(1) as f64,
    )
}

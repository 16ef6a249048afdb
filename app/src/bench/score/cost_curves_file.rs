//! A `cost_curves.csv` read back (write/cost_curves.rs writes it): the knob it swept and
//! each configuration's curve, its points in file order (the `--knob` order), as measured.
//! `bench-map` reads the cells' files through it (map.rs smooths their times first), and
//! `bench-plot` redraws `cost_curves.png` from it.

use std::path::Path;

use anyhow::Context;

use super::csv_read::records;
use super::equal_error::CostPoint;

/// A curve: the configuration's name without the knob, and its points.
pub type NamedCurve = (String, Vec<CostPoint>);

/// The knob's name (the second column's heading) and the curves of the file at `path`.
pub fn read(path: &Path) -> anyhow::Result<(String, Vec<NamedCurve>)> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("{}: cannot read", path.display()))?;
    parse(&text).with_context(|| path.display().to_string())
}

/// `read` from the file's text.
pub fn parse(text: &str) -> anyhow::Result<(String, Vec<NamedCurve>)> {
    let mut rows = records(text).into_iter();
    let header = rows.next().context("no header")?;
    let knob = header.get(1).context("no knob column")?.clone();
    let mut curves: Vec<NamedCurve> = Vec::new();
    for f in rows.filter(|r| r.iter().any(|c| !c.trim().is_empty())) {
        anyhow::ensure!(
            f.len() >= 7,
            "a row with {} fields: {}",
            f.len(),
            f.join(",")
        );
        let num = |i: usize| f[i].trim().parse::<f64>().unwrap_or(f64::NAN);
        // The eighth column, each seed's median frame time, came later.
        let seed_ms = f
            .get(7)
            .map(|cell| {
                cell.split(';')
                    .filter(|x| !x.trim().is_empty())
                    .map(|x| x.trim().parse::<f64>().unwrap_or(f64::NAN))
                    .collect()
            })
            .unwrap_or_default();
        let point = CostPoint {
            knob: f[1].clone(),
            ms: num(2),
            seed_ms,
            rays_per_pixel: num(3),
            candidates_per_pixel: num(4),
            rmse: num(5),
            rmse_ci95: num(6),
        };
        match curves.iter_mut().find(|(c, _)| *c == f[0]) {
            Some((_, points)) => points.push(point),
            None => curves.push((f[0].clone(), vec![point])),
        }
    }
    Ok((knob, curves))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cost_curves_csv_reads_back_with_quoted_names_and_seed_times() {
        let text = "config,light_candidates,median_frame_ms,shadow_rays_per_pixel,\
                    light_candidates_per_pixel,frame_luma_rmse_without_reference_noise,\
                    frame_luma_rmse_ci95,seed_median_frame_ms\n\
                    \"ris[preset=a,b]\",8,100,2,8,0.02,0.001,99;101\n\
                    \"ris[preset=a,b]\",16,120,2,16,0.015,0.001,119;121\n\
                    restir,8,90,2,8,0.01,\n";
        let (knob, curves) = parse(text).unwrap();
        assert_eq!(knob, "light_candidates");
        assert_eq!(curves.len(), 2);
        // The quoted comma stays in the name: a split on commas made "\"ris[preset=a" a
        // curve and every later column one to the right.
        assert_eq!(curves[0].0, "ris[preset=a,b]");
        let p = &curves[0].1[1];
        assert_eq!((p.knob.as_str(), p.ms, p.rmse), ("16", 120.0, 0.015));
        assert_eq!(p.seed_ms, vec![119.0, 121.0]);
        // An older file without the seeds' column, and one seed's interval (none: empty).
        assert!(curves[1].1[0].seed_ms.is_empty());
        assert!(curves[1].1[0].rmse_ci95.is_nan());
    }
}

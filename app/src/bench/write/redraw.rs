//! `bench-plot DIR`: the pictures of committed bench folders redrawn from their tables,
//! without rerunning anything: every `cost_curves.png` under DIR from the `cost_curves.csv`
//! beside it (cost_curves_plot.rs), every `map.png` from the `map.csv` beside it
//! (map_png.rs). Nothing else is written: the tables stay as the runs left them.

use std::path::{Path, PathBuf};

use anyhow::Context;

use super::{cost_curves_plot, map_png};

/// Every folder at or under `dir`, in name order, `dir` first.
fn folders(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut found = vec![dir.to_path_buf()];
    let mut inner: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("{}: cannot read", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_dir())
        .collect();
    inner.sort();
    for d in inner {
        found.extend(folders(&d)?);
    }
    Ok(found)
}

/// Redraws the pictures under `dir`; returns the files written.
pub fn redraw(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    for d in folders(dir)? {
        if d.join("cost_curves.csv").is_file() {
            cost_curves_plot::redraw(&d)?;
            written.push(d.join("cost_curves.png"));
        }
        if d.join("map.csv").is_file() {
            map_png::write(&d)?;
            if d.join("map.png").is_file() {
                written.push(d.join("map.png"));
            }
        }
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_plot_redraws_every_picture_under_a_folder_and_nothing_else() {
        let dir = std::env::temp_dir().join(format!("restir-redraw-{}", std::process::id()));
        let cell = dir.join("maps/concourse-static");
        std::fs::create_dir_all(&cell).unwrap();
        let curves = "config,light_candidates,median_frame_ms,shadow_rays_per_pixel,\
                      light_candidates_per_pixel,frame_luma_rmse_without_reference_noise,\
                      frame_luma_rmse_ci95,seed_median_frame_ms\n\
                      ris,8,100,2,8,0.02,0.001,99;101\nris,16,120,2,16,0.015,0.001,119;121\n";
        std::fs::write(cell.join("cost_curves.csv"), curves).unwrap();
        let map = "folder,scene,size,camera,config,ms_vs_baseline_at_best,reach_at_best\n\
                   concourse-static,builtin:concourse,384×256,static,ris,1,interpolated\n\
                   concourse-static,builtin:concourse,384×256,static,restir,0.8,at_most\n";
        std::fs::write(dir.join("maps/map.csv"), map).unwrap();
        let before: Vec<u8> = std::fs::read(dir.join("maps/map.csv")).unwrap();
        let written = redraw(&dir).unwrap();
        assert_eq!(
            written,
            vec![dir.join("maps/map.png"), cell.join("cost_curves.png")]
        );
        for png in &written {
            assert!(image::open(png).is_ok(), "{}", png.display());
        }
        assert_eq!(std::fs::read(dir.join("maps/map.csv")).unwrap(), before);
        assert!(!dir.join("maps/command.txt").exists());
        std::fs::remove_dir_all(&dir).ok();
    }
}

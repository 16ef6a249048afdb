//! `strip.png` (still camera): the last frame of every configuration beside the reference,
//! each labelled with its mean per-frame error — the picture README opens with. Every
//! panel is tonemapped the same way (one exposure, from the reference), so brightness
//! differences are real and noise is seen as it is.

use std::path::Path;

use plotters::prelude::*;
use restir_render::LinearImage;
use restir_render::view::auto_exposure_ev;

use super::plots::canvas::{DrawResult, render_png, text};
use crate::bench::run::reference_sets::ReferenceSets;
use crate::bench::score::result::ConfigResult;

/// Height of the label band under each panel, in pixels.
const LABEL_HEIGHT: u32 = 34;
/// Panels are enlarged by a whole factor (nearest neighbour) to at least this height, so
/// a 180-pixel frame shows its noise pixel by pixel instead of being smoothed away.
const MIN_PANEL_HEIGHT: u32 = 360;

/// One panel: a label and a linear image.
pub struct Panel<'a> {
    pub label: String,
    pub image: &'a LinearImage,
}

/// Writes the panels side by side, left to right, to `path`.
pub fn write(path: &Path, panels: &[Panel]) -> anyhow::Result<()> {
    let Some(last) = panels.last() else {
        anyhow::bail!("{}: no image for the strip", path.display());
    };
    // The exposure of the last panel (the reference): the same for all.
    write_grid(path, &[panels], 2f32.powf(auto_exposure_ev(last.image)))
}

/// Writes rows of panels (each row left to right, rows top to bottom) to `path`, every
/// panel at the linear `exposure`.
pub fn write_grid(path: &Path, rows: &[&[Panel]], exposure: f32) -> anyhow::Result<()> {
    write_grid_with(path, rows, &|rgb| display_srgb8(rgb, exposure))
}

/// Writes rows of panels whose images already hold display-ready sRGB values in [0, 1]
/// (maps and heatmaps, not radiance) to `path`.
pub fn write_display_grid(path: &Path, rows: &[&[Panel]]) -> anyhow::Result<()> {
    write_grid_with(path, rows, &|rgb| {
        rgb.map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8)
    })
}

/// Writes rows of panels, each pixel's colour from `color`.
fn write_grid_with(
    path: &Path,
    rows: &[&[Panel]],
    color: &dyn Fn([f32; 3]) -> [u8; 3],
) -> anyhow::Result<()> {
    let Some(first) = rows.iter().flat_map(|r| r.iter()).next() else {
        anyhow::bail!("{}: no image for the strip", path.display());
    };
    let (w, h) = (first.image.width, first.image.height);
    anyhow::ensure!(
        rows.iter()
            .flat_map(|r| r.iter())
            .all(|p| (p.image.width, p.image.height) == (w, h)),
        "{}: strip panels differ in size",
        path.display()
    );
    let zoom = MIN_PANEL_HEIGHT.div_ceil(h.max(1)).max(1);
    let (pw, ph) = (w * zoom, h * zoom);
    let columns = rows.iter().map(|r| r.len()).max().unwrap_or(0) as u32;
    let row_height = ph + LABEL_HEIGHT;
    let size = (pw * columns, row_height * rows.len() as u32);
    render_png(path, size, |area| {
        area.fill(&BLACK)?;
        for (j, row) in rows.iter().enumerate() {
            let y0 = j as u32 * row_height;
            for (i, panel) in row.iter().enumerate() {
                draw_panel(area, panel, color, (i as u32 * pw, y0, zoom))?;
                let label = Text::new(
                    panel.label.clone(),
                    ((i as u32 * pw + 8) as i32, (y0 + ph + 6) as i32),
                    text(22).color(&WHITE),
                );
                area.draw(&label)?;
            }
        }
        Ok(())
    })
}

fn draw_panel(
    area: &super::plots::canvas::Area,
    panel: &Panel,
    color: &dyn Fn([f32; 3]) -> [u8; 3],
    (x0, y0, zoom): (u32, u32, u32),
) -> DrawResult {
    let img = panel.image;
    for y in 0..img.height {
        for x in 0..img.width {
            let [r, g, b] = color(img.rgb(x, y));
            let (px, py) = ((x0 + x * zoom) as i32, (y0 + y * zoom) as i32);
            let z = zoom as i32;
            area.draw(&Rectangle::new(
                [(px, py), (px + z, py + z)],
                RGBColor(r, g, b).filled(),
            ))?;
        }
    }
    Ok(())
}

/// The display pass's final view for one pixel: exposure, ACES (Narkowicz 2015), sRGB
/// encoding — the same formulas as shaders/display.wgsl, so the strip looks like the viewer.
pub fn display_srgb8(rgb: [f32; 3], exposure: f32) -> [u8; 3] {
    let aces = |x: f32| {
        let x = (x * exposure).max(0.0);
        ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0)
    };
    let srgb = |c: f32| {
        if c <= 0.003_130_8 {
            c * 12.92
        } else {
            1.055 * c.powf(1.0 / 2.4) - 0.055
        }
    };
    rgb.map(|c| {
        let v = if c.is_finite() { aces(c) } else { 0.0 };
        (srgb(v) * 255.0).round() as u8
    })
}

/// The strip's panel of each configuration: its run's last frame (seed S's, run/seeds.rs),
/// labelled with that run's error. The renderers hold the last seed's frames once every
/// seed ran; labelled with seed S's error, those panels showed one run and named another.
pub fn config_panels(results: &[ConfigResult]) -> Vec<Panel<'_>> {
    results
        .iter()
        .filter_map(|r| {
            Some(Panel {
                label: match &r.scores {
                    Some(s) => format!("{} · RMSE {:.3}", r.config.name, s.mean_luma_rmse),
                    None => r.config.name.clone(),
                },
                image: r.last_frame.as_ref()?,
            })
        })
        .collect()
}

/// `strip.png`: each configuration's last frame, then the reference (one per bounce count).
pub fn write_last_frames(
    out: &Path,
    results: &[ConfigResult],
    sets: &ReferenceSets,
) -> anyhow::Result<()> {
    let mut panels = config_panels(results);
    anyhow::ensure!(
        panels.len() == results.len(),
        "strip.png: a configuration's last frame was not kept"
    );
    for (bounces, refs) in sets.bounces() {
        let label = match bounces {
            1 => format!("reference · {} spp", refs.spp),
            n => format!("reference · {n} bounces · {} spp", refs.spp),
        };
        panels.push(Panel {
            label,
            image: &refs.images[0],
        });
    }
    write(&out.join("strip.png"), &panels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_strip_tonemap_matches_the_display_pass() {
        // ACES(1) = 2.54 / 3.16 = 0.8038 → sRGB 0.9106 → 232.
        assert_eq!(display_srgb8([1.0, 0.0, f32::NAN], 1.0), [232, 0, 0]);
        assert_eq!(display_srgb8([1e9, -1.0, 0.5], 1.0)[..2], [255, 0]);
    }

    #[test]
    fn the_strip_has_one_panel_per_image_and_a_label_band() {
        let a = LinearImage::from_fn(4, 3, |x, _| [x as f32, 0.5, 0.25, 1.0]);
        let path = std::env::temp_dir().join(format!("restir-strip-{}.png", std::process::id()));
        let panels = [
            Panel {
                label: "a".into(),
                image: &a,
            },
            Panel {
                label: "b".into(),
                image: &a,
            },
        ];
        write(&path, &panels).unwrap();
        let png = image::open(&path).unwrap();
        let zoom = MIN_PANEL_HEIGHT.div_ceil(3);
        assert_eq!(
            (png.width(), png.height()),
            (2 * 4 * zoom, 3 * zoom + LABEL_HEIGHT)
        );
        let bad = LinearImage::new(2, 2);
        let mixed = [
            Panel {
                label: "x".into(),
                image: &bad,
            },
            Panel {
                label: "a".into(),
                image: &a,
            },
        ];
        assert!(write(&path, &mixed).is_err());
    }

    #[test]
    fn each_strip_panel_shows_the_run_its_label_names() {
        use crate::bench::score::result::planted;
        // Seed S's run: its error and its own last frame.
        let first = LinearImage::from_fn(2, 2, |_, _| [1.0, 1.0, 1.0, 1.0]);
        let mut seed_s = planted("ris", 0.125);
        seed_s.last_frame = Some(first.clone());
        let results = [seed_s];
        let panels = config_panels(&results);
        assert_eq!(panels[0].label, "ris · RMSE 0.125");
        assert_eq!(panels[0].image.pixels, first.pixels);
        // A result without a kept frame has no panel (write_last_frames refuses it).
        assert!(config_panels(&[planted("ris", 0.1)]).is_empty());
    }
}

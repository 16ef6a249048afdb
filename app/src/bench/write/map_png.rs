//! `map.png`: the crossover map as one figure (docs/src/measured/denoiser.md, "The crossover
//! map at 384×256"), drawn from the folder's `map.csv` so the picture shows the table's
//! numbers and nothing else. Scenes are rows, still and panning columns; inside a cell one
//! band per configuration that is not the baseline, coloured by its cost ratio on a
//! diverging scale centred on 1× (map_colours.rs) and labelled with the ratio, its interval
//! over the seeds and its bound (`≤`: already below the baseline's best error at its
//! cheapest point; `≥`: not reached within the sweep). Every configuration rather than the
//! cheapest alone: a map folder holds one to three of them, and the chapter reads the
//! default ReSTIR's losses beside the preset's gains, which the cheapest would hide.

use std::path::Path;

use anyhow::Context;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::map_colours::{colour_bar, ratio_colour, text_on};
use super::map_rows::{MapRow, read_rows};
use super::plots::canvas::{Area, DrawResult, TEXT_SIZE, TITLE_SIZE, render_png, text};

const WIDTH: u32 = 1200;
const BAND: u32 = 58;
const HEADER: u32 = 96;
const COLUMN_HEAD: u32 = 40;
const FOOT: u32 = 150;
/// Pixels per character of a row label, roughly (the font is proportional), and the least
/// width of a label column.
const SCENE_CHAR: u32 = 11;
const BAND_CHAR: u32 = 10;
const LABEL_MIN: u32 = 120;

/// The figure's grid: the row labels (scene, with its size where the folder has several),
/// the column labels (cameras, still first), the bands (configurations) and the cell of
/// each (row, column, band).
pub struct Grid<'a> {
    pub rows: Vec<String>,
    pub columns: Vec<String>,
    pub bands: Vec<String>,
    /// Whether the bands are configurations' bare names (each cell ran its own settings).
    pub bare: bool,
    pub cells: Vec<(usize, usize, usize, &'a MapRow)>,
}

/// `ris+denoise[denoise_iterations=2]` → `ris+denoise`.
fn bare(config: &str) -> &str {
    config.split('[').next().unwrap_or(config)
}

/// A scene as a row label: `builtin:` left out.
fn scene_label(row: &MapRow, sizes: usize) -> String {
    let scene = row.scene.strip_prefix("builtin:").unwrap_or(&row.scene);
    if sizes > 1 {
        format!("{scene} {}", row.size)
    } else {
        scene.to_string()
    }
}

/// "still" for a still camera, else the camera as map.csv names it.
fn camera_label(camera: &str) -> String {
    if camera == "static" {
        "still".into()
    } else {
        format!("panning ({camera})")
    }
}

/// The grid of `rows`: the first configuration of each cell (folder) is its baseline and
/// gets no band.
pub fn grid(rows: &[MapRow]) -> Grid<'_> {
    let mut sizes: Vec<&str> = rows.iter().map(|r| r.size.as_str()).collect();
    sizes.sort_unstable();
    sizes.dedup();
    let mut folders: Vec<&str> = rows.iter().map(|r| r.folder.as_str()).collect();
    folders.dedup();
    let challengers: Vec<&MapRow> = rows
        .iter()
        .enumerate()
        .filter(|(i, r)| *i > 0 && rows[i - 1].folder == r.folder)
        .map(|(_, r)| r)
        .collect();
    let names = |f: &str| -> Vec<&str> {
        challengers
            .iter()
            .filter(|r| r.folder == f)
            .map(|r| r.config.as_str())
            .collect()
    };
    // Cells that ran the same configurations with other settings share bands by bare name.
    let bare_names = folders.iter().any(|f| names(f) != names(folders[0]));
    let band_of = |r: &MapRow| -> String {
        if bare_names {
            bare(&r.config).to_string()
        } else {
            r.config.clone()
        }
    };
    let mut g = Grid {
        rows: Vec::new(),
        columns: Vec::new(),
        bands: Vec::new(),
        bare: bare_names,
        cells: Vec::new(),
    };
    let mut cameras: Vec<&str> = rows.iter().map(|r| r.camera.as_str()).collect();
    cameras.sort_by_key(|c| *c != "static");
    cameras.dedup();
    g.columns = cameras.iter().map(|c| camera_label(c)).collect();
    for r in challengers {
        let place = |list: &mut Vec<String>, key: String| match list.iter().position(|k| *k == key)
        {
            Some(i) => i,
            None => {
                list.push(key);
                list.len() - 1
            }
        };
        let row = place(&mut g.rows, scene_label(r, sizes.len()));
        let band = place(&mut g.bands, band_of(r));
        let column = cameras.iter().position(|c| *c == r.camera).unwrap_or(0);
        g.cells.push((row, column, band, r));
    }
    g
}

/// "0.44× [0.41–0.46]", "≤ 0.44×", "≥ 1.07×": the ratio as map.md states it, the bound as
/// a reader reads it.
pub fn cell_text(r: &MapRow) -> String {
    let Some(x) = r.ratio else {
        return "—".into();
    };
    let bound = match r.reach.as_str() {
        "at_most" => "≤ ",
        "beyond" => "≥ ",
        _ => "",
    };
    let interval = match (r.seed_mean, r.seed_ci95) {
        (Some(m), Some(h)) if h > 0.0 && h.is_finite() => {
            format!(" [{:.2}–{:.2}]", m - h, m + h)
        }
        _ => String::new(),
    };
    format!("{bound}{x:.2}×{interval}")
}

/// The settings in a configuration's brackets, for a band named by its bare name.
fn settings(config: &str) -> Option<&str> {
    let inner = config.split_once('[')?.1.trim_end_matches(']');
    (!inner.is_empty()).then_some(inner)
}

/// The title: what the colour is, then the folder, its size(s), its seeds (from the cells'
/// figures.json, where they are there), what is compared and the baseline (by bare name
/// where the bands are).
fn title(dir: &Path, rows: &[MapRow], g: &Grid) -> String {
    let mut seeds: Vec<u64> = Vec::new();
    let mut sizes: Vec<&str> = Vec::new();
    let mut baselines: Vec<&str> = Vec::new();
    for (i, r) in rows.iter().enumerate() {
        sizes.push(&r.size);
        if i == 0 || rows[i - 1].folder != r.folder {
            baselines.push(if g.bare { bare(&r.config) } else { &r.config });
            let figures = std::fs::read_to_string(dir.join(&r.folder).join("figures.json"));
            let json: Option<serde_json::Value> =
                figures.ok().and_then(|t| serde_json::from_str(&t).ok());
            if let Some(n) = json
                .as_ref()
                .and_then(|j| j[0]["figures"]["seeds"].as_u64())
            {
                seeds.push(n);
            }
        }
    }
    for list in [&mut sizes, &mut baselines] {
        list.sort_unstable();
        list.dedup();
    }
    seeds.sort_unstable();
    seeds.dedup();
    let seeds = match seeds.as_slice() {
        [] => String::new(),
        [one] => format!(" · {one} seeds"),
        [lo, .., hi] => format!(" · {lo}–{hi} seeds"),
    };
    let name = dir
        .canonicalize()
        .ok()
        .and_then(|d| d.file_name().map(|f| f.to_string_lossy().into_owned()))
        .unwrap_or_else(|| dir.display().to_string());
    let cells = rows
        .iter()
        .enumerate()
        .filter(|(i, r)| *i == 0 || rows[i - 1].folder != r.folder)
        .count();
    let compared = match g.bands.as_slice() {
        [one] => one.clone(),
        many => format!("{} configurations", many.len()),
    };
    let cells = match cells {
        1 => "1 cell".to_string(),
        n => format!("{n} cells"),
    };
    format!(
        "Time to reach the baseline's best error, ÷ the baseline's\n{name} · {} · {cells}\
         {seeds} · {compared} against {}",
        sizes.join(", "),
        baselines.join(", ")
    )
}

/// Writes `dir`'s `map.png` from its `map.csv`.
pub fn write(dir: &Path) -> anyhow::Result<()> {
    let rows = read_rows(&dir.join("map.csv"))?;
    let g = grid(&rows);
    let title = title(dir, &rows, &g);
    if g.cells.is_empty() {
        eprintln!(
            "{}: no configuration besides the baseline, no map.png",
            dir.display()
        );
        return Ok(());
    }
    let height = HEADER + COLUMN_HEAD + (g.rows.len() * g.bands.len()) as u32 * BAND + FOOT;
    let path = dir.join("map.png");
    render_png(&path, (WIDTH, height), |area| draw(area, &title, &g))
        .with_context(|| format!("{}: cannot draw", path.display()))
}

/// The width of a label column holding `labels` at `per_char` pixels a character.
fn label_width<'a>(labels: impl Iterator<Item = &'a String>, per_char: u32) -> u32 {
    let chars = labels.map(|l| l.chars().count() as u32).max().unwrap_or(0);
    (chars * per_char + 24).max(LABEL_MIN)
}

/// The widths of the scene labels and of the band labels (none with one band), the left
/// edge of the cells and a cell's width.
fn columns_of(g: &Grid) -> (u32, u32, u32, u32) {
    let scenes = 16 + label_width(g.rows.iter(), SCENE_CHAR);
    let bands = if g.bands.len() > 1 {
        label_width(g.bands.iter(), BAND_CHAR)
    } else {
        0
    };
    let left = (scenes + bands).min(WIDTH / 2);
    (
        scenes,
        bands,
        left,
        (WIDTH - left - 16) / g.columns.len().max(1) as u32,
    )
}

/// The top left corner of the band of (row, column, band).
pub fn band_origin(g: &Grid, (r, c, b): (usize, usize, usize)) -> (i32, i32) {
    let (_, _, left, cell_w) = columns_of(g);
    let row_h = g.bands.len() as u32 * BAND;
    (
        (left + c as u32 * cell_w) as i32,
        (HEADER + COLUMN_HEAD + r as u32 * row_h + b as u32 * BAND) as i32,
    )
}

fn draw(area: &Area, title: &str, g: &Grid) -> DrawResult {
    area.fill(&WHITE)?;
    let centred = |size: u32| text(size).pos(Pos::new(HPos::Center, VPos::Center));
    let (t1, t2) = title.split_once('\n').unwrap_or((title, ""));
    area.draw(&Text::new(
        t1.to_string(),
        (WIDTH as i32 / 2, 28),
        centred(TITLE_SIZE),
    ))?;
    area.draw(&Text::new(
        t2.to_string(),
        (WIDTH as i32 / 2, 66),
        centred(TEXT_SIZE),
    ))?;
    let (scenes, _, left, cell_w) = columns_of(g);
    let top = HEADER + COLUMN_HEAD;
    for (c, label) in g.columns.iter().enumerate() {
        let x = left + c as u32 * cell_w + cell_w / 2;
        area.draw(&Text::new(
            label.clone(),
            (x as i32, (HEADER + 18) as i32),
            centred(TEXT_SIZE),
        ))?;
    }
    let row_h = g.bands.len() as u32 * BAND;
    let left_text = |size: u32| text(size).pos(Pos::new(HPos::Left, VPos::Center));
    for (r, label) in g.rows.iter().enumerate() {
        let y = top + r as u32 * row_h;
        area.draw(&Text::new(
            label.clone(),
            (16, (y + row_h / 2) as i32),
            left_text(TEXT_SIZE),
        ))?;
        if g.bands.len() > 1 {
            for (b, band) in g.bands.iter().enumerate() {
                let yb = y + b as u32 * BAND + BAND / 2;
                area.draw(&Text::new(
                    band.clone(),
                    (scenes as i32, yb as i32),
                    left_text(TEXT_SIZE - 2),
                ))?;
            }
        }
        // A rule between scenes.
        area.draw(&PathElement::new(
            vec![(16, y as i32), ((WIDTH - 16) as i32, y as i32)],
            RGBColor(200, 200, 200),
        ))?;
    }
    for &(r, c, b, row) in &g.cells {
        let (x0, y0) = band_origin(g, (r, c, b));
        let fill = row.ratio.map_or(RGBColor(235, 235, 235), ratio_colour);
        area.draw(&Rectangle::new(
            [
                (x0 + 3, y0 + 3),
                (x0 + cell_w as i32 - 3, y0 + BAND as i32 - 3),
            ],
            fill.filled(),
        ))?;
        let ink = text_on(fill);
        let mid = x0 + cell_w as i32 / 2;
        let note = if g.bare { settings(&row.config) } else { None };
        let (y_text, y_note) = match note {
            Some(_) => (y0 + 22, y0 + 44),
            None => (y0 + BAND as i32 / 2, 0),
        };
        area.draw(&Text::new(
            cell_text(row),
            (mid, y_text),
            centred(TEXT_SIZE + 2).color(&ink),
        ))?;
        if let Some(n) = note {
            area.draw(&Text::new(
                n.to_string(),
                (mid, y_note),
                centred(TEXT_SIZE - 6).color(&ink),
            ))?;
        }
    }
    // A place no cell filled (a scene not run with that camera) says so.
    for r in 0..g.rows.len() {
        for c in 0..g.columns.len() {
            for b in 0..g.bands.len() {
                if !g
                    .cells
                    .iter()
                    .any(|&(r2, c2, b2, _)| (r2, c2, b2) == (r, c, b))
                {
                    let (x0, y0) = band_origin(g, (r, c, b));
                    area.draw(&Text::new(
                        "not measured",
                        (x0 + cell_w as i32 / 2, y0 + BAND as i32 / 2),
                        centred(TEXT_SIZE - 4).color(&RGBColor(150, 150, 150)),
                    ))?;
                }
            }
        }
    }
    let bar_top = (top + g.rows.len() as u32 * row_h + 24) as i32;
    // Short of the right edge: the last tick's label is centred on the bar's end.
    colour_bar(
        area,
        (left as i32, bar_top),
        WIDTH as i32 - 48 - left as i32,
    )?;
    let foot = [
        "≤: below the baseline's best error already at its cheapest point; ≥: not reached \
         within the sweep (its dearest point's cost)",
        "[ ]: 95 % interval of the ratio read with each seed's timings (none where the cell \
         kept one seed's)",
    ];
    for (k, line) in foot.iter().enumerate() {
        area.draw(&Text::new(
            line.to_string(),
            (16, bar_top + 80 + 22 * k as i32),
            text(TEXT_SIZE - 4).color(&RGBColor(90, 90, 90)),
        ))?;
    }
    Ok(())
}

#[cfg(test)]
#[path = "map_png_tests.rs"]
mod tests;

//! map.png's grid, texts and colours, from map.csv rows as bench-map writes them.

use super::*;
use crate::bench::write::map_colours::ratio_colour;
use crate::bench::write::map_rows::parse;

const HEADER_ROW: &str = "folder,scene,size,camera,config,baseline_best_rmse,\
    ms_vs_baseline_at_best,ms_vs_baseline_at_best_seed_mean,ms_vs_baseline_at_best_seed_ci95,\
    reach_at_best\n";

const BODY: &str = "\
city-pan,builtin:city:131072,384×256,pan 0.5°/frame,ris+denoise[d=3],0.006,1,1,0,interpolated
city-pan,builtin:city:131072,384×256,pan 0.5°/frame,restir-denoised[d=3],0.006,0.49,0.49,0.04,interpolated
city-static,builtin:city:131072,384×256,static,ris+denoise[d=3],0.006,1,1,0,interpolated
city-static,builtin:city:131072,384×256,static,restir-denoised[d=3],0.006,0.44,0.44,0.027,at_most
detail-static,builtin:detail,384×256,static,ris+denoise[d=1],0.04,1,1,0,interpolated
detail-static,builtin:detail,384×256,static,restir-denoised[d=1],0.04,1.07,1.07,0.17,beyond
";

/// Two scenes, still and panning, each at its own depth (the best-depth map's shape).
fn best_depth_rows() -> Vec<MapRow> {
    parse(&format!("{HEADER_ROW}{BODY}")).unwrap()
}

#[test]
fn the_map_picture_has_a_row_per_scene_a_column_per_camera_and_no_baseline_band() {
    let rows = best_depth_rows();
    let g = grid(&rows);
    assert_eq!(g.rows, vec!["city:131072", "detail"]);
    assert_eq!(g.columns, vec!["still", "panning (pan 0.5°/frame)"]);
    // The depth differs by scene: bands by bare name, the settings written in the cell.
    assert_eq!(g.bands, vec!["restir-denoised"]);
    assert!(g.bare);
    let placed: Vec<(usize, usize, usize, &str)> = g
        .cells
        .iter()
        .map(|&(r, c, b, row)| (r, c, b, row.folder.as_str()))
        .collect();
    assert_eq!(
        placed,
        vec![
            (0, 1, 0, "city-pan"),
            (0, 0, 0, "city-static"),
            (1, 0, 0, "detail-static")
        ]
    );
}

#[test]
fn a_map_cell_states_its_ratio_interval_and_bound() {
    let rows = best_depth_rows();
    let text: Vec<String> = rows.iter().map(cell_text).collect();
    assert_eq!(text[1], "0.49× [0.45–0.53]");
    assert_eq!(text[3], "≤ 0.44× [0.41–0.47]");
    assert_eq!(text[5], "≥ 1.07× [0.90–1.24]");
    // The baseline against itself has no interval; a cell without a reading says so.
    assert_eq!(text[0], "1.00×");
    let none = MapRow {
        ratio: None,
        ..rows[1].clone()
    };
    assert_eq!(cell_text(&none), "—");
    // An older map.csv without the seeds' columns: the ratio alone.
    let old = parse(
        "folder,scene,size,camera,config,ms_vs_baseline_at_best,reach_at_best\n\
         a,s,1×1,static,base,1,interpolated\na,s,1×1,static,\"x[p=1,q=2]\",0.8,interpolated\n",
    )
    .unwrap();
    assert_eq!(old[1].config, "x[p=1,q=2]");
    assert_eq!(cell_text(&old[1]), "0.80×");
}

#[test]
fn map_png_paints_each_cell_in_its_ratios_colour() {
    let dir = std::env::temp_dir().join(format!("restir-map-png-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let rows = best_depth_rows();
    let mut csv = HEADER_ROW.to_string();
    csv.push_str(BODY);
    std::fs::write(dir.join("map.csv"), csv).unwrap();
    write(&dir).unwrap();
    let png = image::open(dir.join("map.png")).unwrap().to_rgb8();
    assert_eq!(png.width(), WIDTH);
    let g = grid(&rows);
    for &(r, c, b, row) in &g.cells {
        let (x, y) = band_origin(&g, (r, c, b));
        // Inside the band's fill, clear of its centred text.
        let p = png.get_pixel(x as u32 + 8, y as u32 + 8).0;
        let want = ratio_colour(row.ratio.unwrap());
        assert_eq!(p, [want.0, want.1, want.2], "{}", row.folder);
    }
    // The empty place (detail, panning) stays white, "not measured" written in its middle.
    let (x, y) = band_origin(&g, (1, 1, 0));
    assert_eq!(png.get_pixel(x as u32 + 8, y as u32 + 8).0, [255, 255, 255]);
    std::fs::remove_dir_all(&dir).ok();
}

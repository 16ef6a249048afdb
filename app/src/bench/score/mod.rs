//! Scoring: frames in, the numbers of docs/src/measured/how-the-bench-measures.md, "How it
//! measures", out. Each frame is scored as it is rendered (`scoring.rs`, into
//! `frame_figures.rs`' numbers, kept in a configuration's `result.rs`); once every seed
//! ran, the figures over the seeds with their intervals (`seed_figures.rs`, gathered by
//! `over_seeds.rs`), the ratios to `nee` (`vs_nee.rs`), the equal-time gain
//! (`equal_time_gain.rs`), the cost to reach a target error (`equal_error.rs`), the lag
//! around light events (`lag.rs`) and, from a folder of `--knob` runs, the crossover map
//! (`map.rs`, reading each cell's `cost_curves.csv` through `cost_curves_file.rs` and
//! `csv_read.rs`). Nothing here renders or writes a file.

pub mod cost_curves_file;
pub mod csv_read;
pub mod equal_error;
pub mod equal_time_gain;
pub mod frame_figures;
pub mod lag;
pub mod map;
pub mod over_seeds;
pub mod result;
pub mod scoring;
pub mod seed_figures;
pub mod vs_nee;

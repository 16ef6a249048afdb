//! `event_strip.png`: what lag looks like. One row per configuration, the frames of the
//! first event at `STRIP_OFFSETS` frames after it, each as frame | reference | |difference|,
//! all at the exposure of the event frame's reference (so a ghost shows as light where the
//! reference is dark, and a dark lag as a difference where the reference is bright).

use std::path::Path;

use restir_render::LinearImage;
use restir_render::view::auto_exposure_ev;

use super::strip::{Panel, write_grid};
use crate::bench::run::events::Events;
use crate::bench::run::references::References;
use crate::bench::score::result::ConfigResult;

pub fn write(
    path: &Path,
    events: &Events,
    results: &[ConfigResult],
    refs: &References,
) -> anyhow::Result<()> {
    let first = events.frames[0];
    // Differences first (panels borrow them), then the rows.
    let diffs: Vec<Vec<LinearImage>> = results
        .iter()
        .map(|r| {
            r.event_frames
                .iter()
                .map(|(i, img)| abs_difference(img, &refs.images[*i]))
                .collect()
        })
        .collect();
    let rows: Vec<Vec<Panel>> = results
        .iter()
        .zip(&diffs)
        .map(|(r, diffs)| {
            r.event_frames
                .iter()
                .zip(diffs)
                .flat_map(|((i, img), diff)| {
                    let after = i - first;
                    [
                        Panel {
                            label: format!("{} +{after}", r.config.name),
                            image: img,
                        },
                        Panel {
                            label: format!("reference +{after}"),
                            image: &refs.images[*i],
                        },
                        Panel {
                            label: format!("|difference| +{after}"),
                            image: diff,
                        },
                    ]
                })
                .collect()
        })
        .collect();
    let rows: Vec<&[Panel]> = rows
        .iter()
        .map(Vec::as_slice)
        .filter(|r| !r.is_empty())
        .collect();
    let exposure = 2f32.powf(auto_exposure_ev(&refs.images[first]));
    write_grid(path, &rows, exposure)
}

/// |a − b| per channel.
fn abs_difference(a: &LinearImage, b: &LinearImage) -> LinearImage {
    let pixels = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .map(|(p, q)| {
            [
                (p[0] - q[0]).abs(),
                (p[1] - q[1]).abs(),
                (p[2] - q[2]).abs(),
                1.0,
            ]
        })
        .collect();
    LinearImage {
        width: a.width,
        height: a.height,
        pixels,
    }
}

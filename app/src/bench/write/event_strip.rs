//! `event_strip.png`: what lag looks like. One row per configuration, the frames of the
//! first event at `STRIP_OFFSETS` frames after it, each as frame | reference | |difference|,
//! all at the exposure of the event frame's reference (so a ghost shows as light where the
//! reference is dark, and a dark lag as a difference where the reference is bright). Each
//! configuration beside its own references, those of its `max_bounces` (the ones its
//! errors were measured against: run/reference_sets.rs).

use std::path::Path;

use restir_render::LinearImage;
use restir_render::view::auto_exposure_ev;

use super::strip::{Panel, write_grid};
use crate::bench::run::events::Events;
use crate::bench::score::result::ConfigResult;

/// Each configuration's frames at the event less its own references there: `refs[i]` are
/// result i's reference images, one per measured frame.
fn differences(results: &[ConfigResult], refs: &[&[LinearImage]]) -> Vec<Vec<LinearImage>> {
    results
        .iter()
        .zip(refs)
        .map(|(r, refs)| {
            r.event_frames
                .iter()
                .map(|(i, img)| abs_difference(img, &refs[*i]))
                .collect()
        })
        .collect()
}

/// Writes the strip; `refs[i]`: result i's reference images (of its own bounce count).
pub fn write(
    path: &Path,
    events: &Events,
    results: &[ConfigResult],
    refs: &[&[LinearImage]],
) -> anyhow::Result<()> {
    anyhow::ensure!(
        !refs.is_empty() && refs.len() == results.len(),
        "event_strip.png: references for {} of {} configurations",
        refs.len(),
        results.len()
    );
    let first = events.frames[0];
    // Differences first (panels borrow them), then the rows.
    let diffs = differences(results, refs);
    let rows: Vec<Vec<Panel>> = results
        .iter()
        .zip(&diffs)
        .zip(refs)
        .map(|((r, diffs), refs)| {
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
                            image: &refs[*i],
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
    // One exposure for every row: the first configuration's reference at the event.
    let exposure = 2f32.powf(auto_exposure_ev(&refs[0][first]));
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::score::result::planted;

    #[test]
    fn each_configuration_is_compared_with_its_own_references() {
        let grey = |v: f32| LinearImage::from_fn(2, 1, move |_, _| [v, v, v, 1.0]);
        // Both show 1.0 at the event; the 1-bounce reference there is 1.0, the 2-bounce
        // one 1.5 (the second bounce's light).
        let mut direct = planted("ris", 0.1);
        direct.event_frames = vec![(0, grey(1.0))];
        let mut two_bounce = planted("path-2b", 0.1);
        two_bounce.event_frames = vec![(0, grey(1.0))];
        let (one, two) = (vec![grey(1.0)], vec![grey(1.5)]);
        let diffs = differences(&[direct, two_bounce], &[&one, &two]);
        assert_eq!(diffs[0][0].pixels[0][..3], [0.0, 0.0, 0.0]);
        // Against the first configuration's references this would read 0: no difference.
        assert_eq!(diffs[1][0].pixels[0][..3], [0.5, 0.5, 0.5]);
    }
}

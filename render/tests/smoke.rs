use crate::common;

use restir_render::{Mode, Settings};

#[test]
fn every_mode_renders_cornell_without_nan() {
    for mode in Mode::ALL {
        let mut r = common::renderer("builtin:cornell", 64, 48, mode, Settings::default());
        let img = common::accumulate(&mut r, 4);
        assert_eq!(img.non_finite_count(), 0, "{mode:?}");
        let mean = img.mean_luminance();
        eprintln!(
            "{mode:?}: mean luminance {mean}, passes {:?}",
            r.last_passes()
        );
        assert!(mean > 0.01, "{mode:?} is black: {mean}");
    }
}

//! The masks of a moving shot (`metrics::motion_masks`): for each measured frame, the pixels
//! it disoccludes and those near triangles that moved since the frame before, from the
//! scene posed at both frames' times and both frames' cameras. Computed once per bench;
//! every configuration and seed is scored within the same masks.

use restir_render::Scene;
use restir_render::metrics::motion_masks::{MaskTracer, MotionMasks, Posed};
use restir_render::scene::animation::ClipChoice;

use super::shot::Shot;

/// One mask pair per measured frame `warmup..warmup + measured` (counted from the first
/// warm-up frame, as the shot counts); the very first frame of a shot has no frame before
/// it and marks nothing.
pub fn shot_masks(
    scene: &Scene,
    shot: &Shot,
    warmup: u32,
    measured: u32,
    size: (u32, u32),
) -> Vec<MotionMasks> {
    let mut posed = scene.clone();
    let mut positions_at = |frame: u32| -> Vec<[glam::Vec3; 3]> {
        if posed.animation.is_some() {
            posed.pose(shot.time(frame), ClipChoice::All);
        }
        (0..posed.triangles.len())
            .map(|t| posed.triangle_positions(t))
            .collect()
    };
    let first = warmup.saturating_sub(1);
    let mut previous = positions_at(first);
    let mut tracer = MaskTracer::new(&previous);
    (warmup..warmup + measured)
        .map(|frame| {
            if frame == 0 {
                return MotionMasks::empty(size.0, size.1);
            }
            let current = positions_at(frame);
            let masks = tracer.masks(
                Posed {
                    camera: shot.camera(frame - 1),
                    positions: &previous,
                },
                Posed {
                    camera: shot.camera(frame),
                    positions: &current,
                },
                size.0,
                size.1,
            );
            previous = current;
            masks
        })
        .collect()
}

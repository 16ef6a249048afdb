//! The images `render` writes from its sides' renderers: the linear image of one side or
//! the split of both (EXR, the recording's linear frames, `--stats`), and what the display
//! pass shows at an exposure (PNG, the recording's display frames).

use restir_render::{DebugView, LinearImage, Renderer};

use super::render_loop::SideRun;
use crate::compare::split_columns;

/// The linear image a side shows: the last frame, or the average with `--accumulate`.
pub fn read_image(renderer: &Renderer, accumulate: bool) -> LinearImage {
    if accumulate {
        renderer.read_accumulated()
    } else {
        renderer.read_radiance()
    }
}

/// What is written: one side's image, or A left of the middle and B right of it.
pub fn shown_image(
    left: &SideRun,
    right: Option<&SideRun>,
    divider: u32,
    accumulate: bool,
) -> LinearImage {
    let a = read_image(&left.renderer, accumulate);
    match right {
        None => a,
        Some(r) => LinearImage {
            width: a.width,
            height: a.height,
            pixels: split_columns(
                &a.pixels,
                &read_image(&r.renderer, accumulate).pixels,
                a.width,
                divider,
            ),
        },
    }
}

/// What the display shows for the last frame at exposure `ev`: one side, the split of
/// both, or |A − B| over the whole image.
pub fn display_rgba8(
    left: &mut SideRun,
    right: Option<&mut SideRun>,
    view: DebugView,
    ev: f32,
    divider: u32,
) -> anyhow::Result<Vec<u8>> {
    let (w, _) = left.renderer.size();
    match (right, view) {
        (Some(r), DebugView::Difference) => {
            let b = r.renderer.read_radiance();
            left.renderer.set_comparison_image(&b)?;
            redisplay(&mut left.renderer, ev)
        }
        (Some(r), _) => {
            let a = redisplay(&mut left.renderer, ev)?;
            let b = redisplay(&mut r.renderer, ev)?;
            Ok(split_columns(&a, &b, w * 4, divider * 4))
        }
        (None, _) => redisplay(&mut left.renderer, ev),
    }
}

/// The last frame's display pass again at exposure `ev` (the view is set once, before the
/// first frame: the boiling views keep their window only while they are shown).
fn redisplay(renderer: &mut Renderer, ev: f32) -> anyhow::Result<Vec<u8>> {
    let mut settings = *renderer.view();
    settings.exposure_ev = ev;
    renderer.set_view(settings);
    renderer.redisplay()?;
    Ok(renderer.read_display_rgba8())
}

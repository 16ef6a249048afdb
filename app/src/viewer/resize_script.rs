//! `--test-resize-script` (hidden): the viewer resizes, minimises and restores its own
//! window while rendering, for the Xvfb test. Driving it from inside is deterministic
//! where an external `xdotool` race against a running viewer is not, and it reaches the
//! cases X11 cannot produce: an X server never reports a 0×0 window (Windows does, on
//! minimise) and, without a window manager, nobody answers an iconify request. So the
//! script makes real X resizes (ConfigureNotify → `Resized` → swapchain reconfigure,
//! render targets re-created), unmaps/maps the window (what a window manager does on
//! minimise), and feeds the 0×0 `Resized` through the same handler a real one takes.

use std::time::{Duration, Instant};

use anyhow::bail;
use winit::dpi::PhysicalSize;

use super::window::Viewer;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Step {
    /// Ask the window system for this inner size; done when frames render at it.
    Resize(u32, u32),
    /// The 0×0 size a minimise reports: no frame may render meanwhile.
    Minimise,
    /// Back to the window's real size.
    Restore,
    /// Unmap / map the window.
    Hide,
    Show,
}

const STEPS: &[Step] = &[
    Step::Resize(900, 560),
    Step::Resize(240, 160),
    Step::Minimise,
    Step::Restore,
    Step::Resize(1000, 300),
    Step::Hide,
    Step::Show,
    Step::Resize(720, 450),
];

/// Frames each visible step must render before the next step.
const FRAMES_PER_STEP: u64 = 2;
/// How long the invisible steps last.
const HIDDEN_TIME: Duration = Duration::from_millis(400);
const STEP_TIMEOUT: Duration = Duration::from_secs(60);

#[derive(Default)]
pub struct ResizeScript {
    next: usize,
    current: Option<(Step, Instant, u64)>,
}

impl ResizeScript {
    /// Advances the script; `Ok(true)` once every step is done.
    pub fn tick(&mut self, viewer: &mut Viewer) -> anyhow::Result<bool> {
        if let Some((step, started, frames)) = self.current {
            if !done(step, started, frames, viewer)? {
                if started.elapsed() > STEP_TIMEOUT {
                    bail!(
                        "resize script: step {step:?} did not finish in {STEP_TIMEOUT:?} (window {:?})",
                        viewer.surface_size()
                    );
                }
                return Ok(false);
            }
            eprintln!(
                "resize script: {step:?} done, window {:?}, {} frames",
                viewer.surface_size(),
                viewer.frames_rendered()
            );
        }
        let Some(&step) = STEPS.get(self.next) else {
            return Ok(true);
        };
        self.next += 1;
        start(step, viewer);
        self.current = Some((step, Instant::now(), viewer.frames_rendered()));
        Ok(false)
    }
}

fn start(step: Step, viewer: &mut Viewer) {
    let window = viewer.window();
    match step {
        Step::Resize(w, h) => {
            if let Some(size) = window.request_inner_size(PhysicalSize::new(w, h)) {
                viewer.resized(size);
            }
        }
        Step::Minimise => {
            window.set_minimized(true);
            viewer.resized(PhysicalSize::new(0, 0));
        }
        Step::Restore => {
            window.set_minimized(false);
            let size = window.inner_size();
            viewer.resized(size);
        }
        Step::Hide => window.set_visible(false),
        Step::Show => window.set_visible(true),
    }
}

fn done(
    step: Step,
    started: Instant,
    frames_at_start: u64,
    viewer: &Viewer,
) -> anyhow::Result<bool> {
    let rendered = viewer.frames_rendered() - frames_at_start;
    Ok(match step {
        Step::Resize(w, h) => rendered >= FRAMES_PER_STEP && viewer.surface_size() == (w, h),
        Step::Minimise => {
            if rendered > 0 {
                bail!("resize script: {rendered} frames rendered while minimised");
            }
            started.elapsed() >= HIDDEN_TIME
        }
        Step::Hide => started.elapsed() >= HIDDEN_TIME,
        Step::Restore | Step::Show => rendered >= FRAMES_PER_STEP,
    })
}

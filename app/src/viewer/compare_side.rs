//! The viewer's configuration B: a second renderer on the same device and scene, rendered
//! every frame with A's camera, size and view, with its own mode, settings and history.
//! Created when the Compare section turns on, re-created when B or the scene changes.

use restir_render::{DebugView, Gpu, Renderer, Scene};

use super::state::{CompareState, ViewerState};
use crate::compare::CompareTarget;

pub struct CompareSide {
    /// What B was made from: the Compare field, and for a mode the A settings it follows.
    spec: String,
    pub target: CompareTarget,
    pub renderer: Renderer,
}

impl CompareSide {
    /// Keeps `side` in step with the Compare state: off drops it, a new B (or new A
    /// settings for a mode target) replaces or updates it; an unusable B turns the
    /// comparison off with a message. Returns whether the side was (re-)created, which
    /// re-binds its image.
    pub fn sync(
        side: &mut Option<CompareSide>,
        gpu: &Gpu,
        scene: &Scene,
        a: &Renderer,
        state: &mut ViewerState,
    ) -> bool {
        let compare = &mut state.compare;
        // A tour's inline B holds while the field shows its label.
        if compare
            .target
            .as_ref()
            .is_some_and(|t| t.label != compare.spec)
        {
            compare.target = None;
        }
        if !compare.enabled {
            *side = None;
            compare.errors = None;
            return false;
        }
        if let Some(s) = side.as_mut().filter(|s| s.spec == compare.spec) {
            // A mode target follows A's settings as they are tuned; a preset stays.
            if restir_render::Mode::from_name(&s.spec).is_some() {
                s.target.settings = state.settings.clone();
            }
            return false;
        }
        let target = match &compare.target {
            Some(t) => Ok(t.clone()),
            None => CompareTarget::parse(&compare.spec, &state.settings),
        };
        match target.and_then(|t| Self::create(gpu, scene, a, &compare.spec, t)) {
            Ok(s) => {
                compare.error = None;
                *side = Some(s);
                true
            }
            Err(e) => {
                *compare = CompareState {
                    enabled: false,
                    error: Some(format!("{e:#}")),
                    ..compare.clone()
                };
                *side = None;
                false
            }
        }
    }

    fn create(
        gpu: &Gpu,
        scene: &Scene,
        a: &Renderer,
        spec: &str,
        target: CompareTarget,
    ) -> anyhow::Result<CompareSide> {
        let (w, h) = a.size();
        let mut renderer = Renderer::new(gpu.clone(), scene, w, h, target.settings.clone())?;
        renderer.set_mode(target.mode);
        renderer.set_camera(a.camera());
        Ok(CompareSide {
            spec: spec.to_string(),
            target,
            renderer,
        })
    }

    /// Renders B's frame for A's camera, size and view (B shows the final image where A
    /// shows the difference to B), then hands B's image to A for the difference view.
    pub fn render(&mut self, a: &mut Renderer) -> anyhow::Result<()> {
        let b = &mut self.renderer;
        let (w, h) = a.size();
        b.resize(w, h)?;
        b.set_mode(self.target.mode);
        let settings = super::apply::runnable_settings(b, &self.target.settings);
        b.set_settings(settings);
        if b.camera() != a.camera() {
            b.set_camera(a.camera());
            b.reset_accumulation();
        }
        let mut view = *a.view();
        if view.view == DebugView::Difference {
            view.view = DebugView::Final;
        }
        let turned_on = view.accumulate && !b.view().accumulate;
        b.set_view(view);
        if turned_on {
            b.reset_accumulation();
        }
        b.render_frame()?;
        // Keep B's report queue short: the panels show A's statistics.
        b.collect_reports(false);
        if a.view().view == DebugView::Difference {
            a.copy_comparison_from(b)?;
        }
        Ok(())
    }

    /// A view change on a frozen frame: B's display pass runs again too.
    pub fn redisplay(&mut self, a: &Renderer) -> anyhow::Result<()> {
        let mut view = *a.view();
        if view.view == DebugView::Difference {
            view.view = DebugView::Final;
        }
        super::apply::redisplay_if_changed(&mut self.renderer, &view)
    }
}

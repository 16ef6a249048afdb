//! The winit side: the window is created on `resumed`, events go to egui first and then
//! to the viewer, and frames are requested continuously while the window can be drawn
//! (a minimised window waits for events instead of spinning).

use std::sync::Arc;
use std::time::{Duration, Instant};

use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::window::{Window, WindowId};

use super::Launch;
use super::frame::After;
use super::resize_script::ResizeScript;
use super::window::Viewer;

pub struct App {
    launch: Option<(Launch, restir_render::Scene)>,
    viewer: Option<Viewer>,
    script: Option<ResizeScript>,
    /// Why the viewer stopped, when it stopped on an error.
    pub error: Option<anyhow::Error>,
}

impl App {
    pub fn new(launch: Launch, scene: restir_render::Scene) -> App {
        let script = launch.resize_script.then(ResizeScript::default);
        App {
            launch: Some((launch, scene)),
            viewer: None,
            script,
            error: None,
        }
    }

    fn open(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<()> {
        let Some((launch, scene)) = self.launch.take() else {
            return Ok(());
        };
        let attributes = Window::default_attributes()
            .with_title("ReSTIR lab")
            .with_inner_size(winit::dpi::LogicalSize::new(
                launch.window_size.0,
                launch.window_size.1,
            ));
        let window = Arc::new(event_loop.create_window(attributes)?);
        let mut viewer = Viewer::new(window, launch, Arc::new(scene))?;
        viewer.hold_screenshot(self.script.is_some());
        self.viewer = Some(viewer);
        Ok(())
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, error: anyhow::Error) {
        self.error = Some(error);
        event_loop.exit();
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if let Err(e) = self.open(event_loop) {
            self.fail(event_loop, e);
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(viewer) = &mut self.viewer else {
            return;
        };
        viewer.egui_event(&event);
        let after = match event {
            WindowEvent::CloseRequested | WindowEvent::Destroyed => Ok(After::Exit),
            WindowEvent::Resized(size) => {
                viewer.resized(size);
                Ok(After::Continue)
            }
            WindowEvent::RedrawRequested => viewer.redraw(),
            WindowEvent::Occluded(occluded) => {
                viewer.set_occluded(occluded);
                Ok(After::Continue)
            }
            _ => Ok(After::Continue),
        };
        match after {
            Ok(After::Continue) => {}
            Ok(After::Exit) => event_loop.exit(),
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let Some(viewer) = &mut self.viewer else {
            return;
        };
        if let Some(script) = &mut self.script {
            match script.tick(viewer) {
                Ok(true) => {
                    self.script = None;
                    viewer.hold_screenshot(false);
                }
                Ok(false) => {}
                Err(e) => return self.fail(event_loop, e),
            }
        }
        let now = Instant::now();
        let mut wake = viewer.next_redraw(now);
        if wake.is_some_and(|t| t <= now) {
            viewer.window().request_redraw();
            wake = None;
        }
        if self.script.is_some() {
            // The script advances on its own clock, also while nothing is drawn.
            let tick = now + Duration::from_millis(20);
            wake = Some(wake.map_or(tick, |t| t.min(tick)));
        }
        event_loop.set_control_flow(wake.map_or(ControlFlow::Wait, ControlFlow::WaitUntil));
    }
}

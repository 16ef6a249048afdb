//! egui on the window: input through egui-winit, drawing through egui-wgpu, and the
//! renderer's display texture registered as an egui image (re-bound whenever the
//! renderer re-creates it on resize).

use std::time::Duration;

use egui_wgpu::ScreenDescriptor;
use restir_render::{Gpu, Renderer};
use winit::window::Window;

pub struct EguiLayer {
    pub ctx: egui::Context,
    input: egui_winit::State,
    painter: egui_wgpu::Renderer,
    image: egui::TextureId,
    bound: Binding,
    /// The split screen's B image and what it was bound to, while there is a B.
    compare: Option<(egui::TextureId, Binding)>,
}

/// Size and filter (smooth or not) of the texture an egui image was bound to: when either
/// changes, the image is re-bound.
type Binding = ((u32, u32), bool);

fn filter(smooth: bool) -> wgpu::FilterMode {
    if smooth {
        wgpu::FilterMode::Linear
    } else {
        wgpu::FilterMode::Nearest
    }
}

impl EguiLayer {
    pub fn new(
        window: &Window,
        gpu: &Gpu,
        format: wgpu::TextureFormat,
        renderer: &Renderer,
        smooth: bool,
    ) -> EguiLayer {
        let ctx = egui::Context::default();
        ctx.set_visuals(egui::Visuals::dark());
        let max_texture_side = gpu.device.limits().max_texture_dimension_2d as usize;
        let input = egui_winit::State::new(
            ctx.clone(),
            egui::ViewportId::ROOT,
            window,
            Some(window.scale_factor() as f32),
            window.theme(),
            Some(max_texture_side),
        );
        // No dithering: the image must reach the screen (and screenshots) unaltered.
        let options = egui_wgpu::RendererOptions {
            dithering: false,
            ..Default::default()
        };
        let mut painter = egui_wgpu::Renderer::new(&gpu.device, format, options);
        let image =
            painter.register_native_texture(&gpu.device, renderer.display_view(), filter(smooth));
        EguiLayer {
            ctx,
            input,
            painter,
            image,
            bound: (renderer.size(), smooth),
            compare: None,
        }
    }

    pub fn compare_image(&self) -> Option<egui::TextureId> {
        self.compare.map(|(id, _)| id)
    }

    /// Registers B's display texture (or follows its re-creation); `None` frees it.
    pub fn bind_compare_image(&mut self, gpu: &Gpu, b: Option<&Renderer>, smooth: bool) {
        let Some(b) = b else {
            self.unbind_compare_image();
            return;
        };
        let wanted = (b.size(), smooth);
        match &mut self.compare {
            None => {
                let id = self.painter.register_native_texture(
                    &gpu.device,
                    b.display_view(),
                    filter(smooth),
                );
                self.compare = Some((id, wanted));
            }
            Some((id, bound)) if *bound != wanted => {
                self.painter.update_egui_texture_from_wgpu_texture(
                    &gpu.device,
                    b.display_view(),
                    filter(smooth),
                    *id,
                );
                *bound = wanted;
            }
            Some(_) => {}
        }
    }

    /// Forgets B's texture (B was re-created: the next bind registers the new one).
    pub fn unbind_compare_image(&mut self) {
        if let Some((id, _)) = self.compare.take() {
            self.painter.free_texture(&id);
        }
    }

    pub fn image(&self) -> egui::TextureId {
        self.image
    }

    /// Feeds a window event to egui; true when egui wants to repaint because of it.
    pub fn on_window_event(&mut self, window: &Window, event: &winit::event::WindowEvent) -> bool {
        self.input.on_window_event(window, event).repaint
    }

    /// Runs the UI for one frame; also returns how soon egui wants to run again (an
    /// animation, a tooltip delay; `Duration::MAX` when idle).
    pub fn run(
        &mut self,
        window: &Window,
        ui: impl FnMut(&mut egui::Ui),
    ) -> (egui::FullOutput, Duration) {
        let raw = self.input.take_egui_input(window);
        let mut output = self.ctx.run_ui(raw, ui);
        let platform = std::mem::take(&mut output.platform_output);
        self.input.handle_platform_output(window, platform);
        let delay = output
            .viewport_output
            .get(&egui::ViewportId::ROOT)
            .map_or(Duration::MAX, |v| v.repaint_delay);
        (output, delay)
    }

    /// Points the image at the renderer's current display texture if it was re-created.
    pub fn bind_image(&mut self, gpu: &Gpu, renderer: &Renderer, smooth: bool) {
        let wanted = (renderer.size(), smooth);
        if wanted != self.bound {
            self.painter.update_egui_texture_from_wgpu_texture(
                &gpu.device,
                renderer.display_view(),
                filter(smooth),
                self.image,
            );
            self.bound = wanted;
        }
    }

    /// Draws the UI into each of `targets` (the window, plus a capture texture when a
    /// screenshot is due). With no targets (frame skipped) only the textures update.
    pub fn paint(
        &mut self,
        gpu: &Gpu,
        mut output: egui::FullOutput,
        targets: &[&wgpu::TextureView],
        size_in_pixels: [u32; 2],
    ) {
        for (id, deltas) in &output.textures_delta.set {
            for delta in deltas {
                self.painter
                    .update_texture(&gpu.device, &gpu.queue, *id, delta);
            }
        }
        if !targets.is_empty() {
            let jobs = self.ctx.tessellate(output.shapes, output.pixels_per_point);
            let screen = ScreenDescriptor {
                size_in_pixels,
                pixels_per_point: output.pixels_per_point,
            };
            let mut encoder = gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("egui"),
                });
            let callbacks =
                self.painter
                    .update_buffers(&gpu.device, &gpu.queue, &mut encoder, &jobs, &screen);
            for view in targets {
                let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("egui"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                            store: wgpu::StoreOp::Store,
                        },
                    })],
                    ..Default::default()
                });
                self.painter
                    .render(&mut pass.forget_lifetime(), &jobs, &screen);
            }
            gpu.queue
                .submit(callbacks.into_iter().chain([encoder.finish()]));
        }
        for id in &output.textures_delta.free {
            self.painter.free_texture(id);
        }
        // Applied above; epaint insists on being told so.
        output.textures_delta.clear();
    }
}

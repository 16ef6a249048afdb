//! The other side of a split-screen comparison (configuration B), kept in the targets for
//! the `difference` view (|A − B|). The viewer copies it on the GPU every frame from B's
//! renderer; headless rendering uploads B's image once.

use super::Renderer;
use crate::image::LinearImage;
use crate::passes::resources::{ACCUMULATION, COMPARISON, RADIANCE};

impl Renderer {
    /// Uploads B's linear image (same size) for the difference view.
    pub fn set_comparison_image(&mut self, image: &LinearImage) -> anyhow::Result<()> {
        anyhow::ensure!(
            (image.width, image.height) == self.size(),
            "comparison image is {}x{}, the output is {}x{}",
            image.width,
            image.height,
            self.targets.width,
            self.targets.height
        );
        self.ensure_comparison();
        self.comparison_scale = 1.0;
        self.gpu.queue.write_buffer(
            self.targets.pixels(&COMPARISON),
            0,
            bytemuck::cast_slice(&image.pixels),
        );
        Ok(())
    }

    /// Copies what `other` displays (its last frame, or its running average) into this
    /// renderer's comparison image, on the GPU. Both must share one `Gpu` and one size.
    pub fn copy_comparison_from(&mut self, other: &Renderer) -> anyhow::Result<()> {
        anyhow::ensure!(
            other.size() == self.size(),
            "comparison side is {}x{}, this side {}x{}",
            other.size().0,
            other.size().1,
            self.targets.width,
            self.targets.height
        );
        anyhow::ensure!(
            other.gpu.device == self.gpu.device,
            "the two sides of a comparison must share one device"
        );
        self.ensure_comparison();
        let (source, scale) = if other.shows_accumulation() {
            let n = other.accumulated_frames.max(1);
            (other.targets.pixels(&ACCUMULATION), 1.0 / n as f32)
        } else {
            (other.targets.pixels(&RADIANCE), 1.0)
        };
        self.comparison_scale = scale;
        let mut encoder = self.gpu.device.create_command_encoder(&Default::default());
        let target = self.targets.pixels(&COMPARISON);
        encoder.copy_buffer_to_buffer(source, 0, target, 0, source.size());
        self.gpu.queue.submit([encoder.finish()]);
        Ok(())
    }

    fn ensure_comparison(&mut self) {
        if self.targets.ensure_full(&self.gpu, &COMPARISON) {
            self.bind_groups.clear();
        }
    }
}

//! Screenshots. The window is captured by drawing the same frame a second time into an
//! offscreen texture of the surface's format and size (surfaces cannot portably be read
//! back); the image alone is the renderer's display texture; the EXR is linear radiance.

use std::path::{Path, PathBuf};

use restir_render::{Gpu, Renderer};

/// An offscreen copy of the window for one frame.
pub struct WindowCapture {
    texture: wgpu::Texture,
    pub view: wgpu::TextureView,
}

impl WindowCapture {
    pub fn new(
        gpu: &Gpu,
        format: wgpu::TextureFormat,
        (width, height): (u32, u32),
    ) -> WindowCapture {
        let texture = restir_render::gpu::texture_2d(
            gpu,
            "window capture",
            width,
            height,
            format,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            &[],
        );
        let view = texture.create_view(&Default::default());
        WindowCapture { texture, view }
    }

    /// Reads the capture back (blocking) and writes it as an opaque RGBA PNG.
    pub fn save_png(&self, gpu: &Gpu, path: &Path) -> anyhow::Result<(u32, u32)> {
        let mut rgba = restir_render::gpu::readback::read_rgba8_texture(gpu, &self.texture);
        let bgra = matches!(
            self.texture.format(),
            wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
        );
        for px in rgba.chunks_exact_mut(4) {
            if bgra {
                px.swap(0, 2);
            }
            px[3] = 255;
        }
        let (w, h) = (self.texture.width(), self.texture.height());
        restir_render::image::save_png_rgba8(path, w, h, &rgba)?;
        Ok((w, h))
    }
}

/// A screenshot to take this frame.
#[derive(Clone, Debug, PartialEq)]
pub enum Shot {
    /// `--screenshot-after`: the window only, to the given file.
    AfterFrames(PathBuf),
    /// F12 / the button: window, image and EXR into the screenshot folder.
    Requested,
}

/// Which screenshots are wanted, and when.
#[derive(Debug, Default)]
pub struct Schedule {
    /// `--screenshot-after N FILE`, until taken.
    pub after: Option<(u64, PathBuf)>,
    /// Holds back the `--screenshot-after` shot (the resize test script runs first).
    pub hold: bool,
    /// F12 or the button, since the last frame.
    pub requested: bool,
}

impl Schedule {
    /// The shot this frame should capture: `--screenshot-after` on a frame that rendered
    /// the N-th frame or later, otherwise a requested one.
    pub fn due(&mut self, frames_rendered: u64, rendered_now: bool) -> Option<Shot> {
        if let Some((n, _)) = &self.after
            && rendered_now
            && frames_rendered >= *n
            && !self.hold
        {
            return self.after.take().map(|(_, path)| Shot::AfterFrames(path));
        }
        std::mem::take(&mut self.requested).then_some(Shot::Requested)
    }
}

/// Writes `STEM.png` (the window), `STEM-image.png` and `STEM.exr`; returns the line
/// the View panel shows (the files, or why not).
pub fn save_all(gpu: &Gpu, capture: &WindowCapture, renderer: &Renderer, stem: &Path) -> String {
    let window_png = stem.with_extension("png");
    let written = capture
        .save_png(gpu, &window_png)
        .and_then(|_| save_image_and_exr(renderer, stem));
    match written {
        Ok(files) => {
            let files: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
            format!("saved {} and {}", window_png.display(), files.join(", "))
        }
        Err(e) => format!("error: {e:#}"),
    }
}

/// `dir/restir-SCENE-FRAME`: the stem every file of one screenshot shares.
pub fn stem(dir: &str, scene: &str, frame: u64) -> PathBuf {
    let name: String = scene
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    Path::new(if dir.trim().is_empty() {
        "."
    } else {
        dir.trim()
    })
    .join(format!("restir-{name}-{frame:05}"))
}

/// Writes `STEM-image.png` (what the image area shows, at render resolution) and
/// `STEM.exr` (the linear image: the running average while accumulating).
fn save_image_and_exr(renderer: &Renderer, stem: &Path) -> anyhow::Result<Vec<PathBuf>> {
    if let Some(dir) = stem.parent() {
        std::fs::create_dir_all(dir)
            .map_err(|e| anyhow::anyhow!("{}: cannot create folder: {e}", dir.display()))?;
    }
    let (w, h) = renderer.size();
    let png = stem.with_file_name(format!("{}-image.png", file_name(stem)));
    restir_render::image::save_png_rgba8(&png, w, h, &renderer.read_display_rgba8())?;
    let exr = stem.with_extension("exr");
    let linear = if renderer.view().accumulate {
        renderer.read_accumulated()
    } else {
        renderer.read_radiance()
    };
    linear.save_exr(&exr)?;
    Ok(vec![png, exr])
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_frame_count_shot_comes_once_and_waits_for_a_hold() {
        let mut s = Schedule {
            after: Some((3, "f.png".into())),
            hold: true,
            ..Default::default()
        };
        assert_eq!(s.due(5, true), None, "held");
        s.hold = false;
        assert_eq!(s.due(2, true), None, "too early");
        assert_eq!(s.due(3, false), None, "no new frame");
        assert_eq!(s.due(3, true), Some(Shot::AfterFrames("f.png".into())));
        assert_eq!(s.due(4, true), None, "taken");
        s.requested = true;
        assert_eq!(s.due(4, false), Some(Shot::Requested));
        assert_eq!(s.due(5, false), None);
    }

    #[test]
    fn stems_are_safe_file_names() {
        assert_eq!(
            stem("shots", "builtin:many-lights", 7),
            Path::new("shots/restir-builtin_many-lights-00007")
        );
        assert_eq!(stem(" ", "a/b", 0), Path::new("./restir-a_b-00000"));
    }
}

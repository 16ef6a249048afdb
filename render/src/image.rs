//! Linear HDR images on the CPU: what readbacks produce, what metrics compare and what
//! gets written to EXR (untonemapped) or PNG.

use std::path::Path;

/// Rec. 709 luminance weights, the same as `luminance()` in `shaders/common/math.wgsl`.
pub const LUMINANCE_WEIGHTS: [f32; 3] = [0.2126, 0.7152, 0.0722];

pub fn luminance(rgb: [f32; 3]) -> f32 {
    rgb[0] * LUMINANCE_WEIGHTS[0] + rgb[1] * LUMINANCE_WEIGHTS[1] + rgb[2] * LUMINANCE_WEIGHTS[2]
}

/// Row-major RGBA32F pixels, top row first. Alpha is carried along but metrics ignore it.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearImage {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[f32; 4]>,
}

impl LinearImage {
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            pixels: vec![[0.0; 4]; (width as usize) * (height as usize)],
        }
    }

    pub fn from_fn(width: u32, height: u32, f: impl Fn(u32, u32) -> [f32; 4]) -> Self {
        let mut pixels = Vec::with_capacity((width * height) as usize);
        for y in 0..height {
            for x in 0..width {
                pixels.push(f(x, y));
            }
        }
        Self {
            width,
            height,
            pixels,
        }
    }

    pub fn get(&self, x: u32, y: u32) -> [f32; 4] {
        self.pixels[(y * self.width + x) as usize]
    }

    pub fn rgb(&self, x: u32, y: u32) -> [f32; 3] {
        let p = self.get(x, y);
        [p[0], p[1], p[2]]
    }

    pub fn luminance_at(&self, x: u32, y: u32) -> f32 {
        luminance(self.rgb(x, y))
    }

    /// Number of pixels with a NaN or infinite colour channel.
    pub fn non_finite_count(&self) -> usize {
        self.pixels
            .iter()
            .filter(|p| p[..3].iter().any(|c| !c.is_finite()))
            .count()
    }

    pub fn mean_luminance(&self) -> f64 {
        if self.pixels.is_empty() {
            return 0.0;
        }
        let sum: f64 = self
            .pixels
            .iter()
            .map(|p| luminance([p[0], p[1], p[2]]) as f64)
            .sum();
        sum / self.pixels.len() as f64
    }

    /// Writes an untonemapped RGBA32F OpenEXR file.
    pub fn save_exr(&self, path: &Path) -> anyhow::Result<()> {
        let flat: Vec<f32> = self.pixels.iter().flatten().copied().collect();
        let buffer = image::Rgba32FImage::from_raw(self.width, self.height, flat)
            .ok_or_else(|| anyhow::anyhow!("image buffer has the wrong size"))?;
        image::DynamicImage::ImageRgba32F(buffer)
            .save_with_format(path, image::ImageFormat::OpenExr)
            .map_err(|e| anyhow::anyhow!("{}: cannot write EXR: {e}", path.display()))
    }

    /// Reads an RGBA or RGB OpenEXR file (used for cached references).
    pub fn load_exr(path: &Path) -> anyhow::Result<Self> {
        let img = image::open(path)
            .map_err(|e| anyhow::anyhow!("{}: cannot read EXR: {e}", path.display()))?
            .into_rgba32f();
        let (width, height) = img.dimensions();
        let pixels = img
            .into_raw()
            .chunks_exact(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect();
        Ok(Self {
            width,
            height,
            pixels,
        })
    }
}

/// Writes 8-bit RGBA pixels (already tonemapped / encoded) as PNG.
pub fn save_png_rgba8(path: &Path, width: u32, height: u32, rgba: &[u8]) -> anyhow::Result<()> {
    image::save_buffer_with_format(
        path,
        rgba,
        width,
        height,
        image::ExtendedColorType::Rgba8,
        image::ImageFormat::Png,
    )
    .map_err(|e| anyhow::anyhow!("{}: cannot write PNG: {e}", path.display()))
}

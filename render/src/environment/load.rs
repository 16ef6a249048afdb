//! Reading an environment: `builtin:sky`, or a Radiance `.hdr` / OpenEXR `.exr` file
//! through the image crate. Every failure is one line that starts with the file as given
//! (`sky.hdr: 3 texels are not finite, the first at (12, 40)`), so `render` can print it
//! and exit and the viewer can show it and keep the environment it had.

use std::path::Path;

use super::{Environment, MAX_TEXELS, sky};

#[derive(Debug, thiserror::Error)]
#[error("{file}: {detail}")]
pub struct EnvironmentError {
    pub file: String,
    pub detail: String,
}

fn fail(file: &str, detail: impl Into<String>) -> EnvironmentError {
    EnvironmentError {
        file: file.to_string(),
        // Error text from the image crate may span lines; the promise is one line.
        detail: detail.into().replace(['\n', '\r'], " "),
    }
}

/// `builtin:sky` or a path to an .hdr/.exr file.
pub fn load_environment(spec: &str) -> Result<Environment, EnvironmentError> {
    if let Some(name) = spec.strip_prefix("builtin:") {
        return match name {
            "sky" => Ok(sky::clear_sky()),
            _ => Err(fail(
                spec,
                format!("unknown built-in environment (known: {})", sky::BUILTIN_SKY),
            )),
        };
    }
    let path = Path::new(spec);
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let format = match extension.as_deref() {
        Some("hdr") => image::ImageFormat::Hdr,
        Some("exr") => image::ImageFormat::OpenExr,
        other => {
            return Err(fail(
                spec,
                format!(
                    "unsupported environment format '{}' (expected .hdr or .exr)",
                    other.unwrap_or("")
                ),
            ));
        }
    };
    let bytes = std::fs::read(path).map_err(|e| fail(spec, format!("cannot read: {e}")))?;
    if bytes.is_empty() {
        return Err(fail(spec, "the file is empty (0 bytes)"));
    }
    let image = image::load_from_memory_with_format(&bytes, format)
        .map_err(|e| fail(spec, format!("cannot decode as {format:?}: {e}")))?
        .into_rgb32f();
    let (width, height) = image.dimensions();
    if width == 0 || height == 0 {
        return Err(fail(
            spec,
            format!("the image has zero size ({width}x{height})"),
        ));
    }
    let texels: Vec<[f32; 3]> = image.pixels().map(|p| [p.0[0], p.0[1], p.0[2]]).collect();
    check_texels(spec, width, &texels)?;
    let (width, height, texels) = fit_to(spec, width, height, texels, MAX_TEXELS);
    Ok(Environment::from_texels(spec, width, height, texels))
}

/// Radiance must be finite and non-negative: a NaN or an infinity would reach every pixel
/// the environment lights, a negative texel would make a negative pdf.
pub(crate) fn check_texels(
    file: &str,
    width: u32,
    texels: &[[f32; 3]],
) -> Result<(), EnvironmentError> {
    let at = |i: usize| (i as u32 % width, i as u32 / width);
    let bad: Vec<usize> = (0..texels.len())
        .filter(|&i| texels[i].iter().any(|c| !c.is_finite()))
        .collect();
    if let Some(&first) = bad.first() {
        return Err(fail(
            file,
            format!(
                "{} texels are not finite, the first at {:?}",
                bad.len(),
                at(first)
            ),
        ));
    }
    if let Some(i) = (0..texels.len()).find(|&i| texels[i].iter().any(|&c| c < 0.0)) {
        return Err(fail(
            file,
            format!(
                "texel {:?} is negative ({:?}): radiance must be ≥ 0",
                at(i),
                texels[i]
            ),
        ));
    }
    Ok(())
}

/// Halves the image (2×2 box filter) until it has at most `max_texels` texels and fits
/// WebGPU's default 8192 texture side.
pub(super) fn fit_to(
    file: &str,
    mut w: u32,
    mut h: u32,
    mut texels: Vec<[f32; 3]>,
    max_texels: usize,
) -> (u32, u32, Vec<[f32; 3]>) {
    let (w0, h0) = (w, h);
    while (w as usize * h as usize > max_texels || w > 8192 || h > 8192) && w > 1 && h > 1 {
        let (nw, nh) = (w / 2, h / 2);
        let mut out = Vec::with_capacity((nw * nh) as usize);
        for y in 0..nh {
            for x in 0..nw {
                let mut sum = [0.0f32; 3];
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let t = texels[((2 * y + dy) * w + 2 * x + dx) as usize];
                    for c in 0..3 {
                        sum[c] += t[c] * 0.25;
                    }
                }
                out.push(sum);
            }
        }
        (w, h, texels) = (nw, nh, out);
    }
    if (w, h) != (w0, h0) {
        log::warn!("{file}: {w0}x{h0} reduced to {w}x{h} (at most {max_texels} texels)");
    }
    (w, h, texels)
}

//! Comparing a compressed file with its uncompressed twin: triangles matched by where they
//! are (compression may reorder vertices, triangles and corners), texels by their mean
//! error, and the planted twins that prove each comparison can fail.

use std::collections::HashMap;

use glam::Vec3;
use restir_render::scene::{Scene, Vertex};

/// The largest differences between matched corners of two scenes, in world space.
#[derive(Debug, Default)]
pub struct TwinErrors {
    pub position: f32,
    pub normal: f32,
    pub uv: f32,
    /// Triangles of the twin with no plain triangle of the same material near them.
    pub unmatched: usize,
}

/// Centroid grid cell (world units): far above any quantisation error, far below a
/// triangle's size, so a twin triangle's match lies in its cell or a neighbour.
const CELL: f32 = 1e-3;

fn corners(scene: &Scene, t: usize) -> [Vertex; 3] {
    scene.triangles[t]
        .indices
        .map(|i| scene.vertices[i as usize])
}

fn cell(corners: &[Vertex; 3]) -> [i32; 3] {
    let c = (corners[0].position + corners[1].position + corners[2].position) / 3.0;
    (c / CELL).floor().as_ivec3().to_array()
}

/// For every triangle of `twin`, the triangle of `plain` with the same material whose corners
/// (in one of the three rotations that keep the winding) are nearest; the largest position,
/// normal and uv differences over all matched corners.
pub fn twin_errors(plain: &Scene, twin: &Scene) -> TwinErrors {
    let mut grid: HashMap<[i32; 3], Vec<usize>> = HashMap::new();
    for t in 0..plain.triangles.len() {
        grid.entry(cell(&corners(plain, t))).or_default().push(t);
    }
    let mut errors = TwinErrors::default();
    for t in 0..twin.triangles.len() {
        let twin_corners = corners(twin, t);
        let [x, y, z] = cell(&twin_corners);
        let mut best: Option<(f32, [Vertex; 3])> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let candidates = grid.get(&[x + dx, y + dy, z + dz]);
                    for &p in candidates.into_iter().flatten() {
                        if plain.triangles[p].material != twin.triangles[t].material {
                            continue;
                        }
                        let c = corners(plain, p);
                        for r in 0..3 {
                            let rotated = [c[r], c[(r + 1) % 3], c[(r + 2) % 3]];
                            let d = (0..3)
                                .map(|k| rotated[k].position.distance(twin_corners[k].position))
                                .fold(0.0, f32::max);
                            if best.is_none_or(|(b, _)| d < b) {
                                best = Some((d, rotated));
                            }
                        }
                    }
                }
            }
        }
        let Some((distance, plain_corners)) = best else {
            errors.unmatched += 1;
            continue;
        };
        errors.position = errors.position.max(distance);
        for (a, b) in plain_corners.iter().zip(&twin_corners) {
            errors.normal = errors.normal.max(a.normal.distance(b.normal));
            errors.uv = errors.uv.max(a.uv.distance(b.uv));
        }
    }
    errors
}

/// The largest side of the world-space bounding box of any single material's triangles: the
/// scale that quantisation grids (per mesh) are at most.
pub fn largest_extent(scene: &Scene) -> f32 {
    let mut boxes: HashMap<u32, (Vec3, Vec3)> = HashMap::new();
    for (t, tri) in scene.triangles.iter().enumerate() {
        for v in corners(scene, t) {
            let b = boxes
                .entry(tri.material)
                .or_insert((Vec3::INFINITY, Vec3::NEG_INFINITY));
            *b = (b.0.min(v.position), b.1.max(v.position));
        }
    }
    boxes
        .values()
        .map(|(lo, hi)| (*hi - *lo).max_element())
        .fold(0.0, f32::max)
}

/// Planted twin: the positions a decoder that skipped dequantisation would return — each
/// coordinate as its integer step on a `bits`-bit grid over the scene's bounds.
pub fn skip_dequantisation(scene: &Scene, bits: u32) -> Scene {
    let bounds = scene.bounds();
    let (lo, hi) = (bounds.min, bounds.max);
    let steps = ((1u32 << bits) - 1) as f32;
    let mut planted = scene.clone();
    for v in &mut planted.vertices {
        v.position = ((v.position - lo) / (hi - lo).max(Vec3::splat(1e-6)) * steps).round();
    }
    planted
}

/// Mean and largest absolute difference of two RGBA8 images' texels, in 8-bit units.
pub fn texel_errors(a: &[[u8; 4]], b: &[[u8; 4]]) -> (f64, u8) {
    assert_eq!(a.len(), b.len(), "texel counts differ");
    let mut sum = 0u64;
    let mut largest = 0u8;
    for (x, y) in a.iter().zip(b) {
        for c in 0..4 {
            let d = x[c].abs_diff(y[c]);
            sum += d as u64;
            largest = largest.max(d);
        }
    }
    (sum as f64 / (a.len() * 4) as f64, largest)
}

/// Planted twin: texels a decoder converting sRGB to linear would return (the renderer
/// decodes sRGB itself, so the loader must keep the encoded values).
pub fn srgb_to_linear(texels: &[[u8; 4]]) -> Vec<[u8; 4]> {
    let linear = |c: u8| {
        let c = c as f32 / 255.0;
        let l = if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        };
        (l * 255.0).round() as u8
    };
    texels
        .iter()
        .map(|p| [linear(p[0]), linear(p[1]), linear(p[2]), p[3]])
        .collect()
}

/// The decoded texels of an image file, as the loader stores them.
pub fn png_texels(path: &std::path::Path) -> Vec<[u8; 4]> {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
        .pixels()
        .map(|p| p.0)
        .collect()
}

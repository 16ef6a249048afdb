//! `EXT_meshopt_compression`, the bytes half: every compressed buffer view decoded (vertex
//! codec for ATTRIBUTES, index codecs for TRIANGLES and INDICES, then the OCTAHEDRAL,
//! QUATERNION or EXPONENTIAL filter) into the buffer bytes its accessors read, so that from
//! here on the view is read and checked like an uncompressed one (`data::check_accessor`, the
//! index range and finite-position checks of `primitives`).
//!
//! The decoder is meshoptimizer-rs's checked EXT entry point (`codec::BufferView::decode`): it
//! checks mode, filter, count and stride, refuses a stream shorter than the count needs
//! before allocating (so a corrupt count cannot make it allocate much more than the file
//! holds) and reports a malformed stream as an error.

use std::panic::{AssertUnwindSafe, catch_unwind};

use meshoptimizer_rs::Workspace;

use super::super::validate::SceneError;
use super::compressed::MeshoptView;

/// Decode every view of `views` into `buffers` (fallback buffers are empty until here).
/// Returns the decoded byte count.
pub(super) fn decode_views(
    file: &str,
    views: &[MeshoptView],
    fallback: &std::collections::BTreeMap<usize, usize>,
    buffers: &mut [Vec<u8>],
) -> Result<usize, SceneError> {
    for (&b, &length) in fallback {
        if let Some(buffer) = buffers.get_mut(b) {
            *buffer = vec![0; length];
        }
    }
    let mut total = 0;
    for view in views {
        let fail = |what: String| SceneError::invalid(file, format!("{}: {what}", view.label()));
        let (b, offset, length) = view.source;
        let source = buffers
            .get(b)
            .and_then(|data| data.get(offset..offset.checked_add(length)?))
            .ok_or_else(|| {
                fail(format!(
                    "its stream (bytes {offset}..+{length} of buffer {b}) is past the end of the \
                     buffer ({} bytes)",
                    buffers.get(b).map_or(0, Vec::len)
                ))
            })?;
        let decoded = decode(view, source).map_err(fail)?;
        let (b, offset) = view.target;
        let target = buffers
            .get_mut(b)
            .and_then(|data| data.get_mut(offset..offset.checked_add(decoded.len())?))
            .ok_or_else(|| {
                fail(format!(
                    "the view (bytes {offset}..+{} of buffer {b}) is past the end of the buffer",
                    decoded.len()
                ))
            })?;
        target.copy_from_slice(&decoded);
        total += decoded.len();
    }
    Ok(total)
}

/// One view's bytes. A panic inside the decoder (none is known) is caught here, so the
/// message still names the view and the extension.
fn decode(view: &MeshoptView, source: &[u8]) -> Result<Vec<u8>, String> {
    let run = || view.layout.decode(source, &mut Workspace::default());
    match catch_unwind(AssertUnwindSafe(run)) {
        Ok(Ok(bytes)) => Ok(bytes),
        Ok(Err(e)) => Err(format!("the stream does not decode ({e})")),
        Err(_) => Err("the decoder crashed on this stream".to_string()),
    }
}

#[cfg(test)]
mod tests {
    //! The three EXT_meshopt_compression filters through `decode_views`, against the spec's
    //! reference decoders written out here (Appendix "Filters"), on vectors of every sign:
    //! another meshopt port is known to get the quaternion filter wrong for negative
    //! components.
    use std::collections::BTreeMap;

    use meshoptimizer_rs::Workspace;
    use meshoptimizer_rs::codec::{
        BufferView, ExpMode, Filter, Mode, VertexEncoding, encode_filter_exp, encode_filter_oct,
        encode_filter_quat, encode_vertex_buffer,
    };

    use super::super::compressed::MeshoptView;
    use super::decode_views;

    /// Filtered bytes → vertex codec (version 0) → `decode_views` into a fallback buffer.
    fn through_loader(filtered: &[u8], filter: Filter, stride: usize) -> Vec<u8> {
        let count = filtered.len() / stride;
        let ws = &mut Workspace::default();
        let v0 = VertexEncoding::new(0, 0).unwrap();
        let stream = encode_vertex_buffer(filtered, count, stride, v0, ws).unwrap();
        let view = MeshoptView {
            view: 0,
            source: (0, 0, stream.len()),
            target: (1, 0),
            layout: BufferView::new(Mode::Attributes, filter, count, stride).unwrap(),
            names: ("ATTRIBUTES".into(), format!("{filter:?}")),
            count,
            stride,
        };
        let mut buffers = vec![stream, Vec::new()];
        let fallback = BTreeMap::from([(1, filtered.len())]);
        decode_views("test.gltf", &[view], &fallback, &mut buffers).unwrap();
        buffers.swap_remove(1)
    }

    fn i16s(bytes: &[u8]) -> Vec<i16> {
        bytes
            .chunks_exact(2)
            .map(|c| i16::from_le_bytes([c[0], c[1]]))
            .collect()
    }

    /// Unit vectors over the sphere, every octant (a golden-angle spiral).
    fn directions(n: usize) -> Vec<[f32; 3]> {
        (0..n)
            .map(|i| {
                let z = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
                let r = (1.0 - z * z).sqrt();
                let phi = i as f32 * 2.399_963;
                [r * phi.cos(), r * phi.sin(), z]
            })
            .collect()
    }

    #[test]
    fn octahedral_matches_the_spec_for_8_and_16_bits() {
        let normals = directions(200);
        let input: Vec<f32> = normals
            .iter()
            .flat_map(|n| [n[0], n[1], n[2], 0.0])
            .collect();
        for (stride, bits, one) in [(4, 8, 127.0f32), (8, 16, 32767.0)] {
            let ws = &mut Workspace::default();
            let filtered = encode_filter_oct(normals.len(), stride, bits, &input, ws).unwrap();
            let decoded = through_loader(&filtered, Filter::Octahedral, stride);
            let component = |bytes: &[u8], i: usize| match stride {
                4 => bytes[i] as i8 as f32,
                _ => i16::from_le_bytes([bytes[2 * i], bytes[2 * i + 1]]) as f32,
            };
            for (k, n) in normals.iter().enumerate() {
                let (e, d) = (&filtered[k * stride..], &decoded[k * stride..]);
                // Spec: z = c2 − |x| − |y|; where z < 0 the fold x −= sign(x)·(−z), same for
                // y; then normalise and scale to the component's range.
                let (mut x, mut y) = (component(e, 0), component(e, 1));
                let z = component(e, 2) - x.abs() - y.abs();
                let t = (-z).max(0.0);
                x -= t.copysign(x);
                y -= t.copysign(y);
                let l = (x * x + y * y + z * z).sqrt();
                let spec = [x, y, z].map(|c| (c / l * one).round() as i16);
                let got = [0, 1, 2].map(|i| component(d, i) as i16);
                assert_eq!(got, spec, "{n:?}");
                let error = (0..3)
                    .map(|i| (got[i] as f32 / one - n[i]).abs())
                    .fold(0.0, f32::max);
                assert!(error < 8.0 / one, "{n:?}: {got:?} is {error} off");
            }
        }
    }

    #[test]
    fn quaternion_matches_the_spec_for_every_sign() {
        // Unit quaternions with every sign pattern of (x, y, z, w) and each component largest.
        let mut quats: Vec<[f32; 4]> = Vec::new();
        for d in directions(64) {
            for signs in 0..16 {
                let s = |i: u32| if signs >> i & 1 == 1 { -1.0 } else { 1.0 };
                let q = [
                    d[0] * 0.8 * s(0),
                    d[1] * 0.8 * s(1),
                    d[2] * 0.8 * s(2),
                    0.6 * s(3),
                ];
                quats.push(q);
            }
        }
        let input: Vec<f32> = quats.iter().flatten().copied().collect();
        let ws = &mut Workspace::default();
        let filtered = encode_filter_quat(quats.len(), 8, 12, &input, ws).unwrap();
        let decoded = i16s(&through_loader(&filtered, Filter::Quaternion, 8));
        let encoded = i16s(&filtered);
        let mut truncation_differs = 0;
        for (k, q) in quats.iter().enumerate() {
            let e = &encoded[4 * k..4 * k + 4];
            // Spec: the 4th word holds the scale ("one", low 2 bits forced set) and, in its
            // low 2 bits, the index of the largest component, rebuilt from the other three.
            let one = (e[3] | 3) as f32;
            let range = std::f32::consts::FRAC_1_SQRT_2;
            let [x, y, z] = [0, 1, 2].map(|i| e[i] as f32 / one * range);
            let w = (1.0 - x * x - y * y - z * z).max(0.0).sqrt();
            let largest = (e[3] & 3) as usize;
            let mut spec = [0i16; 4];
            for (i, c) in [x, y, z].into_iter().enumerate() {
                spec[(largest + 1 + i) & 3] = (c * 32767.0).round() as i16;
            }
            spec[largest] = (w * 32767.0).round() as i16;
            let got = &decoded[4 * k..4 * k + 4];
            assert_eq!(got, spec, "{q:?}");
            // Planted twin: truncating toward zero instead of rounding (how a port goes wrong
            // on negative components) does not match the spec.
            truncation_differs += [x, y, z]
                .iter()
                .any(|c| (c * 32767.0).trunc() != (c * 32767.0).round())
                as usize;
            // And it is the quaternion (or its negation, the same rotation).
            let dot: f32 = (0..4).map(|i| got[i] as f32 / 32767.0 * q[i]).sum();
            assert!(dot.abs() > 0.999, "{q:?}: {got:?}, dot {dot}");
        }
        assert!(truncation_differs > quats.len() / 2, "{truncation_differs}");
    }

    #[test]
    fn exponential_matches_the_spec() {
        let values: Vec<f32> = (0..300)
            .map(|i| (i as f32 * 0.37).sin() * 10f32.powi(i % 9 - 4))
            .collect();
        let ws = &mut Workspace::default();
        let filtered = encode_filter_exp(100, 12, 15, &values, ExpMode::Separate, ws).unwrap();
        let decoded = through_loader(&filtered, Filter::Exponential, 12);
        for (k, v) in values.iter().enumerate() {
            let word = u32::from_le_bytes(filtered[4 * k..4 * k + 4].try_into().unwrap());
            // Spec: a 24-bit signed mantissa times 2 to an 8-bit signed exponent.
            let mantissa = ((word << 8) as i32) >> 8;
            let exponent = (word as i32) >> 24;
            let spec = mantissa as f32 * 2f32.powi(exponent);
            let got = f32::from_le_bytes(decoded[4 * k..4 * k + 4].try_into().unwrap());
            assert_eq!(got, spec, "{v}");
            assert!((got - v).abs() <= v.abs() * 2f32.powi(-14), "{v}: {got}");
        }
    }
}

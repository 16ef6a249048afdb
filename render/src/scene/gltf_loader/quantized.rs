//! Vertex attributes as f32, from float or integer accessors (core glTF's normalized
//! texture coordinates and everything `KHR_mesh_quantization` allows). The crate's accessor
//! iterator handles strides and sparse storage; this module only turns components into
//! floats, by the glTF 2.0 rules for normalized integers ("Animations" and "Meshes":
//! f = max(c / 127, −1) for i8, c / 255 for u8, max(c / 32767, −1) for i16, c / 65535 for
//! u16) or as plain integers when the accessor is not normalized. Any dequantization scale
//! and offset live in the node transform, which the loader applies afterwards.

use gltf::accessor::util::{Item, Iter};
use gltf::accessor::{Accessor, DataType};

/// One component type an attribute may use.
trait Component: Item + Copy {
    fn to_f32(self, normalized: bool) -> f32;
}

impl Component for f32 {
    fn to_f32(self, _: bool) -> f32 {
        self
    }
}

macro_rules! integer_component {
    ($t:ty, $signed:expr) => {
        impl Component for $t {
            fn to_f32(self, normalized: bool) -> f32 {
                let c = self as f32;
                match (normalized, $signed) {
                    (false, _) => c,
                    (true, true) => (c / <$t>::MAX as f32).max(-1.0),
                    (true, false) => c / <$t>::MAX as f32,
                }
            }
        }
    };
}
integer_component!(i8, true);
integer_component!(u8, false);
integer_component!(i16, true);
integer_component!(u16, false);

fn read<T: Component, const N: usize>(
    accessor: &Accessor,
    buffers: &[Vec<u8>],
    normalized: bool,
) -> Option<Vec<[f32; N]>>
where
    [T; N]: Item,
{
    let iter = Iter::<[T; N]>::new(accessor.clone(), |b| {
        buffers.get(b.index()).map(Vec::as_slice)
    })?;
    Some(iter.map(|c| c.map(|x| x.to_f32(normalized))).collect())
}

/// The accessor's elements as floats; `None` for a component type no vertex attribute may
/// have (u32) or unreadable data. `check_accessor` has checked the type and the ranges.
pub(super) fn read_floats<const N: usize>(
    accessor: &Accessor,
    buffers: &[Vec<u8>],
) -> Option<Vec<[f32; N]>>
where
    [f32; N]: Item,
    [i8; N]: Item,
    [u8; N]: Item,
    [i16; N]: Item,
    [u16; N]: Item,
{
    let normalized = accessor.normalized();
    match accessor.data_type() {
        DataType::F32 => read::<f32, N>(accessor, buffers, normalized),
        DataType::I8 => read::<i8, N>(accessor, buffers, normalized),
        DataType::U8 => read::<u8, N>(accessor, buffers, normalized),
        DataType::I16 => read::<i16, N>(accessor, buffers, normalized),
        DataType::U16 => read::<u16, N>(accessor, buffers, normalized),
        DataType::U32 => None,
    }
}

/// A normalized integer component `c` of type `data_type` as glTF reads it (for integers
/// that arrive as floats, from a Draco stream); floats and u32 are returned as they are.
pub(super) fn dequantize(c: f32, data_type: DataType) -> f32 {
    match data_type {
        DataType::I8 => (c as i8).to_f32(true),
        DataType::U8 => (c as u8).to_f32(true),
        DataType::I16 => (c as i16).to_f32(true),
        DataType::U16 => (c as u16).to_f32(true),
        DataType::F32 | DataType::U32 => c,
    }
}

#[cfg(test)]
mod tests {
    use super::Component;

    #[test]
    fn normalized_integers_follow_the_gltf_rules() {
        assert_eq!((-128i8).to_f32(true), -1.0);
        assert_eq!((-127i8).to_f32(true), -1.0);
        assert_eq!(127i8.to_f32(true), 1.0);
        assert_eq!(255u8.to_f32(true), 1.0);
        assert_eq!(51u8.to_f32(true), 0.2);
        assert_eq!((-32768i16).to_f32(true), -1.0);
        assert_eq!(16384i16.to_f32(true), 16384.0 / 32767.0);
        assert_eq!(65535u16.to_f32(true), 1.0);
        assert_eq!((-3i16).to_f32(false), -3.0);
        assert_eq!(300u16.to_f32(false), 300.0);
    }
}

//! Raw bytes: loading buffers (GLB chunk, external file or data URI) and proving that every
//! accessor we read lies inside them. The gltf crate's readers silently return `None` (or
//! panic on a zero count) for out-of-range data; these checks turn that into an error that
//! says which buffer and accessor are at fault.

use std::collections::BTreeMap;
use std::path::Path;

use gltf::accessor::{Accessor, DataType, Dimensions};
use gltf::buffer::{self, View};

use super::super::validate::{SceneError, one_line};
use super::compressed;

/// A label for a buffer in messages: its URI, or where its bytes live.
pub(super) fn buffer_label(buffer: &gltf::Buffer) -> String {
    if buffer.name() == Some(compressed::FALLBACK_NAME) {
        return compressed::FALLBACK_NAME.to_string();
    }
    match buffer.source() {
        buffer::Source::Bin => "GLB BIN chunk".to_string(),
        buffer::Source::Uri(uri) if uri.starts_with("data:") => "data URI".to_string(),
        buffer::Source::Uri(uri) => uri.to_string(),
    }
}

/// Read the bytes a URI names: a `data:` URI or a path relative to the glTF file.
pub(super) fn read_uri(
    file: &str,
    base: &Path,
    uri: &str,
    what: &str,
) -> Result<Vec<u8>, SceneError> {
    // The crate's buffer reader handles both data URIs and relative paths; images use it too.
    buffer::Data::from_source(buffer::Source::Uri(uri), Some(base))
        .map(|data| data.0)
        .map_err(|e| match e {
            gltf::Error::Io(source) => SceneError::Io {
                file: file.to_string(),
                what: what.to_string(),
                error: source,
            },
            other => SceneError::invalid(file, format!("{what}: {other}")),
        })
}

/// The bytes of an image URI, exactly: the crate's reader pads what it reads to a multiple
/// of 4 bytes (buffers want that), which would hand a cut-short KTX2 or WebP file its
/// missing bytes as zeros and hide it from the decoders' length checks.
pub(super) fn read_image_uri(
    file: &str,
    base: &Path,
    uri: &str,
    what: &str,
) -> Result<Vec<u8>, SceneError> {
    let mut bytes = read_uri(file, base, uri, what)?;
    if let Some(length) = unpadded_length(base, uri) {
        bytes.truncate(length);
    }
    Ok(bytes)
}

/// The length of what `uri` names before padding: a base64 data URI's decoded length, or a
/// file's size. `None` when it cannot be told (the padded bytes are then used).
fn unpadded_length(base: &Path, uri: &str) -> Option<usize> {
    if let Some(data) = uri.strip_prefix("data:") {
        let base64 = data.split_once(";base64,").map_or(data, |(_, b)| b);
        return Some(base64.trim_end_matches('=').len() * 6 / 8);
    }
    let path = match uri.strip_prefix("file://").or(uri.strip_prefix("file:")) {
        Some(path) => Path::new(path).to_path_buf(),
        None if uri.contains(':') => return None,
        None => base.join(uri),
    };
    std::fs::metadata(path).ok().map(|m| m.len() as usize)
}

/// The bytes of every buffer, in document order. A meshopt fallback buffer (in `fallback`)
/// is not read: it stays empty until its views are decoded (`meshopt::decode_views`).
pub(super) fn load_buffers(
    file: &str,
    doc: &gltf::Document,
    base: &Path,
    mut blob: Option<Vec<u8>>,
    fallback: &BTreeMap<usize, usize>,
) -> Result<Vec<Vec<u8>>, SceneError> {
    let mut buffers = Vec::new();
    for buffer in doc.buffers() {
        if fallback.contains_key(&buffer.index()) {
            buffers.push(Vec::new());
            continue;
        }
        let label = format!("buffer {} ('{}')", buffer.index(), buffer_label(&buffer));
        let data = match buffer.source() {
            buffer::Source::Bin => blob.take().ok_or_else(|| {
                SceneError::invalid(
                    file,
                    format!("{label} refers to a GLB BIN chunk that is missing"),
                )
            })?,
            buffer::Source::Uri(uri) => read_uri(file, base, uri, &label)?,
        };
        if data.len() < buffer.length() {
            // Not fatal by itself: the accessor checks report the first read past the end.
            log::warn!(
                "{file}: {label} is {} bytes but declares byteLength {}",
                data.len(),
                buffer.length()
            );
        }
        buffers.push(data);
    }
    for warning in views_past_declared_length(doc) {
        log::warn!("{file}: {warning}");
    }
    Ok(buffers)
}

/// One message per buffer view that ends past its buffer's declared `byteLength`. The
/// bytes may exist (a longer file than declared), so reads still work, but the file breaks
/// the spec and other tools will reject or truncate it: say which view and which buffer.
pub(super) fn views_past_declared_length(doc: &gltf::Document) -> Vec<String> {
    doc.views()
        .filter_map(|view| {
            let end = view.offset().saturating_add(view.length());
            let buffer = view.buffer();
            (end > buffer.length()).then(|| {
                format!(
                    "bufferView {} ends at byte {end}, past the declared byteLength {} of buffer {} ('{}')",
                    view.index(),
                    buffer.length(),
                    buffer.index(),
                    buffer_label(&buffer)
                )
            })
        })
        .collect()
}

/// The bytes of a buffer view (used for images stored in the binary buffer).
pub(super) fn view_bytes<'b>(
    file: &str,
    view: &View,
    buffers: &'b [Vec<u8>],
) -> Result<&'b [u8], SceneError> {
    let data = &buffers[view.buffer().index()];
    view.offset()
        .checked_add(view.length())
        .and_then(|end| data.get(view.offset()..end))
        .ok_or_else(|| {
            SceneError::invalid(
                file,
                format!(
                    "buffer {} ('{}') is {} bytes but bufferView {} needs {}",
                    view.buffer().index(),
                    buffer_label(&view.buffer()),
                    data.len(),
                    view.index(),
                    view.offset().saturating_add(view.length())
                ),
            )
        })
}

/// Check that `accessor` has one of the expected layouts and that every element it reads
/// (including sparse indices and values) lies inside its buffer view and buffer.
pub(super) fn check_accessor(
    file: &str,
    accessor: &Accessor,
    buffers: &[Vec<u8>],
    what: &str,
    types: &[DataType],
    dimensions: Dimensions,
) -> Result<(), SceneError> {
    let name = format!("accessor {} ({what})", accessor.index());
    if !types.contains(&accessor.data_type()) || accessor.dimensions() != dimensions {
        return Err(SceneError::invalid(
            file,
            format!(
                "{name} is {:?} {:?}, expected {dimensions:?} of {types:?}",
                accessor.dimensions(),
                accessor.data_type()
            ),
        ));
    }
    let element = accessor.size();
    match (accessor.view(), accessor.sparse()) {
        (None, None) => Err(SceneError::invalid(
            file,
            format!("{name} has no bufferView (all-zero accessors are not supported)"),
        )),
        (view, sparse) => {
            if let Some(view) = view {
                let range = Range {
                    offset: accessor.offset(),
                    count: accessor.count(),
                    element,
                };
                range.check(file, &name, &view, buffers)?;
            }
            if let Some(sparse) = sparse {
                let count = sparse.count();
                let indices = sparse.indices();
                let index_range = Range {
                    offset: indices.offset(),
                    count,
                    element: indices.index_type().size(),
                };
                index_range.check(
                    file,
                    &format!("{name} sparse indices"),
                    &indices.view(),
                    buffers,
                )?;
                let values = sparse.values();
                let value_range = Range {
                    offset: values.offset(),
                    count,
                    element,
                };
                value_range.check(
                    file,
                    &format!("{name} sparse values"),
                    &values.view(),
                    buffers,
                )?;
            }
            Ok(())
        }
    }
}

/// `count` elements of `element` bytes at `offset` in a buffer view, spaced by its stride.
struct Range {
    offset: usize,
    count: usize,
    element: usize,
}

impl Range {
    fn check(
        &self,
        file: &str,
        name: &str,
        view: &View,
        buffers: &[Vec<u8>],
    ) -> Result<(), SceneError> {
        let fail = |detail: String| Err(SceneError::invalid(file, one_line(detail)));
        if self.count == 0 {
            return fail(format!("{name} has count 0"));
        }
        let stride = view.stride().unwrap_or(self.element);
        if stride < self.element {
            return fail(format!(
                "{name}: byteStride {stride} is smaller than one element ({} bytes)",
                self.element
            ));
        }
        // Bytes from the start of the view to the end of the last element.
        let end_in_view = stride
            .checked_mul(self.count - 1)
            .and_then(|n| n.checked_add(self.offset))
            .and_then(|n| n.checked_add(self.element));
        let Some(end_in_view) = end_in_view else {
            return fail(format!("{name} is too large to address"));
        };
        let buffer = view.buffer();
        let data_len = buffers[buffer.index()].len();
        let label = || format!("buffer {} ('{}')", buffer.index(), buffer_label(&buffer));
        let end_in_buffer = view.offset().saturating_add(end_in_view);
        if end_in_buffer > data_len {
            return fail(format!(
                "{} is {data_len} bytes but {name} needs {end_in_buffer}",
                label()
            ));
        }
        if end_in_view > view.length() {
            return fail(format!(
                "{name} needs {end_in_view} bytes of bufferView {} which has {}",
                view.index(),
                view.length()
            ));
        }
        if view.offset().saturating_add(view.length()) > data_len {
            return fail(format!(
                "{} is {data_len} bytes but bufferView {} needs {}",
                label(),
                view.index(),
                view.offset().saturating_add(view.length())
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::views_past_declared_length;

    fn doc(view_length: usize) -> gltf::Document {
        let json = format!(
            r#"{{"asset": {{"version": "2.0"}},
                "buffers": [{{"uri": "mesh.bin", "byteLength": 36}}],
                "bufferViews": [{{"buffer": 0, "byteLength": 36}},
                                {{"buffer": 0, "byteOffset": 12, "byteLength": {view_length}}}]}}"#
        );
        gltf::Gltf::from_slice_without_validation(json.as_bytes())
            .unwrap()
            .document
    }

    #[test]
    fn a_view_past_its_buffers_byte_length_is_named() {
        assert!(views_past_declared_length(&doc(24)).is_empty());
        let warnings = views_past_declared_length(&doc(36));
        assert_eq!(
            warnings,
            [
                "bufferView 1 ends at byte 48, past the declared byteLength 36 of buffer 0 ('mesh.bin')"
            ]
        );
    }
}

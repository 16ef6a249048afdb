//! JSON/GLB → `gltf::Document`: the extension report and refusal, the JSON the gltf crate
//! (1.4) cannot read taken out first (KHR_animation_pointer channels, the compression
//! extensions), then the crate's schema validation.

use super::super::validate::{SceneError, one_line};
use super::compressed::{self, Compression};
use super::extensions::{self, ExtensionStatus, ExtensionUse};
use super::pointer_channels::{self, PointerChannel};

/// A parsed file and what was taken out of its JSON.
pub(super) struct Parsed {
    pub gltf: gltf::Gltf,
    pub pointers: Vec<PointerChannel>,
    pub extensions: Vec<ExtensionUse>,
    pub compression: Compression,
}

/// Parse JSON/GLB, report the extensions and refuse unsupported required ones
/// (`extensions`), then run the crate's schema validation. The crate's own
/// required-extension check is skipped because it does not know all the extensions this
/// loader reads (KHR_materials_specular, KHR_mesh_quantization, the compression ones).
pub(super) fn open_document(file: &str, bytes: &[u8]) -> Result<Parsed, SceneError> {
    let parse_error = |e: gltf::Error| SceneError::Parse {
        file: file.to_string(),
        detail: one_line(e.to_string()),
    };
    let rewritten = parse_rewritten(file, bytes)?;
    let (gltf, pointers, compression) = match rewritten {
        Some(r) => r,
        None => (
            gltf::Gltf::from_slice_without_validation(bytes).map_err(parse_error)?,
            Vec::new(),
            Compression::default(),
        ),
    };
    let mut json = gltf.document.into_json();
    let report = extensions::report(&json.extensions_used, &json.extensions_required);
    if let Some(detail) = extensions::refusal(&report) {
        return Err(SceneError::Unsupported {
            file: file.to_string(),
            detail,
        });
    }
    for e in report.iter().filter(|e| e.status != ExtensionStatus::Used) {
        log::info!("{file}: {e}");
    }
    json.extensions_required.clear();
    check_crate_assumptions(file, &json)?;
    let document = gltf::Document::from_json(json).map_err(parse_error)?;
    Ok(Parsed {
        gltf: gltf::Gltf {
            document,
            blob: gltf.blob,
        },
        pointers,
        extensions: report,
        compression,
    })
}

type Rewritten = (gltf::Gltf, Vec<PointerChannel>, Compression);

/// Files with KHR_animation_pointer channels or compression extensions: the JSON read as a
/// `serde_json::Value`, pointer channels taken out (the crate cannot deserialise them) and
/// the compression extensions read (`compressed::take`), then parsed as usual. `None` when
/// the file has neither, so every other file takes exactly the crate's own path.
fn parse_rewritten(file: &str, bytes: &[u8]) -> Result<Option<Rewritten>, SceneError> {
    let parse_error = |detail: String| SceneError::Parse {
        file: file.to_string(),
        detail: one_line(detail),
    };
    let is_glb = bytes.starts_with(b"glTF");
    let (json_bytes, blob) = if is_glb {
        let glb = gltf::binary::Glb::from_slice(bytes).map_err(|e| parse_error(e.to_string()))?;
        (glb.json.into_owned(), glb.bin.map(|b| b.into_owned()))
    } else {
        (bytes.to_vec(), None)
    };
    // Cheap tests first: most files mention neither.
    const POINTER: &[u8] = b"KHR_animation_pointer";
    let has_pointers = json_bytes.windows(POINTER.len()).any(|w| w == POINTER);
    let has_compression = compressed::mentions_compression(&json_bytes);
    if !has_pointers && !has_compression {
        return Ok(None);
    }
    let mut value: serde_json::Value =
        serde_json::from_slice(&json_bytes).map_err(|e| parse_error(e.to_string()))?;
    let pointers = if has_pointers {
        pointer_channels::take_pointer_channels(file, &mut value)?
    } else {
        Vec::new()
    };
    let compression = if has_compression {
        compressed::take(file, &mut value)?
    } else {
        Compression::default()
    };
    let root: gltf::json::Root =
        serde_json::from_value(value).map_err(|e| parse_error(e.to_string()))?;
    let gltf = gltf::Gltf {
        document: gltf::Document::from_json_without_validation(root),
        blob,
    };
    Ok(Some((gltf, pointers, compression)))
}

/// References the gltf crate (1.4.1) reads with `unwrap` or unchecked indexing before or
/// without validating them (each found by the mutation fuzz test): checked here first.
fn check_crate_assumptions(file: &str, json: &gltf::json::Root) -> Result<(), SceneError> {
    use gltf::json::validation::Checked;
    let fail = |detail: String| {
        Err(SceneError::Parse {
            file: file.to_string(),
            detail,
        })
    };
    // Validation indexes accessors[POSITION] before checking the index.
    let position = Checked::Valid(gltf::Semantic::Positions);
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let index = primitive.attributes.get(&position).map(|i| i.value());
            if let Some(index) = index.filter(|&i| i >= json.accessors.len()) {
                return fail(format!(
                    "meshes[{m}].primitives[{p}] POSITION refers to accessor {index} of {}",
                    json.accessors.len()
                ));
            }
        }
    }
    // `Image::source` unwraps the URI, or the MIME type of an image in a buffer view.
    for (i, image) in json.images.iter().enumerate() {
        match (&image.uri, &image.buffer_view, &image.mime_type) {
            (Some(_), None, _) | (None, Some(_), Some(_)) => {}
            (None, Some(_), None) => {
                return fail(format!("images[{i}] has a bufferView but no mimeType"));
            }
            _ => {
                return fail(format!(
                    "images[{i}] needs exactly one of uri and bufferView"
                ));
            }
        }
    }
    Ok(())
}

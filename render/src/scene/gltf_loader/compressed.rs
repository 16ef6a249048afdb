//! Compressed glTF, the JSON half: what `KHR_draco_mesh_compression`,
//! `EXT_meshopt_compression`, `KHR_texture_basisu` and `EXT_texture_webp` ask of the loader,
//! read from the raw JSON before the gltf crate (1.4) sees it, which knows none of them.
//!
//! - Textures: `source` becomes the extension's image (KTX2 first, then WebP), so the rest of
//!   the loader reads it like any other image (the format is told by the bytes, see
//!   `materials::decode_image`). A texture may leave out `source` when an extension gives one.
//! - meshopt: each compressed buffer view is recorded (`MeshoptView`), to be decoded into the
//!   bytes its accessors then read (`meshopt`). A fallback buffer (`"fallback": true`) has no
//!   data: its views are laid out again back to back, so it holds exactly their decoded bytes
//!   whatever `byteLength`/`byteOffset` the file claims (a corrupt claim cannot make the loader
//!   allocate more than the streams decode to).
//! - Draco: each compressed primitive is recorded (`DracoPrimitive`); its accessors have no
//!   buffer view, their data comes from the Draco stream (`draco`).

use std::collections::BTreeMap;

use meshoptimizer_rs::codec::{BufferView, Filter, Mode};
use serde_json::{Value, json};

use super::super::validate::SceneError;

pub(super) const DRACO: &str = "KHR_draco_mesh_compression";
pub(super) const MESHOPT: &str = "EXT_meshopt_compression";
pub(super) const BASISU: &str = "KHR_texture_basisu";
pub(super) const WEBP: &str = "EXT_texture_webp";

/// The name a fallback buffer is given, which messages show (`data::buffer_label`).
pub(super) const FALLBACK_NAME: &str = "EXT_meshopt_compression fallback, decoded";

/// Whether the JSON may need `take` (a cheap byte test: most files never mention these).
pub(super) fn mentions_compression(json: &[u8]) -> bool {
    [DRACO, MESHOPT, BASISU, WEBP]
        .iter()
        .any(|name| json.windows(name.len()).any(|w| w == name.as_bytes()))
}

/// What the loader decodes besides plain glTF. Empty for an uncompressed file.
#[derive(Debug, Default)]
pub(super) struct Compression {
    /// Draco primitives by (mesh, primitive index).
    pub draco: BTreeMap<(usize, usize), DracoPrimitive>,
    /// meshopt-compressed buffer views, in file order.
    pub meshopt: Vec<MeshoptView>,
    /// Fallback buffers (no bytes of their own) and their length once laid out again.
    pub fallback: BTreeMap<usize, usize>,
    /// Images a texture reads through KHR_texture_basisu or EXT_texture_webp, and which:
    /// their errors name the extension.
    pub images: BTreeMap<usize, &'static str>,
}

impl Compression {
    /// " (decoded from EXT_meshopt_compression bufferView N)" when `view` was decoded, for
    /// messages about data read from it; empty otherwise.
    pub fn origin(&self, view: Option<usize>) -> String {
        match view {
            Some(v) if self.meshopt.iter().any(|m| m.view == v) => {
                format!(" (decoded from {MESHOPT} bufferView {v})")
            }
            _ => String::new(),
        }
    }
}

/// One `KHR_draco_mesh_compression` object of a primitive.
#[derive(Debug)]
pub(super) struct DracoPrimitive {
    /// The buffer view holding the Draco stream.
    pub view: usize,
    /// glTF semantic (POSITION, NORMAL, TEXCOORD_0, ...) → Draco unique attribute id.
    pub attributes: BTreeMap<String, u32>,
}

/// One `EXT_meshopt_compression` buffer view.
#[derive(Debug)]
pub(super) struct MeshoptView {
    /// The glTF buffer view whose bytes this decodes to.
    pub view: usize,
    /// Where the compressed stream is: buffer, byte offset, byte length.
    pub source: (usize, usize, usize),
    /// Where the decoded bytes go: buffer, byte offset (the view's, after any new layout).
    pub target: (usize, usize),
    /// Validated mode, filter, count and stride.
    pub layout: BufferView,
    /// The mode and filter as the file names them, for messages.
    pub names: (String, String),
    pub count: usize,
    pub stride: usize,
}

impl MeshoptView {
    /// "bufferView 3: EXT_meshopt_compression (ATTRIBUTES, OCTAHEDRAL, 120 × 4 bytes)".
    pub fn label(&self) -> String {
        let (mode, filter) = &self.names;
        let (view, count, stride) = (self.view, self.count, self.stride);
        format!("bufferView {view}: {MESHOPT} ({mode}, {filter}, {count} × {stride} bytes)")
    }
}

/// Read (and where said above, rewrite) the compression extensions of `json`.
pub(super) fn take(file: &str, json: &mut Value) -> Result<Compression, SceneError> {
    prefer_extension_images(json);
    let fallback_buffers: Vec<usize> = array(json, "buffers")
        .iter()
        .enumerate()
        .filter(|(_, b)| b["extensions"][MESHOPT]["fallback"] == json!(true))
        .map(|(i, _)| i)
        .collect();
    let mut compression = Compression {
        draco: draco_primitives(file, json)?,
        images: extension_images(json),
        ..Compression::default()
    };
    give_draco_accessors_a_view(json, &compression.draco);
    let mut laid_out: BTreeMap<usize, usize> = fallback_buffers.iter().map(|&b| (b, 0)).collect();
    let views = json
        .get_mut("bufferViews")
        .and_then(Value::as_array_mut)
        .map(std::mem::take)
        .unwrap_or_default();
    let mut rewritten = Vec::with_capacity(views.len());
    for (i, mut view) in views.into_iter().enumerate() {
        let buffer = view["buffer"].as_u64().map(|b| b as usize);
        let fallback = buffer.filter(|b| laid_out.contains_key(b));
        let ext = &view["extensions"][MESHOPT];
        if ext.is_null() {
            if let Some(b) = fallback {
                return Err(SceneError::invalid(
                    file,
                    format!(
                        "bufferView {i} reads buffer {b}, a {MESHOPT} fallback buffer without \
                         data of its own, but is not compressed"
                    ),
                ));
            }
            rewritten.push(view);
            continue;
        }
        let mut m = meshopt_view(file, i, &view, ext)?;
        if laid_out.contains_key(&m.source.0) {
            return Err(SceneError::invalid(
                file,
                format!("{}: its stream is in a fallback buffer", m.label()),
            ));
        }
        if let Some(b) = fallback {
            // Back to back, 4-byte aligned, as the decoded views' only home.
            let end = laid_out.get_mut(&b).expect("a fallback buffer");
            let offset = end.next_multiple_of(4);
            *end = offset + m.layout.byte_length();
            view["byteOffset"] = json!(offset);
            m.target = (b, offset);
        }
        compression.meshopt.push(m);
        rewritten.push(view);
    }
    if let Some(views) = json.get_mut("bufferViews") {
        *views = Value::Array(rewritten);
    }
    for (&b, &length) in &laid_out {
        json["buffers"][b]["byteLength"] = json!(length.max(1));
        // Its name is only ever shown in messages: say where its bytes come from.
        json["buffers"][b]["name"] = json!(FALLBACK_NAME);
    }
    compression.fallback = laid_out;
    Ok(compression)
}

fn array<'a>(json: &'a Value, key: &str) -> &'a [Value] {
    json.get(key)
        .and_then(Value::as_array)
        .map_or(&[], Vec::as_slice)
}

/// A texture reads its KTX2 image when it has one, else its WebP image, else `source`.
fn prefer_extension_images(json: &mut Value) {
    let Some(textures) = json.get_mut("textures").and_then(Value::as_array_mut) else {
        return;
    };
    for texture in textures {
        let preferred = [BASISU, WEBP]
            .iter()
            .find_map(|ext| texture["extensions"][*ext].get("source").cloned());
        if let (Some(source), Some(object)) = (preferred, texture.as_object_mut()) {
            object.insert("source".to_string(), source);
        }
    }
}

fn extension_images(json: &Value) -> BTreeMap<usize, &'static str> {
    let mut images = BTreeMap::new();
    for texture in array(json, "textures") {
        for ext in [WEBP, BASISU] {
            if let Some(i) = index(&texture["extensions"][ext]["source"]) {
                images.insert(i, ext);
            }
        }
    }
    images
}

/// The gltf crate (1.4) refuses an accessor with neither a buffer view nor sparse storage,
/// which glTF allows and Draco primitives have (their data is in the stream). Such accessors
/// are pointed at their primitive's Draco view to pass validation; nothing reads them through
/// it (`draco::read` takes only their type), and a plain primitive sharing one fails the
/// accessor range check instead.
fn give_draco_accessors_a_view(json: &mut Value, draco: &BTreeMap<(usize, usize), DracoPrimitive>) {
    for (&(m, p), d) in draco {
        let primitive = &json["meshes"][m]["primitives"][p];
        let mut used: Vec<usize> = primitive["attributes"]
            .as_object()
            .into_iter()
            .flat_map(|a| a.values().filter_map(index))
            .collect();
        used.extend(index(&primitive["indices"]));
        for a in used {
            let accessors = json.get_mut("accessors").and_then(Value::as_array_mut);
            if let Some(accessor) = accessors.and_then(|all| all.get_mut(a)?.as_object_mut())
                && !accessor.contains_key("bufferView")
                && !accessor.contains_key("sparse")
            {
                accessor.insert("bufferView".to_string(), json!(d.view));
            }
        }
    }
}

fn draco_primitives(
    file: &str,
    json: &Value,
) -> Result<BTreeMap<(usize, usize), DracoPrimitive>, SceneError> {
    let mut found = BTreeMap::new();
    for (m, mesh) in array(json, "meshes").iter().enumerate() {
        for (p, primitive) in array(mesh, "primitives").iter().enumerate() {
            let ext = &primitive["extensions"][DRACO];
            if ext.is_null() {
                continue;
            }
            let fail = |what: &str| {
                SceneError::invalid(file, format!("mesh {m} primitive {p}: {DRACO}: {what}"))
            };
            let view = index(&ext["bufferView"]).ok_or_else(|| fail("no bufferView"))?;
            let attributes = ext["attributes"]
                .as_object()
                .ok_or_else(|| fail("no attributes"))?
                .iter()
                .map(|(semantic, id)| {
                    let id = id.as_u64().and_then(|id| u32::try_from(id).ok());
                    id.map(|id| (semantic.clone(), id))
                        .ok_or_else(|| fail(&format!("attribute {semantic} is not an id")))
                })
                .collect::<Result<_, _>>()?;
            found.insert((m, p), DracoPrimitive { view, attributes });
        }
    }
    Ok(found)
}

fn index(value: &Value) -> Option<usize> {
    value.as_u64().and_then(|v| usize::try_from(v).ok())
}

/// One view's extension object, checked against the spec's rules (mode, filter, count,
/// stride, and that it decodes to exactly the view's `byteLength`).
fn meshopt_view(
    file: &str,
    i: usize,
    view: &Value,
    ext: &Value,
) -> Result<MeshoptView, SceneError> {
    let fail =
        |what: String| SceneError::invalid(file, format!("bufferView {i}: {MESHOPT}: {what}"));
    let number = |key: &str, default: Option<usize>| {
        index(&ext[key])
            .or(if ext[key].is_null() { default } else { None })
            .ok_or_else(|| fail(format!("{key} is missing or not a whole number")))
    };
    let text = |key: &str, default: &'static str| {
        ext[key]
            .as_str()
            .or(ext[key].is_null().then_some(default))
            .map(str::to_string)
            .ok_or_else(|| fail(format!("{key} is not a string")))
    };
    let (buffer, offset, length) = (
        number("buffer", None)?,
        number("byteOffset", Some(0))?,
        number("byteLength", None)?,
    );
    let (stride, count) = (number("byteStride", None)?, number("count", None)?);
    let mode_name = text("mode", "")?;
    let filter_name = text("filter", "NONE")?;
    let mode = Mode::parse(&mode_name).map_err(|_| {
        fail(format!(
            "mode '{mode_name}' is not one of ATTRIBUTES, TRIANGLES, INDICES"
        ))
    })?;
    let filter = Filter::parse(&filter_name).map_err(|_| {
        fail(format!(
            "unknown filter '{filter_name}' (known: NONE, OCTAHEDRAL, QUATERNION, EXPONENTIAL)"
        ))
    })?;
    let layout = BufferView::new(mode, filter, count, stride).map_err(|e| {
        fail(format!(
            "mode {mode_name}, filter {filter_name}, count {count}, byteStride {stride}: {e}"
        ))
    })?;
    let view_length = index(&view["byteLength"]).unwrap_or(0);
    let view_stride = index(&view["byteStride"]);
    let parent_stride = if mode == Mode::Attributes {
        view_stride
    } else {
        None
    };
    layout.validate_parent(view_length, parent_stride).map_err(|_| {
        fail(format!(
            "decodes to {count} × {stride} = {} bytes but the view has byteLength {view_length}{}",
            layout.byte_length(),
            view_stride.map_or_else(String::new, |s| format!(" and byteStride {s}"))
        ))
    })?;
    let target = (
        index(&view["buffer"]).unwrap_or(usize::MAX),
        index(&view["byteOffset"]).unwrap_or(0),
    );
    Ok(MeshoptView {
        view: i,
        source: (buffer, offset, length),
        target,
        layout,
        names: (mode_name, filter_name),
        count,
        stride,
    })
}

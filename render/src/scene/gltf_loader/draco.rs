//! `KHR_draco_mesh_compression`: a primitive's vertices and triangles decoded from its Draco
//! stream (draco-core, a pure-Rust port of Google's decoder). Draco dequantizes on its own
//! (positions and texture coordinates by the stream's quantization grid, normals from their
//! octahedral code), so its float attributes are the vertex data; an integer attribute is
//! read as glTF reads one (`KHR_mesh_quantization`, by the accessor's `normalized`).
//!
//! The accessors of a Draco primitive have no buffer view: only their type is checked here.
//! The decoded points and faces then take the same path as plain data (`primitives`): the
//! index range check, the node transform and the finite-position check, and later
//! `validate::validate`. A stream that does not decode, or decodes to nothing usable, is one line
//! naming the primitive and the extension.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::rc::Rc;

use draco_core::{DataType as DracoType, DecoderBuffer, Mesh, MeshDecoder};
use glam::{Vec2, Vec3};
use gltf::accessor::{DataType, Dimensions};

use super::super::Vertex;
use super::super::validate::{SceneError, one_line};
use super::compressed::{DRACO, DracoPrimitive};
use super::data;
use super::quantized::dequantize;
use super::sources::{PrimitiveId, Sources};

/// The primitive's local vertices (POSITION, NORMAL, TEXCOORD_`uv_set`) and its triangle
/// list, from the Draco stream.
pub(super) fn read(
    file: &str,
    id: &PrimitiveId,
    primitive: &gltf::Primitive,
    draco: &DracoPrimitive,
    uv_set: u32,
    sources: &mut Sources,
) -> Result<(Vec<Vertex>, Vec<u32>), SceneError> {
    let doc = sources.doc;
    let fail = |what: String| {
        SceneError::invalid(
            file,
            format!("{id}: {DRACO} (bufferView {}): {what}", draco.view),
        )
    };
    let mesh = match sources.draco.0.get(&draco.view) {
        Some(mesh) => Rc::clone(mesh),
        None => {
            let view = doc.views().nth(draco.view).ok_or_else(|| {
                fail(format!(
                    "the bufferView does not exist ({} views)",
                    doc.views().len()
                ))
            })?;
            let bytes = data::view_bytes(file, &view, sources.buffers).map_err(|e| match e {
                SceneError::Invalid { detail, .. } => fail(detail),
                other => other,
            })?;
            let mesh = Rc::new(decode(bytes).map_err(fail)?);
            sources.draco.0.insert(draco.view, Rc::clone(&mesh));
            mesh
        }
    };
    let points = mesh.num_points();
    if mesh.num_faces() == 0 {
        return Err(fail(format!(
            "the stream decodes to {points} points and no triangles"
        )));
    }
    let indices: Vec<u32> = mesh.faces().iter().flatten().map(|p| p.0).collect();
    let channel = |semantic: &str, dims: Dimensions| -> Result<Option<Vec<f32>>, SceneError> {
        attribute(&mesh, draco, primitive, semantic, dims).map_err(fail)
    };
    let positions = channel("POSITION", Dimensions::Vec3)?
        .ok_or_else(|| fail("POSITION is not in the stream's attributes".to_string()))?;
    let mut vertices: Vec<Vertex> = positions
        .chunks_exact(3)
        .map(|p| Vertex {
            position: Vec3::new(p[0], p[1], p[2]),
            ..Vertex::default()
        })
        .collect();
    if let Some(i) = vertices.iter().position(|v| !v.position.is_finite()) {
        return Err(fail(format!(
            "point {i} decodes to a non-finite position {}",
            vertices[i].position
        )));
    }
    if let Some(normals) = channel("NORMAL", Dimensions::Vec3)? {
        for (v, n) in vertices.iter_mut().zip(normals.chunks_exact(3)) {
            v.normal = Vec3::new(n[0], n[1], n[2]);
        }
    }
    if let Some(uvs) = channel(&format!("TEXCOORD_{uv_set}"), Dimensions::Vec2)? {
        for (v, uv) in vertices.iter_mut().zip(uvs.chunks_exact(2)) {
            v.uv = Vec2::new(uv[0], uv[1]);
        }
    }
    if let Some(accessor) = primitive.get(&gltf::Semantic::Positions)
        && accessor.count() != points
    {
        // Web viewers draw what the stream decodes to; so does this loader, with a warning.
        log::warn!(
            "{file}: {id}: {DRACO}: the stream decodes to {points} points but the POSITION \
             accessor says {}; the decoded points are used",
            accessor.count()
        );
    }
    Ok((vertices, indices))
}

/// Decode a stream; a decoder panic (none is known) becomes an error like any other.
fn decode(bytes: &[u8]) -> Result<Mesh, String> {
    let run = || {
        let mut mesh = Mesh::new();
        MeshDecoder::new()
            .decode(&mut DecoderBuffer::new(bytes), &mut mesh)
            .map(|()| mesh)
    };
    match catch_unwind(AssertUnwindSafe(run)) {
        Ok(Ok(mesh)) => Ok(mesh),
        Ok(Err(e)) => Err(one_line(format!("the stream does not decode ({e})"))),
        Err(_) => Err("the decoder crashed on this stream".to_string()),
    }
}

/// One attribute as floats, `dims` components per point; `None` when the primitive or the
/// stream does not name it.
fn attribute(
    mesh: &Mesh,
    draco: &DracoPrimitive,
    primitive: &gltf::Primitive,
    semantic: &str,
    dims: Dimensions,
) -> Result<Option<Vec<f32>>, String> {
    let Some(&unique_id) = draco.attributes.get(semantic) else {
        return Ok(None);
    };
    let accessor = primitive
        .attributes()
        .find(|(s, _)| s.to_string() == semantic)
        .map(|(_, a)| a);
    let attribute = mesh.attribute_by_unique_id(unique_id).ok_or_else(|| {
        format!("{semantic} is Draco attribute {unique_id}, which the stream lacks")
    })?;
    let components = dims.multiplicity();
    if let Some(accessor) = &accessor
        && accessor.dimensions() != dims
    {
        return Err(format!(
            "{semantic} (accessor {}) is {:?}, expected {dims:?}",
            accessor.index(),
            accessor.dimensions()
        ));
    }
    if (attribute.num_components() as usize) < components {
        return Err(format!(
            "{semantic} (Draco attribute {unique_id}) has {} components, {components} needed",
            attribute.num_components()
        ));
    }
    let mut values = attribute.read_f32s(mesh.num_points(), components);
    let normalized = accessor.as_ref().is_some_and(|a| a.normalized());
    if let Some(data_type) = integer_type(attribute.data_type()).filter(|_| normalized) {
        values
            .iter_mut()
            .for_each(|v| *v = dequantize(*v, data_type));
    }
    Ok(Some(values))
}

/// The glTF component type of an integer Draco attribute (`None` for floats and types glTF
/// vertex attributes do not have).
fn integer_type(t: DracoType) -> Option<DataType> {
    match t {
        DracoType::Int8 => Some(DataType::I8),
        DracoType::Uint8 => Some(DataType::U8),
        DracoType::Int16 => Some(DataType::I16),
        DracoType::Uint16 => Some(DataType::U16),
        _ => None,
    }
}

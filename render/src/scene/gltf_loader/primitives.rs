//! One glTF primitive → world-space vertices and counter-clockwise triangles appended to the
//! scene. Every accessor is range-checked first (see `data`), so the crate's readers cannot
//! run past the end of a buffer.

use glam::{Mat3, Mat4, Vec2, Vec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;

use super::super::validate::SceneError;
use super::super::{Scene, Triangle, Vertex};
use super::compressed::DRACO;
use super::data::check_accessor;
use super::draco;
use super::quantized::read_floats;
use super::sources::{PrimitiveId, Sources};

/// Append `primitive`, transformed by `world`, with every triangle using `material`.
/// Returns the vertices in the primitive's local space (kept for nodes that move).
pub(super) fn append_primitive(
    file: &str,
    id: &PrimitiveId,
    primitive: &gltf::Primitive,
    sources: &mut Sources,
    world: Mat4,
    material: u32,
    scene: &mut Scene,
) -> Result<Vec<Vertex>, SceneError> {
    let fail = |detail: String| SceneError::invalid(file, format!("{id}: {detail}"));
    let mut mode = primitive.mode();
    if !matches!(
        mode,
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    ) {
        return Err(SceneError::Unsupported {
            file: file.to_string(),
            detail: format!(
                "{id} has mode {mode:?}; only triangles (lists, strips, fans) can be rendered"
            ),
        });
    }
    let uv_set = scene
        .materials
        .get(material as usize)
        .map_or(0, |m| m.uv_set());
    let compression = sources.compression;
    let draco = compression.draco.get(&(id.mesh.index(), id.index));
    let (local, indices) = match draco {
        Some(draco) => {
            // Draco faces are triangles whatever the mode says.
            mode = Mode::Triangles;
            draco::read(file, id, primitive, draco, uv_set, sources)?
        }
        None => {
            let local = read_vertices(file, id, primitive, sources.buffers, uv_set)?;
            let indices = read_indices(file, id, primitive, sources.buffers, local.len())?;
            (local, indices)
        }
    };
    // Where the data came from, for the messages below (meshopt-decoded views are named).
    let origin = |accessor: Option<gltf::Accessor>| match draco {
        Some(d) => format!(" (decoded from {DRACO} bufferView {})", d.view),
        None => compression.origin(accessor.and_then(|a| a.view()).map(|v| v.index())),
    };
    if let Some(&bad) = indices.iter().find(|&&i| i as usize >= local.len()) {
        return Err(fail(format!(
            "index {bad} is out of range ({} vertices){}",
            local.len(),
            origin(primitive.indices())
        )));
    }
    let base = u32::try_from(scene.vertices.len())
        .ok()
        .filter(|b| b.checked_add(local.len() as u32).is_some())
        .ok_or_else(|| fail("the scene has more than 2^32 vertices".into()))?;

    // Normals transform by the inverse transpose; a mirroring transform flips the winding,
    // so two indices are swapped to keep the front face counter-clockwise.
    let normal_matrix = Mat3::from_mat4(world).inverse().transpose();
    let mirrored = Mat3::from_mat4(world).determinant() < 0.0;
    for (i, v) in local.iter().enumerate() {
        let position = world.transform_point3(v.position);
        if !position.is_finite() {
            return Err(fail(format!(
                "vertex {i} has a non-finite position {position}{}",
                origin(primitive.get(&gltf::Semantic::Positions))
            )));
        }
        scene.vertices.push(Vertex {
            position,
            normal: (normal_matrix * v.normal).normalize_or_zero(),
            uv: v.uv,
        });
    }
    let triangles = triangle_list(mode, &indices);
    if mode == Mode::Triangles && indices.len() % 3 != 0 {
        log::warn!(
            "{file}: {id}: {} indices is not a multiple of 3; the rest is ignored",
            indices.len()
        );
    }
    scene
        .triangles
        .extend(triangles.into_iter().map(|[a, b, c]| Triangle {
            indices: if mirrored {
                [base + a, base + c, base + b]
            } else {
                [base + a, base + b, base + c]
            },
            material,
        }));
    Ok(local)
}

/// The primitive's indices as u32 (0, 1, 2, ... without an index accessor).
fn read_indices(
    file: &str,
    id: &PrimitiveId,
    primitive: &gltf::Primitive,
    buffers: &[Vec<u8>],
    vertex_count: usize,
) -> Result<Vec<u32>, SceneError> {
    let Some(accessor) = primitive.indices() else {
        return Ok((0..vertex_count as u32).collect());
    };
    check_accessor(
        file,
        &accessor,
        buffers,
        &format!("{id} indices"),
        &[DataType::U8, DataType::U16, DataType::U32],
        Dimensions::Scalar,
    )?;
    let reader = primitive.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
    Ok(reader
        .read_indices()
        .ok_or_else(|| SceneError::invalid(file, format!("{id}: indices unreadable")))?
        .into_u32()
        .collect())
}

/// POSITION (required), NORMAL (optional, zero when absent) and TEXCOORD_`uv_set`
/// (optional) in the primitive's local space, as floats: `KHR_mesh_quantization`'s integer
/// types are dequantized by the accessor's `normalized` flag (see `quantized`).
fn read_vertices(
    file: &str,
    id: &PrimitiveId,
    primitive: &gltf::Primitive,
    buffers: &[Vec<u8>],
    uv_set: u32,
) -> Result<Vec<Vertex>, SceneError> {
    use DataType::{F32, I8, I16, U8, U16};
    let fail = |detail: String| SceneError::invalid(file, format!("{id}: {detail}"));
    let positions = primitive
        .get(&gltf::Semantic::Positions)
        .ok_or_else(|| fail("has no POSITION".into()))?;
    let count = positions.count();
    let checked = |semantic: gltf::Semantic, types: &[DataType], dims: Dimensions| {
        let Some(accessor) = primitive.get(&semantic) else {
            return Ok(None);
        };
        check_accessor(
            file,
            &accessor,
            buffers,
            &format!("{id} {}", semantic.to_string()),
            types,
            dims,
        )?;
        if accessor.count() != count {
            return Err(fail(format!(
                "{} has {} elements but POSITION has {count}",
                semantic.to_string(),
                accessor.count()
            )));
        }
        Ok(Some(accessor))
    };
    let unreadable = |semantic: &str| fail(format!("{semantic} unreadable"));
    let positions = checked(
        gltf::Semantic::Positions,
        &[F32, I8, U8, I16, U16],
        Dimensions::Vec3,
    )?
    .ok_or_else(|| fail("has no POSITION".into()))?;
    let mut vertices: Vec<Vertex> = read_floats::<3>(&positions, buffers)
        .ok_or_else(|| unreadable("POSITION"))?
        .into_iter()
        .map(|p| Vertex {
            position: Vec3::from_array(p),
            ..Vertex::default()
        })
        .collect();
    if let Some(normals) = checked(gltf::Semantic::Normals, &[F32, I8, I16], Dimensions::Vec3)? {
        if normals.data_type() != F32 && !normals.normalized() {
            return Err(fail(format!(
                "NORMAL (accessor {}) is {:?} but not normalized; KHR_mesh_quantization \
                 allows integer normals only as normalized values",
                normals.index(),
                normals.data_type()
            )));
        }
        let normals = read_floats::<3>(&normals, buffers).ok_or_else(|| unreadable("NORMAL"))?;
        for (v, n) in vertices.iter_mut().zip(normals) {
            v.normal = Vec3::from_array(n);
        }
    }
    let uvs = checked(
        gltf::Semantic::TexCoords(uv_set),
        &[F32, I8, U8, I16, U16],
        Dimensions::Vec2,
    )?;
    match uvs {
        Some(uvs) => {
            let uvs = read_floats::<2>(&uvs, buffers)
                .ok_or_else(|| unreadable(&format!("TEXCOORD_{uv_set}")))?;
            for (v, uv) in vertices.iter_mut().zip(uvs) {
                v.uv = Vec2::from_array(uv);
            }
        }
        None if uv_set != 0 => log::warn!(
            "{file}: {id}: its material reads TEXCOORD_{uv_set}, which the primitive lacks; \
             uvs are 0"
        ),
        None => {}
    }
    Ok(vertices)
}

/// Triangle list from any triangle mode, in the glTF spec's vertex order for strips and fans
/// (which keeps every triangle's winding consistent with the first).
fn triangle_list(mode: Mode, indices: &[u32]) -> Vec<[u32; 3]> {
    let n = indices.len();
    match mode {
        Mode::TriangleStrip => (0..n.saturating_sub(2))
            .map(|i| {
                let odd = i % 2;
                [indices[i], indices[i + 1 + odd], indices[i + 2 - odd]]
            })
            .collect(),
        Mode::TriangleFan => (1..n.saturating_sub(1))
            .map(|i| [indices[i], indices[i + 1], indices[0]])
            .collect(),
        _ => indices
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_become_consistently_wound_lists() {
        // A strip over a quad 0-1-2-3: triangles (0,1,2) and (1,3,2) wind the same way.
        assert_eq!(
            triangle_list(Mode::TriangleStrip, &[0, 1, 2, 3]),
            vec![[0, 1, 2], [1, 3, 2]]
        );
        assert_eq!(
            triangle_list(Mode::TriangleFan, &[0, 1, 2, 3]),
            vec![[1, 2, 0], [2, 3, 0]]
        );
        assert_eq!(
            triangle_list(Mode::Triangles, &[0, 1, 2, 3]),
            vec![[0, 1, 2]]
        );
        assert!(triangle_list(Mode::TriangleStrip, &[0, 1]).is_empty());
    }
}

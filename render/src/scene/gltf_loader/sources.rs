//! What a primitive is read from and how it is named in errors: shared by the plain reader
//! (`primitives`) and the Draco decoder (`draco`) it hands compressed primitives to, and
//! kept below both so that the decoder need not import its caller.

use std::collections::HashMap;
use std::rc::Rc;

use draco_core::Mesh;

use super::compressed::Compression;

/// Where a primitive sits in the file, for error messages.
pub(super) struct PrimitiveId<'a> {
    pub mesh: &'a gltf::Mesh<'a>,
    pub index: usize,
}

impl std::fmt::Display for PrimitiveId<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.mesh.name() {
            Some(name) => write!(
                f,
                "mesh {} ('{name}') primitive {}",
                self.mesh.index(),
                self.index
            ),
            None => write!(f, "mesh {} primitive {}", self.mesh.index(), self.index),
        }
    }
}

/// What primitives are read from: the buffers (meshopt views already decoded into them) and
/// the Draco streams, decoded on first use.
pub(super) struct Sources<'a> {
    pub doc: &'a gltf::Document,
    pub buffers: &'a [Vec<u8>],
    pub compression: &'a Compression,
    pub draco: DracoCache,
}

/// Decoded Draco streams by buffer view: a mesh instanced by several nodes is decoded once.
#[derive(Default)]
pub(super) struct DracoCache(pub HashMap<usize, Rc<Mesh>>);

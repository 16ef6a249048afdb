//! How a pass describes itself: its shader, what its group-2 bindings name (binding i is
//! entry i), and how it is dispatched. The bind group layout, the bind group and the
//! dispatch all follow from this one declaration.

use super::resources::Resource;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Access {
    Read,
    ReadWrite,
}

#[derive(Clone, Copy, Debug)]
pub struct Binding {
    pub resource: Resource,
    pub access: Access,
}

/// A binding the shader only reads (storage `read`, a uniform or a sampled texture).
pub const fn read(resource: Resource) -> Binding {
    Binding {
        resource,
        access: Access::Read,
    }
}

/// A binding the shader writes (storage `read_write` or a write-only storage texture).
pub const fn write(resource: Resource) -> Binding {
    Binding {
        resource,
        access: Access::ReadWrite,
    }
}

/// `head` then `tail`: the group of a pass whose family binds the same last bindings
/// (PT's outputs). `N` must be `H + T`; a wrong `N` fails when the constant is compiled.
pub const fn concat<const H: usize, const T: usize, const N: usize>(
    head: [Binding; H],
    tail: [Binding; T],
) -> [Binding; N] {
    assert!(
        H + T == N,
        "a concatenated group's length is the sum of its parts"
    );
    let mut out = [read(Resource::Surfaces); N];
    let mut i = 0;
    while i < N {
        out[i] = if i < H { head[i] } else { tail[i - H] };
        i += 1;
    }
    out
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dispatch {
    /// One invocation per pixel, in 8 × 8 workgroups.
    Pixels,
    /// `invocations` in 1-D workgroups of `workgroup`.
    Threads { invocations: u32, workgroup: u32 },
    /// The G-buffer raster: one draw of every triangle into the visibility target.
    Raster,
}

#[derive(Debug)]
pub struct PassDef {
    /// Shown in timings, `last_passes` and the stats JSON.
    pub name: &'static str,
    pub shader: &'static str,
    /// Group 2 (groups 0 frame and 1 scene are shared by every pass).
    pub group: &'static [Binding],
    pub dispatch: Dispatch,
}

impl PassDef {
    pub fn reads_pass_info(&self) -> bool {
        self.group
            .iter()
            .any(|b| matches!(b.resource, Resource::PassInfo))
    }
}

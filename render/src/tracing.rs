//! The two tracing backends behind one interface. Every pass calls the functions of
//! `shaders/common/trace.wgsl` (`trace_closest`, `trace_any`, `trace_transmittance`, and the
//! `_in` variants that name last frame's geometry); which implementation is compiled behind
//! them is this choice, made per pipeline variant (the `RAY_QUERY` define):
//!
//! - **software**: the binned-SAH BVH built on the CPU (`scene/bvh.rs`), walked by a stack
//!   loop in WGSL (`trace_bvh.wgsl`). Any adapter; refitted and rebuilt for animated scenes
//!   (`gpu_scene/rebuild.rs`).
//! - **ray-query**: the driver's acceleration structures (`gpu_scene/accel.rs`: a BLAS for
//!   the static scene, one per distinct moving mesh, a TLAS of their instances per frame)
//!   queried with WGSL ray queries (`trace_ray_query.wgsl`). Needs wgpu's
//!   `EXPERIMENTAL_RAY_QUERY` (Vulkan `VK_KHR_ray_query`).
//!
//! Both apply the same hit rules (`take_hit` in trace.wgsl: culling, alpha mask, the
//! transparent layers' product), so they give the same image up to ties between equally
//! near hits.

use crate::gpu::Gpu;
use crate::settings::RayBackendChoice;

/// The backend a pipeline variant is compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RayBackend {
    Software,
    RayQuery,
}

impl RayBackend {
    /// The name `ray_backend` takes, shown in the Stats panel, `--stats` and bench tables.
    pub fn name(self) -> &'static str {
        match self {
            RayBackend::Software => "software",
            RayBackend::RayQuery => "ray-query",
        }
    }

    /// The WGSL define that selects the implementation (none for the software BVH).
    pub fn define(self) -> Option<&'static str> {
        match self {
            RayBackend::Software => None,
            RayBackend::RayQuery => Some(RAY_QUERY_DEFINE),
        }
    }

    /// The backend a set of defines compiles (what a pipeline's layout must match).
    pub fn of_defines(defines: &std::collections::BTreeSet<String>) -> RayBackend {
        if defines.contains(RAY_QUERY_DEFINE) {
            RayBackend::RayQuery
        } else {
            RayBackend::Software
        }
    }
}

/// Compiles trace_ray_query.wgsl behind trace.wgsl (and `enable wgpu_ray_query;`).
pub const RAY_QUERY_DEFINE: &str = "RAY_QUERY";

pub use crate::gpu::RayQueryUnavailable;

/// What a device offers the choice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Device<'a> {
    pub ray_query: bool,
    /// A CPU implementation (lavapipe): its ray queries are software too, and slower than
    /// this project's BVH (docs/src/measured/compile-and-load.md "Ray queries"), so `auto` keeps
    /// the BVH there.
    pub is_cpu: bool,
    pub adapter: &'a str,
}

/// What `choice` means on `device`: `auto` takes hardware ray queries where the device is
/// a GPU that has them, the software BVH elsewhere.
pub fn resolve(
    choice: RayBackendChoice,
    device: Device,
) -> Result<RayBackend, RayQueryUnavailable> {
    match (choice, device.ray_query) {
        (RayBackendChoice::Software, _) | (RayBackendChoice::Auto, false) => {
            Ok(RayBackend::Software)
        }
        (RayBackendChoice::Auto, true) if device.is_cpu => Ok(RayBackend::Software),
        (RayBackendChoice::RayQuery | RayBackendChoice::Auto, true) => Ok(RayBackend::RayQuery),
        (RayBackendChoice::RayQuery, false) => Err(RayQueryUnavailable {
            adapter: device.adapter.to_string(),
            hint: if std::env::var(crate::gpu::NO_RAY_QUERY_ENV).is_ok_and(|v| v == "1") {
                format!(", switched off by {}=1", crate::gpu::NO_RAY_QUERY_ENV)
            } else {
                "; lavapipe has them from Mesa 25".to_string()
            },
        }),
    }
}

/// `resolve` for this device.
pub fn resolve_for(gpu: &Gpu, choice: RayBackendChoice) -> Result<RayBackend, RayQueryUnavailable> {
    let adapter = gpu.adapter_name();
    resolve(
        choice,
        Device {
            ray_query: gpu.ray_query,
            is_cpu: gpu.is_cpu(),
            adapter: &adapter,
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn device(ray_query: bool, is_cpu: bool) -> Device<'static> {
        Device {
            ray_query,
            is_cpu,
            adapter: "llvmpipe (Vulkan)",
        }
    }

    #[test]
    fn auto_takes_ray_queries_on_a_gpu_that_has_them() {
        let auto = RayBackendChoice::Auto;
        assert_eq!(resolve(auto, device(true, false)), Ok(RayBackend::RayQuery));
        assert_eq!(
            resolve(auto, device(false, false)),
            Ok(RayBackend::Software)
        );
        // lavapipe: its ray queries run on the CPU, slower than the BVH.
        assert_eq!(resolve(auto, device(true, true)), Ok(RayBackend::Software));
        let software = RayBackendChoice::Software;
        assert_eq!(
            resolve(software, device(true, false)),
            Ok(RayBackend::Software)
        );
        let forced = RayBackendChoice::RayQuery;
        assert_eq!(
            resolve(forced, device(true, true)),
            Ok(RayBackend::RayQuery)
        );
    }

    #[test]
    fn ray_query_without_the_feature_is_one_line_naming_the_adapter() {
        let e = resolve(RayBackendChoice::RayQuery, device(false, true)).unwrap_err();
        let text = e.to_string();
        assert!(!text.contains('\n'), "{text}");
        assert!(text.contains("llvmpipe (Vulkan)"), "{text}");
        assert!(text.contains("ray_backend=software"), "{text}");
    }
}

//! Adapter and device creation with the features and limits the passes need, and a clear
//! error when there is no adapter at all (e.g. a machine without lavapipe).

use std::sync::{Arc, Mutex};

/// Storage buffers one shader stage binds at most (scene group + pass group + stats): 24
/// for ReSTIR PT's temporal pass (14 scene buffers with the previous frame's triangles,
/// materials, punctual lights and BVH nodes, the environment table and the ray-query
/// triangle map, 9 of its own with the light BVH's two, the stats). Desktop adapters offer
/// far more (Metal 31, Mesa 22's lavapipe 32, Vulkan and D3D12 drivers thousands).
const STORAGE_BUFFERS_PER_STAGE: u32 = 24;

/// Set to `1` to create the device without ray queries even where the adapter has them, as
/// on an adapter without (testing the software backend's fallback and the error of
/// `ray_backend=ray-query`; working around a driver's ray-query bug).
pub const NO_RAY_QUERY_ENV: &str = "RESTIR_NO_RAY_QUERY";

#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    #[error(
        "no GPU adapter found ({0}). On a machine without a GPU driver install Mesa's \
         lavapipe (Vulkan on the CPU) and the Vulkan loader: `.ci/setup` in the repository \
         does it on Debian/Ubuntu (or: sudo apt-get install mesa-vulkan-drivers libvulkan1), \
         then run again"
    )]
    NoAdapter(String),
    #[error("the GPU adapter '{adapter}' is not capable enough: {problem}")]
    Unsupported { adapter: String, problem: String },
    #[error("cannot create the GPU device: {0}")]
    Device(String),
    #[error("GPU error: {0}")]
    Validation(String),
    #[error(transparent)]
    RayQueryUnavailable(#[from] RayQueryUnavailable),
}

/// Why `ray_backend=ray-query` cannot run on this device (one line for the CLI and the
/// viewer).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "ray_backend=ray-query: the adapter '{adapter}' has no hardware ray queries \
     (wgpu EXPERIMENTAL_RAY_QUERY / VK_KHR_ray_query{hint}); use ray_backend=software or auto"
)]
pub struct RayQueryUnavailable {
    pub adapter: String,
    /// Why, when known (the environment switch that turned them off).
    pub(crate) hint: String,
}

/// A device and queue plus what the renderer needs to know about them.
#[derive(Clone)]
pub struct Gpu {
    pub instance: wgpu::Instance,
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    /// Whether passes can be timed with timestamp queries.
    pub timestamps: bool,
    /// Whether the device has hardware ray queries (`EXPERIMENTAL_RAY_QUERY`: Vulkan's
    /// `VK_KHR_ray_query`), so the `ray-query` tracing backend can run (see `tracing.rs`).
    pub ray_query: bool,
    /// The first uncaptured GPU error since the last `take_error` (instead of a panic).
    errors: Arc<Mutex<Option<String>>>,
}

impl Gpu {
    /// A device without a window (tests, `render`, `bench`).
    pub fn new_headless() -> Result<Gpu, GpuError> {
        Gpu::headless(true)
    }

    /// A device without ray queries even where the adapter has them: what an adapter
    /// without them gives (tests of the software fallback and of the error).
    pub fn new_headless_without_ray_queries() -> Result<Gpu, GpuError> {
        Gpu::headless(false)
    }

    fn headless(allow_ray_query: bool) -> Result<Gpu, GpuError> {
        let instance = new_instance();
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            apply_limit_buckets: false,
        }))
        .map_err(|e| GpuError::NoAdapter(e.to_string()))?;
        Gpu::from_adapter_with(instance, adapter, allow_ray_query)
    }

    /// Requests the device on an adapter chosen by the caller (the viewer picks one that
    /// can present to its window).
    pub fn from_adapter(instance: wgpu::Instance, adapter: wgpu::Adapter) -> Result<Gpu, GpuError> {
        Gpu::from_adapter_with(instance, adapter, true)
    }

    fn from_adapter_with(
        instance: wgpu::Instance,
        adapter: wgpu::Adapter,
        allow_ray_query: bool,
    ) -> Result<Gpu, GpuError> {
        let info = adapter.get_info();
        let adapter_limits = adapter.limits();
        if adapter_limits.max_storage_buffers_per_shader_stage < STORAGE_BUFFERS_PER_STAGE {
            return Err(GpuError::Unsupported {
                adapter: info.name.clone(),
                problem: format!(
                    "{} storage buffers per shader stage, {STORAGE_BUFFERS_PER_STAGE} needed",
                    adapter_limits.max_storage_buffers_per_shader_stage
                ),
            });
        }
        let timestamps = adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        let ray_query = allow_ray_query
            && adapter
                .features()
                .contains(wgpu::Features::EXPERIMENTAL_RAY_QUERY)
            && std::env::var(NO_RAY_QUERY_ENV).map_or(true, |v| v != "1");
        let mut features = wgpu::Features::empty();
        if timestamps {
            features |= wgpu::Features::TIMESTAMP_QUERY;
        }
        if ray_query {
            features |= wgpu::Features::EXPERIMENTAL_RAY_QUERY;
        }
        let base_limits = wgpu::Limits {
            max_storage_buffers_per_shader_stage: STORAGE_BUFFERS_PER_STAGE,
            max_storage_buffer_binding_size: adapter_limits.max_storage_buffer_binding_size,
            max_buffer_size: adapter_limits.max_buffer_size,
            max_texture_dimension_2d: adapter_limits.max_texture_dimension_2d,
            // Storage + uniform buffers (+ two acceleration structures with ray queries).
            max_buffers_and_acceleration_structures_per_shader_stage: adapter_limits
                .max_buffers_and_acceleration_structures_per_shader_stage,
            ..wgpu::Limits::default()
        };
        let limits = if ray_query {
            base_limits.using_acceleration_structure_values(adapter_limits.clone())
        } else {
            base_limits
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("restir"),
            required_features: features,
            required_limits: limits,
            // SAFETY: the only experimental feature requested is ray queries, used through
            // wgpu's validated API (BLAS/TLAS builds, `ray_query` in WGSL); wgpu asks for
            // this token because the API may still change, not for unsafe calls of ours.
            experimental_features: if ray_query {
                unsafe { wgpu::ExperimentalFeatures::enabled() }
            } else {
                wgpu::ExperimentalFeatures::disabled()
            },
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        }))
        .map_err(|e| GpuError::Device(e.to_string()))?;
        let errors = Arc::new(Mutex::new(None));
        let sink = errors.clone();
        // wgpu's default handler panics; keep the first error and let the caller report it.
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            log::error!("GPU error: {e}");
            let mut slot = sink.lock().unwrap_or_else(|p| p.into_inner());
            slot.get_or_insert_with(|| e.to_string());
        }));
        log::info!(
            "GPU: {} ({:?}, {:?}, {}; ray queries: {ray_query})",
            info.name,
            info.backend,
            info.device_type,
            info.driver_info
        );
        Ok(Gpu {
            instance,
            adapter,
            device,
            queue,
            timestamps,
            ray_query,
            errors,
        })
    }

    /// A second device on the same adapter with the same features: a scene's pipelines can
    /// be compiled (and run once) there while this device keeps drawing, and the driver's
    /// shader cache then has them for this device too (`renderer/prepare.rs`).
    pub fn sibling(&self) -> Result<Gpu, GpuError> {
        Gpu::from_adapter_with(self.instance.clone(), self.adapter.clone(), self.ray_query)
    }

    pub fn adapter_name(&self) -> String {
        let info = self.adapter.get_info();
        format!("{} ({:?})", info.name, info.backend)
    }

    /// The driver and its version as the adapter reports them (lavapipe: "Mesa 25.0.7…"),
    /// so every measurement can say which driver made it.
    pub fn driver_info(&self) -> String {
        let info = self.adapter.get_info();
        format!("{} {}", info.driver, info.driver_info)
            .trim()
            .to_string()
    }

    /// True when the adapter is a CPU implementation (lavapipe): timings are CPU timings.
    pub fn is_cpu(&self) -> bool {
        self.adapter.get_info().device_type == wgpu::DeviceType::Cpu
    }

    /// The first GPU error since the last call, if any.
    pub fn take_error(&self) -> Option<String> {
        self.errors.lock().unwrap_or_else(|p| p.into_inner()).take()
    }

    /// Fails with the pending GPU error, if any.
    pub fn check(&self) -> Result<(), GpuError> {
        match self.take_error() {
            Some(e) => Err(GpuError::Validation(e)),
            None => Ok(()),
        }
    }

    /// Blocks until all submitted work is done.
    pub fn wait_idle(&self) {
        let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
    }
}

/// An instance over the native backends (WGPU_BACKEND overrides, e.g. `vulkan`).
pub fn new_instance() -> wgpu::Instance {
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
    desc.backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::PRIMARY);
    wgpu::Instance::new(desc)
}

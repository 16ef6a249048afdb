//! Device set-up and small GPU helpers shared by the passes.

pub mod context;
pub mod readback;
pub mod timing;

pub use context::{Gpu, GpuError};

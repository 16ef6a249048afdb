//! The headless commands.

pub mod camera_path;
pub mod environment;
pub mod params;
pub mod render;
mod render_job;
mod render_loop;
mod render_reference;
mod render_stats;
pub mod setup;

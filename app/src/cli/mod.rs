//! The headless commands.

pub mod camera_path;
pub mod environment;
pub mod params;
pub mod render;
pub mod setup;

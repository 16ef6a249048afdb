//! The boiling and survivor-change views (window_view.wgsl), drawn over the display's
//! output from the temporal window when one of them is selected.

use super::pass::{Dispatch, PassDef, read, write};
use super::resources::Resource::*;
use super::temporal_window::WINDOW;

pub const PASS: PassDef = PassDef {
    name: "window view",
    shader: "window_view.wgsl",
    group: &[
        read(Surfaces),
        read(Pixels(&WINDOW)),
        read(DisplayUniform),
        write(Output),
    ],
    dispatch: Dispatch::Pixels,
};

//! One row per shader constant: a `pub const` inside `wgsl_constants!` is a Rust constant
//! and, through `shader_source::wgsl_prelude`, the WGSL `const` of the same name and
//! value at the top of every composed shader. Nothing is written twice, so the host and
//! the shaders cannot drift apart.

/// A constant's value as WGSL declares it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WgslValue {
    U32(u32),
    F32(f32),
}

impl WgslValue {
    /// `const NAME: u32 = 7u;` or `const NAME: f32 = 1e-6;` (exact: `{:e}` prints the
    /// shortest decimal that reads back as the same f32).
    pub fn declaration(self, name: &str) -> String {
        match self {
            WgslValue::U32(v) => format!("const {name}: u32 = {v}u;"),
            WgslValue::F32(v) => format!("const {name}: f32 = {v:e};"),
        }
    }
}

impl From<u32> for WgslValue {
    fn from(v: u32) -> Self {
        WgslValue::U32(v)
    }
}

impl From<usize> for WgslValue {
    fn from(v: usize) -> Self {
        WgslValue::U32(u32::try_from(v).expect("a shader constant fits in u32"))
    }
}

impl From<f32> for WgslValue {
    fn from(v: f32) -> Self {
        WgslValue::F32(v)
    }
}

/// Declares its `pub const` rows as Rust constants and `fn $list()`, the rows as
/// (name, WGSL value) for the prelude.
macro_rules! wgsl_constants {
    (fn $list:ident; $( $(#[$meta:meta])* pub const $name:ident : $ty:ty = $value:expr; )*) => {
        $( $(#[$meta])* pub const $name: $ty = $value; )*

        /// This block's rows, for the WGSL prelude.
        pub(crate) fn $list() -> Vec<(&'static str, $crate::wgsl_constants::WgslValue)> {
            vec![$( (stringify!($name), $crate::wgsl_constants::WgslValue::from($name)) ),*]
        }
    };
}

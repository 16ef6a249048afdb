//! The separate cost commands: what building, loading, compiling, tracing and shifting
//! cost, each measured on its own and printed as a table, never asserted (`bench-bvh`,
//! `bench-load` with its compile table, `bench-rays`, `bench-shifts`, `bench-env`), and
//! `bench --sweep-lights`, which times light selection against the light count.

pub mod bvh_cost;
mod compile_table;
pub mod env_cost;
pub mod light_sweep;
pub mod load_cost;
pub mod ray_cost;
pub mod shift_cost;

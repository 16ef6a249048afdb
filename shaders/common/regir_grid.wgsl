// ReGIR's grid (docs/src/light-samplers.md, "ReGIR"): regir_grid³ cells of side
// regir_cell_size × the scene's diagonal, centred on the camera and snapped to whole cells
// (regir.wgsl fills and reads them; the regir-cell view draws them).
#include "common/frame_bindings.wgsl"

const REGIR_NO_CELL: u32 = 0xffffffffu;

fn regir_cell_side() -> f32 {
    return params.regir_cell_size * frame.scene_scale;
}

// The world position of cell (0, 0, 0)'s low corner.
fn regir_origin() -> vec3<f32> {
    let side = regir_cell_side();
    return (floor(frame.camera_position / side) - f32(params.regir_grid / 2u)) * side;
}

fn regir_cell_at(p: vec3<f32>) -> u32 {
    let c = floor((p - regir_origin()) / regir_cell_side());
    let g = f32(params.regir_grid);
    if any(c < vec3<f32>(0.0)) || any(c >= vec3<f32>(g)) || !all(c == c) {
        return REGIR_NO_CELL;
    }
    let i = vec3<u32>(c);
    return (i.z * params.regir_grid + i.y) * params.regir_grid + i.x;
}

fn regir_cell_centre(cell: u32) -> vec3<f32> {
    let g = params.regir_grid;
    let i = vec3<u32>(cell % g, (cell / g) % g, cell / (g * g));
    return regir_origin() + (vec3<f32>(i) + 0.5) * regir_cell_side();
}

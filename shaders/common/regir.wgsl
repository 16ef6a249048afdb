// ReGIR's grid (docs/src/light-samplers.md, "ReGIR"; Boksansky, Jukarainen & Wyman 2021,
// RTXDI's grid mode): regir_grid³ cells of side regir_cell_size × the scene's diagonal,
// centred on the camera and snapped to whole cells, each with regir_slots light samples
// resampled every frame toward the cell's target (lights/regir_fill.wgsl). A pixel reads a cell
// at its position jittered by up to ± regir_jitter / 2 cells; outside the grid, the power
// table. The slots' contribution weights W are unbiased estimates of 1 / p(light) (RIS),
// so a candidate read from a slot weighs p̂ · W — never p̂ / p_power, which is the planted
// error PLANTED_REGIR_WEIGHT_IGNORED.
#include "common/lights.wgsl"
#include "common/regir_grid.wgsl"

// The radius of the sphere around a cell's centre that holds every point whose jittered
// lookup can land in the cell: half a cell plus half the jitter, along each axis.
fn regir_reach() -> f32 {
    return (0.5 + 0.5 * params.regir_jitter) * regir_cell_side() * sqrt(3.0);
}

// The cell's target for a light point: luminance over squared distance (at least the
// reach), 0 only where no point within reach can receive it (wholly behind a one-sided
// emitter), so the slots' support covers every pixel that reads the cell. The
// environment and directional lights: luminance alone.
fn regir_cell_target(centre: vec3<f32>, reach: f32, lp: LightPoint) -> f32 {
    let lum = luminance(lp.radiance);
    if lp.kind == LIGHT_POINT_ENVIRONMENT || lp.kind == LIGHT_POINT_DIRECTION {
        return lum;
    }
    let d = centre - lp.position;
    if lp.kind == LIGHT_POINT_AREA && !lp.double_sided && dot(d, lp.normal) < -reach {
        return 0.0;
    }
    return lum / max(dot(d, d), reach * reach);
}

// Group 0: what every pass sees. The stats counters are cleared every frame and read back
// with the frame's statistics (the STAT_* indices of render/src/shader_constants.rs say what
// each counts; render/src/renderer/stats.rs reads them).
#include "common/types.wgsl"

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> params: Params;

// The pixel a compute invocation shades, or false when the dispatch overhangs the image.
fn pixel_in_frame(id: vec3<u32>) -> bool {
    return all(id.xy < frame.size);
}

fn pixel_index(pixel: vec2<u32>) -> u32 {
    return pixel.y * frame.size.x + pixel.x;
}

// Group 0: what every pass sees. The stats counters are cleared every frame and read back
// with the frame's statistics (see render/src/passes/stats.rs for the index meanings).
#include "common/types.wgsl"

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> params: Params;

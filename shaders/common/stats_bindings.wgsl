// Per-frame counters (rejections by reason, sources, caps, non-finite values per pass).
@group(0) @binding(2) var<storage, read_write> stats: array<atomic<u32>, STAT_COUNT>;

fn count_stat(index: u32) {
    atomicAdd(&stats[index], 1u);
}

// Adds n to a counter with one atomic (a pass sums its rays per invocation first).
fn add_stat(index: u32, n: u32) {
    if n > 0u {
        atomicAdd(&stats[index], n);
    }
}

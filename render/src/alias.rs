//! Vose's alias method, shared by the light table (one entry per light) and the
//! environment's row and column tables: sampling an entry costs one uniform slot and
//! one coin, whatever the number of entries.

/// One slot: keep the slot's own entry when u < `threshold`, else take `alias`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AliasSlot {
    pub threshold: f32,
    pub alias: u32,
}

/// The alias table of non-negative `weights`, computed in f64 so that a 1e-20 weight next
/// to a 1e8 one keeps its probability; also returns the total weight. With a total that is
/// not positive and finite every slot keeps itself (callers never sample such a table).
pub fn alias_slots(weights: &[f64]) -> (Vec<AliasSlot>, f64) {
    let n = weights.len();
    let total: f64 = weights.iter().sum();
    let mut slots: Vec<AliasSlot> = (0..n)
        .map(|i| AliasSlot {
            threshold: 1.0,
            alias: i as u32,
        })
        .collect();
    if !(total > 0.0 && total.is_finite()) {
        return (slots, total);
    }
    // Slot i keeps its own entry with probability scaled[i] and gives the rest to its alias.
    let mut scaled: Vec<f64> = weights.iter().map(|w| w / total * n as f64).collect();
    let (mut small, mut large): (Vec<usize>, Vec<usize>) = (0..n).partition(|&i| scaled[i] < 1.0);
    while let (Some(&s), Some(&l)) = (small.last(), large.last()) {
        small.pop();
        large.pop();
        slots[s].threshold = scaled[s] as f32;
        slots[s].alias = l as u32;
        scaled[l] -= 1.0 - scaled[s];
        if scaled[l] < 1.0 {
            small.push(l)
        } else {
            large.push(l)
        }
    }
    // Whatever is left is 1 up to rounding and keeps its own slot (the defaults) — except
    // a zero-weight slot, which must never be picked: it hands its slot to an entry that
    // has weight (only reachable by rounding, but a zero pdf picked is a division by zero;
    // dynamic scenes keep zero-power slots for lights that are off).
    if let Some(donor) = weights.iter().position(|&w| w > 0.0) {
        for s in small {
            if weights[s] <= 0.0 {
                slots[s].threshold = 0.0;
                slots[s].alias = donor as u32;
            }
        }
    }
    (slots, total)
}

/// Picks an entry exactly as the shaders do (`alias_pick` in environment.wgsl,
/// `sample_light_index` in lights.wgsl): slot from `u_slot`, then the coin `u_alias`.
pub fn alias_pick(slots: &[AliasSlot], u_slot: f32, u_alias: f32) -> usize {
    let n = slots.len() as u32;
    let slot = ((u_slot * n as f32) as u32).min(n - 1) as usize;
    if u_alias < slots[slot].threshold {
        slot
    } else {
        slots[slot].alias as usize
    }
}

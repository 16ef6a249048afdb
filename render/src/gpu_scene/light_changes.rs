//! Which light entries each recent scene update changed (moved, or a new power), so a
//! light structure that refits (the light BVH, docs/src/light-samplers.md "Moving lights")
//! reads the changed lights instead of comparing every light of the scene. A consumer
//! remembers the generation it last caught up with and asks for what changed since; the
//! log keeps only the recent updates (about one scene's worth of entries), and an update
//! that could not say what it changed (a full upload) breaks the chain: the consumer then
//! compares every light, as without a log.

use std::collections::VecDeque;

/// One update's changes: the generation it produced, and its entries (`None`: unknown).
struct Update {
    generation: u64,
    entries: Option<Vec<u32>>,
}

#[derive(Default)]
pub struct LightChangeLog {
    generation: u64,
    updates: VecDeque<Update>,
    /// Entries held over all `updates`, and the most the log keeps before dropping the
    /// oldest update.
    held: usize,
    capacity: usize,
}

impl LightChangeLog {
    /// A log that keeps about `light_count` entries (at least a few thousand).
    pub fn new(light_count: usize) -> LightChangeLog {
        LightChangeLog {
            capacity: light_count.max(4096),
            ..LightChangeLog::default()
        }
    }

    /// The generation after the latest update.
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// One update changed `entries` (any order, repeats allowed), or lights it cannot
    /// name (`None`).
    pub fn record(&mut self, entries: Option<Vec<u32>>) {
        self.generation += 1;
        self.held += entries.as_ref().map_or(0, Vec::len);
        self.updates.push_back(Update {
            generation: self.generation,
            entries,
        });
        while self.held > self.capacity && self.updates.len() > 1 {
            let dropped = self.updates.pop_front().expect("more than one update");
            self.held -= dropped.entries.map_or(0, |e| e.len());
        }
    }

    /// The entries changed by the updates after generation `since`, sorted without
    /// repeats; `None` if the log no longer reaches back to `since` or one of those
    /// updates could not name its lights.
    pub fn since(&self, since: u64) -> Option<Vec<u32>> {
        if since == self.generation {
            return Some(Vec::new());
        }
        let oldest_kept = self.updates.front()?.generation;
        if since + 1 < oldest_kept || since > self.generation {
            return None;
        }
        let mut out = Vec::new();
        for update in self.updates.iter().filter(|u| u.generation > since) {
            out.extend_from_slice(update.entries.as_deref()?);
        }
        out.sort_unstable();
        out.dedup();
        Some(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_what_changed_since_a_generation() {
        let mut log = LightChangeLog::new(0);
        assert_eq!(log.since(0), Some(vec![]));
        log.record(Some(vec![5, 2]));
        log.record(Some(vec![2, 9]));
        assert_eq!(log.since(0), Some(vec![2, 5, 9]));
        assert_eq!(log.since(1), Some(vec![2, 9]));
        assert_eq!(log.since(2), Some(vec![]));
        assert_eq!(log.since(3), None, "a generation from the future");
        log.record(None);
        assert_eq!(
            log.since(1),
            None,
            "an update that could not name its lights"
        );
        log.record(Some(vec![1]));
        assert_eq!(log.since(3), Some(vec![1]));
    }

    #[test]
    fn forgets_the_oldest_updates_past_its_capacity() {
        let mut log = LightChangeLog::new(0);
        for g in 0..3u32 {
            log.record(Some((0..3000).map(|i| i + g).collect()));
        }
        // 9000 entries over a capacity of 4096: only the last update is kept.
        assert_eq!(log.since(0), None);
        assert_eq!(log.since(1), None);
        assert_eq!(log.since(2).map(|e| e.len()), Some(3000));
    }
}

//! Equal-time mode (`--budget-ms T`), the paper's headline comparison: every configuration
//! accumulates frames until the sum of its measured frame times reaches T, and the error of
//! its running average is compared at that point. The frame that crosses T is included
//! (so every configuration gets at least one frame, and overshoots T by less than one of its
//! frames); the times used are the same reported pass times the tables show.

/// The budget of one configuration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget {
    pub ms: f64,
    /// Safety stop for configurations whose frames report (almost) no time.
    pub max_frames: u32,
}

/// Counts measured time against a budget.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BudgetClock {
    pub budget: Budget,
    pub used_ms: f64,
    pub frames: u32,
}

impl BudgetClock {
    pub fn new(budget: Budget) -> BudgetClock {
        BudgetClock {
            budget,
            used_ms: 0.0,
            frames: 0,
        }
    }

    /// Adds one frame's measured time.
    pub fn add(&mut self, ms: f64) {
        self.used_ms += ms;
        self.frames += 1;
    }

    /// True once the budget is used up (or the frame cap is hit).
    pub fn done(&self) -> bool {
        self.used_ms >= self.budget.ms || self.frames >= self.budget.max_frames
    }

    /// True when the frame cap, not the budget, stopped it.
    pub fn capped(&self) -> bool {
        self.frames >= self.budget.max_frames && self.used_ms < self.budget.ms
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_budget_stops_on_the_frame_that_reaches_it() {
        let mut clock = BudgetClock::new(Budget {
            ms: 10.0,
            max_frames: 100,
        });
        let mut frames = 0;
        while !clock.done() {
            clock.add(3.0);
            frames += 1;
        }
        // 3 + 3 + 3 = 9 < 10, the fourth frame reaches 12.
        assert_eq!((frames, clock.used_ms), (4, 12.0));
        assert!(!clock.capped());
        let mut slow = BudgetClock::new(Budget {
            ms: 10.0,
            max_frames: 100,
        });
        slow.add(50.0);
        assert!(slow.done() && slow.frames == 1);
        let mut free = BudgetClock::new(Budget {
            ms: 10.0,
            max_frames: 5,
        });
        while !free.done() {
            free.add(0.0);
        }
        assert!(free.capped() && free.frames == 5);
    }
}

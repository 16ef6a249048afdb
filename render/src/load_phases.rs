//! How long each phase of getting a scene to its first frame took: the loader's (file,
//! buffers, images, geometry), the upload's (BVH, light table, GPU buffers, acceleration
//! structures) and the pipelines'. `render --stats` writes them as its `load` block, the
//! Scene panel lists them, `bench-load` prints them, and a watcher hears each phase begin
//! and end (headless `render` prints them as they go, the viewer's progress bar names them).

use std::time::Instant;

/// One finished phase.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Phase {
    pub name: &'static str,
    pub ms: f64,
    /// What it worked on ("18 images, 2048×2048 largest, 2 threads"); may be empty.
    pub detail: String,
}

/// What a watcher hears.
#[derive(Clone, Copy, Debug)]
pub enum LoadEvent<'a> {
    Started(&'static str),
    /// Part of a long phase is done (`done` of `total`: images decoded, pipelines compiled).
    Progress {
        phase: &'static str,
        done: usize,
        total: usize,
    },
    Finished(&'a Phase),
}

/// Called from whichever thread runs the phase.
pub type Watcher<'a> = &'a (dyn Fn(LoadEvent) + Sync);

/// A watcher that ignores everything.
pub fn unwatched(_: LoadEvent) {}

/// The phases of one load, in the order they ran.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct LoadPhases {
    pub phases: Vec<Phase>,
}

impl LoadPhases {
    /// Runs `f` as phase `name`, telling `watch`; `f` returns its result and the detail.
    pub fn time<T>(
        &mut self,
        watch: Watcher,
        name: &'static str,
        f: impl FnOnce() -> (T, String),
    ) -> T {
        watch(LoadEvent::Started(name));
        let start = Instant::now();
        let (value, detail) = f();
        self.record(watch, name, start.elapsed().as_secs_f64() * 1e3, detail);
        value
    }

    /// As `time`, for a phase that can fail (a failed phase is not recorded).
    pub fn try_time<T, E>(
        &mut self,
        watch: Watcher,
        name: &'static str,
        f: impl FnOnce() -> Result<(T, String), E>,
    ) -> Result<T, E> {
        watch(LoadEvent::Started(name));
        let start = Instant::now();
        let (value, detail) = f()?;
        self.record(watch, name, start.elapsed().as_secs_f64() * 1e3, detail);
        Ok(value)
    }

    /// Adds a phase timed elsewhere.
    pub fn record(&mut self, watch: Watcher, name: &'static str, ms: f64, detail: String) {
        let phase = Phase { name, ms, detail };
        watch(LoadEvent::Finished(&phase));
        self.phases.push(phase);
    }

    pub fn extend(&mut self, other: &LoadPhases) {
        self.phases.extend(other.phases.iter().cloned());
    }

    pub fn total_ms(&self) -> f64 {
        self.phases.iter().map(|p| p.ms).sum()
    }

    pub fn get(&self, name: &str) -> Option<&Phase> {
        self.phases.iter().find(|p| p.name == name)
    }
}

/// One line per phase, for a terminal: `  images        812.4 ms  18 images, ...`.
pub fn phase_line(phase: &Phase) -> String {
    format!(
        "  {:<24}{:>10.1} ms  {}",
        phase.name, phase.ms, phase.detail
    )
    .trim_end()
    .to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    #[test]
    fn phases_are_recorded_in_order_and_watched() {
        let heard = Mutex::new(Vec::new());
        let watch = |e: LoadEvent| {
            heard.lock().unwrap().push(match e {
                LoadEvent::Started(n) => format!("start {n}"),
                LoadEvent::Progress { phase, done, total } => format!("{phase} {done}/{total}"),
                LoadEvent::Finished(p) => format!("end {}", p.name),
            })
        };
        let mut phases = LoadPhases::default();
        let x = phases.time(&watch, "a", || (2, "two".into()));
        let failed: Result<(), &str> = phases.try_time(&watch, "b", || Err("no"));
        phases.record(&watch, "c", 1.5, String::new());
        assert_eq!((x, failed), (2, Err("no")));
        let names: Vec<_> = phases.phases.iter().map(|p| p.name).collect();
        assert_eq!(names, ["a", "c"], "a failed phase is not recorded");
        assert_eq!(
            *heard.lock().unwrap(),
            ["start a", "end a", "start b", "end c"]
        );
        assert!(phases.total_ms() >= 1.5);
        assert_eq!(phases.get("a").unwrap().detail, "two");
        assert!(phase_line(&phases.phases[1]).starts_with("  c "));
    }
}

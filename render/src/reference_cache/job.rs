//! A reference rendered in the background (the viewer's accuracy panel): a thread with its
//! own `Renderer` on the caller's device loads the cached image or renders and stores it,
//! sending progress back. The caller polls once per frame and never waits.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, TryRecvError, channel};
use std::thread::JoinHandle;

use super::{Cancelled, Progress, Reference, ReferenceCache, ReferenceRequest, reference_settings};
use crate::Renderer;
use crate::gpu::Gpu;
use crate::scene::Scene;

/// Where a background reference stands.
#[derive(Debug)]
pub enum JobState {
    /// Looking in the cache, or uploading the scene for rendering.
    Starting,
    Rendering(Progress),
    /// The reference (`from_cache` tells whether it was loaded).
    Done(Reference),
    Failed(String),
    Cancelled,
}

enum Event {
    Progress(Progress),
    Finished(Result<Reference, String>),
}

pub struct ReferenceJob {
    request: ReferenceRequest,
    events: Receiver<Event>,
    cancel: Arc<AtomicBool>,
    state: JobState,
    last_progress: Option<Progress>,
    thread: Option<JoinHandle<()>>,
}

impl ReferenceJob {
    /// Starts loading or rendering `request` on a thread. `scene` must be what
    /// `request.scene` names; `gpu` is usually the caller's own device (a clone shares it).
    pub fn spawn(
        cache: ReferenceCache,
        request: ReferenceRequest,
        gpu: Gpu,
        scene: Arc<Scene>,
    ) -> ReferenceJob {
        let (send, events) = channel();
        let cancel = Arc::new(AtomicBool::new(false));
        let thread = {
            let (request, cancel) = (request.clone(), cancel.clone());
            std::thread::Builder::new()
                .name("reference".into())
                .spawn(move || {
                    let progress_send = send.clone();
                    let mut progress = |p: &Progress| {
                        let _ = progress_send.send(Event::Progress(*p));
                        !cancel.load(Ordering::Relaxed)
                    };
                    let result = run(&cache, &request, gpu, &scene, &mut progress);
                    let _ = send.send(Event::Finished(result));
                })
                .expect("spawning a thread")
        };
        ReferenceJob {
            request,
            events,
            cancel,
            state: JobState::Starting,
            last_progress: None,
            thread: Some(thread),
        }
    }

    pub fn request(&self) -> &ReferenceRequest {
        &self.request
    }

    /// Takes in what the thread reported since the last call; never blocks.
    pub fn poll(&mut self) -> &JobState {
        loop {
            match self.events.try_recv() {
                Ok(event) => self.apply(event),
                Err(TryRecvError::Empty) => break,
                Err(TryRecvError::Disconnected) => {
                    if !self.is_finished() {
                        self.state = JobState::Failed("the reference thread stopped".into());
                    }
                    break;
                }
            }
        }
        &self.state
    }

    /// The latest progress report (it stays after the job ends; None when nothing was
    /// rendered, e.g. the reference was in the cache).
    pub fn last_progress(&self) -> Option<Progress> {
        self.last_progress
    }

    fn apply(&mut self, event: Event) {
        self.state = match event {
            Event::Progress(p) => {
                self.last_progress = Some(p);
                JobState::Rendering(p)
            }
            Event::Finished(Ok(r)) => JobState::Done(r),
            Event::Finished(Err(e))
                if self.cancel.load(Ordering::Relaxed) && e == Cancelled.to_string() =>
            {
                JobState::Cancelled
            }
            Event::Finished(Err(e)) => JobState::Failed(e),
        };
    }

    pub fn is_finished(&self) -> bool {
        matches!(
            self.state,
            JobState::Done(_) | JobState::Failed(_) | JobState::Cancelled
        )
    }

    /// Asks the thread to stop after the frame it is rendering.
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    /// Blocks until the job ends (tests, command-line tools).
    pub fn wait(mut self) -> anyhow::Result<Reference> {
        while !self.is_finished() {
            match self.events.recv() {
                Ok(event) => self.apply(event),
                Err(_) => self.state = JobState::Failed("the reference thread stopped".into()),
            }
        }
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
        match std::mem::replace(&mut self.state, JobState::Starting) {
            JobState::Done(r) => Ok(r),
            JobState::Cancelled => Err(Cancelled.into()),
            JobState::Failed(e) => Err(anyhow::anyhow!(e)),
            JobState::Starting | JobState::Rendering(_) => unreachable!("finished above"),
        }
    }
}

impl Drop for ReferenceJob {
    /// A dropped job stops at its next frame (the thread is not waited for).
    fn drop(&mut self) {
        self.cancel();
    }
}

fn run(
    cache: &ReferenceCache,
    request: &ReferenceRequest,
    gpu: Gpu,
    scene: &Scene,
    progress: &mut dyn FnMut(&Progress) -> bool,
) -> Result<Reference, String> {
    let text = |e: anyhow::Error| format!("{e:#}");
    if let Some(reference) = cache.load(request).map_err(text)? {
        return Ok(reference);
    }
    let settings = reference_settings(
        request.jitter,
        1,
        request.max_bounces,
        request.light_bvh,
        request.light_samples,
    );
    let mut renderer =
        Renderer::new(gpu, scene, request.width, request.height, settings).map_err(text)?;
    cache
        .get_or_render(&mut renderer, request, progress)
        .map_err(text)
}

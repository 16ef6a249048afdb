//! The shift mappings (module docs of `path_reuse`): a path found at pixel `from` moved to
//! pixel `to`, with the Jacobian of the move, or the reason it cannot be moved.

use glam::Vec3;

use super::path::{PathSample, Pixel, lobe_at, w_in};
use super::toy_scene::{Hit, Kind, ToyScene};
use crate::gi::model::jacobian::reconnection_jacobian;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shift {
    /// Keep every vertex after the primary; connect the new primary to the second.
    Reconnection,
    /// Trace again from the new primary with the path's random numbers.
    RandomReplay,
    /// Replay up to the first bounce with two rough ends at least `min_distance` apart, then
    /// reconnect there.
    Hybrid {
        rough_threshold: f32,
        min_distance: f32,
    },
}

/// Why a shift failed (the future "shift failure by reason" view counts these).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Failure {
    /// The replayed prefix left the path: it missed, went below a surface, hit the blocker
    /// or an emitter early, or did not reach one at the same bounce.
    ReplayLeft,
    /// The reconnection is undefined: too close, too far, grazing, or the other side of the
    /// reconnection vertex's surface (the GI reconnection's rules).
    ReconnectionUndefined,
    /// The reconnection segment is blocked.
    Occluded,
    /// Hybrid: the shifted path would reconnect at another bounce, so the shift back would
    /// not return the path (the shift would not be a bijection).
    ReconnectsElsewhere,
}

/// A shifted path and `|J|` of the shift (the density ratio: the shifted sample's contribution
/// weight is the original's times `|J|`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shifted {
    pub path: PathSample,
    pub jacobian: f32,
}

fn is_rough(scene: &ToyScene, hit: &Hit, threshold: f32) -> bool {
    match scene.kind(hit) {
        Kind::Reflects(_) => scene.lobe(hit).is_some_and(|l| l.is_rough(threshold)),
        // An emitter is diffuse: the light leaving it does not depend on the angle much.
        Kind::Emits { .. } => true,
        Kind::Absorbs => false,
    }
}

/// The bounce at which `shift` reconnects `path` (`b`: the segment `vertices[b] →
/// vertices[b+1]` is replaced), `None` for pure replay.
pub fn reconnection_bounce(scene: &ToyScene, path: &PathSample, shift: Shift) -> Option<usize> {
    match shift {
        Shift::Reconnection => Some(0),
        Shift::RandomReplay => None,
        Shift::Hybrid {
            rough_threshold,
            min_distance,
        } => (0..path.bounces).find(|&b| {
            let (a, c) = (&path.vertices[b], &path.vertices[b + 1]);
            is_rough(scene, a, rough_threshold)
                && is_rough(scene, c, rough_threshold)
                && a.position.distance(c.position) >= min_distance
        }),
    }
}

fn direction(a: &Hit, b: &Hit) -> Vec3 {
    (b.position - a.position).normalize()
}

/// `path`, found at `from`, moved to `to` by `shift`.
pub fn shift_path(
    scene: &ToyScene,
    path: &PathSample,
    from: &Pixel,
    to: &Pixel,
    shift: Shift,
) -> Result<Shifted, Failure> {
    let k = reconnection_bounce(scene, path, shift);
    let mut out = *path;
    out.vertices[0] = to.primary;
    let mut jacobian = 1.0;
    for b in 0..k.unwrap_or(path.bounces) {
        let (x, y) = (path.vertices[b], out.vertices[b]);
        let (lobe_x, lobe_y) = (
            lobe_at(scene, &x).ok_or(Failure::ReplayLeft)?,
            lobe_at(scene, &y).ok_or(Failure::ReplayLeft)?,
        );
        let (w_x, w_y) = (w_in(from, path, b), w_in(to, &out, b));
        let sampled = lobe_y.sample(y.normal, w_y, path.numbers[b]);
        if lobe_y.eval(y.normal, w_y, sampled.direction) <= 0.0 {
            return Err(Failure::ReplayLeft);
        }
        let hit = scene
            .intersect(y.position, sampled.direction, f32::MAX)
            .ok_or(Failure::ReplayLeft)?;
        let last = b + 1 == path.bounces;
        let fits = match scene.kind(&hit) {
            Kind::Emits { .. } => last,
            Kind::Reflects(_) => !last,
            Kind::Absorbs => false,
        };
        if !fits {
            return Err(Failure::ReplayLeft);
        }
        jacobian *= lobe_x.pdf(x.normal, w_x, direction(&x, &path.vertices[b + 1])) / sampled.pdf;
        out.vertices[b + 1] = hit;
    }
    if let Some(k) = k {
        let (x_k, y_k, next) = (path.vertices[k], out.vertices[k], path.vertices[k + 1]);
        let lobe_y = lobe_at(scene, &y_k).ok_or(Failure::ReplayLeft)?;
        let j = reconnection_jacobian(next.position, next.normal, x_k.position, y_k.position)
            .ok_or(Failure::ReconnectionUndefined)?;
        if !scene.visible(y_k.position, next.position) {
            return Err(Failure::Occluded);
        }
        jacobian *= j;
        // The numbers that would draw the reconnected direction: a later replay of the
        // shifted path (a temporal chain) follows it.
        let w_y = w_in(to, &out, k);
        out.numbers[k] = lobe_y.numbers_of(y_k.normal, w_y, direction(&y_k, &next));
    }
    if matches!(shift, Shift::Hybrid { .. }) && reconnection_bounce(scene, &out, shift) != k {
        return Err(Failure::ReconnectsElsewhere);
    }
    if !(jacobian.is_finite() && jacobian > 0.0) {
        return Err(Failure::ReplayLeft);
    }
    Ok(Shifted {
        path: out,
        jacobian,
    })
}

//! The glossy toy scene of the path-reuse tests, traced exactly on the CPU: a rough-glossy
//! floor (the pixels' primary surfaces), a near-mirror wall, a Lambertian back wall, an
//! emitter above whose radiance varies over it, and a black blocker between floor and
//! emitter. Light reaches the floor indirectly by the mirror (a glossy chain: reconnection
//! fails there, replay works), by the back wall (rough: reconnection works) and by both.

use glam::Vec3;

use super::lobe::Lobe;

/// What a surface does with light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    Reflects(Lobe),
    /// Emits `radiance · profile(x, y)` from its front side, reflects nothing.
    Emits {
        radiance: f32,
    },
    /// Absorbs (the blocker): a path that hits it carries nothing.
    Absorbs,
}

/// An axis-aligned rectangle: `center ± half.x · u ± half.y · v`, front side along `normal`.
#[derive(Clone, Copy, Debug)]
pub struct Quad {
    pub center: Vec3,
    pub u: Vec3,
    pub v: Vec3,
    pub half: [f32; 2],
    pub normal: Vec3,
    pub kind: Kind,
    /// How a reflecting quad's roughness changes across it (per unit of distance from
    /// its center): the floor's varies, so random replay meets other lobes at the new
    /// pixel and its Jacobian is not 1.
    pub roughness_gradient: Vec3,
}

/// A ray's hit: where, the surface's front normal, and which quad.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Hit {
    pub position: Vec3,
    pub normal: Vec3,
    pub quad: usize,
}

pub struct ToyScene {
    pub quads: Vec<Quad>,
}

/// Offset of secondary rays off their surface and the shortened end of shadow segments.
const RAY_EPSILON: f32 = 1e-4;

pub const FLOOR: usize = 0;
pub const MIRROR: usize = 1;
pub const BACK_WALL: usize = 2;
pub const EMITTER: usize = 3;
pub const BLOCKER: usize = 4;

/// The emitter's radiance profile over its surface, in [0.4, 1.6].
pub fn profile(p: Vec3) -> f32 {
    1.0 + 0.6 * (2.1 * p.x + 0.3).sin() * (1.7 * p.y).cos()
}

impl ToyScene {
    /// The scene with the floor's and mirror's roughness given (the tests vary them).
    pub fn new(floor_roughness: f32, mirror_roughness: f32) -> ToyScene {
        let quad = |center: [f32; 3], u: Vec3, v: Vec3, half: [f32; 2], normal: Vec3, kind| Quad {
            center: Vec3::from(center),
            u,
            v,
            half,
            normal,
            kind,
            roughness_gradient: Vec3::ZERO,
        };
        let lobe = |albedo, roughness| Kind::Reflects(Lobe { albedo, roughness });
        let mut scene = ToyScene {
            quads: vec![
                quad(
                    [0.0, 0.0, 0.0],
                    Vec3::X,
                    Vec3::Y,
                    [3.0, 3.0],
                    Vec3::Z,
                    lobe(0.7, floor_roughness),
                ),
                quad(
                    [1.2, 0.0, 1.0],
                    Vec3::Y,
                    Vec3::Z,
                    [1.5, 1.0],
                    Vec3::NEG_X,
                    lobe(0.95, mirror_roughness),
                ),
                quad(
                    [0.0, 1.6, 1.25],
                    Vec3::X,
                    Vec3::Z,
                    [3.0, 1.25],
                    Vec3::NEG_Y,
                    lobe(0.6, 1.0),
                ),
                quad(
                    [-0.7, 0.0, 2.2],
                    Vec3::X,
                    Vec3::Y,
                    [0.5, 0.7],
                    Vec3::NEG_Z,
                    Kind::Emits { radiance: 6.0 },
                ),
                quad(
                    [-0.3, 0.1, 1.0],
                    Vec3::X,
                    Vec3::Y,
                    [0.3, 0.3],
                    Vec3::Z,
                    Kind::Absorbs,
                ),
            ],
        };
        scene.quads[FLOOR].roughness_gradient = Vec3::new(0.3, 0.2, 0.0);
        scene
    }

    /// The lobe of a reflecting surface at `hit` (`None` for emitters and the blocker).
    pub fn lobe(&self, hit: &Hit) -> Option<Lobe> {
        let q = &self.quads[hit.quad];
        match q.kind {
            Kind::Reflects(lobe) => Some(Lobe {
                roughness: (lobe.roughness + q.roughness_gradient.dot(hit.position - q.center))
                    .clamp(0.01, 1.0),
                ..lobe
            }),
            _ => None,
        }
    }

    /// The nearest hit along `origin + t·dir`, `t` in (ε, `t_max`).
    pub fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<Hit> {
        let mut best: Option<(f32, Hit)> = None;
        for (i, q) in self.quads.iter().enumerate() {
            let denom = q.normal.dot(dir);
            if denom.abs() < 1e-8 {
                continue;
            }
            let t = q.normal.dot(q.center - origin) / denom;
            if !(t > RAY_EPSILON && t < t_max) || best.is_some_and(|(bt, _)| t >= bt) {
                continue;
            }
            let p = origin + dir * t;
            let d = p - q.center;
            if d.dot(q.u).abs() <= q.half[0] && d.dot(q.v).abs() <= q.half[1] {
                best = Some((
                    t,
                    Hit {
                        position: p,
                        normal: q.normal,
                        quad: i,
                    },
                ));
            }
        }
        best.map(|(_, h)| h)
    }

    /// Whether the segment `a → b` is free (both ends excluded).
    pub fn visible(&self, a: Vec3, b: Vec3) -> bool {
        let d = b - a;
        let len = d.length();
        len > 0.0
            && self
                .intersect(a, d / len, len * (1.0 - RAY_EPSILON))
                .is_none()
    }

    pub fn kind(&self, hit: &Hit) -> Kind {
        self.quads[hit.quad].kind
    }

    /// The radiance leaving emitter point `hit` toward `to` (0 behind it or off an emitter).
    pub fn emitted(&self, hit: &Hit, to: Vec3) -> f32 {
        match self.kind(hit) {
            Kind::Emits { radiance } if hit.normal.dot(to - hit.position) > 0.0 => {
                radiance * profile(hit.position)
            }
            _ => 0.0,
        }
    }
}

//! Scenes generated in code, loaded as `builtin:NAME`. All are deterministic (fixed-seed
//! PRNG), diffuse materials are exactly Lambertian (`Material::diffuse`), and emitters light
//! their front (counter-clockwise) side only unless double-sided.

mod city;
mod concourse;
mod cornell;
mod detail;
pub mod dynamic;
mod glossy;
mod hard;
mod lamps;
mod many_lights;
mod plane_light;
pub(crate) mod rng;
mod shapes;

use super::Scene;
use super::validate::SceneError;
use cornell::cornell_box;
use many_lights::{diffuse_floor, glossy_floor, many_lights_room};

/// The scene the viewer opens without `--scene` (the showcase, `scenes` marks it).
pub const DEFAULT_SCENE: &str = "builtin:concourse";

/// Lights in `many-lights` without a count.
pub const DEFAULT_LIGHT_COUNT: usize = 4096;
/// The largest N `many-lights:N` accepts (2^22 lights, 2^23 triangles).
pub const MAX_LIGHT_COUNT: usize = 4_194_304;

/// Builds a scene given its name (without `builtin:`), which becomes `Scene::name`.
type Generator = fn(&str) -> Scene;

/// Every scene by name (without `builtin:`), with the line `scenes` prints beside it.
const SCENES: &[(&str, &str, Generator)] = &[
    (
        "concourse",
        "a station concourse at night: 480 downlights, sconces, signs, a glossy floor (the showcase)",
        concourse::concourse,
    ),
    (
        "cornell",
        "the Cornell box, one small area light, Lambertian",
        |name| cornell_box(name, 1.0),
    ),
    (
        "many-lights",
        "a room of 4096 small coloured lights over occluders and a glossy floor",
        |name| many_lights_room(name, DEFAULT_LIGHT_COUNT, glossy_floor()),
    ),
    (
        "many-lights-diffuse",
        "the many-lights room, all Lambertian",
        |name| many_lights_room(name, DEFAULT_LIGHT_COUNT, diffuse_floor()),
    ),
    (
        "plane-light",
        "a plane under one square emitter: the closed-form irradiance test",
        plane_light::plane_light,
    ),
    (
        "lamps",
        "lights behind glass: bulbs in globes, neon tubes, a paper shade",
        lamps::lamps,
    ),
    (
        "glossy",
        "a room lit only indirectly, a glossy floor and near-mirror panels (for PT shifts)",
        glossy::glossy_room,
    ),
    (
        "detail",
        "tiny lights over a grille of thin slats: small shadow detail",
        detail::detail,
    ),
    (
        "hard:tiny-bright",
        "hard case: an emitter of 1e-6 m² at radiance 1e6 beside ordinary lights",
        hard::tiny_bright,
    ),
    (
        "hard:touching",
        "hard case: emitters lying on, cutting through and grazing a lit floor",
        hard::touching,
    ),
    (
        "hard:back-facing",
        "hard case: the only emitters face away from everything seen",
        hard::back_facing,
    ),
    (
        "hard:degenerate",
        "hard case: zero-area and zero-emission emitters beside one good light",
        hard::degenerate,
    ),
    (
        "hard:no-emitters",
        "hard case: nothing emits",
        hard::no_emitters,
    ),
    (
        "hard:occluded",
        "hard case: every emitter sealed inside a closed box",
        hard::occluded,
    ),
    (
        "hard:scale-small",
        "hard case: the Cornell box at 1e-3",
        |name| cornell_box(name, 1e-3),
    ),
    (
        "hard:scale-large",
        "hard case: the Cornell box at 1e4",
        |name| cornell_box(name, 1e4),
    ),
    (
        "hard:radiance-range",
        "hard case: emitted radiance spanning 1e-20 to 1e8",
        hard::radiance_range,
    ),
    (
        "hard:mirror",
        "hard case: 512 lights over a near-mirror floor",
        |name| many_lights_room(name, 512, hard::mirror_floor()),
    ),
    (
        "dynamic:moving-light",
        "one bright light sweeping past a pillar every 4 s",
        dynamic::moving_light,
    ),
    (
        "dynamic:blinking-lights",
        "about half of 256 lights switch off at 1 s and on at 2 s, every 3 s",
        dynamic::blinking_lights,
    ),
    (
        "dynamic:moving-occluder",
        "a turning blade under a ceiling light: disocclusion every frame",
        dynamic::moving_occluder,
    ),
    (
        "dynamic:many-lights",
        "the many-lights room, every light orbiting its own centre",
        |name| dynamic::orbiting_lights(name, DEFAULT_LIGHT_COUNT),
    ),
];

/// A scene with a light count: `many-lights:N`, `many-lights-diffuse:N`,
/// `dynamic:many-lights:N`, `city:N` and `city-roofs:N` (N emissive triangles over a night
/// city, seen from the street or over the roofs) and `city-traffic:N` (the street view
/// with moving cars and blinking signs).
type Room = fn(&str, usize) -> Scene;
const FAMILIES: [(&str, &str, Room); 6] = [
    (
        "city:",
        "a night city 572 m across seen from the street: lamps, windows, signs",
        |name, n| city::city(name, n, city::View::Street),
    ),
    (
        "city-traffic:",
        "city:N with cars driving and signs blinking (moving lights)",
        city::city_traffic,
    ),
    (
        "city-roofs:",
        "city:N seen over the roofs from 150 m",
        |name, n| city::city(name, n, city::View::Roofs),
    ),
    (
        "many-lights:",
        "the many-lights room with N lights",
        |name, n| many_lights_room(name, n, glossy_floor()),
    ),
    (
        "many-lights-diffuse:",
        "the Lambertian many-lights room with N lights",
        |name, n| many_lights_room(name, n, diffuse_floor()),
    ),
    (
        "dynamic:many-lights:",
        "the orbiting many-lights room with N lights",
        dynamic::orbiting_lights,
    ),
];

/// The N of a family's `:N`, checked.
fn light_count(count: &str) -> Result<usize, String> {
    let n: usize = count
        .parse()
        .map_err(|_| format!("'{count}' is not a light count"))?;
    if !(1..=MAX_LIGHT_COUNT).contains(&n) {
        return Err(format!("light count must be in 1..={MAX_LIGHT_COUNT}"));
    }
    Ok(n)
}

/// Whether `name` (without `builtin:`) names a built-in scene, without building it (a
/// tour file's scenes are checked when it is read).
pub fn is_builtin_name(name: &str) -> bool {
    SCENES.iter().any(|(n, _, _)| *n == name)
        || FAMILIES.iter().any(|(prefix, _, _)| {
            name.strip_prefix(prefix)
                .is_some_and(|count| light_count(count).is_ok())
        })
}

/// Build a built-in scene. `name` has no `builtin:` prefix; `many-lights:N` takes a light
/// count in 1..=MAX_LIGHT_COUNT.
pub fn builtin_scene(name: &str) -> Result<Scene, SceneError> {
    if let Some((_, _, build)) = SCENES.iter().find(|(n, _, _)| *n == name) {
        return Ok(build(name));
    }
    for (prefix, _, room) in FAMILIES {
        let Some(count) = name.strip_prefix(prefix) else {
            continue;
        };
        let n = light_count(count).map_err(|detail| SceneError::Builtin {
            name: name.to_string(),
            detail,
        })?;
        return Ok(room(name, n));
    }
    Err(SceneError::Builtin {
        name: name.to_string(),
        detail: format!(
            "unknown built-in scene (known: {}; `restir-viewer scenes` describes each)",
            catalogue()
                .iter()
                .map(|(name, _)| name.trim_start_matches("builtin:"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    })
}

/// Every built-in scene's full name, `builtin:` prefix included (`many-lights` once, with
/// its default count).
pub fn builtin_names() -> Vec<String> {
    SCENES
        .iter()
        .map(|(name, _, _)| format!("builtin:{name}"))
        .collect()
}

/// The families, each as `builtin:PREFIX:N` (N lights, 1..=[`MAX_LIGHT_COUNT`]).
pub fn family_names() -> Vec<String> {
    FAMILIES
        .iter()
        .map(|(prefix, _, _)| format!("builtin:{prefix}N"))
        .collect()
}

/// Every built-in scene and family (`builtin:city:N`) with its one-line description, in
/// the order `scenes` lists them.
pub fn catalogue() -> Vec<(String, &'static str)> {
    let scenes = SCENES
        .iter()
        .map(|(name, line, _)| (format!("builtin:{name}"), *line));
    let families = FAMILIES
        .iter()
        .map(|(prefix, line, _)| (format!("builtin:{prefix}N"), *line));
    scenes.chain(families).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_prefixed() {
        let names = builtin_names();
        let mut sorted = names.clone();
        sorted.sort();
        sorted.dedup();
        assert_eq!(sorted.len(), names.len());
        assert!(names.iter().all(|n| n.starts_with("builtin:")));
    }

    #[test]
    fn scenes_are_deterministic() {
        let (a, b) = (
            builtin_scene("many-lights:300").unwrap(),
            builtin_scene("many-lights:300").unwrap(),
        );
        assert_eq!(a.vertices, b.vertices);
        assert_eq!(a.triangles, b.triangles);
        assert_eq!(a.name, "builtin:many-lights:300");
    }

    #[test]
    fn light_counts_out_of_range_are_errors() {
        for bad in [
            "many-lights:0",
            "many-lights:4194305",
            "many-lights:x",
            "many-lights:",
        ] {
            let e = builtin_scene(bad).unwrap_err().to_string();
            assert!(e.starts_with(&format!("builtin:{bad}:")), "{e}");
        }
        assert!(builtin_scene("many-lights:1").is_ok());
    }

    #[test]
    fn every_hard_case_has_what_it_promises() {
        let emitters = |n: &str| builtin_scene(n).unwrap().emissive_triangle_count();
        assert_eq!(emitters("hard:no-emitters"), 0);
        assert!(emitters("hard:degenerate") >= 7);
        assert_eq!(emitters("hard:mirror"), 1024);
        assert_eq!(emitters("hard:radiance-range"), 16);
        let scene = builtin_scene("hard:tiny-bright").unwrap();
        let tiny = scene
            .materials
            .iter()
            .position(|m| m.emission.x == 1e6)
            .unwrap();
        let t = scene
            .triangles
            .iter()
            .position(|t| t.material as usize == tiny)
            .unwrap();
        let [a, b, c] = scene.triangle_positions(t);
        let area = (b - a).cross(c - a).length(); // two triangles of half this each
        assert!((area - 1e-6).abs() < 1e-8, "{area}");
    }
}

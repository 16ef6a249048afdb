//! Mutation fuzz of real exporters' files: ~300 deterministic corruptions each of the Blender
//! 2.80 Cornell box and of the 2.79 box's Draco and meshopt twins (.gltf text and .bin
//! bytes). The loader may refuse any of them, but must never panic: not even a panic it
//! catches itself, since each one is a check we are missing.

use std::path::Path;

use restir_render::scene::gltf_loader::load_gltf;
use restir_render::scene::load::SceneError;
use serde_json::Value;

use super::files::TempDir;

const MUTATIONS: u64 = 300;

/// Knuth's MMIX linear congruential generator, high bits only: plenty for picking
/// mutations, and a fixed stream so failures reproduce.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        self.0 >> 33
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Every node of a JSON tree, preorder, each given to `f` with its preorder number.
fn visit(value: &mut Value, counter: &mut usize, f: &mut dyn FnMut(usize, &mut Value)) {
    f(*counter, value);
    *counter += 1;
    match value {
        Value::Array(items) => items.iter_mut().for_each(|v| visit(v, counter, f)),
        Value::Object(map) => map.values_mut().for_each(|v| visit(v, counter, f)),
        _ => {}
    }
}

/// Apply `f` to the `k`-th (mod count) node for which `select` holds.
fn edit_nth(doc: &mut Value, k: usize, select: fn(&Value) -> bool, f: &mut dyn FnMut(&mut Value)) {
    let mut matching = Vec::new();
    visit(doc, &mut 0, &mut |i, v| {
        if select(v) {
            matching.push(i)
        }
    });
    let Some(&target) = matching.get(k % matching.len().max(1)) else {
        return;
    };
    visit(doc, &mut 0, &mut |i, v| {
        if i == target {
            f(v)
        }
    });
}

/// One random corruption of (json text, bin bytes).
fn mutate(rng: &mut Rng, json: &[u8], bin: &[u8]) -> (Vec<u8>, Vec<u8>) {
    let (mut json, mut bin) = (json.to_vec(), bin.to_vec());
    match rng.next() % 6 {
        0 => {
            for _ in 0..1 + rng.below(4) {
                let i = rng.below(json.len());
                json[i] = rng.next() as u8;
            }
        }
        1 => json.truncate(rng.below(json.len())),
        2 | 3 => {
            let mut doc: Value = serde_json::from_slice(&json).unwrap();
            let k = rng.below(100_000);
            if rng.next().is_multiple_of(2) {
                let drop = rng.below(64);
                edit_nth(&mut doc, k, Value::is_object, &mut |v| {
                    let map = v.as_object_mut().unwrap();
                    if let Some(key) = map.keys().nth(drop % map.len().max(1)).cloned() {
                        map.remove(&key);
                    }
                });
            } else {
                // Integers for counts, offsets and indices; floats for factors and positions.
                const INTEGERS: [i64; 9] = [-1, 0, 1, 2, 3, 100, 65536, 4_294_967_295, i64::MAX];
                const FLOATS: [f64; 5] = [0.5, -1e20, 1e20, 1e-40, -0.0];
                let n = match rng.below(INTEGERS.len() + FLOATS.len()) {
                    i if i < INTEGERS.len() => serde_json::json!(INTEGERS[i]),
                    i => serde_json::json!(FLOATS[i - INTEGERS.len()]),
                };
                edit_nth(&mut doc, k, Value::is_number, &mut |v| *v = n.clone());
            }
            json = serde_json::to_vec(&doc).unwrap();
        }
        4 => {
            for _ in 0..1 + rng.below(16) {
                let i = rng.below(bin.len());
                bin[i] = rng.next() as u8;
            }
        }
        _ => bin.truncate(rng.below(bin.len())),
    }
    (json, bin)
}

#[test]
fn mutated_files_never_panic() {
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/blender-2.80-cornell");
    let json = std::fs::read(source.join("cornellBox-2.80-Eevee-gltf.gltf")).unwrap();
    let bin = std::fs::read(source.join("cornellBox-2.80-Eevee-gltf.bin")).unwrap();
    let dir = TempDir::new("fuzz");
    fuzz(
        &dir,
        &source,
        "cornellBox-2.80-Eevee-gltf",
        &json,
        &bin,
        0x00F0_22ED,
    );
}

/// The same mutations of the Draco and meshopt twins (assets/compressed): their JSON is read
/// by the loader's own code first (`compressed::take`), their streams by the decoders.
#[test]
fn mutated_compressed_files_never_panic() {
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets");
    let dir = TempDir::new("fuzz-compressed");
    for (name, seed) in [("cornell-draco", 0xD2AC0), ("cornell-meshopt", 0x3E540)] {
        let mut doc: Value = serde_json::from_slice(
            &std::fs::read(assets.join(format!("compressed/{name}.gltf"))).unwrap(),
        )
        .unwrap();
        for image in doc["images"].as_array_mut().unwrap() {
            let uri = image["uri"]
                .as_str()
                .unwrap()
                .rsplit('/')
                .next()
                .unwrap()
                .to_string();
            image["uri"] = Value::String(uri);
        }
        let json = serde_json::to_vec(&doc).unwrap();
        let bin = std::fs::read(assets.join(format!("compressed/{name}.bin"))).unwrap();
        fuzz(
            &dir,
            &assets.join("blender-2.79-cornell"),
            name,
            &json,
            &bin,
            seed,
        );
    }
}

/// `MUTATIONS` corruptions of `name`.gltf + `name`.bin (its buffer) loaded from `dir`, with
/// the images of `images` (a folder of the Cornell box) as the small checker.
fn fuzz(dir: &Path, images: &Path, name: &str, json: &[u8], bin: &[u8], seed: u64) {
    // Both image names get the small checker: decoding speed is not what is fuzzed here.
    let small = std::fs::read(images.join("checker-meter.png")).unwrap();
    for image in ["checker-meter.png", "checkerBJS.png"] {
        std::fs::write(dir.join(image), &small).unwrap();
    }
    let (mut rng, mut refused) = (Rng(seed), 0);
    for i in 0..MUTATIONS {
        let (json, bin) = mutate(&mut rng, json, bin);
        std::fs::write(dir.join(format!("{name}.bin")), &bin).unwrap();
        let path = dir.join(format!("{name}.gltf"));
        std::fs::write(&path, &json).unwrap();
        match load_gltf(&path) {
            Ok(scene) => assert!(scene.vertices.iter().all(|v| v.position.is_finite())),
            Err(SceneError::Panicked { detail, .. }) => {
                panic!("{name}: mutation {i}: caught panic: {detail}")
            }
            Err(e) => {
                let message = e.to_string();
                assert!(message.contains(&format!("{name}.gltf")), "{message}");
                assert!(
                    !message.contains("crashed"),
                    "{name}: mutation {i}: {message}"
                );
                refused += 1;
            }
        }
    }
    // Sanity: the mutations do bite.
    assert!(
        refused > 30,
        "{name}: only {refused} of {MUTATIONS} mutations were refused"
    );
}

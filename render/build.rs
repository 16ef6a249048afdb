//! Embeds every WGSL file under ../shaders into the library (release builds read only
//! these; debug builds prefer the files on disk so shaders can be edited and reloaded).

use std::{env, fs, path::Path};

fn collect(dir: &Path, root: &Path, out: &mut Vec<String>) {
    let mut entries: Vec<_> = fs::read_dir(dir)
        .expect("shaders directory")
        .flatten()
        .collect();
    entries.sort_by_key(|e| e.path());
    for entry in entries {
        let path = entry.path();
        if path.is_dir() {
            collect(&path, root, out);
        } else if path.extension().is_some_and(|e| e == "wgsl") {
            println!("cargo:rerun-if-changed={}", path.display());
            let rel = path
                .strip_prefix(root)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            out.push(format!(
                "    ({rel:?}, include_str!({:?})),\n",
                path.canonicalize().unwrap()
            ));
        }
    }
}

fn main() {
    let root = Path::new(&env::var("CARGO_MANIFEST_DIR").unwrap()).join("../shaders");
    println!("cargo:rerun-if-changed={}", root.display());
    let mut entries = Vec::new();
    collect(&root, &root, &mut entries);
    let code = format!(
        "pub static EMBEDDED_SHADERS: &[(&str, &str)] = &[\n{}];\n",
        entries.concat()
    );
    fs::write(
        Path::new(&env::var("OUT_DIR").unwrap()).join("embedded_shaders.rs"),
        code,
    )
    .unwrap();
}

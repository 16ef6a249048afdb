//! Import circles between the modules of both crates (docs/src/source-layout.md, "Layers").
//! A module is a source file (test files left out); it imports another when it names a
//! path into it (`use crate::a::b::{c, d}`, `super::x`, `crate::a::f()` in code). A circle
//! is a strongly connected set of two or more modules: none may exist in `app/`, and in
//! `render/` the modules still in a circle are listed below and may only shrink (a module
//! that leaves every circle must leave the list too, so the list stays exact). The planted
//! twin at the end shows the detector catches one back import. No GPU: it reads the
//! sources as text.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The `render/` modules still inside an import circle, to be broken into layers.
const RENDER_CIRCLES: &[&str] = &[
    "effects",
    "environment",
    "environment::upload",
    "frame_targets",
    "gpu_scene",
    "gpu_scene::layout",
    "gpu_types",
    "light_sampler",
    "passes::compile",
    "passes::gbuffer",
    "reference_cache",
    "reference_cache::key",
    "renderer",
    "scene",
    "scene::animation",
    "scene::builtin",
    "scene::bvh",
    "scene::gltf_loader",
    "scene::gltf_loader::draco",
    "scene::gltf_loader::primitives",
    "scene::lights",
    "scene::load",
    "settings",
    "shader_constants",
    "view",
];

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Module path (`a::b`) → file text, for every non-test `.rs` file under `src`.
fn modules(src: &Path) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap().flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if !name.ends_with(".rs") || name.ends_with("tests.rs") {
                continue;
            }
            let rel = path.strip_prefix(src).unwrap().with_extension("");
            let mut parts: Vec<String> = rel
                .iter()
                .map(|p| p.to_string_lossy().into_owned())
                .collect();
            if matches!(
                parts.last().map(String::as_str),
                Some("mod" | "lib" | "main")
            ) {
                parts.pop();
            }
            let text = std::fs::read_to_string(&path).unwrap();
            // A file's own unit tests are test code too.
            let text = match text.find("#[cfg(test)]\nmod tests {") {
                Some(i) => text[..i].to_string(),
                None => text,
            };
            out.insert(parts.join("::"), text);
        }
    }
    out
}

/// Every path a text names from `crate` or `super`, use-trees expanded.
fn named_paths(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < text.len() {
        let rest = &text[i..];
        let at_word = i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_');
        let root = ["crate::", "super::"]
            .into_iter()
            .find(|r| rest.starts_with(r));
        match root {
            Some(r) if at_word => {
                let (paths, used) = use_tree(&rest[..], r.len() - 2);
                out.extend(paths);
                i += used.max(1);
            }
            _ => i += rest.chars().next().map_or(1, char::len_utf8),
        }
    }
    out
}

/// Parses `prefix::a::b`, `prefix::{a, b::{c, d}}` starting at `s` (whose first `head`
/// bytes are the root word); returns the full paths and the bytes consumed.
fn use_tree(s: &str, head: usize) -> (Vec<String>, usize) {
    let mut i = head;
    let b = s.as_bytes();
    while i + 2 < s.len() && &s[i..i + 2] == "::" {
        let j = i + 2;
        if b.get(j) == Some(&b'{') {
            let close = matching_brace(s, j);
            let base = &s[..i];
            let mut out = Vec::new();
            for item in split_top_level(&s[j + 1..close]) {
                let item = item.trim();
                if item.is_empty() || item == "self" {
                    out.push(base.to_string());
                    continue;
                }
                let joined = format!("{base}::{item}");
                let (paths, _) = use_tree(&joined, base.len());
                out.extend(paths);
            }
            return (out, close + 1);
        }
        let end = s[j..]
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .map_or(s.len(), |k| j + k);
        if end == j {
            break;
        }
        i = end;
    }
    (vec![s[..i].to_string()], i)
}

fn matching_brace(s: &str, open: usize) -> usize {
    let mut depth = 0;
    for (k, c) in s[open..].char_indices() {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    return open + k;
                }
            }
            _ => {}
        }
    }
    s.len() - 1
}

fn split_top_level(s: &str) -> Vec<&str> {
    let (mut out, mut depth, mut start) = (Vec::new(), 0, 0);
    for (k, c) in s.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                out.push(&s[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    out.push(&s[start..]);
    out
}

/// Module → the modules it imports (the deepest module each named path lands in).
fn graph(modules: &BTreeMap<String, String>) -> BTreeMap<String, BTreeSet<String>> {
    let mut edges = BTreeMap::new();
    for (name, text) in modules {
        let here: Vec<&str> = name.split("::").filter(|s| !s.is_empty()).collect();
        let mut targets = BTreeSet::new();
        for path in named_paths(text) {
            let mut segs: Vec<&str> = path.split("::").collect();
            let mut full: Vec<&str> = if segs[0] == "crate" {
                segs.remove(0);
                Vec::new()
            } else {
                here.clone()
            };
            while segs.first() == Some(&"super") {
                segs.remove(0);
                full.pop();
            }
            full.extend(segs);
            let target = (1..=full.len())
                .rev()
                .map(|k| full[..k].join("::"))
                .find(|m| modules.contains_key(m));
            if let Some(t) = target.filter(|t| t != name) {
                targets.insert(t);
            }
        }
        edges.insert(name.clone(), targets);
    }
    edges
}

/// The strongly connected sets of two or more modules (Tarjan).
fn circles(edges: &BTreeMap<String, BTreeSet<String>>) -> Vec<BTreeSet<String>> {
    struct State<'a> {
        edges: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on_stack: BTreeSet<&'a str>,
        out: Vec<BTreeSet<String>>,
    }
    fn visit<'a>(s: &mut State<'a>, v: &'a str) {
        let n = s.index.len();
        s.index.insert(v, n);
        s.low.insert(v, n);
        s.stack.push(v);
        s.on_stack.insert(v);
        let edges = s.edges;
        for w in edges.get(v).into_iter().flatten() {
            let w = w.as_str();
            if !edges.contains_key(w) {
                continue;
            }
            if !s.index.contains_key(w) {
                visit(s, w);
                let low = s.low[v].min(s.low[w]);
                s.low.insert(v, low);
            } else if s.on_stack.contains(w) {
                let low = s.low[v].min(s.index[w]);
                s.low.insert(v, low);
            }
        }
        if s.low[v] == s.index[v] {
            let mut set = BTreeSet::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack.remove(w);
                set.insert(w.to_string());
                if w == v {
                    break;
                }
            }
            if set.len() > 1 {
                s.out.push(set);
            }
        }
    }
    let mut s = State {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        out: Vec::new(),
    };
    for v in edges.keys() {
        if !s.index.contains_key(v.as_str()) {
            visit(&mut s, v);
        }
    }
    s.out
}

#[test]
fn the_app_has_no_import_circle() {
    let found = circles(&graph(&modules(&repo().join("app/src"))));
    assert!(found.is_empty(), "import circles in app/src: {found:?}");
}

#[test]
fn render_circles_only_shrink() {
    let found = circles(&graph(&modules(&repo().join("render/src"))));
    for c in &found {
        eprintln!("render circle of {}: {c:?}", c.len());
    }
    let in_circles: BTreeSet<String> = found.iter().flatten().cloned().collect();
    let listed: BTreeSet<String> = RENDER_CIRCLES.iter().map(|s| s.to_string()).collect();
    let new: Vec<&String> = in_circles.difference(&listed).collect();
    assert!(
        new.is_empty(),
        "modules newly in an import circle: {new:?} (circles: {found:?})"
    );
    let left: Vec<&String> = listed.difference(&in_circles).collect();
    assert!(
        left.is_empty(),
        "no longer in any circle, take them off RENDER_CIRCLES: {left:?}"
    );
}

#[test]
fn use_trees_expand_to_every_path() {
    let paths = named_paths("use crate::a::{b, c::{d, e}, self};\nlet x = super::f::g();");
    assert_eq!(
        paths,
        [
            "crate::a::b",
            "crate::a::c::d",
            "crate::a::c::e",
            "crate::a",
            "super::f::g"
        ]
    );
}

#[test]
fn planted_back_import_is_caught() {
    // A layered toy crate (core ← scene ← renderer), then one back import from core.
    let mut m: BTreeMap<String, String> = BTreeMap::new();
    m.insert("core".into(), String::new());
    m.insert("scene".into(), "use crate::core::Vec3;".into());
    m.insert(
        "renderer".into(),
        "use crate::scene::Scene;\nuse crate::core::X;".into(),
    );
    assert!(circles(&graph(&m)).is_empty());
    m.insert(
        "core".into(),
        "fn f(r: &crate::renderer::Renderer) {}".into(),
    );
    let found = circles(&graph(&m));
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].len(), 3, "{found:?}");
}

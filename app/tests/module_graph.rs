//! Import circles between the modules of both crates (docs/src/source-layout.md, "Layers").
//! A module is a source file (test files left out); it imports another when it names a
//! path into it (`use crate::a::b::{c, d}`, `super::x`, `crate::a::f()` in code). A circle
//! is a strongly connected set of two or more modules: none may exist in either crate. The planted
//! twin at the end shows the detector catches one back import.
//!
//! Above the files, each crate's modules stand on floors, drawn in the book's "Layers"
//! block (top-level modules, and the parts of a technique's folder); a module may import
//! from its own floor and the ones below, never from above, and every module stands on
//! exactly one floor (so the picture cannot drift from the code). No GPU: it reads the sources and the page as text.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

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
fn the_render_crate_has_no_import_circle() {
    let found = circles(&graph(&modules(&repo().join("render/src"))));
    assert!(found.is_empty(), "import circles in render/src: {found:?}");
}

/// One crate's floors from the "Layers" block of docs/src/source-layout.md, bottom first:
/// after a line `CRATE/src, top floor first` come lines `floor name:  module  module ...`
/// (a line with no floor name goes on naming the floor above it) up to the first line that
/// is not indented.
fn documented_floors(crate_src: &str) -> Vec<Vec<String>> {
    let page = std::fs::read_to_string(repo().join("docs/src/source-layout.md")).unwrap();
    let header = format!("{crate_src}, top floor first");
    let mut lines = page.lines().skip_while(|l| l.trim() != header);
    assert!(
        lines.next().is_some(),
        "source-layout.md has no '{header}' block"
    );
    let mut floors: Vec<Vec<String>> = Vec::new();
    for line in lines.take_while(|l| l.starts_with("  ")) {
        // `floor name:  a  b::c`, or a line of more modules for the floor above it.
        let names = match line.split_once(": ") {
            Some((floor, names)) if !floor.contains("::") => {
                floors.push(Vec::new());
                names
            }
            _ => line,
        };
        let floor = floors
            .last_mut()
            .expect("the block opens with a floor line");
        floor.extend(names.split_whitespace().map(str::to_string));
    }
    floors.reverse();
    floors
}

/// The floor a module stands on: that of the longest floor entry its path starts with, by
/// whole segments (`di::passes` holds `di::passes::initial`; `scene` holds `scene::bvh`).
fn floor_of(module: &str, floor_of_entry: &BTreeMap<String, usize>) -> Option<usize> {
    let segments: Vec<&str> = module.split("::").collect();
    (1..=segments.len())
        .rev()
        .find_map(|k| floor_of_entry.get(&segments[..k].join("::")).copied())
}

/// Imports that climb to a higher floor, and modules on no floor or entries on several
/// (floors bottom first). An entry is a top-level module or, inside a technique's folder,
/// one of its parts (`di::model`, `di::passes`): a technique's files stand on different
/// floors. The folder's own `mod.rs` may stand on none when it only lists its parts.
fn floor_violations(
    edges: &BTreeMap<String, BTreeSet<String>>,
    floors: &[Vec<String>],
) -> Vec<String> {
    let mut floor_of_entry: BTreeMap<String, usize> = BTreeMap::new();
    let mut out = Vec::new();
    for (i, floor) in floors.iter().enumerate() {
        for name in floor {
            if floor_of_entry.insert(name.clone(), i).is_some() {
                out.push(format!("{name} stands on two floors"));
            }
        }
    }
    let within =
        |module: &str, entry: &str| module == entry || module.starts_with(&format!("{entry}::"));
    for (module, targets) in edges {
        if module.is_empty() || floor_of(module, &floor_of_entry).is_some() {
            continue;
        }
        let lists_parts = floor_of_entry
            .keys()
            .any(|e| within(e, module) && e != module);
        if !(lists_parts && targets.is_empty()) {
            out.push(format!("{module} stands on no floor"));
        }
    }
    for name in floor_of_entry.keys() {
        if !edges.keys().any(|m| within(m, name)) {
            out.push(format!("{name} is on a floor but is no module"));
        }
    }
    for (from, targets) in edges {
        for to in targets {
            let (fa, fb) = (
                floor_of(from, &floor_of_entry),
                floor_of(to, &floor_of_entry),
            );
            if let (Some(fa), Some(fb)) = (fa, fb)
                && fb > fa
            {
                out.push(format!("{from} (floor {fa}) imports {to} (floor {fb})"));
            }
        }
    }
    out
}

#[test]
fn both_crates_keep_their_floors() {
    for crate_src in ["render/src", "app/src"] {
        let edges = graph(&modules(&repo().join(crate_src)));
        let floors = documented_floors(crate_src);
        let bad = floor_violations(&edges, &floors);
        assert!(
            bad.is_empty(),
            "{crate_src} against the floors in docs/src/source-layout.md: {bad:#?}"
        );
    }
}

#[test]
fn planted_climb_between_floors_is_caught() {
    // Two floors with no circle: only the floors see an import from below reaching up.
    let floors = vec![vec!["core".to_string()], vec!["renderer".to_string()]];
    let mut m: BTreeMap<String, String> = BTreeMap::new();
    m.insert("core".into(), String::new());
    m.insert("core::math".into(), String::new());
    m.insert("renderer".into(), "use crate::core::math::Vec3;".into());
    assert!(floor_violations(&graph(&m), &floors).is_empty());
    m.insert("core::math".into(), "use crate::renderer::Frame;".into());
    let bad = floor_violations(&graph(&m), &floors);
    assert_eq!(bad, ["core::math (floor 0) imports renderer (floor 1)"]);
    m.insert("stats".into(), String::new());
    assert!(
        floor_violations(&graph(&m), &floors)
            .iter()
            .any(|b| b == "stats stands on no floor")
    );
}

#[test]
fn planted_climb_inside_a_technique_folder_is_caught() {
    // A technique's model on the lower floor, its passes on the upper one; the folder's
    // mod.rs lists them and stands on no floor.
    let floors = vec![
        vec!["core".to_string(), "gi::model".to_string()],
        vec!["gi::passes".to_string()],
    ];
    let mut m: BTreeMap<String, String> = BTreeMap::new();
    m.insert("core".into(), String::new());
    m.insert("gi".into(), String::new());
    m.insert("gi::model".into(), "use crate::core::X;".into());
    m.insert(
        "gi::passes".into(),
        "use crate::gi::model::Reservoir;".into(),
    );
    assert!(floor_violations(&graph(&m), &floors).is_empty());
    m.insert("gi::model".into(), "use crate::gi::passes::PASS;".into());
    let bad = floor_violations(&graph(&m), &floors);
    assert_eq!(bad, ["gi::model (floor 0) imports gi::passes (floor 1)"]);
    m.insert("gi::model".into(), String::new());
    m.insert("gi".into(), "use crate::core::X;".into());
    let bad = floor_violations(&graph(&m), &floors);
    assert_eq!(bad, ["gi stands on no floor"]);
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

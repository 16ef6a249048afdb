//! docs/src/source-layout.md cannot drift: its tree names every file and folder directly
//! under `render/src/` and `app/src/` (a folder's contents are described by its line), and
//! every folder of `shaders/`. The planted twin removes one line of the tree and must be
//! caught. No GPU: it reads the file system and the page as text.

use std::collections::BTreeSet;
use std::path::Path;

fn repository() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap()
}

/// The names the page's tree must hold: a file's name with its extension, a folder's with
/// a slash after it.
fn entries(dir: &str, folders_only: bool) -> BTreeSet<String> {
    let path = repository().join(dir);
    std::fs::read_dir(&path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .map(|e| e.unwrap())
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().to_string();
            if e.file_type().unwrap().is_dir() {
                Some(format!("{name}/"))
            } else {
                (!folders_only && (name.ends_with(".rs") || name.ends_with(".wgsl")))
                    .then_some(name)
            }
        })
        .collect()
}

/// The first fenced block of the page: the tree.
fn tree(page: &str) -> String {
    page.split("```")
        .nth(1)
        .expect("the page opens with its tree in a fenced block")
        .to_string()
}

/// The section of the tree under `root` (a line starting with it, up to the next line
/// that starts in column 0), and the entries of `expected` it does not name as a word.
fn missing(tree: &str, root: &str, expected: &BTreeSet<String>) -> Vec<String> {
    let mut lines = tree.lines().skip_while(|l| !l.starts_with(root));
    let head = lines
        .next()
        .unwrap_or_else(|| panic!("{root} is not in the tree"));
    let section: Vec<&str> = std::iter::once(head)
        .chain(lines.take_while(|l| l.starts_with(' ')))
        .collect();
    let words: BTreeSet<&str> = section
        .iter()
        .flat_map(|l| l.split(|c: char| c.is_whitespace() || c == ',' || c == ';' || c == '('))
        .map(|w| w.trim_end_matches([',', ';', ':', ')']))
        .collect();
    expected
        .iter()
        .filter(|e| !words.contains(e.as_str()))
        .cloned()
        .collect()
}

fn check(tree: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (root, folders_only) in [
        ("render/src/", false),
        ("app/src/", false),
        ("shaders/", true),
    ] {
        for e in missing(tree, root, &entries(root, folders_only)) {
            out.push(format!("{root}{e}"));
        }
    }
    out
}

fn page() -> String {
    std::fs::read_to_string(repository().join("docs/src/source-layout.md")).unwrap()
}

#[test]
fn the_source_layout_page_names_every_file_and_folder() {
    let missing = check(&tree(&page()));
    assert!(
        missing.is_empty(),
        "docs/src/source-layout.md does not name: {missing:?}"
    );
}

/// Planted: the tree without its line for `light_probe.rs` must be caught.
#[test]
fn a_file_left_out_of_the_page_is_caught() {
    let tree = tree(&page());
    let planted: String = tree
        .lines()
        .filter(|l| !l.trim_start().starts_with("light_probe.rs"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_ne!(planted, tree, "the page has a line for light_probe.rs");
    assert_eq!(check(&planted), ["render/src/light_probe.rs"]);
}

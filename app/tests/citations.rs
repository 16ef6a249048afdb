//! Every pointer a comment or a page gives can be followed from a checkout: a repository
//! path names a file or folder that exists, a book section (`docs/src/X.md#anchor`, or
//! `docs/src/X.md, "Heading"`, or a Markdown link `X.md#anchor`) names a heading that
//! exists, and nothing cites what a reader cannot open (an issue number, the notes file the
//! book was written from). No GPU: it reads the repository's source and doc files as text.
//! The planted twin at the end proves the checker fires.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The repository's files (tracked, or new and not ignored) and the headings of its pages.
struct Repo {
    files: HashSet<String>,
    dirs: HashSet<String>,
    anchors: HashMap<String, Vec<String>>,
}

const TEXT: [&str; 4] = [".rs", ".wgsl", ".md", ".toml"];
const ROOTS: [&str; 5] = ["render/", "app/", "shaders/", "docs/", "assets/"];
/// Third-party files carried as they came, and this file, whose twin breaks every rule.
const SKIP: [&str; 2] = ["assets/khronos/", "app/tests/citations.rs"];

/// A measurement's `results.md` under `docs/bench/` is what `bench` wrote when it ran: its
/// footnotes cite the book as it was then, and a rerun writes them anew. The book's pages,
/// the presets and the scripts beside them are checked.
fn bench_output(file: &str) -> bool {
    file.starts_with("docs/bench/") && file.ends_with("/results.md")
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn listed_files(root: &Path) -> Vec<String> {
    let listed = Command::new("git")
        .args([
            "ls-files",
            "-z",
            "--cached",
            "--others",
            "--exclude-standard",
        ])
        .current_dir(root)
        .output();
    match listed {
        Ok(out) if out.status.success() => String::from_utf8_lossy(&out.stdout)
            .split('\0')
            .filter(|f| !f.is_empty() && root.join(f).is_file()) // deleted but not yet staged
            .map(String::from)
            .collect(),
        // A checkout without git (an exported tree): every file below the root but the
        // build output and hidden folders.
        _ => {
            let mut files = Vec::new();
            walk(root, root, &mut files);
            files
        }
    }
}

fn walk(root: &Path, dir: &Path, out: &mut Vec<String>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name().to_string_lossy().to_string();
        if name.starts_with('.') || (dir == root && name == "target") {
            continue;
        }
        if path.is_dir() {
            walk(root, &path, out);
        } else if let Ok(relative) = path.strip_prefix(root) {
            out.push(relative.to_string_lossy().replace('\\', "/"));
        }
    }
}

/// mdBook's id for a heading: lower case, whitespace to '-', punctuation but '-' and '_' dropped.
fn anchor(heading: &str) -> String {
    heading
        .chars()
        .filter_map(|c| match c {
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c.to_lowercase().next()?),
            c if c.is_whitespace() => Some('-'),
            _ => None,
        })
        .collect()
}

/// The anchors of a Markdown page's headings (code blocks skipped, repeats numbered as mdBook does).
fn page_anchors(text: &str) -> Vec<String> {
    let (mut out, mut seen, mut in_code) = (Vec::new(), HashMap::new(), false);
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_code = !in_code;
        } else if !in_code && line.starts_with('#') {
            let id = anchor(line.trim_start_matches('#').trim());
            let repeats: &mut usize = seen.entry(id.clone()).or_default();
            out.push(if *repeats == 0 {
                id
            } else {
                format!("{id}-{repeats}")
            });
            *repeats += 1;
        }
    }
    out
}

impl Repo {
    fn new(files: Vec<(String, String)>) -> Repo {
        let mut dirs = HashSet::new();
        for (f, _) in &files {
            let mut p = f.as_str();
            while let Some(i) = p.rfind('/') {
                p = &p[..i];
                dirs.insert(p.to_string());
            }
        }
        let anchors = files
            .iter()
            .filter(|(f, _)| f.ends_with(".md"))
            .map(|(f, text)| (f.clone(), page_anchors(text)))
            .collect();
        Repo {
            files: files.into_iter().map(|(f, _)| f).collect(),
            dirs,
            anchors,
        }
    }

    /// The files a path written in `from` can mean: relative to `from`'s folder, to the
    /// root, or (a partial path such as `gi/model.rs`) any file that ends with it.
    fn resolve(&self, from: &str, path: &str) -> Vec<String> {
        let dir = from.rfind('/').map_or("", |i| &from[..i]);
        let beside = normalise(&format!("{dir}/{path}"));
        let rooted = path
            .trim_start_matches(['.', '/'])
            .trim_end_matches('/')
            .to_string();
        for p in [beside, rooted.clone()] {
            if self.files.contains(&p) || self.dirs.contains(&p) {
                return vec![p];
            }
        }
        if ROOTS.iter().any(|r| rooted.starts_with(r)) {
            return Vec::new();
        }
        let tail = format!("/{rooted}");
        self.files
            .iter()
            .filter(|f| f.ends_with(&tail))
            .cloned()
            .collect()
    }
}

/// `a/b/../c` to `a/c`, `./` dropped.
fn normalise(path: &str) -> String {
    let mut parts: Vec<&str> = Vec::new();
    for part in path.split('/') {
        match part {
            "" | "." => {}
            ".." => _ = parts.pop(),
            p => parts.push(p),
        }
    }
    parts.join("/")
}

fn is_path_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || "_./-".contains(c)
}

/// One line's findings: missing paths, missing sections, citations nobody can open.
fn check_line(repo: &Repo, file: &str, line: &str, out: &mut Vec<String>) {
    let lower = line.to_lowercase();
    for (i, _) in lower.match_indices("issue") {
        let rest = lower[i + 5..].trim_start_matches([' ', '#']);
        if rest.starts_with(|c: char| c.is_ascii_digit())
            || rest.starts_with("\"")
            || rest.starts_with("\\\"")
        {
            out.push(format!(
                "cites an issue: \"{}\"",
                &line[i..(i + 9).min(line.len())]
            ));
        }
    }
    for cited in ["restir-notes", "notes §"] {
        if lower.contains(cited) {
            out.push(format!(
                "cites the notes file (\"{cited}\"): cite the book's chapter"
            ));
        }
    }
    if file.ends_with(".md") {
        for (i, _) in line.match_indices("](#") {
            let id: String = line[i + 3..].chars().take_while(|&c| c != ')').collect();
            check_section(repo, file, &[file.to_string()], &id, true, out);
        }
    }
    let chars: Vec<(usize, char)> = line.char_indices().collect();
    let mut k = 0;
    while k < chars.len() {
        let start = k;
        while k < chars.len() && is_path_char(chars[k].1) {
            k += 1;
        }
        if k == start {
            k += 1;
            continue;
        }
        let end = chars.get(k).map_or(line.len(), |c| c.0);
        let token = line[chars[start].0..end].trim_end_matches('.');
        let before = start.checked_sub(1).map(|j| chars[j].1);
        let after = line[end..].chars().next();
        // `seed-*/`, `{name}.toml`, `https://...`: patterns and addresses, not paths.
        let templated = matches!(after, Some('*' | '{' | '<' | '$')) || before == Some(':');
        // A Rust string that is only a path is data the code opens (a fixture, an output).
        let data = file.ends_with(".rs") && before == Some('"') && after == Some('"');
        let stripped = token.trim_start_matches(['.', '/']);
        let rooted = ROOTS.iter().any(|r| stripped.starts_with(r));
        // Partial paths (`gi/model.rs`), source files by name, Markdown link targets.
        let linked = file.ends_with(".md") && line[..chars[start].0].ends_with("](");
        let named =
            (token.contains('/') || token.ends_with(".rs") || token.ends_with(".wgsl") || linked)
                && [".rs", ".wgsl", ".md"]
                    .iter()
                    .any(|e| token.ends_with(e) && token.len() > e.len());
        if token == "README" {
            check_quoted(
                repo,
                "README.md",
                &["README.md".to_string()],
                &line[end..],
                out,
            );
        }
        if templated || data || !(rooted || named) {
            continue;
        }
        let found = repo.resolve(file, token);
        if found.is_empty() {
            out.push(format!("names `{token}`, which does not exist"));
            continue;
        }
        if !token.ends_with(".md") {
            continue;
        }
        if after == Some('#') {
            let id: String = line[end + 1..]
                .chars()
                .take_while(|&c| c.is_alphanumeric() || c == '-' || c == '_')
                .collect();
            check_section(repo, token, &found, &id, true, out);
        } else {
            check_quoted(repo, token, &found, &line[end..], out);
        }
    }
}

/// `X.md, "Heading"` or `X.md "Heading"` (also inside a Rust string, `\"Heading\"`).
fn check_quoted(repo: &Repo, page: &str, found: &[String], rest: &str, out: &mut Vec<String>) {
    if !rest.starts_with([',', ' ']) {
        return;
    }
    let rest = rest.trim_start_matches([',', ' ', '(']);
    if let Some(quoted) = rest.trim_start_matches('\\').strip_prefix('"') {
        let title = quoted.split(['"', '\\']).next().unwrap_or("");
        check_section(repo, page, found, &anchor(title), false, out);
    }
}

/// A section exists: `#anchor` exactly, a quoted title as the start of a heading.
fn check_section(
    repo: &Repo,
    page: &str,
    found: &[String],
    id: &str,
    exact: bool,
    out: &mut Vec<String>,
) {
    let known = |f: &String| {
        repo.anchors.get(f).is_some_and(|all| {
            all.iter().any(|a| {
                if exact {
                    a == id
                } else {
                    !id.is_empty() && a.starts_with(id)
                }
            })
        })
    };
    if !found.iter().any(known) {
        out.push(format!(
            "names section `{id}` of {page}, which has no such heading"
        ));
    }
}

fn check_file(repo: &Repo, file: &str, text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let mut found = Vec::new();
        check_line(repo, file, line, &mut found);
        out.extend(found.into_iter().map(|f| format!("{file}:{}: {f}", n + 1)));
    }
    out
}

fn read_repo() -> (Repo, Vec<(String, String)>) {
    let root = root();
    let files: Vec<(String, String)> = listed_files(&root)
        .into_iter()
        .map(|f| {
            let text = if TEXT.iter().any(|e| f.ends_with(e)) {
                std::fs::read_to_string(root.join(&f)).unwrap_or_default()
            } else {
                String::new()
            };
            (f, text)
        })
        .collect();
    let checked = files
        .iter()
        .filter(|(f, _)| TEXT.iter().any(|e| f.ends_with(e)))
        .filter(|(f, _)| !SKIP.iter().any(|s| f.starts_with(s)) && !bench_output(f))
        .cloned()
        .collect();
    (Repo::new(files), checked)
}

#[test]
fn every_path_and_section_a_comment_or_page_names_exists() {
    let (repo, checked) = read_repo();
    assert!(
        checked.len() > 100,
        "found only {} files to check",
        checked.len()
    );
    let findings: Vec<String> = checked
        .iter()
        .flat_map(|(f, text)| check_file(&repo, f, text))
        .collect();
    assert!(
        findings.is_empty(),
        "{} pointers a reader cannot follow (cite the book's section instead; \
         docs/src/SUMMARY.md lists the chapters):\n{}",
        findings.len(),
        findings.join("\n")
    );
}

/// The planted twin: a made-up path, a made-up section and an issue number, each found
/// once, while the real pointers beside them pass.
#[test]
fn the_checker_finds_a_planted_twin() {
    let (repo, _) = read_repo();
    let twin = "// The merge (docs/src/temporal-reuse.md, \"The merge\"; render/src/reservoir.rs).\n\
                // See render/src/reservoir_typo.rs for the CPU mirror.\n\
                // Derived in docs/src/ris.md#the-streamed-reservoir, issue 12.\n";
    let findings = check_file(&repo, "render/src/twin.rs", twin);
    assert_eq!(findings.len(), 3, "{findings:#?}");
    assert!(findings[0].starts_with("render/src/twin.rs:2: names `render/src/reservoir_typo.rs`"));
    assert!(
        findings[1].starts_with("render/src/twin.rs:3: cites an issue"),
        "{}",
        findings[1]
    );
    assert!(findings[2].contains("section `the-streamed-reservoir` of docs/src/ris.md"));
    assert_eq!(
        anchor("Unbiased reuse: what `M` costs (1/M)"),
        "unbiased-reuse-what-m-costs-1m"
    );
}

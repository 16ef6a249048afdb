//! Every figure README and the book quote from a measurement agrees with the data file it
//! came from (docs/src/figures.md): a figure link `[0.44×](../bench/x/map.csv "formula")`
//! is recomputed from its CSV or JSON and compared under the one rounding rule, a table
//! bound by a `<!-- figures: ... -->` comment is recomputed cell by cell, and a ratio or a
//! time printed outside both fails as unbound. `cargo test figures` runs these tests;
//! `FIGURES_WRITE=1 cargo test figures` rewrites the numbers that only drifted (bounds and
//! anything else are left to a person). No GPU: it reads text files. The planted twins at
//! the end prove the checker fires.

mod check;
mod data;
mod expr;
mod pages;
mod text;

use std::path::{Path, PathBuf};

use check::{Report, check_page};
use data::Tables;
use pages::Page;

fn root() -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    root.canonicalize().unwrap_or(root)
}

/// README and every page of the book, relative to the root.
fn book_pages(root: &Path) -> Vec<String> {
    let mut pages = vec!["README.md".to_string()];
    let mut dirs = vec![root.join("docs/src")];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).into_iter().flatten().flatten() {
            let path = entry.path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "md") {
                let name = path.strip_prefix(root).unwrap_or(&path);
                pages.push(name.to_string_lossy().replace('\\', "/"));
            }
        }
    }
    pages.sort();
    pages
}

/// `FIGURES_ONLY=measured/denoiser,README`: check (and rewrite) only the pages whose path
/// contains one of these, so that two people binding figures in different chapters can
/// each run `FIGURES_WRITE=1` on their own pages.
fn selected(name: &str) -> bool {
    match std::env::var("FIGURES_ONLY") {
        Ok(only) if !only.trim().is_empty() => only.split(',').any(|s| name.contains(s.trim())),
        _ => true,
    }
}

fn check_all(root: &Path, write: bool) -> (Vec<String>, usize, usize, bool) {
    let mut tables = Tables::default();
    let (mut findings, mut figures, mut bound) = (Vec::new(), 0, 0);
    let only = std::env::var("FIGURES_ONLY").is_ok_and(|v| !v.trim().is_empty());
    for name in book_pages(root).into_iter().filter(|n| selected(n)) {
        let page = match Page::read(root, &name) {
            Ok(p) => p,
            Err(e) => {
                findings.push(e);
                continue;
            }
        };
        let report = check_page(&page, &mut tables, root);
        figures += report.figures;
        bound += report.tables;
        if write && !report.edits.is_empty() {
            rewrite(&page, &report);
        }
        findings.extend(report.findings);
    }
    (findings, figures, bound, only)
}

/// Applies a page's corrections, last first so the earlier ranges stay valid.
fn rewrite(page: &Page, report: &Report) {
    let mut text = page.text.clone();
    let mut edits = report.edits.clone();
    edits.sort_by_key(|(r, _)| std::cmp::Reverse(r.start));
    for (range, fixed) in edits {
        eprintln!(
            "{}:{}: {} -> {fixed}",
            page.name,
            page.line_of(range.start),
            &text[range.clone()]
        );
        text.replace_range(range, &fixed);
    }
    std::fs::write(&page.path, text).expect("cannot write the corrected page");
}

#[test]
fn figures_in_readme_and_the_book_agree_with_their_data() {
    let root = root();
    let write = std::env::var_os("FIGURES_WRITE").is_some_and(|v| v == "1");
    let (findings, figures, tables, only) = check_all(&root, write);
    eprintln!("figures: {figures} figure links and {tables} bound tables checked");
    assert!(
        findings.is_empty(),
        "{} figures disagree with their data or have none (docs/src/figures.md; \
         `FIGURES_WRITE=1 cargo test figures` rewrites numbers that only drifted):\n{}",
        findings.len(),
        findings.join("\n")
    );
    assert!(
        only || (figures >= 50 && tables >= 10),
        "only {figures} figure links and {tables} bound tables found: is the checker reading the book?"
    );
}

/// A page, its data and its command in a temporary tree, checked as the book is.
struct Twin {
    root: PathBuf,
}

impl Twin {
    fn new(name: &str, page: &str, command: bool) -> Twin {
        let root = std::env::temp_dir().join(format!("figures-twin-{}-{name}", std::process::id()));
        let data = root.join("docs/bench/showcase");
        std::fs::create_dir_all(&data).unwrap();
        std::fs::write(
            data.join("results.csv"),
            "config,median_frame_ms,mean_luma_rmse,black_pixel_fraction\n\
             nee,31.77,0.4824,0.6503\nris,70.14,0.1030,0.1866\n\
             restir-pairwise,252.13,0.03297,0.00119\nfrozen,never,0.2,0.1\n",
        )
        .unwrap();
        let cmd = data.join("command.txt");
        if command {
            std::fs::write(&cmd, "restir-viewer bench --scene builtin:concourse\n").unwrap();
        } else {
            let _ = std::fs::remove_file(&cmd);
        }
        std::fs::write(root.join("twin.md"), page).unwrap();
        Twin { root }
    }

    fn findings(&self) -> Vec<String> {
        let page = Page::read(&self.root, "twin.md").unwrap();
        check_page(&page, &mut Tables::default(), &self.root).findings
    }
}

impl Drop for Twin {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.root);
    }
}

const TWIN_PAGE: &str = "# Showcase\n\
\n\
ReSTIR's frame costs [3.59×](docs/bench/showcase/results.csv \"median_frame_ms[config=restir-pairwise] / median_frame_ms[config=ris]\")\n\
RIS's and its MSE is [0.10×](docs/bench/showcase/results.csv \"(mean_luma_rmse[config=restir-pairwise] /\n\
mean_luma_rmse[config=ris])^2\") RIS's, in `1.5×` code that is not a figure.\n\
\n\
<!-- figures: docs/bench/showcase/results.csv key: config\n\
     columns: -; median_frame_ms / median_frame_ms[config='x;y'|nee]; 100 * black_pixel_fraction -->\n\
| configuration | time × `nee` | black pixels |\n\
| --- | --- | --- |\n\
| `nee` | 1.00× | 65.0 % |\n\
| `restir-pairwise` | 7.94× | 0.12 % |\n\
| `frozen` | never | 10.0 % |\n";

#[test]
fn figures_twin_that_agrees_has_no_findings() {
    let twin = Twin::new("agrees", TWIN_PAGE, true);
    assert_eq!(twin.findings(), Vec::<String>::new());
}

#[test]
fn figures_planted_edits_are_caught_with_their_line() {
    let cases = [
        (
            "[3.59×]",
            "[3.95×]",
            "twin.md:3: prints 3.95, the data give 3.5946",
        ),
        (
            "[0.10×]",
            "[0.12×]",
            "twin.md:4: prints 0.12, the data give 0.1024",
        ),
        (
            "| 7.94× |",
            "| 7.49× |",
            "twin.md:12: prints 7.49, the data give 7.9361",
        ),
        (
            "| 65.0 % |",
            "| 56.0 % |",
            "twin.md:11: prints 56.0, the data give 65.03",
        ),
        (
            "Showcase",
            "Showcase at 2.5× the cost",
            "twin.md:1: `2.5× the cost",
        ),
        (
            "[config=ris]\")",
            "[config=nee]\")",
            "twin.md:3: prints 3.59, the data give 7.9361",
        ),
        (
            "| never |",
            "| always |",
            "twin.md:13: prints `always`, the data say `never`",
        ),
    ];
    for (from, to, expected) in cases {
        let twin = Twin::new("edited", &TWIN_PAGE.replacen(from, to, 1), true);
        let found = twin.findings();
        assert!(
            found.len() == 1 && found[0].starts_with(expected),
            "planting `{to}`: expected one finding starting `{expected}`, got {found:#?}"
        );
    }
}

#[test]
fn figures_without_their_command_are_caught() {
    let twin = Twin::new("no-command", TWIN_PAGE, false);
    let found = twin.findings();
    assert!(
        !found.is_empty()
            && found
                .iter()
                .all(|f| f.contains("has no command.txt or run*.sh")),
        "{found:#?}"
    );
}

/// The real book, one figure edited: the check on the real pages fires on it.
#[test]
fn figures_planted_in_the_real_book_are_caught() {
    let root = root();
    let mut planted = 0;
    for name in book_pages(&root) {
        let page = Page::read(&root, &name).unwrap();
        let (figures, _) = page.links();
        // The first figure that prints a value (a bound such as "under 41 s" may still
        // hold after the edit).
        let Some((link, first)) = figures.iter().find_map(|link| {
            let printed = text::numbers(&page.text[link.text.clone()]);
            let first = printed
                .into_iter()
                .find(|p| p.claim == text::Claim::Equals)?;
            Some((link, first))
        }) else {
            continue;
        };
        // Add 3 to the last printed digit of the first number: a drift of 3 units.
        let at = link.text.start + first.span.end - 1;
        let digit = page.text.as_bytes()[at];
        let Some(d) = (digit as char).to_digit(10) else {
            continue;
        };
        let mut text = page.text.clone();
        text.replace_range(at..at + 1, &((d + 3) % 10).to_string());
        let edited = Page::new(&name, page.path.clone(), text);
        let line = edited.line_of(link.text.start);
        let before = check_page(&page, &mut Tables::default(), &root)
            .findings
            .len();
        let after = check_page(&edited, &mut Tables::default(), &root).findings;
        let prefix = format!("{name}:{line}: prints");
        assert!(
            after.len() > before && after.iter().any(|f| f.starts_with(&prefix)),
            "{name}: an edited figure on line {line} went unnoticed"
        );
        planted += 1;
    }
    assert!(
        planted >= 5,
        "only {planted} pages bind a figure to plant an edit in"
    );
}

//! `command.txt`: the command line that made an output folder, as a shell reads it back
//! (`restir-viewer`, then the arguments as given), so that every data folder says how to
//! remake it.

use std::path::Path;

use anyhow::Context;

use crate::bench::plan::jobs::shell_words;

/// The file, in the folder it describes.
pub const COMMAND_FILE: &str = "command.txt";

/// Writes `restir-viewer ARGS` into `dir`'s `command.txt`; `args` are the words after the
/// program name (`bench --scene ...`).
pub fn write(dir: &Path, args: &[String]) -> anyhow::Result<()> {
    let words: Vec<&str> = std::iter::once("restir-viewer")
        .chain(args.iter().map(String::as_str))
        .collect();
    let path = dir.join(COMMAND_FILE);
    std::fs::write(&path, shell_words(&words) + "\n")
        .with_context(|| format!("{}: cannot write", path.display()))
}

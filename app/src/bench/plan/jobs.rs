//! A bench as independent jobs (docs/src/headless.md, "Sweeps as independent jobs"):
//! `--list-jobs` prints one `bench` command per configuration, each writing its own folder
//! under `OUT/jobs/`; `--merge` (write/jobs_merge.rs) gathers what they wrote. The shell
//! quoting here also writes each output folder's `command.txt`.

use std::path::{Path, PathBuf};

use super::configs::Config;

/// The folder of configuration `name`'s job under `out`.
pub fn job_dir(out: &Path, name: &str) -> PathBuf {
    out.join("jobs").join(slug(name))
}

/// This process's `bench` arguments with `--list-jobs` left out and `--configs` and `--out`
/// replaced: one job's command line.
pub fn job_argv(args: &[String], config: &str, out: &Path) -> Vec<String> {
    let mut kept = Vec::new();
    let mut skip_value = false;
    for a in args {
        if skip_value {
            skip_value = false;
            continue;
        }
        match a.as_str() {
            "--list-jobs" | "--merge" => {}
            // A job runs one configuration, a `--knob` point already named in it.
            "--configs" | "--out" | "--knob" => skip_value = true,
            _ if a.starts_with("--configs=")
                || a.starts_with("--out=")
                || a.starts_with("--knob=") => {}
            _ => kept.push(a.clone()),
        }
    }
    kept.extend([
        "--configs".to_string(),
        config.to_string(),
        "--out".to_string(),
        job_dir(out, config).to_string_lossy().into_owned(),
    ]);
    kept
}

/// Prints one command per configuration.
pub fn list(configs: &[Config], out: &Path) -> anyhow::Result<()> {
    let exe = std::env::current_exe()?;
    // The arguments after `bench`.
    let argv: Vec<String> = std::env::args()
        .skip_while(|a| a != "bench")
        .skip(1)
        .collect();
    for c in configs {
        let job = job_argv(&argv, &c.name, out);
        println!("{}", shell_line(&exe.to_string_lossy(), &job));
    }
    Ok(())
}

/// Letters, digits, `-`, `.` and `_` kept, anything else `_`.
pub fn slug(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '-' | '.' | '_') {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// A command line a POSIX shell reads back as `program bench args`.
pub fn shell_line(program: &str, args: &[String]) -> String {
    let words: Vec<&str> = [program, "bench"]
        .into_iter()
        .chain(args.iter().map(String::as_str))
        .collect();
    shell_words(&words)
}

/// Words joined into a line a POSIX shell splits back into them: each word quoted unless
/// it holds only characters no shell treats specially.
pub fn shell_words(words: &[&str]) -> String {
    let quote = |s: &str| {
        if !s.is_empty()
            && s.chars()
                .all(|c| c.is_ascii_alphanumeric() || "-_./:=@+,".contains(c))
        {
            s.to_string()
        } else {
            format!("'{}'", s.replace('\'', r"'\''"))
        }
    };
    words.iter().map(|w| quote(w)).collect::<Vec<_>>().join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_job_keeps_every_argument_but_its_configs_and_out() {
        let args: Vec<String> = [
            "--scene",
            "builtin:cornell",
            "--configs",
            "ris,nee",
            "--list-jobs",
            "--out=x",
            "--seeds",
            "4",
        ]
        .map(String::from)
        .to_vec();
        let job = job_argv(&args, "ris+denoise", Path::new("o"));
        assert_eq!(
            job.join(" "),
            "--scene builtin:cornell --seeds 4 --configs ris+denoise --out o/jobs/ris_denoise"
        );
    }

    #[test]
    fn shell_words_quote_what_a_shell_would_split_and_nothing_else() {
        assert_eq!(
            shell_words(&[
                "restir-viewer",
                "bench",
                "--size",
                "48x32",
                "--set",
                "a=1,b=2"
            ]),
            "restir-viewer bench --size 48x32 --set a=1,b=2"
        );
        assert_eq!(
            shell_words(&["--out", "my runs", "--configs", "it's.toml", ""]),
            r"--out 'my runs' --configs 'it'\''s.toml' ''"
        );
    }
}

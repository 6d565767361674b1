//! Every example a newcomer is shown is run as shown: the command lines of the README and of
//! docs/python.md, the README's Python, and the option examples of every `--help` and of the
//! README's prose. They run from a fresh folder holding only `scenarios/` (as the project's
//! folder does), with `TOUCHDOWN_HOME` set as the README's quick start sets it.

use std::path::Path;
use std::process::{Command, Output};
use touchdown_tests::{python, root};

/// A fresh working folder where the examples' relative paths (`scenarios/...`) resolve.
fn workspace() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink(root().join("scenarios"), dir.path().join("scenarios")).unwrap();
    dir
}

/// The command `program args` run in `cwd` as the quick start leaves a shell.
fn command(program: &Path, args: &[String], cwd: &Path) -> Output {
    Command::new(program)
        .args(args)
        .current_dir(cwd)
        .env("TOUCHDOWN_HOME", root())
        .output()
        .unwrap_or_else(|e| panic!("{} does not run: {e}", program.display()))
}

/// The lines of `text`'s code blocks indented by four spaces, and the bodies of its fenced
/// `python` blocks.
fn code(text: &str) -> (Vec<String>, Vec<String>) {
    let (mut lines, mut blocks) = (Vec::new(), Vec::new());
    let mut fenced: Option<String> = None;
    for line in text.lines() {
        match (&mut fenced, line.trim_start().strip_prefix("```")) {
            (None, Some(lang)) => {
                if lang.trim() == "python" {
                    fenced = Some(String::new())
                }
            }
            (Some(body), Some(_)) => {
                blocks.push(std::mem::take(body));
                fenced = None;
            }
            (Some(body), None) => {
                body.push_str(line);
                body.push('\n');
            }
            (None, None) => {
                if let Some(l) = line.strip_prefix("    ") {
                    if !l.starts_with(' ') && !l.trim().is_empty() {
                        lines.push(l.trim().to_string());
                    }
                }
            }
        }
    }
    (lines, blocks)
}

/// What a command line of the docs is, and why a few are not run here.
enum Example {
    /// `touchdown ARGS` (or `cargo run --release --bin touchdown -- ARGS`), expecting this exit
    /// status.
    Touchdown(Vec<String>, i32),
    /// `.venv/bin/python ARGS`.
    Python(Vec<String>),
    /// Not run here, for the reason given.
    Elsewhere(&'static str),
}

fn classify(line: &str) -> Example {
    let words = shlex::split(line).unwrap_or_else(|| panic!("{line}: not shell words"));
    let rest = |n: usize| words[n..].to_vec();
    match words.iter().map(String::as_str).collect::<Vec<_>>()[..] {
        ["scripts/test", ..] => Example::Elsewhere("the test suite itself"),
        ["scripts/setup-python"] => Example::Elsewhere("scripts/test runs it before these tests"),
        ["export", "TOUCHDOWN_HOME=\"$PWD\""] | ["export", "TOUCHDOWN_HOME=$PWD"] => {
            Example::Elsewhere("every example runs with TOUCHDOWN_HOME set")
        }
        ["cargo", "install", ..] => Example::Elsewhere(
            "a release build; an installed binary is a copied one, tested by a_copied_binary_runs_mujoco_with_touchdown_home_alone (tests/cli/engines.rs)",
        ),
        ["pip", "install", "."] => Example::Elsewhere(
            "a release build into another environment; the package installed outside the project is tested by test_mujoco_runs_from_the_package_installed_elsewhere_with_no_variable (python/tests)",
        ),
        [".venv/bin/python", "docs/python/dispersion_study.py", ..] => Example::Elsewhere(
            "test_the_worked_example_regenerates_its_data (python/tests) runs it",
        ),
        ["cargo", "run", "--release", "--bin", "touchdown", "--", ..] => {
            Example::Touchdown(rest(6), 0)
        }
        // The README says why: the engines part on the lightly loaded legs.
        ["touchdown", "compare", "scenarios/fig-25-26.toml"] => Example::Touchdown(rest(1), 3),
        ["touchdown", ..] => Example::Touchdown(rest(1), 0),
        [".venv/bin/python", ..] => Example::Python(rest(1)),
        _ => panic!("{line}: an example this test does not know how to run"),
    }
}

/// Runs the command-line examples of `page`, in order, in the folder `dir` (as a reader would
/// in one shell); how many ran.
fn run_page(page: &str, dir: &Path) -> usize {
    let text = std::fs::read_to_string(root().join(page)).unwrap();
    let (lines, blocks) = code(&text);
    let mut ran = 0;
    for line in &lines {
        let out = match classify(line) {
            Example::Elsewhere(why) => {
                eprintln!("{page}: `{line}` is not run here: {why}");
                continue;
            }
            Example::Touchdown(args, status) => {
                let out = command(Path::new(env!("CARGO_BIN_EXE_touchdown")), &args, dir);
                assert_eq!(
                    out.status.code(),
                    Some(status),
                    "{page}: `{line}`: {}",
                    String::from_utf8_lossy(&out.stderr)
                );
                out
            }
            Example::Python(args) => {
                let out = command(&python(), &args, dir);
                assert!(
                    out.status.success(),
                    "{page}: `{line}`: {}",
                    String::from_utf8_lossy(&out.stderr)
                );
                out
            }
        };
        assert!(!out.stdout.is_empty(), "{page}: `{line}` printed nothing");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!stderr.contains("panicked"), "{page}: `{line}`: {stderr}");
        ran += 1;
    }
    for block in &blocks {
        let out = command(&python(), &["-c".into(), block.clone()], dir);
        assert!(
            out.status.success(),
            "{page}: the Python example\n{block}\nfails: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        ran += 1;
    }
    ran
}

#[test]
fn the_readme_examples_run_as_shown() {
    // The two commands' landing, the quick start's seven commands, the Python block; the
    // quick start's folders are where it says.
    let dir = workspace();
    assert_eq!(run_page("README.md", dir.path()), 9);
    for written in [
        "runs/fig/history.csv",
        "views/fig-25-26.html",
        "campaigns/small/landings.parquet",
        "campaigns/shard-2/landings.jsonl",
    ] {
        assert!(dir.path().join(written).is_file(), "{written} is missing");
    }
}

#[test]
fn the_python_page_examples_run_as_shown() {
    assert_eq!(run_page("docs/python.md", workspace().path()), 1);
}

/// The option examples in backquotes of every `--help` and of the README's prose, each run on
/// a command that takes it; `completions` and `man` as their help says.
#[test]
fn the_help_and_readme_option_examples_run_as_shown() {
    let touchdown = Path::new(env!("CARGO_BIN_EXE_touchdown"));
    let dir = workspace();
    let help = |args: &[&str]| {
        let mut args: Vec<String> = args.iter().map(|a| a.to_string()).collect();
        args.push("--help".into());
        String::from_utf8(command(touchdown, &args, dir.path()).stdout).unwrap()
    };
    // Every subcommand `touchdown --help` lists.
    let top = help(&[]);
    let commands: Vec<&str> = top
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter(|l| l.as_bytes().get(2).is_some_and(|b| b.is_ascii_lowercase()))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .collect();
    assert!(commands.len() >= 14, "{commands:?}");
    let mut text = top.clone();
    for c in &commands {
        text += &help(&[c]);
    }
    text += &std::fs::read_to_string(root().join("README.md")).unwrap();
    // Backquoted fragments, the help's line breaks joined.
    let joined = text.split_whitespace().collect::<Vec<_>>().join(" ");
    let mut fragments: Vec<&str> = joined
        .split('`')
        .skip(1)
        .step_by(2)
        .filter(|f| {
            f.starts_with("--set ")
                || f.starts_with("--vv=")
                || f.starts_with("--stop-restitution ")
        })
        // A synopsis (`--set FIELD=VALUE`) is not an example.
        .filter(|f| {
            !f.split(|c: char| !c.is_alphanumeric())
                .any(|w| w.len() > 1 && w.chars().all(|c| c.is_ascii_uppercase()))
        })
        .collect();
    fragments.sort();
    fragments.dedup();
    assert!(fragments.len() >= 6, "{fragments:?}");
    for fragment in &fragments {
        let words = shlex::split(fragment).unwrap();
        let args: Vec<String> = if fragment.starts_with("--set ") {
            ["run", "scenarios/fig-25-26.toml"]
                .iter()
                .map(|s| s.to_string())
                .chain(words)
                .collect()
        } else {
            // A boundary option, on a coarse search so that it stays quick.
            let mut a: Vec<String> = [
                "boundary",
                "scenarios/fig-25-26.toml",
                "--vh-step",
                "8",
                "--vh-max",
                "16",
                "--scan-step",
                "0",
            ]
            .iter()
            .map(|s| s.to_string())
            .collect();
            if !fragment.starts_with("--vv=") {
                a.push("--vv=-8:-8:2".into());
            }
            a.extend(words);
            a
        };
        let out = command(touchdown, &args, dir.path());
        assert!(
            out.status.success(),
            "`{fragment}`: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    // `touchdown completions bash > FILE` and `touchdown man --out DIR` then `man -l DIR/touchdown.1`.
    assert!(joined.contains(
        "`touchdown completions bash > ~/.local/share/bash-completion/completions/touchdown`"
    ));
    let out = command(
        touchdown,
        &["completions".into(), "bash".into()],
        dir.path(),
    );
    assert!(out.status.success() && String::from_utf8_lossy(&out.stdout).contains("_touchdown"));
    assert!(joined.contains("`man -l DIR/touchdown.1`"));
    let out = command(
        touchdown,
        &["man".into(), "--out".into(), "manual".into()],
        dir.path(),
    );
    assert!(out.status.success());
    assert!(dir.path().join("manual/touchdown.1").is_file());
}

//! The command line's help: typo suggestions, help within 100 columns, completions, man pages.

use super::{temp, touchdown};

/// The command line helps itself: a typo gets clap's suggestion, every help text wraps at 100
/// columns, and the shell completions and manual pages are generated from the same definition.
#[test]
fn typos_get_suggestions_help_wraps_and_completions_and_man_pages_are_generated() {
    let o = touchdown(&["campain"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("'campaign'"));
    let o = touchdown(&["run", "scenarios/flat-drop.toml", "--formt", "json"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("a similar argument exists: '--format'"));

    let commands = [
        "run",
        "compare",
        "precision",
        "robustness",
        "export-mjcf",
        "validate",
        "calibrate",
        "estimate",
        "sensitivity",
        "campaign",
        "boundary",
        "completions",
        "man",
    ];
    let every = commands.iter().map(|c| vec![*c, "--help"]);
    for c in every.chain([vec!["--help"], vec!["campaign", "merge", "--help"]]) {
        let o = touchdown(&c);
        assert!(o.status.success(), "{c:?}");
        let text = String::from_utf8_lossy(&o.stdout);
        for line in text.lines() {
            assert!(
                line.chars().count() <= 100,
                "{c:?}: a help line of {} columns: {line}",
                line.chars().count()
            );
        }
    }

    let o = touchdown(&["completions", "bash"]);
    assert!(o.status.success());
    let script = String::from_utf8_lossy(&o.stdout);
    assert!(
        script.contains("_touchdown()") && script.contains("campaign") && script.contains("--set")
    );
    let dir = temp("man");
    let o = touchdown(&["man", "--out", dir.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let page = std::fs::read_to_string(dir.join("touchdown.1")).unwrap();
    assert!(page.contains(".TH touchdown 1"), "{page}");
    for c in commands {
        let page = std::fs::read_to_string(dir.join(format!("touchdown-{c}.1"))).unwrap();
        assert!(page.contains(&format!(".TH touchdown-{c} 1")), "{c}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

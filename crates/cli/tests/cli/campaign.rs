//! `touchdown campaign`: records and statistics, progress, plots, paired pages, arguments.

use super::{assert_png, root, temp, touchdown};
use std::process::Command;

#[test]
fn a_campaign_streams_json_lines_then_its_statistics_and_draws_its_plots() {
    let dir = temp("campaign");
    let plots = dir.to_path_buf();
    let out = touchdown(&[
        "campaign",
        "scenarios/campaigns/small.toml",
        "--format",
        "json",
        "--threads",
        "2",
        "--out",
        dir.to_str().unwrap(),
        "--plot",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 25);
    for (i, l) in lines[..24].iter().enumerate() {
        assert_eq!(l["landing"], i, "in landing order");
        assert!(l["outcome"].is_string() && l["failure"].is_string());
    }
    let stats = &lines[24]["statistics"];
    assert_eq!(stats["landings"], 24);
    let lower = stats["stable"]["lower_bound"].as_f64().unwrap();
    assert!(lower > 0.0 && lower < stats["stable"]["fraction"].as_f64().unwrap());
    assert!(!text.contains("null") && !text.contains("NaN"));
    // The lines on standard output are the file's.
    let file = std::fs::read_to_string(dir.join("landings.jsonl")).unwrap();
    assert!(text.starts_with(&file));
    assert_png(&plots.join("outcomes.png"));
    assert_png(&plots.join("strokes.png"));
    // The text report says what its numbers are.
    let out = touchdown(&["campaign", "scenarios/campaigns/small.toml"]);
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(
        report.contains("P(stable landing) = ") && report.contains("one-sided Clopper-Pearson")
    );
}

/// Long commands draw their progress on a terminal's standard error, with the rate and the
/// time left, and nothing when standard error is not a terminal or with `--quiet`. The terminal
/// is a pseudo-terminal from `script` (util-linux, in every Debian).
#[test]
fn a_campaign_shows_its_progress_on_a_terminal_only() {
    let on_terminal = |extra: &str| {
        let command = format!(
            "{} campaign scenarios/campaigns/small.toml{extra} > /dev/null",
            env!("CARGO_BIN_EXE_touchdown")
        );
        let out = Command::new("script")
            .args(["-qec", &command, "/dev/null"])
            .current_dir(root())
            .output()
            .expect("`script` runs (Debian package bsdutils)");
        assert!(out.status.success(), "{out:?}");
        String::from_utf8_lossy(&out.stdout).replace('\r', "\n")
    };
    let shown = on_terminal("");
    let bar = shown
        .lines()
        .find(|l| l.contains("/24 landings · "))
        .unwrap_or_else(|| panic!("no progress bar in {shown:?}"));
    assert!(bar.ends_with(" left") || bar.contains(" left "), "{bar:?}");
    assert!(!on_terminal(" --quiet").contains("landings"));
    let piped = touchdown(&["campaign", "scenarios/campaigns/small.toml"]);
    assert!(piped.status.success());
    assert!(
        piped.stderr.is_empty(),
        "{:?}",
        String::from_utf8_lossy(&piped.stderr)
    );
}

#[test]
fn campaign_arguments_are_checked_by_name() {
    let expect = |args: &[&str], says: &str| {
        let out = touchdown(args);
        assert!(!out.status.success(), "{args:?} succeeded");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(says), "{args:?}: {stderr}");
    };
    let small = "scenarios/campaigns/small.toml";
    let cases: [(&[&str], &str); 8] = [
        (&["--shard", "5/4"], "expected K/N with 1 ≤ K ≤ N"),
        (
            &["--engines", "core,core"],
            "scenarios/campaigns/small.toml: field `--engines`: core is named twice",
        ),
        (
            &["--engines", "core,bullet"],
            "invalid value 'bullet' for '--engines",
        ),
        (
            &["--view", "2", "--out", "x"],
            "--view: a campaign on one engine has no disagreements to watch",
        ),
        (
            &["--plot"],
            "the following required arguments were not provided:\n  --out <DIR>",
        ),
        (
            &["--add", "3"],
            "--add: name the finished campaign's folder with --out",
        ),
        (&["--threads", "0"], "--threads: expected at least 1 thread"),
        (&["--format", "yaml"], "invalid value 'yaml' for '--format"),
    ];
    for (extra, says) in cases {
        let args: Vec<&str> = ["campaign", small].iter().chain(extra).copied().collect();
        expect(&args, says);
    }
    expect(
        &["campaign", "scenarios/campaigns/nothing.toml"],
        "scenarios/campaigns/nothing.toml: cannot read the campaign file",
    );
    let empty = temp("merge-empty");
    std::fs::create_dir_all(&empty).unwrap();
    let e = empty.to_str().unwrap();
    expect(
        &["campaign", "estimate", "--paired", e, "--low", e],
        "manifest.json: No such file or directory",
    );
    expect(
        &[
            "campaign",
            "estimate",
            "--paired",
            e,
            "--low",
            e,
            "--cost-ratio=0",
        ],
        "--cost-ratio: expected a positive number, got 0",
    );
    expect(
        &["campaign", "merge", empty.to_str().unwrap(), "--out", "x"],
        "expected a campaign folder written by `touchdown campaign --out`",
    );
}

#[test]
fn a_campaign_of_descent_and_horizontal_speeds_plots_the_engines_boundary() {
    let dir = temp("speeds");
    let plots = dir.join("out");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("speeds.toml");
    std::fs::write(
        &file,
        format!(
            "schema_version = 1\nname = \"speeds\"\nscenario = {:?}\nlandings = 40\nseed = 3\n\n[[dispersion]]\nfield = \"touchdown.vertical_velocity\"\nunit = \"ft/s\"\ndistribution = \"uniform\"\nmin = -12.0\nmax = -4.0\n\n[[dispersion]]\nfield = \"touchdown.horizontal_velocity[1]\"\nunit = \"ft/s\"\ndistribution = \"uniform\"\nmin = 0.0\nmax = 30.0\n",
            root().join("scenarios/table-i-2-2-vv8.toml").display().to_string()
        ),
    )
    .unwrap();
    let out = touchdown(&[
        "campaign",
        file.to_str().unwrap(),
        "--out",
        dir.join("out").to_str().unwrap(),
        "--plot",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let b: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(plots.join("boundary.json")).unwrap())
            .unwrap();
    let points = b["points"].as_array().unwrap();
    // The base configuration overturns within 30 ft/s up to about 8 ft/s of descent (four of
    // the search's descent speeds; docs/python.md has the same landing's boundary): each is a
    // point of the plot.
    assert!(points.len() >= 4, "{b}");
    for p in points {
        let vh = p["applied.touchdown.horizontal_velocity[1]_ft_s"]
            .as_f64()
            .unwrap();
        let vv = p["applied.touchdown.vertical_velocity_ft_s"]
            .as_f64()
            .unwrap();
        assert!(
            (0.0..=30.0).contains(&vh) && (-12.0..=-4.0).contains(&vv),
            "{p}"
        );
    }
    assert_png(&plots.join("outcomes.png"));
}

#[test]
fn a_paired_campaign_draws_where_its_engines_disagree_and_writes_pages_of_the_worst() {
    let dir = temp("paired-plots");
    std::fs::create_dir_all(&*dir).unwrap();
    let file = dir.join("paired.toml");
    let small = std::fs::read_to_string(root().join("scenarios/campaigns/small.toml")).unwrap();
    let t_end = "\n[[dispersion]]\nfield = \"integrator.t_end\"\nunit = \"s\"\ndistribution = \"list\"\nvalues = [0.2]\n\n[[correlation]]";
    let text = small
        .replace(
            "scenario = \"../",
            &format!("scenario = \"{}/scenarios/", root().display()),
        )
        .replace("engine = \"core\"", "engines = [\"core\", \"rapier\"]")
        .replace("landings = 24", "landings = 4")
        .replace("histories = [3]", "histories = []")
        .replacen("\n[[correlation]]", t_end, 1);
    std::fs::write(&file, text).unwrap();
    let out = dir.join("out");
    let run = touchdown(&[
        "campaign",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--plot",
        "--view",
        "2",
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    for f in [
        "disagreement.png",
        "disagreement.csv",
        "differences.png",
        "differences.csv",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    // One row a landing, each with both engines' outcomes as the records hold them.
    let csv = std::fs::read_to_string(out.join("disagreement.csv")).unwrap();
    let records = std::fs::read_to_string(out.join("landings.jsonl")).unwrap();
    assert_eq!(csv.lines().count(), 1 + records.lines().count());
    for (row, record) in csv.lines().skip(1).zip(records.lines()) {
        let r: serde_json::Value = serde_json::from_str(record).unwrap();
        let expected = format!(
            ",{},{}",
            r["core.outcome"].as_str().unwrap(),
            r["rapier.outcome"].as_str().unwrap()
        );
        assert!(row.ends_with(&expected), "{row} against {expected}");
    }
    // The pages of the first two landings the pair lists.
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("statistics.json")).unwrap())
            .unwrap();
    for w in stats["pairs"][0]["worst"]
        .as_array()
        .unwrap()
        .iter()
        .take(2)
    {
        let page = out.join(format!("views/landing-{}.html", w["landing"]));
        assert!(page.is_file(), "{} missing", page.display());
    }
}

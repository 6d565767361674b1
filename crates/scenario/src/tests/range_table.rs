//! The Ranges table: every number has a range and a dimension, checked on load and documented.

use super::{bundled, display, nodes, resolved, root, scratch};
use crate::check::{RANGE_CHECKED, SI_FACTORS};
use crate::dimension::{Dimension, Powers};
use crate::ranges::{self, RANGES};
use crate::Scenario;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// A similar vehicle (`[similarity]`) written into `dir`: the figure 25-26 landing at full scale
/// on the Moon. Returns its path.
fn similar_vehicle(dir: &Path) -> PathBuf {
    fig_25_26_with(
        dir,
        "similar",
        "[similarity]\nlength = 6.0\nmass = 216.0\ntime = 6.0\n",
    )
}

/// The figure 25-26 landing with the TOML `tables` added, written into `dir` as `name`.toml.
/// Returns its path.
fn fig_25_26_with(dir: &Path, name: &str, tables: &str) -> PathBuf {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(
        &path,
        format!(
            "schema_version = 1\nextends = {:?}\nname = {name:?}\n{tables}",
            root()
                .join("scenarios/fig-25-26.toml")
                .display()
                .to_string()
        ),
    )
    .unwrap();
    path
}

/// Every number of every bundled scenario (and of explicit cantilever legs) has a range and is
/// checked against it on load; every range is of a field some scenario has.
#[test]
fn every_numeric_field_has_a_range_checked_on_load() {
    let mut files = bundled();
    // Explicit cantilever legs (with l21): the catalogue's standalone file, its third leg fixed.
    let folder = scratch("coverage");
    let dir = folder.path();
    let text = std::fs::read_to_string(
        root().join("tests/data/malformed/strut-cannot-reach-footpad.toml"),
    )
    .unwrap()
    .replace("l21 = 1.6", "l21 = 0.9375");
    let explicit = dir.join("explicit.toml");
    std::fs::write(&explicit, text).unwrap();
    files.push(explicit);
    let similar = similar_vehicle(dir);
    files.push(similar);
    // The strides scheme's own settings.
    files.push(fig_25_26_with(
        dir,
        "strides",
        "[integrator]\nscheme = \"strides\"\nstride = 8.0\nmode_step = 1.0\n",
    ));
    // rapier's step between the stops.
    files.push(fig_25_26_with(
        dir,
        "rapier-stride",
        "[engines.rapier]\nstride = 2.0\n",
    ));
    // The settled end's tolerance.
    files.push(fig_25_26_with(
        dir,
        "settled",
        "[stability]\nsettled_tolerance = 0.001\n",
    ));
    // A landing's own comparison tolerances.
    files.push(fig_25_26_with(
        dir,
        "comparison",
        "[comparison]\nprimary_stroke = 0.1\nsecondary_stroke = 0.1\npeak_pitch_rate = 0.1\npeak_pitch_rate_time = 0.1\npitch_rate_history_rms_difference = 0.1\npitch_rate_history_largest_difference = 0.1\npeak_vertical_acceleration = 0.1\nmin_stability_distance = 0.1\noverturn_velocity = 0.1\npast_capacity = 0.1\nenergy = 0.1\n",
    ));
    let mut leaves = BTreeSet::new();
    RANGE_CHECKED.with(|c| c.borrow_mut().clear());
    for path in &files {
        let value = resolved(path);
        for (at, node) in nodes(&value) {
            if node.is_float() {
                leaves.insert(ranges::normalize(&display(&at)));
            }
        }
    }
    let checked = RANGE_CHECKED.with(|c| c.borrow().clone());
    let unranged: Vec<_> = leaves
        .iter()
        .filter(|f| ranges::lookup(f).is_none())
        .collect();
    assert!(
        unranged.is_empty(),
        "numeric fields without a range: {unranged:?}"
    );
    let unchecked: Vec<_> = leaves.difference(&checked).collect();
    assert!(
        unchecked.is_empty(),
        "fields not range-checked on load: {unchecked:?}"
    );
    let unused: Vec<_> = RANGES
        .iter()
        .filter(|r| !leaves.iter().any(|f| ranges::lookup(f) == Some(*r)))
        .map(|r| r.field)
        .collect();
    assert!(unused.is_empty(), "ranges of no field: {unused:?}");
}

/// The Ranges table's units are the dimensions the loader reads: every number of every bundled
/// scenario (and of a similar vehicle) is brought to SI by its dimension's factor in the file's
/// units, the one a campaign's unit is checked against.
#[test]
fn every_fields_dimension_is_the_one_it_is_read_with() {
    let folder = scratch("dimensions");
    let dir = folder.path();
    let similar = similar_vehicle(dir);
    let mut files = bundled();
    files.push(similar);
    let mut checked = 0;
    for path in &files {
        SI_FACTORS.with(|c| c.borrow_mut().clear());
        let scenario = Scenario::load(path).unwrap();
        let units = scenario.units();
        for (field, factor) in SI_FACTORS.with(|c| c.borrow().clone()) {
            let dimension = scenario
                .dimension_of(&field)
                .unwrap_or_else(|| panic!("{}: `{field}` has no row", path.display()))
                .unwrap_or_else(|e| panic!("{}: `{field}`: {e}", path.display()));
            let expected = dimension.si_factor(&units);
            assert!(
                (factor - expected).abs() <= 1e-12 * expected.abs(),
                "{}: `{field}` is read with {factor}, its dimension ({}) gives {expected}",
                path.display(),
                dimension.words()
            );
            checked += 1;
        }
    }
    assert!(checked > 1000, "{checked} numbers checked");
}

/// docs/scenario-format.md's fields table gives each field the dimension its range has.
#[test]
fn the_fields_table_states_each_fields_dimension() {
    let doc = std::fs::read_to_string(root().join("docs/scenario-format.md")).unwrap();
    let table = doc
        .split("## Fields")
        .nth(1)
        .and_then(|t| t.split("\n## ").next())
        .unwrap();
    let mut checked = 0;
    for line in table.lines().filter(|l| l.starts_with("| `")) {
        let cells: Vec<&str> = line.split(" | ").collect();
        let (names, words) = (cells[0].trim_start_matches("| "), cells[1].trim());
        if words == "as above" || words.contains(',') || names.contains("...") {
            continue;
        }
        // "—": a pure number (or no number at all: such fields have no range).
        let words = if words.starts_with('—') { "1" } else { words };
        for name in names.split(", ") {
            let field = name.trim_matches('`');
            let Some(row) = ranges::lookup(field) else {
                continue;
            };
            let powers = Powers {
                gamma: Some(1.0),
                index: Some(2.0),
            };
            let table = Dimension::parse(row.unit, powers).unwrap();
            let stated = Dimension::parse(words, powers)
                .unwrap_or_else(|e| panic!("`{field}`: its dimension {words:?}: {e}"));
            assert_eq!(stated, table, "`{field}`: {words:?} against {:?}", row.unit);
            checked += 1;
        }
    }
    assert!(checked >= 40, "{checked} fields checked");
}

/// docs/scenario-format.md lists every range as the code has it.
#[test]
fn the_format_page_documents_every_range() {
    let doc = std::fs::read_to_string(root().join("docs/scenario-format.md")).unwrap();
    let mut missing = Vec::new();
    for r in RANGES {
        let usual = r.usual_interval().unwrap_or_else(|| "—".into());
        let row = format!(
            "| `{}` | {} | {} | {} |",
            r.field,
            r.interval(),
            usual,
            r.reason
        );
        if !doc.lines().any(|l| l == row) {
            missing.push(row);
        }
    }
    assert!(
        missing.is_empty(),
        "rows missing from docs/scenario-format.md (\"Ranges\"):\n{}",
        missing.join("\n")
    );
    assert!(doc.contains(&format!(
        "at least {} deg apart",
        crate::units::short(ranges::MIN_LEG_SEPARATION_DEG)
    )));
}

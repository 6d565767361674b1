//! The engine crates' public surfaces are deliberate: `touchdown-core` and
//! `touchdown-multibody` keep their modules private and re-export, at the crate root, what the
//! other crates use. A new public module, re-export or root item fails this test until it is
//! added to the list below (and so is a dropped one), so that widening a surface is a decision
//! seen in review, not a side effect.

use std::collections::BTreeSet;

/// The public names at the root of the crate whose `lib.rs` is at `path` (under the project's
/// folder): `pub mod`, each name a `pub use` brings in, and each `pub fn`, `struct`, `enum`,
/// `trait`, `const`, `static` and `type`.
fn public_names(path: &str) -> BTreeSet<String> {
    let text = std::fs::read_to_string(touchdown_tests::root().join(path)).unwrap();
    // One statement per `pub ...;` even when rustfmt spreads a `pub use` over lines.
    let mut names = BTreeSet::new();
    let mut rest = text.as_str();
    while let Some(at) = rest.find("\npub ") {
        rest = &rest[at + 1..];
        let end = rest.find([';', '{', '(']).unwrap_or(rest.len());
        let statement = &rest[..end];
        let statement = statement.split_whitespace().collect::<Vec<_>>().join(" ");
        if let Some(used) = statement.strip_prefix("pub use ") {
            // `a::b::{C, D}` or `a::b::C`: the names after the last `::`.
            let tail = if let Some(open) = rest[..rest.find(';').unwrap()].find('{') {
                let close = rest.find('}').unwrap();
                rest[open + 1..close].to_string()
            } else {
                used.rsplit("::").next().unwrap().to_string()
            };
            for name in tail.split(',').map(str::trim).filter(|n| !n.is_empty()) {
                names.insert(format!("use {name}"));
            }
        } else {
            let words: Vec<&str> = statement.split(' ').collect();
            if let [_, kind, name, ..] = words[..] {
                let name = name.trim_end_matches(':').split('<').next().unwrap();
                names.insert(format!("{kind} {name}"));
            }
        }
    }
    names
}

fn assert_surface(path: &str, expected: &[&str]) {
    let found = public_names(path);
    let expected: BTreeSet<String> = expected.iter().map(|s| s.to_string()).collect();
    let added: Vec<_> = found.difference(&expected).collect();
    let dropped: Vec<_> = expected.difference(&found).collect();
    assert!(
        added.is_empty() && dropped.is_empty(),
        "{path}: public surface changed; new: {added:?}, gone: {dropped:?} (update this test \
         if the change is meant)"
    );
    assert!(
        !found.iter().any(|n| n.starts_with("mod ")),
        "{path}: modules stay private: {found:?}"
    );
}

#[test]
fn the_core_exports_only_what_other_crates_use() {
    assert_surface(
        "crates/core/src/lib.rs",
        &[
            "use Simulation",
            "use VehicleState",
            "use ContactState",
            "use Footpad",
            "use GearState",
            "use MechanismState",
            "use Mechanisms",
            "use EnergyReport",
            "use Landing",
            "use Observer",
            "use Outcome",
            "use RunError",
            "use Summary",
            "fn unsupported",
            "fn run",
        ],
    );
}

#[test]
fn the_multibody_crate_exports_only_what_the_engines_use() {
    assert_surface(
        "crates/multibody/src/lib.rs",
        &[
            "use VehicleLoads",
            "use BodyEnergy",
            "use GearModel",
            "use GearState",
            "use StepTaken",
            "use PadStep",
            "use Reading",
            "use CONTACT_FLAG_SETTINGS",
            "use unsupported",
            "use BodyMotion",
            "use Fault",
            "use MujocoSettings",
            "use RapierSettings",
            "use StrutForces",
            "use StrutKinematics",
        ],
    );
}

/// The parser above reads what it is meant to: a crate with a public module is caught.
#[test]
fn a_public_module_is_seen() {
    let names = public_names("crates/record/src/lib.rs");
    assert!(names.contains("mod summary"), "{names:?}");
    assert!(names.contains("use Summary"), "{names:?}");
}

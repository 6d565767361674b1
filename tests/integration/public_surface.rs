//! The public surfaces of the crates other crates need only a few names of are deliberate: the
//! engines (`touchdown-core`, `touchdown-rapier`, `touchdown-mujoco`), what the multibody
//! engines share (`touchdown-multibody`), the frames (`touchdown-frames`) and the viewer
//! (`touchdown-view`) keep their modules private and re-export, at the crate root, what the
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
            "use StepWork",
            "use StrutWork",
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
            "use hinge_axes",
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

/// The rapier engine: its landing, what it models and its run.
#[test]
fn the_rapier_engine_exports_its_run_and_its_simulation() {
    assert_surface(
        "crates/rapier/src/lib.rs",
        &[
            "use LinkMasses",
            "use RapierSimulation",
            "use unsupported",
            "use Landing",
            "use Observer",
            "use RunError",
            "fn run",
        ],
    );
}

/// The MuJoCo engine: the landing its runner drives, the runner (and its stopped status), the
/// exported model.
#[test]
fn the_mujoco_engine_exports_its_landing_its_runner_and_its_model() {
    assert_surface(
        "crates/mujoco/src/lib.rs",
        &[
            "use refusal",
            "use GearIndex",
            "use MjArrays",
            "use ModelSizes",
            "use MujocoLanding",
            "use Launch",
            "use Worker",
            "use RUNNER_STOPPED_STATUS",
            "use export",
            "use GENERATOR",
            "use unsupported",
            "enum MujocoError",
        ],
    );
}

/// The frames: the rotations of eqs. (1)-(9) and the attitude's trigonometry.
#[test]
fn the_frames_crate_exports_its_rotations() {
    assert_surface(
        "crates/frames/src/lib.rs",
        &[
            "use t_be",
            "use t_eb",
            "use GIMBAL_LOCK_COS",
            "use euler_from_t_bi",
            "use gravity_inertial",
            "use rot_x",
            "use rot_y",
            "use rot_z",
            "use t_bi",
            "use t_gi",
            "use t_ig",
            "use EulerTrig",
        ],
    );
}

/// The viewer: the trajectory page, the landing page and the recording they are made from.
#[test]
fn the_viewer_exports_its_pages_and_its_recording() {
    assert_surface(
        "crates/view/src/lib.rs",
        &[
            "use page",
            "use landing_page",
            "use Series",
            "use Recorder",
            "use ContactEvent",
            "use CurbView",
            "use Frames",
            "use LegFrames",
            "use LegView",
            "use PadGround",
            "use WallFrames",
            "use SurfaceView",
            "use VehicleView",
            "use Recording",
            "use Scene",
            "use DEFAULT_FRAME_INTERVAL",
            "struct EngineTrajectory",
            "struct Trajectory",
        ],
    );
}

/// The `.rs` files under `dir`, unit-test files (`tests.rs`, `tests/`) left out.
fn sources(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if path.is_dir() && name != "tests" {
            out.extend(sources(&path));
        } else if name.ends_with(".rs") && name != "tests.rs" {
            out.push(path);
        }
    }
    out.sort();
    out
}

/// The type names a piece of Rust text mentions: its identifiers that start with a capital
/// letter and have a lower-case letter (so `Vector3` and `GearState`, not `N` or `MAX`).
fn type_names(text: &str) -> BTreeSet<String> {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .filter(|w| w.starts_with(|c: char| c.is_ascii_uppercase()))
        .filter(|w| w.chars().any(|c| c.is_ascii_lowercase()))
        .map(str::to_string)
        .collect()
}

/// What a crate's public items reach that other crates cannot name: for the crate whose root is
/// `lib` (keeping its modules private), each type it defines (`pub struct`, `enum`, `trait`,
/// `type` in any of its files) that appears in the signature of a `pub fn` of a type it
/// exports or of a function it exports, or in a `pub` field of a struct it exports, without
/// being exported itself. Read as text, a code block's lines at the top of a file (an `impl`
/// or a `struct` at column 0 up to its closing `}` at column 0), outside the file's tests.
fn unnameable(lib: &str) -> Vec<String> {
    let root = touchdown_tests::root().join(lib);
    let exported: BTreeSet<String> = public_names(lib)
        .iter()
        .filter_map(|n| n.split(' ').nth(1).map(str::to_string))
        .collect();
    let files = sources(root.parent().unwrap());
    let texts: Vec<(String, String)> = files
        .iter()
        .map(|f| {
            let text = std::fs::read_to_string(f).unwrap();
            // Code only: a file's unit tests are not its surface.
            let code = text.split("\n#[cfg(test)]").next().unwrap().to_string();
            (f.display().to_string(), code)
        })
        .collect();
    let mut defined = BTreeSet::new();
    for (_, text) in &texts {
        for line in text.lines() {
            let words: Vec<&str> = line.split_whitespace().collect();
            if let ["pub", "struct" | "enum" | "trait" | "type", name, ..] = words[..] {
                let name = name.split(['<', '(', ';', ':']).next().unwrap();
                defined.insert(name.to_string());
            }
        }
    }
    let mut problems = Vec::new();
    for (file, text) in &texts {
        let mut owner: Option<String> = None;
        let mut signature: Option<String> = None;
        for line in text.lines() {
            if line.starts_with("impl") || line.starts_with("pub struct") {
                // `impl<T> Trait for X<T> {`, `impl X {`, `pub struct X {`: the type is the
                // last name before the brace (or after `for`).
                let head = line.split('{').next().unwrap();
                let head = head.rsplit(" for ").next().unwrap();
                let names: Vec<String> = type_names(head).into_iter().collect();
                let last = head
                    .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                    .rfind(|w| names.iter().any(|n| n == w));
                owner = last.map(str::to_string);
                if line.ends_with(';') || line.ends_with("{}") {
                    owner = None;
                }
                continue;
            }
            if line == "}" {
                owner = None;
                continue;
            }
            let trimmed = line.trim_start();
            let top = line.starts_with("pub fn ");
            let member = owner.as_ref().is_some_and(|o| exported.contains(o))
                && (trimmed.starts_with("pub fn ")
                    || (trimmed.starts_with("pub ")
                        && trimmed.contains(':')
                        && !trimmed.contains('(')));
            let exported_fn = top && {
                let name = trimmed["pub fn ".len()..].split(['<', '(']).next().unwrap();
                exported.contains(name)
            };
            if signature.is_none() && (member || exported_fn) {
                signature = Some(String::new());
            }
            if let Some(s) = &mut signature {
                s.push_str(line);
                s.push('\n');
                if line.contains('{') || line.ends_with(';') || line.ends_with(',') {
                    let text = s.split('{').next().unwrap().to_string();
                    for name in type_names(&text) {
                        if defined.contains(&name) && !exported.contains(&name) {
                            problems.push(format!("{file}: `{}` reaches `{name}`", text.trim()));
                        }
                    }
                    signature = None;
                }
            }
        }
    }
    problems
}

/// Every type a crate's public items hand out can be named by the crates that get it: a method
/// of an exported type that returns one of the crate's own types exports that type too (the
/// core's `Simulation::footpads` returns `Footpad`, exported; a `GearState` of the multibody
/// book is returned by `GearModel::new`, exported).
#[test]
fn public_items_reach_only_types_other_crates_can_name() {
    let mut problems = Vec::new();
    for lib in [
        "crates/core/src/lib.rs",
        "crates/multibody/src/lib.rs",
        "crates/rapier/src/lib.rs",
        "crates/mujoco/src/lib.rs",
        "crates/frames/src/lib.rs",
        "crates/view/src/lib.rs",
    ] {
        problems.extend(unnameable(lib));
    }
    assert!(
        problems.is_empty(),
        "public items reach types that are not exported:\n{}",
        problems.join("\n")
    );
}

/// The check above sees a method that hands out an unexported type, and a field of one
/// (`tests/data/surface-fixture/`), and nothing else.
#[test]
fn the_reach_check_finds_an_unexported_type_in_a_signature() {
    let problems = unnameable("tests/data/surface-fixture/lib.rs");
    assert_eq!(problems.len(), 2, "{problems:#?}");
    assert!(problems[0].contains("pub inner: Hidden"), "{problems:#?}");
    assert!(
        problems[1].contains("pub fn hidden(&self) -> Hidden"),
        "{problems:#?}"
    );
}

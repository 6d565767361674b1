//! Wall time of whole landings on each engine, the same scenarios on all (criterion). Figures go
//! into docs/performance.md. `cargo bench -p touchdown-tests --bench engines`.
//!
//! Before timing, each landing is run once to print its steps, so that the time per step can be
//! read off the time per landing. A MuJoCo landing is timed end to end as a user runs it (the
//! Python runner started, the model compiled, the landing stepped, the summary written); before
//! timing, the runner's `--profile` prints where the stepping time goes (MuJoCo, the Rust laws,
//! the Python loop itself).

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use std::process::Command;
use touchdown_mujoco::Launch;
use touchdown_record::Summary;
use touchdown_scenario::Scenario;
use touchdown_tests::scenario;

const LANDINGS: [&str; 2] = ["table-i-2-2-vv8.toml", "table-i-1-2-1-vv10.toml"];

fn load(name: &str) -> Scenario {
    Scenario::load(scenario(name)).expect("bundled scenario loads")
}

/// Times every landing of `LANDINGS` on one engine (`run`, given the landing's file name and
/// scenario), `samples` samples each.
fn engine(c: &mut Criterion, name: &str, samples: usize, run: impl Fn(&str, &Scenario) -> Summary) {
    let mut group = c.benchmark_group(format!("{name} landing"));
    group.sample_size(samples);
    for landing in LANDINGS {
        let sc = load(landing);
        println!(
            "{name} {landing}: {} steps per landing",
            run(landing, &sc).steps
        );
        group.throughput(Throughput::Elements(1));
        group.bench_function(landing, |b| b.iter(|| run(landing, black_box(&sc))));
    }
    group.finish();
}

fn core(c: &mut Criterion) {
    engine(c, "core", 100, |_, sc| {
        touchdown_core::run(sc).expect("the landing runs")
    });
}

fn rapier(c: &mut Criterion) {
    // A rapier landing takes a few tenths of a second: ten samples keep the bench short.
    engine(c, "rapier", 10, |_, sc| {
        touchdown_rapier::run(sc).expect("the landing runs")
    });
}

fn mujoco(c: &mut Criterion) {
    let launch = Launch::locate().unwrap_or_else(|e| panic!("{e}"));
    let out = std::env::temp_dir().join(format!("touchdown-bench-{}", std::process::id()));
    for landing in LANDINGS {
        let profile = Command::new(&launch.python)
            .arg(&launch.runner)
            .arg(scenario(landing))
            .arg("--out")
            .arg(&out)
            .arg("--library")
            .arg(&launch.library)
            .arg("--profile")
            .output()
            .expect("the runner starts");
        assert!(
            profile.status.success(),
            "{}",
            String::from_utf8_lossy(&profile.stderr)
        );
        println!(
            "mujoco {landing} profile: {}",
            String::from_utf8_lossy(&profile.stdout).trim()
        );
    }
    engine(c, "mujoco", 10, |landing, _| {
        launch
            .run(&scenario(landing), &out, false)
            .expect("the landing runs")
    });
    let _ = std::fs::remove_dir_all(&out);
}

criterion_group!(benches, core, rapier, mujoco);
criterion_main!(benches);

//! Wall time of the core on scenes that declare no optional mechanism (criterion): the cost of
//! having the optional mechanisms in the code when a scene declares none. Compare its figures
//! with the same bench on a commit before the mechanisms existed (docs/performance.md).
//! `cargo bench -p touchdown-core --bench minimal`.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::path::PathBuf;
use touchdown_scenario::Scenario;

/// Rigid-surface scenes without thrust, RCS, slosh, soil, curbs, bending or tripod gear.
const SCENES: [&str; 3] = [
    "flat-drop.toml",
    "level-sliding.toml",
    "table-i-2-2-vv8.toml",
];

fn minimal(c: &mut Criterion) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenarios");
    let mut group = c.benchmark_group("core minimal scene");
    group.sample_size(200);
    for name in SCENES {
        let sc = Scenario::load(dir.join(name)).expect("bundled scenario loads");
        let steps = touchdown_core::run(&sc).expect("the landing runs").steps;
        println!("{name}: {steps} steps per landing");
        group.bench_function(name, |b| {
            b.iter(|| touchdown_core::run(black_box(&sc)).expect("the landing runs"))
        });
    }
    group.finish();
}

criterion_group!(benches, minimal);
criterion_main!(benches);

//! Wall time of whole landings with the core engine (criterion). Figures go into
//! docs/performance.md. `cargo bench -p touchdown-core --bench landing`.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use std::path::Path;
use touchdown_scenario::Scenario;

fn load(name: &str) -> Scenario {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenarios")
        .join(name);
    Scenario::load(path).expect("bundled scenario loads")
}

fn landings(c: &mut Criterion) {
    let mut group = c.benchmark_group("core landing");
    for name in ["table-i-2-2-vv8.toml", "table-i-1-2-1-vv10.toml"] {
        let sc = load(name);
        let steps = touchdown_core::run(&sc).expect("the landing runs").steps;
        println!("{name}: {steps} steps per landing");
        group.throughput(Throughput::Elements(1));
        group.bench_function(name, |b| {
            b.iter(|| touchdown_core::run(black_box(&sc)).expect("the landing runs"))
        });
    }
    group.finish();
}

criterion_group!(benches, landings);
criterion_main!(benches);

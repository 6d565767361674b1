//! Wall time of whole landings on each engine, the same scenarios on all (criterion). Figures go
//! into docs/performance.md. `cargo bench -p touchdown-tests --bench engines`.
//!
//! Before timing, each landing is run once to print its steps, so that the time per step can be
//! read off the time per landing.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use touchdown_record::Summary;
use touchdown_scenario::Scenario;
use touchdown_tests::scenario;

const LANDINGS: [&str; 2] = ["table-i-2-2-vv8.toml", "table-i-1-2-1-vv10.toml"];

fn load(name: &str) -> Scenario {
    Scenario::load(scenario(name)).expect("bundled scenario loads")
}

/// Times every landing of `LANDINGS` on one engine (`run`), `samples` samples each.
fn engine(c: &mut Criterion, name: &str, samples: usize, run: fn(&Scenario) -> Summary) {
    let mut group = c.benchmark_group(format!("{name} landing"));
    group.sample_size(samples);
    for landing in LANDINGS {
        let sc = load(landing);
        println!("{name} {landing}: {} steps per landing", run(&sc).steps);
        group.throughput(Throughput::Elements(1));
        group.bench_function(landing, |b| b.iter(|| run(black_box(&sc))));
    }
    group.finish();
}

fn core(c: &mut Criterion) {
    engine(c, "core", 100, |sc| {
        touchdown_core::run(sc).expect("the landing runs")
    });
}

fn rapier(c: &mut Criterion) {
    // A rapier landing takes a few tenths of a second: ten samples keep the bench short.
    engine(c, "rapier", 10, |sc| {
        touchdown_rapier::run(sc).expect("the landing runs")
    });
}

criterion_group!(benches, core, rapier);
criterion_main!(benches);

//! What a campaign costs beyond its landings, and its throughput on 1 and 2 threads:
//! `cargo bench -p touchdown-campaign --bench campaign` (figures in docs/performance.md,
//! "Campaigns").
//!
//! * `bare landing`: 16 landings of scenarios/campaigns/lm-1-6-d3117.toml resolved beforehand,
//!   landed on the core with nothing else;
//! * `campaign landing`: the same 16 landings as a campaign lands them (draw, resolve, read
//!   back, land, record): the difference is the campaign machinery's overhead;
//! * `64 landings on N threads`: `run_range` over landings 0..64.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::path::Path;
use touchdown_campaign::landing::{draws, land};
use touchdown_campaign::run::run_range;
use touchdown_campaign::Campaign;

const LANDINGS: u64 = 16;

fn campaign() -> Campaign {
    let file =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/campaigns/lm-1-6-d3117.toml");
    Campaign::load(file).expect("the example campaign loads")
}

fn overhead(c: &mut Criterion) {
    let campaign = campaign();
    let scenarios: Vec<_> = (0..LANDINGS)
        .map(|i| {
            let drawn = draws(&campaign, i);
            let overrides: Vec<(&str, toml::Value)> = campaign
                .dispersions
                .iter()
                .zip(&drawn)
                .map(|(d, v)| (d.field.as_str(), v.to_toml()))
                .collect();
            campaign
                .base
                .with(&overrides)
                .expect("the landing resolves")
        })
        .collect();
    let mut g = c.benchmark_group("campaign");
    g.sample_size(10);
    g.bench_function("bare landing x16", |b| {
        b.iter(|| {
            for sc in &scenarios {
                let _ = black_box(touchdown_registry::land(
                    campaign.engines[0],
                    &campaign.scenario_path,
                    sc,
                    &mut (),
                    None,
                ));
            }
        })
    });
    g.bench_function("campaign landing x16", |b| {
        b.iter(|| {
            for i in 0..LANDINGS {
                black_box(land(&campaign, i, None).expect("lands"));
            }
        })
    });
    for threads in [1, 2] {
        g.bench_function(format!("64 landings on {threads} thread(s)"), |b| {
            b.iter(|| {
                run_range(&campaign, 0..64, Some(threads), None, |row| {
                    black_box(row);
                    Ok(())
                })
                .expect("runs")
            })
        });
    }
    g.finish();
}

criterion_group!(benches, overhead);
criterion_main!(benches);

//! A campaign's statistics keep a few numbers a landing, never its records: the heap they hold
//! at their peak, counted by a global allocator for this test binary, against the number of
//! landings (docs/campaigns.md, "Output": the bound stated there).

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use touchdown_campaign::paired::pair;
use touchdown_campaign::record::{Cell, Column, Kind};
use touchdown_campaign::Statistics;

struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

fn grew(bytes: usize) {
    let live = LIVE.fetch_add(bytes, Relaxed) + bytes;
    PEAK.fetch_max(live, Relaxed);
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        grew(layout.size());
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Relaxed);
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // Both blocks count while the old one is copied.
        grew(new_size);
        let moved = unsafe { System.realloc(ptr, layout, new_size) };
        LIVE.fetch_sub(layout.size(), Relaxed);
        moved
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// The heap `f` holds at its peak beyond what was live before it, in bytes.
fn peak_of<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let before = LIVE.load(Relaxed);
    PEAK.store(before, Relaxed);
    let out = f();
    (out, PEAK.load(Relaxed) - before)
}

fn col(name: &str, kind: Kind) -> Column {
    Column {
        name: name.into(),
        kind,
    }
}

/// Cell `k` of column `i` of a made-up paired campaign, made when asked: nothing is stored.
fn cell(columns: &[Column], i: usize, k: usize) -> Cell {
    let x = (k as f64 * 0.618_033_988_749_895).fract();
    let name = &columns[i].name;
    let rapier = name.starts_with("rapier.");
    match columns[i].kind {
        Kind::Integer => Cell::Integer(k as i64),
        Kind::Float if rapier => Cell::Float(x * 1.01),
        Kind::Float => Cell::Float(x),
        Kind::Text if name.ends_with("outcome") => {
            let stable = x < if rapier { 0.8 } else { 0.85 };
            Cell::Text((if stable { "stable" } else { "unstable" }).into())
        }
        Kind::Text if name.ends_with("failure") => Cell::Text("none".into()),
        Kind::Text => Cell::Text((if x > 0.9 { "leg1.primary" } else { "" }).into()),
        Kind::Flag => Cell::Flag(x > 0.5),
    }
}

const LANDINGS: usize = 200_000;

#[test]
fn statistics_hold_sixteen_bytes_a_landing_and_a_pair_fifty() {
    let engine = |prefix: &str| {
        [
            ("outcome", Kind::Text),
            ("failure", Kind::Text),
            ("stroke_outs", Kind::Text),
            ("leg1.primary.stroke_m", Kind::Float),
            ("leg1.primary.stroke_of_capacity", Kind::Float),
            ("min_stability_distance_m", Kind::Float),
        ]
        .map(|(name, kind)| col(&format!("{prefix}{name}"), kind))
    };
    let mut columns = vec![
        col("landing", Kind::Integer),
        col("applied.touchdown.vertical_velocity_m_s", Kind::Float),
        col("applied.surface.slope_deg", Kind::Float),
    ];
    columns.extend(engine("core."));
    columns.extend(engine("rapier."));
    let mut visit = |i: usize, visit: &mut dyn FnMut(Cell)| {
        (0..LANDINGS).for_each(|k| visit(cell(&columns, i, k)));
        Ok::<_, ()>(())
    };
    let n = LANDINGS as u64;
    let (statistics, held) = peak_of(|| {
        Statistics::from_columns(&columns, n, 0.95, "core.", &mut visit, &|by, l| {
            format!("closest/{by}-landing-{l}.toml")
        })
        .unwrap()
    });
    let per_landing = held as f64 / LANDINGS as f64;
    println!("one engine's statistics: {per_landing:.2} bytes a landing at their peak");
    assert!(
        per_landing <= 16.5,
        "one engine's statistics held {held} bytes for {LANDINGS} landings, {per_landing:.1} a landing"
    );
    // What it kept is what it counted.
    assert_eq!(statistics.landings, n);
    let stable = statistics.stable.landings;
    assert!(stable > n * 8 / 10 && stable < n * 9 / 10, "{stable}");
    let (pair, held) = peak_of(|| {
        pair(
            &columns,
            n,
            0.95,
            ["core", "rapier"],
            ["core.", "rapier."],
            &mut visit,
            &|l| format!("disagreements/landing-{l}.toml"),
        )
        .unwrap()
    });
    let per_landing = held as f64 / LANDINGS as f64;
    println!("a pair's statistics: {per_landing:.2} bytes a landing at their peak");
    assert!(
        per_landing <= 50.0,
        "a pair's statistics held {held} bytes for {LANDINGS} landings, {per_landing:.1} a landing"
    );
    assert!(pair.disagreement.landings > 0);
    assert_eq!(pair.worst.len(), touchdown_campaign::paired::WORST);
}

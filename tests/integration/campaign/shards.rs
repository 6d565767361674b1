//! The same bytes whatever the threads, shards or order; added landings leave the first alone.

use super::{assert_same_files, sharded, small, small_with};
use touchdown_campaign::record::Cell;
use touchdown_campaign::run::run;
use touchdown_campaign::Campaign;

#[test]
fn one_shard_or_four_in_any_order_on_any_threads_write_the_same_bytes() {
    let tmp = tempfile::tempdir().unwrap();
    let campaign = Campaign::load(small()).unwrap();
    let whole = tmp.path().join("whole");
    run(&campaign, None, Some(1), Some(&whole), false, |_| ()).unwrap();
    let merged = sharded(&campaign, tmp.path(), &[3, 1, 4, 2]);
    assert_same_files(&whole, &merged);
    // The landings come in order whatever finished first, and the history asked for is kept.
    let mut seen = Vec::new();
    run(&campaign, None, Some(2), None, false, |r| {
        seen.push(r[0].clone())
    })
    .unwrap();
    assert_eq!(seen, (0..24).map(Cell::Integer).collect::<Vec<_>>());
    assert!(whole.join("histories/landing-3.csv").is_file());
}

#[test]
fn added_landings_leave_the_first_ones_unchanged() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("campaign.toml");
    small_with(&file, 16);
    let extended = tmp.path().join("extended");
    let c16 = Campaign::load(&file).unwrap();
    run(&c16, None, None, Some(&extended), false, |_| ()).unwrap();
    touchdown_campaign::add(&c16, &extended, 8, None, false, |_| ()).unwrap();
    small_with(&file, 24);
    let at_once = tmp.path().join("at-once");
    run(
        &Campaign::load(&file).unwrap(),
        None,
        None,
        Some(&at_once),
        false,
        |_| (),
    )
    .unwrap();
    assert_same_files(&extended, &at_once);
}

//! `touchdown boundary`: the stability-boundary search on any engine, its text, JSON and CSV,
//! and the spread over end-stop laws.

use crate::{out, outln};
use anyhow::{bail, Context, Result};
use std::fmt::Write;
use std::path::Path;
use touchdown_record::ScenarioId;
use touchdown_scenario::schema::Engine;
use touchdown_scenario::units::Short;
use touchdown_validation::boundary::{
    self, BoundaryPoint, Direction, EnginePoint, Limit, Settings, Stops, Transition,
};

/// Parses the vertical velocities FROM:TO:STEP, or one vertical velocity, written as in the
/// scenario files (negative down): finite, FROM and TO negative, STEP > 0 and at most
/// [`boundary::MAX_GRID_POINTS`] velocities, FROM, FROM ± STEP, ... towards TO.
fn range(spec: &str) -> Result<Vec<f64>> {
    let parts: Vec<f64> = spec
        .split(':')
        .map(|s| s.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .with_context(|| {
            format!("--vv {spec:?}: expected FROM:TO:STEP numbers (--vv=-4:-12:2) or one (--vv=-8)")
        })?;
    let [from, to, step] = match parts[..] {
        [one] => [one, one, 1.0],
        [from, to, step] => [from, to, step],
        _ => bail!("--vv {spec:?}: expected FROM:TO:STEP (--vv=-4:-12:2) or one vertical velocity (--vv=-8)"),
    };
    if !(from.is_finite() && to.is_finite() && step.is_finite()) {
        bail!("--vv {spec:?}: expected finite FROM:TO:STEP numbers");
    }
    if !(step > 0.0 && from < 0.0 && to < 0.0) {
        bail!(
            "--vv {spec:?}: expected vertical velocities as the scenario files write them, \
             negative down (e.g. --vv=-4:-12:2), and STEP > 0"
        );
    }
    let n = ((to - from).abs() / step + 1e-9).floor();
    if n.is_nan() || n >= boundary::MAX_GRID_POINTS as f64 {
        bail!(
            "--vv {spec:?}: expected at most {} vertical velocities from FROM to TO (a STEP ≥ {}), got {}",
            boundary::MAX_GRID_POINTS,
            Short((to - from).abs() / (boundary::MAX_GRID_POINTS - 1) as f64),
            Short(n + 1.0)
        );
    }
    let sign = if to < from { -1.0 } else { 1.0 };
    Ok((0..=n as usize)
        .map(|i| from + sign * step * i as f64)
        .collect())
}

/// Output of `touchdown boundary`.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum BoundaryFormat {
    /// Readable table.
    Text,
    /// JSON array.
    Json,
    /// CSV.
    Csv,
}

/// `touchdown boundary`.
pub fn boundary(
    scenario: &Path,
    set: &[crate::Set],
    vv: &str,
    asked: boundary::Asked,
    (engines, restitutions): (&[Engine], &[f64]),
    format: BoundaryFormat,
    (out, plot): (Option<&Path>, bool),
) -> Result<()> {
    let vvs = range(vv)?;
    let speeds = boundary::descent_speeds(&vvs, "--vv")?;
    let (base, sc) = crate::load(scenario, set)?;
    let settings = asked.settings(&sc)?;
    settings.validate()?;
    crate::warn(&sc);
    let bar = crate::progress_bar(0, "landings");
    let overrides = crate::overrides(set);
    let vunit = format!("{}/s", sc.file.units.length_label());
    let velocity = sc.units().velocity();
    let id = ScenarioId::new(scenario.display(), &sc);
    let options = boundary::options(&vvs, settings, &vunit, engines, restitutions);
    let settings_json = crate::settings(set, options);
    // JSON Lines: each point as soon as it and those before it are found; the first error
    // writing them ends the command once the search returns.
    let unwritten = std::sync::Mutex::new(None);
    let stream = |p: &EnginePoint| {
        if format == BoundaryFormat::Json {
            let line = boundary::document_line(p, velocity, &id, &settings_json);
            if let Err(e) = bar.suspend(|| outln!("{line}")) {
                if let Ok(mut first) = unwritten.lock() {
                    first.get_or_insert(e);
                }
            }
        }
    };
    let points = boundary::search_engines(
        &base,
        &overrides,
        &speeds,
        settings,
        engines,
        restitutions,
        &|| bar.inc(1),
        &stream,
    )?;
    bar.finish_and_clear();
    if let Some(e) = unwritten.into_inner().ok().flatten() {
        return Err(e);
    }
    match format {
        BoundaryFormat::Json => {}
        BoundaryFormat::Csv => out!("{}", boundary_csv(&points, velocity)?)?,
        BoundaryFormat::Text => out!("{}", boundary_text(&points, &vunit, settings))?,
    }
    if let Some(dir) = out {
        let lines: Vec<String> = points
            .iter()
            .map(|p| boundary::document_line(p, velocity, &id, &settings_json) + "\n")
            .collect();
        let data = crate::out_file(dir, "boundary-", scenario, "jsonl")?;
        std::fs::write(&data, lines.concat())
            .with_context(|| format!("cannot write {}", data.display()))?;
        if !plot {
            return Ok(());
        }
        // The plot says what the search varies and holds, and on which engines.
        let png = data.with_extension("png");
        crate::plots::boundaries(&data, &sc.file.name, &vunit, &png)?;
    }
    Ok(())
}

fn opt(x: Option<f64>) -> String {
    x.map(|v| format!("{v:.3}")).unwrap_or_else(|| "—".into())
}

fn direction(d: Direction) -> &'static str {
    match d {
        Direction::StableToUnstable => "stable_to_unstable",
        Direction::UnstableToStable => "unstable_to_stable",
    }
}

/// Index of the transition a point reports as its boundary (its lowest stable → unstable).
fn reported(p: &BoundaryPoint) -> Option<usize> {
    p.transitions
        .iter()
        .position(|t| t.direction == Direction::StableToUnstable)
}

fn list(vhs: &[f64]) -> String {
    let v: Vec<String> = vhs.iter().map(|v| format!("{v:.3}")).collect();
    v.join(", ")
}

/// The end stops a landing engaged, in words.
fn stops(s: Stops) -> String {
    match s.struts_past_capacity {
        0 => "within capacity".into(),
        n => format!(
            "{n} strut{} past capacity, stop {:.1} kN",
            if n > 1 { "s" } else { "" },
            s.peak_stop_force_n / 1e3
        ),
    }
}

/// One line of the text table for a transition, with the stops at its ends.
fn transition_line(t: &Transition) -> String {
    let arrow = match t.direction {
        Direction::StableToUnstable => "stable → unstable",
        Direction::UnstableToStable => "unstable → stable",
    };
    let at = match t.vh {
        Some(vh) => format!("at Vh {vh:.3}"),
        None => "unresolved".into(),
    };
    let mut bracket = format!(
        "stable at {:.3}: {}; unstable at {:.3}: {}",
        t.stable_at,
        stops(t.stable_stops),
        t.unstable_at,
        stops(t.unstable_stops)
    );
    if !t.undecided_at.is_empty() {
        let _ = write!(bracket, "; undecided at {}", list(&t.undecided_at));
    }
    format!("           transition   {arrow}   {at:<16} ({bracket})")
}

fn restitution(e: Option<f64>) -> String {
    e.map_or_else(|| "file".into(), |e| format!("{e}"))
}

fn boundary_text(points: &[EnginePoint], unit: &str, s: Settings) -> String {
    let mut o = String::new();
    let scan = match s.scan_step {
        Some(step) => format!(", scanned every {} around its changes", Short(step)),
        None => String::new(),
    };
    let _ = writeln!(
        o,
        "stability boundary: where the landing turns unstable, where a strut first goes past its \
         capacity, and the safe envelope (stable and within every capacity), at each vertical \
         velocity Vv (negative down)\n({unit}; Vh grid {} to {} step {}{scan}, tolerance {})",
        Short(s.vh_start),
        Short(s.vh_max),
        Short(s.vh_step),
        Short(s.tolerance)
    );
    let _ = writeln!(
        o,
        "  engine   stop e         Vv   boundary Vh   stable at   unstable at   past capacity   safe to             safe until   landings   undecided"
    );
    for EnginePoint {
        engine,
        stop_restitution,
        point: p,
    } in points
    {
        let boundary = match (p.vh, reported(p)) {
            (None, Some(_)) => "unresolved".into(),
            (vh, _) => opt(vh),
        };
        let past = match p.capacity {
            None => "never".into(),
            Some(c) => {
                c.vh.map_or_else(|| format!("≤ {:.3}", c.past_at), |v| format!("{v:.3}"))
            }
        };
        let _ = writeln!(
            o,
            "  {:<6}   {:>6}   {:>8.3}   {:>11}   {:>9}   {:>11}   {:>13}   {:>7}   {:>21}   {:>8}   {:>9}",
            engine.name(),
            restitution(*stop_restitution),
            -p.vv,
            boundary,
            opt(p.stable_at),
            opt(p.unstable_at),
            past,
            opt(p.safe.safe_to),
            p.safe.limit.map_or("—", Limit::name),
            p.landings,
            p.undecided
        );
        if let Some(b) = p.band {
            let _ = writeln!(
                o,
                "           band         {:.3} to {:.3}: the outcome changes {} times (no single boundary)",
                b.from, b.to, b.changes
            );
        }
        for t in &p.transitions {
            let _ = writeln!(o, "{}", transition_line(t));
        }
        if let Some(c) = p.capacity {
            let _ = writeln!(
                o,
                "           capacity     first past at {:.3}: {}{}",
                c.past_at,
                stops(c.stops),
                c.within_at
                    .map_or_else(String::new, |w| format!(" (within at {w:.3})"))
            );
        }
        if !p.undecided_at.is_empty() {
            let _ = writeln!(o, "           undecided    at Vh {}", list(&p.undecided_at));
        }
    }
    let _ = writeln!(
        o,
        "(boundary Vh: the lowest stable → unstable transition, — if none, unresolved if an \
         undecided landing lies inside its bracket;\n without one, stable at is the largest Vh \
         found stable if none was unstable and unstable at the smallest Vh found unstable;\n \
         past capacity: the first Vh at which a strut goes past its capacity onto its end stop, \
         whose law is an estimate; safe to: the largest Vh below the first landing that is not \
         stable and within capacity, and what ends it)"
    );
    o.push_str(&spread_text(points));
    o
}

/// With several end-stop laws searched: the boundary at each, per engine and Vv, and its
/// spread (largest less smallest), which the stop law alone decides. A search that found no
/// overturn up to the largest Vh tried gives a lower bound, `> Vh`, and so does the spread.
fn spread_text(points: &[EnginePoint]) -> String {
    let mut laws: Vec<f64> = points.iter().filter_map(|p| p.stop_restitution).collect();
    laws.sort_by(f64::total_cmp);
    laws.dedup();
    if laws.len() < 2 {
        return String::new();
    }
    let mut o = String::new();
    let _ = write!(
        o,
        "\nboundary Vh by end-stop restitution e (every diagram; > Vh: stable up to the largest Vh tried; spread —: not known, the lowest value being such a bound)\n  engine         Vv"
    );
    for e in &laws {
        let _ = write!(o, "   {:>8}", format!("e = {e}"));
    }
    let _ = writeln!(o, "     spread");
    let mut rows: Vec<(Engine, f64)> = Vec::new();
    for p in points {
        if !rows.contains(&(p.engine, p.point.vv)) {
            rows.push((p.engine, p.point.vv));
        }
    }
    for (engine, vv) in rows {
        let _ = write!(o, "  {:<6}   {:>8.3}", engine.name(), -vv);
        // Each law's boundary, or a lower bound when it never overturned.
        let mut values: Vec<Option<(f64, bool)>> = Vec::new();
        for e in &laws {
            let p = (points.iter())
                .find(|p| p.engine == engine && p.point.vv == vv && p.stop_restitution == Some(*e))
                .map(|p| &p.point);
            let value = p.and_then(|p| match (p.vh, p.unstable_at, p.stable_at) {
                (Some(vh), _, _) => Some((vh, false)),
                (None, None, Some(stable)) => Some((stable, true)),
                _ => None,
            });
            let shown = match value {
                Some((v, false)) => format!("{v:.3}"),
                Some((v, true)) => format!("> {v:.3}"),
                None => "—".into(),
            };
            let _ = write!(o, "   {shown:>8}");
            values.push(value);
        }
        // The spread is known from below only where the lowest value is a boundary found: a
        // law that never overturned (a lower bound) at the lowest value leaves it open.
        let found: Vec<(f64, bool)> = values.iter().flatten().copied().collect();
        let lo = found.iter().map(|v| v.0).fold(f64::INFINITY, f64::min);
        let hi = found.iter().map(|v| v.0).fold(f64::NEG_INFINITY, f64::max);
        let lowest_found = found.iter().any(|&(v, bound)| !bound && v == lo);
        let spread = if values.iter().all(Option::is_some) && lowest_found {
            let bound = found.iter().any(|v| v.1);
            format!("{}{:.3}", if bound { "> " } else { "" }, hi - lo)
        } else {
            "—".into()
        };
        let _ = writeln!(o, "   {spread:>8}");
    }
    o
}

/// One row per transition (engine, stop_restitution, vv_m_s, direction, stable_at_vh_m_s,
/// unstable_at_vh_m_s, vh_m_s, resolved, undecided: the landings undecided at that descent
/// speed, past_capacity_vh_m_s: the first Vh past a capacity, safe_to_vh_m_s and safe_until:
/// the safe envelope and what ends it), SI, the vertical velocity negative down; a descent
/// speed without a transition has one row with direction `none`, its `stable_at_vh_m_s` /
/// `unstable_at_vh_m_s` and empty `vh_m_s` and `resolved`. `velocity` is the scenario's
/// velocity unit in m/s.
fn boundary_csv(points: &[EnginePoint], velocity: f64) -> Result<String> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        "engine",
        "stop_restitution",
        "vv_m_s",
        "direction",
        "stable_at_vh_m_s",
        "unstable_at_vh_m_s",
        "vh_m_s",
        "resolved",
        "undecided",
        "past_capacity_vh_m_s",
        "safe_to_vh_m_s",
        "safe_until",
    ])?;
    let f = |x: Option<f64>| x.map(|v| format!("{v}")).unwrap_or_default();
    for point in points {
        let p = point.si(velocity);
        let past = p.capacity.map(|c| c.vh_m_s.unwrap_or(c.past_at_vh_m_s));
        let row = |direction: &str, stable_at, unstable_at, vh, resolved: String| {
            [
                p.engine.to_string(),
                f(p.stop_restitution),
                format!("{}", p.vv_m_s),
                direction.to_string(),
                f(stable_at),
                f(unstable_at),
                f(vh),
                resolved,
                p.undecided.to_string(),
                f(past),
                f(p.safe.safe_to_vh_m_s),
                p.safe.limit.map_or("", Limit::name).to_string(),
            ]
        };
        if p.transitions.is_empty() {
            w.write_record(row(
                "none",
                p.stable_at_vh_m_s,
                p.unstable_at_vh_m_s,
                None,
                String::new(),
            ))?;
        }
        for t in &p.transitions {
            w.write_record(row(
                direction(t.direction),
                Some(t.stable_at_vh_m_s),
                Some(t.unstable_at_vh_m_s),
                t.vh_m_s,
                t.resolved.to_string(),
            ))?;
        }
    }
    Ok(String::from_utf8(w.into_inner()?)?)
}

#[cfg(test)]
mod boundary_tests {
    use super::*;

    fn transition(direction: Direction, s: f64, u: f64, vh: Option<f64>) -> Transition {
        Transition {
            direction,
            stable_at: s,
            unstable_at: u,
            vh,
            resolved: vh.is_some(),
            undecided_at: if vh.is_some() {
                vec![]
            } else {
                vec![s.max(u) - 1.0]
            },
            stable_stops: Stops::default(),
            unstable_stops: Stops {
                struts_past_capacity: 2,
                peak_stop_force_n: 38_000.0,
            },
        }
    }

    fn points() -> Vec<EnginePoint> {
        let non_monotonic = BoundaryPoint {
            vv: 8.0,
            vh: Some(10.0),
            stable_at: Some(9.99),
            unstable_at: Some(10.01),
            transitions: vec![
                transition(Direction::StableToUnstable, 9.99, 10.01, Some(10.0)),
                transition(Direction::UnstableToStable, 14.01, 13.99, Some(14.0)),
                transition(Direction::StableToUnstable, 18.0, 22.0, None),
            ],
            band: Some(boundary::Band {
                from: 9.99,
                to: 22.0,
                changes: 3,
            }),
            capacity: Some(boundary::CapacityEdge {
                within_at: Some(9.0),
                past_at: 9.05,
                vh: Some(9.025),
                stops: Stops {
                    struts_past_capacity: 1,
                    peak_stop_force_n: 500.0,
                },
            }),
            safe: boundary::SafeEdge {
                safe_to: Some(9.0),
                unsafe_at: Some(9.05),
                limit: Some(Limit::Capacity),
            },
            undecided_at: vec![17.0, 21.0],
            landings: 40,
            undecided: 2,
        };
        let stable = BoundaryPoint {
            vv: 10.0,
            vh: None,
            stable_at: Some(30.0),
            unstable_at: None,
            transitions: vec![],
            band: None,
            capacity: None,
            safe: boundary::SafeEdge {
                safe_to: Some(30.0),
                unsafe_at: None,
                limit: None,
            },
            undecided_at: vec![],
            landings: 16,
            undecided: 0,
        };
        [non_monotonic, stable]
            .into_iter()
            .map(|point| EnginePoint {
                engine: Engine::Core,
                stop_restitution: None,
                point,
            })
            .collect()
    }

    #[test]
    fn boundary_csv_has_one_row_per_transition() {
        // In SI (a velocity unit of 0.5 m/s), the vertical velocity negative down.
        let csv = boundary_csv(&points(), 0.5).unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(
            lines,
            [
                "engine,stop_restitution,vv_m_s,direction,stable_at_vh_m_s,unstable_at_vh_m_s,vh_m_s,resolved,undecided,past_capacity_vh_m_s,safe_to_vh_m_s,safe_until",
                "core,,-4,stable_to_unstable,4.995,5.005,5,true,2,4.5125,4.5,capacity",
                "core,,-4,unstable_to_stable,7.005,6.995,7,true,2,4.5125,4.5,capacity",
                "core,,-4,stable_to_unstable,9,11,,false,2,4.5125,4.5,capacity",
                "core,,-5,none,15,,,,0,,15,",
            ]
        );
    }

    #[test]
    fn boundary_text_lists_every_transition_the_band_the_capacity_and_the_undecided() {
        let s = Settings {
            vh_start: 0.0,
            vh_step: 2.0,
            vh_max: 30.0,
            tolerance: 0.05,
            scan_step: Some(0.25),
        };
        let text = boundary_text(&points(), "ft/s", s);
        let lines: Vec<&str> = text.lines().collect();
        assert!(lines[0].contains("negative down"), "{text}");
        assert!(lines[1].contains("ft/s") && lines[1].contains("tolerance 0.05"));
        assert!(lines[1].contains("scanned every 0.25"), "{text}");
        // The row: boundary 10, first past capacity 9.025, safe to 9 ended by the capacity.
        let row: Vec<&str> = lines[3].split_whitespace().collect();
        assert_eq!(
            row,
            [
                "core", "file", "-8.000", "10.000", "9.990", "10.010", "9.025", "9.000",
                "capacity", "40", "2"
            ],
            "{text}"
        );
        assert!(lines[4].contains("band") && lines[4].contains("9.990 to 22.000"));
        assert!(lines[4].contains("changes 3 times"), "{text}");
        // Every transition, each end with its stops.
        assert!(lines[5].contains("stable → unstable") && lines[5].contains("at Vh 10.000"));
        assert!(
            lines[5].contains("stable at 9.990: within capacity"),
            "{text}"
        );
        assert!(
            lines[5].contains("2 struts past capacity, stop 38.0 kN"),
            "{text}"
        );
        assert!(lines[6].contains("unstable → stable") && lines[6].contains("at Vh 14.000"));
        assert!(lines[7].contains("unresolved") && lines[7].contains("undecided at 21.000"));
        assert!(lines[8].contains("capacity") && lines[8].contains("first past at 9.050"));
        assert!(lines[8].contains("1 strut past capacity, stop 0.5 kN (within at 9.000)"));
        assert!(lines[9].contains("undecided") && lines[9].ends_with("17.000, 21.000"));
        let row: Vec<&str> = lines[10].split_whitespace().collect();
        assert_eq!(
            row,
            [
                "core", "file", "-10.000", "—", "30.000", "—", "never", "30.000", "—", "16", "0"
            ],
            "{text}"
        );
        // No spread table with one stop law.
        assert!(!text.contains("by end-stop restitution"), "{text}");
    }

    #[test]
    fn the_spread_over_stop_laws_is_the_largest_less_the_smallest_boundary() {
        let mut points = Vec::new();
        for (e, vh) in [(0.5, Some(10.0)), (1.0, Some(7.5)), (0.1, Some(12.25))] {
            let mut p = points_at(e);
            p.point.vh = vh;
            points.push(p);
        }
        let text = spread_text(&points);
        let lines: Vec<&str> = text.lines().collect();
        assert!(lines[1].contains("restitution"), "{text}");
        assert!(
            lines[2].contains("e = 0.1") && lines[2].ends_with("spread"),
            "{text}"
        );
        let row: Vec<&str> = lines[3].split_whitespace().collect();
        assert_eq!(
            row,
            ["core", "-8.000", "12.250", "10.000", "7.500", "4.750"]
        );
        assert_eq!(lines.len(), 4, "one row per engine and Vv: {text}");
        // A law that never overturns up to the largest Vh tried bounds the spread from below.
        points[0].point.vh = None;
        points[0].point.unstable_at = None;
        points[0].point.stable_at = Some(30.0);
        let text = spread_text(&points);
        let row: Vec<&str> = text.lines().nth(3).unwrap().split_whitespace().collect();
        assert_eq!(
            row,
            ["core", "-8.000", "12.250", ">", "30.000", "7.500", ">", "22.500"],
            "{text}"
        );
        // No law overturns: the spread is open, not zero.
        for p in &mut points {
            p.point.vh = None;
            p.point.unstable_at = None;
            p.point.stable_at = Some(36.0);
        }
        let text = spread_text(&points);
        let row: Vec<&str> = text.lines().nth(3).unwrap().split_whitespace().collect();
        assert_eq!(row.last(), Some(&"—"), "{text}");
    }

    fn points_at(e: f64) -> EnginePoint {
        let mut p = points().remove(0);
        p.stop_restitution = Some(e);
        p
    }

    #[test]
    fn vv_ranges_are_finite_negative_and_bounded() {
        assert_eq!(range("-4:-8:2").unwrap(), vec![-4.0, -6.0, -8.0]);
        assert_eq!(range("-8:-4:2").unwrap(), vec![-8.0, -6.0, -4.0]);
        assert_eq!(range("-0.1:-0.4:0.1").unwrap().len(), 4);
        assert_eq!(range("-2.5").unwrap(), vec![-2.5]);
        for bad in [
            "4:8:2",
            "0:-4:1",
            "-4:-8:0",
            "-4:-8:-1",
            "nan:-8:1",
            "-4:-inf:1",
            "-1:-1e9:1",
            "-1:-2",
            "2.5",
            "-1:-2:1:1",
        ] {
            let e = range(bad).unwrap_err().to_string();
            assert!(
                e.starts_with("--vv") && e.contains("expected"),
                "{bad}: {e}"
            );
        }
        assert!(range("-1:-10000:1").is_ok() && range("-1:-10001:1").is_err());
    }
}

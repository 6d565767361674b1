//! The search's text: the table `touchdown boundary` prints, each point with its transitions,
//! band, capacity edge and undecided landings, and, with several end-stop laws, the spread of
//! the boundary over them; in the scenario's velocity unit.

use super::engines::EnginePoint;
use super::search::{BoundaryPoint, Direction, Limit, Stops, Transition};
use super::settings::Settings;
use std::fmt::Write;
use touchdown_core::Outcome;
use touchdown_scenario::schema::Engine;
use touchdown_scenario::units::Short;

fn opt(x: Option<f64>) -> String {
    x.map(|v| format!("{v:.3}")).unwrap_or_else(|| "—".into())
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
    if let Some(r) = t.refined {
        let end = |o: Outcome| format!("{o:?}").to_lowercase();
        let _ = match r.holds {
            true => write!(bracket, "; steps ÷ {}: both ends hold", Short(r.refinement)),
            false => write!(
                bracket,
                "; steps ÷ {}: MOVES, {} at {:.3} and {} at {:.3}",
                Short(r.refinement),
                end(r.stable_end),
                t.stable_at,
                end(r.unstable_end),
                t.unstable_at
            ),
        };
    }
    format!("           transition   {arrow}   {at:<16} ({bracket})")
}

/// The accuracy the search's steps give: how many transitions keep both bracket ends' outcomes
/// with every step limit refined, and which do not; empty when none was refined.
fn accuracy_text(points: &[EnginePoint]) -> String {
    let refined: Vec<(f64, &Transition)> = (points.iter())
        .flat_map(|p| p.point.transitions.iter().map(|t| (p.point.vv, t)))
        .filter(|(_, t)| t.refined.is_some())
        .collect();
    let Some(r) = refined.first().and_then(|(_, t)| t.refined) else {
        return String::new();
    };
    let moved: Vec<String> = (refined.iter())
        .filter(|(_, t)| t.refined.is_some_and(|r| !r.holds))
        .map(|(vv, t)| {
            format!(
                "Vv {:.3} between {:.3} and {:.3}",
                -vv,
                t.lower(),
                t.upper()
            )
        })
        .collect();
    let mut o = format!(
        "accuracy (core): each transition's bracket ends landed again with every step limit ÷ {}: \
         {} of {} hold (the finer steps change outcome within the same bracket)",
        Short(r.refinement),
        refined.len() - moved.len(),
        refined.len()
    );
    if !moved.is_empty() {
        let _ = write!(
            o,
            "; moved by the step, by at least the bracket: {}",
            moved.join("; ")
        );
    }
    o.push('\n');
    o
}

fn restitution(e: Option<f64>) -> String {
    e.map_or_else(|| "file".into(), |e| format!("{e}"))
}

/// The table of `points` in the scenario's velocity unit `unit` (`ft/s`), searched with the
/// settings `s`.
pub(super) fn table(points: &[EnginePoint], unit: &str, s: Settings) -> String {
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
    o.push_str(&accuracy_text(points));
    o.push_str(&spread_text(points));
    o
}

/// With several end-stop laws searched: the boundary at each, per engine and Vv, and its
/// spread (largest less smallest), which the stop law alone decides. A search that found no
/// overturn up to the largest Vh tried gives a lower bound, `> Vh`, and so does the spread.
pub(super) fn spread_text(points: &[EnginePoint]) -> String {
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

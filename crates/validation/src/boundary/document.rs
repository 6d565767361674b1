//! The search's documents: its points in SI, one conversion of every speed the search found in
//! the scenario's velocity unit ([`super::speed`]), as the lines of `touchdown boundary --format json` (JSON
//! Lines, docs/schemas/boundary.schema.json) and the rows of its CSV, and the options a
//! document records.

use super::engines::EnginePoint;
use super::search::{Band, BoundaryPoint, CapacityEdge, Direction, Limit, SafeEdge, Transition};
use super::settings::Settings;
use super::speed::{MetresPerSecond, SiSpeed};
use crate::ValidationError;
use touchdown_scenario::schema::Engine;

impl BoundaryPoint {
    /// The point in SI, `velocity` being the scenario's velocity unit in m/s: every speed the
    /// search found multiplied by it, and nothing else changed.
    pub fn in_si(&self, velocity: f64) -> BoundaryPoint<MetresPerSecond> {
        let si = |v: f64| MetresPerSecond(v * velocity);
        let all = |v: &[f64]| v.iter().map(|x| si(*x)).collect();
        BoundaryPoint {
            vv: si(self.vv),
            vh: self.vh.map(si),
            stable_at: self.stable_at.map(si),
            unstable_at: self.unstable_at.map(si),
            transitions: (self.transitions.iter())
                .map(|t| Transition {
                    direction: t.direction,
                    stable_at: si(t.stable_at),
                    unstable_at: si(t.unstable_at),
                    vh: t.vh.map(si),
                    resolved: t.resolved,
                    undecided_at: all(&t.undecided_at),
                    stable_stops: t.stable_stops,
                    unstable_stops: t.unstable_stops,
                    refined: t.refined,
                })
                .collect(),
            band: self.band.map(|b| Band {
                from: si(b.from),
                to: si(b.to),
                changes: b.changes,
            }),
            capacity: self.capacity.map(|c| CapacityEdge {
                within_at: c.within_at.map(si),
                past_at: si(c.past_at),
                vh: c.vh.map(si),
                stops: c.stops,
            }),
            safe: SafeEdge {
                safe_to: self.safe.safe_to.map(si),
                unsafe_at: self.safe.unsafe_at.map(si),
                limit: self.safe.limit,
            },
            undecided_at: all(&self.undecided_at),
            landings: self.landings,
            undecided: self.undecided,
        }
    }
}

impl EnginePoint {
    /// The point in SI ([`BoundaryPoint::in_si`]), `velocity` being the scenario's velocity
    /// unit in m/s.
    pub fn in_si(&self, velocity: f64) -> EnginePoint<MetresPerSecond> {
        EnginePoint {
            engine: self.engine,
            stop_restitution: self.stop_restitution,
            point: self.point.in_si(velocity),
        }
    }
}

/// The options of a boundary search as its documents record them: the vertical velocities
/// `vvs` (negative down), the grid, the tolerance and the scan step as given, in the
/// scenario's velocity unit `unit` (`ft/s`, written into each name as `_ft_s`), the engines
/// and the end stops' restitutions searched (`stop_restitution`, when given).
pub(super) fn options(
    vvs: &[f64],
    s: Settings,
    unit: &str,
    engines: &[Engine],
    restitutions: &[f64],
) -> serde_json::Value {
    let suffix = unit.replace('/', "_");
    let mut o = serde_json::Map::new();
    let mut put = |name: &str, value: serde_json::Value| {
        o.insert(format!("{name}_{suffix}"), value);
    };
    put("vv", serde_json::json!(vvs));
    put("vh_start", serde_json::json!(s.vh_start));
    put("vh_step", serde_json::json!(s.vh_step));
    put("vh_max", serde_json::json!(s.vh_max));
    put("tolerance", serde_json::json!(s.tolerance));
    if let Some(scan) = s.scan_step {
        put("scan_step", serde_json::json!(scan));
    }
    o.insert("engines".into(), serde_json::json!(engines));
    if !restitutions.is_empty() {
        o.insert("stop_restitution".into(), serde_json::json!(restitutions));
    }
    serde_json::Value::Object(o)
}

/// A point as one line of `touchdown boundary --format json` (JSON Lines): the envelope
/// naming the scenario `id` and the `settings`, then the point in SI ([`EnginePoint::in_si`];
/// `velocity` is the scenario's velocity unit in m/s).
pub(super) fn document_line(
    point: &EnginePoint,
    velocity: f64,
    id: &touchdown_record::ScenarioId,
    settings: &serde_json::Value,
) -> String {
    touchdown_record::Document::new("boundary", Some(id), settings, &point.in_si(velocity)).line()
}

/// The name of a transition's direction in the CSV.
fn direction(d: Direction) -> &'static str {
    match d {
        Direction::StableToUnstable => "stable_to_unstable",
        Direction::UnstableToStable => "unstable_to_stable",
    }
}

/// One row per transition (engine, stop_restitution, vv_m_s, direction, stable_at_vh_m_s,
/// unstable_at_vh_m_s, vh_m_s, resolved, undecided: the landings undecided at that descent
/// speed, past_capacity_vh_m_s: the first Vh past a capacity, safe_to_vh_m_s and safe_until:
/// the safe envelope and what ends it, refined_holds: whether the bracket's ends keep their
/// outcomes with every step limit refined, empty where they were not landed again), SI, the
/// vertical velocity negative down; a descent speed without a transition has one row with
/// direction `none`, its `stable_at_vh_m_s` / `unstable_at_vh_m_s` and empty `vh_m_s`,
/// `resolved` and `refined_holds`. `velocity` is the scenario's velocity unit in m/s.
pub(super) fn csv(points: &[EnginePoint], velocity: f64) -> Result<String, ValidationError> {
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
        "refined_holds",
    ])?;
    let f = |x: Option<f64>| x.map(|v| format!("{v}")).unwrap_or_default();
    let m = |x: Option<MetresPerSecond>| f(x.map(|v| v.0));
    for point in points {
        let p = point.in_si(velocity).point;
        let past = p.capacity.map(|c| c.vh.unwrap_or(c.past_at));
        let row = |direction: &str, stable_at, unstable_at, vh, resolved: String, holds: String| {
            [
                point.engine.name().to_string(),
                f(point.stop_restitution),
                format!("{}", p.vv.negated().0),
                direction.to_string(),
                m(stable_at),
                m(unstable_at),
                m(vh),
                resolved,
                p.undecided.to_string(),
                m(past),
                m(p.safe.safe_to),
                p.safe.limit.map_or("", Limit::name).to_string(),
                holds,
            ]
        };
        if p.transitions.is_empty() {
            let (resolved, holds) = (String::new(), String::new());
            w.write_record(row(
                "none",
                p.stable_at,
                p.unstable_at,
                None,
                resolved,
                holds,
            ))?;
        }
        for t in &p.transitions {
            w.write_record(row(
                direction(t.direction),
                Some(t.stable_at),
                Some(t.unstable_at),
                t.vh,
                t.resolved.to_string(),
                t.refined.map_or(String::new(), |r| r.holds.to_string()),
            ))?;
        }
    }
    let bytes = w
        .into_inner()
        .map_err(|e| csv::Error::from(e.into_error()))?;
    // Every field is a number, a name or empty: ASCII.
    let invalid = |e| csv::Error::from(std::io::Error::new(std::io::ErrorKind::InvalidData, e));
    Ok(String::from_utf8(bytes).map_err(invalid)?)
}

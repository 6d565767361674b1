//! The facts the text states about the figure 25-26 landing, beside our run of it, and the
//! time histories behind the figures (vertical acceleration, pitch rate, strokes).

use crate::reference::{self, Paths};
use crate::ValidationError;
use serde::{Deserialize, Serialize};
use touchdown_core::ContactState;
use touchdown_core::{Landing, Observer, Outcome, Simulation};
use touchdown_scenario::Scenario;

/// Specific force below which the vehicle is taken to be in free flight, g.
const FREE_FLIGHT_G: f64 = 0.05;

/// Tolerance of the fact checks on times (free flight, downhill strike), s.
pub const TIME_TOLERANCE_S: f64 = 0.01;
/// Tolerance of the fact checks on pitch rates, rad/s.
pub const PITCH_RATE_TOLERANCE_RAD_S: f64 = 1.0;

/// `reference/fig-25-26-facts.toml`.
#[derive(Debug, Clone, Deserialize)]
pub struct Facts {
    /// Scenario of the landing (under `scenarios/`).
    pub scenario: String,
    free_flight: Quoted<Duration>,
    downhill_strike: Quoted<Time>,
    pitch_rate_drop: Quoted<PitchDrop>,
    maximum_stroking: Quoted<ByTime>,
    second_stage: Quoted<Depth>,
    outcome: Quoted<Outcomes>,
}

impl Facts {
    /// Free flight between the two acceleration pulses, s.
    pub fn free_flight(&self) -> f64 {
        self.free_flight.value.duration_s
    }
    /// Time the downhill footpads strike, s.
    pub fn downhill_strike(&self) -> f64 {
        self.downhill_strike.value.time_s
    }
    /// Pitch rate before and after the downhill impact, rad/s.
    pub fn pitch_rate_drop(&self) -> (f64, f64) {
        let p = &self.pitch_rate_drop.value;
        (p.before_rad_s, p.after_rad_s)
    }
}

#[derive(Debug, Clone, Deserialize)]
struct Quoted<T> {
    quote: String,
    #[serde(flatten)]
    value: T,
}
#[derive(Debug, Clone, Deserialize)]
struct Duration {
    duration_s: f64,
}
#[derive(Debug, Clone, Deserialize)]
struct Time {
    time_s: f64,
}
#[derive(Debug, Clone, Deserialize)]
struct PitchDrop {
    before_rad_s: f64,
    after_rad_s: f64,
}
#[derive(Debug, Clone, Deserialize)]
struct ByTime {
    by_time_s: f64,
}
#[derive(Debug, Clone, Deserialize)]
struct Depth {
    depth_ft: f64,
}
#[derive(Debug, Clone, Deserialize)]
struct Outcomes {
    experiment: String,
    report_analysis: String,
}

/// One fact: the report's words and value beside ours.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FactCheck {
    /// Short name.
    pub fact: String,
    /// The report's sentence.
    pub quote: String,
    /// The report's value, as text with its unit.
    pub report: String,
    /// Our value.
    pub ours: String,
    /// Whether ours agrees within the stated tolerance.
    pub agrees: bool,
    /// The tolerance used for `agrees`.
    pub tolerance: String,
}

fn fact(
    name: &str,
    quote: &str,
    report: String,
    ours: String,
    agrees: bool,
    tolerance: impl Into<String>,
) -> FactCheck {
    FactCheck {
        fact: name.into(),
        quote: quote.into(),
        report,
        ours,
        agrees,
        tolerance: tolerance.into(),
    }
}

/// Time histories of one landing (SI, plus g for the acceleration).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Series {
    /// Time, s.
    #[serde(rename = "t_s")]
    pub t: Vec<f64>,
    /// Vertical specific force (acceleration less gravity along Z_G), g.
    pub vertical_acceleration_g: Vec<f64>,
    /// Pitch rate (about the inertial X axis), rad/s.
    #[serde(rename = "pitch_rate_rad_s")]
    pub pitch_rate: Vec<f64>,
    /// Primary compression stroke per leg, m.
    #[serde(rename = "primary_stroke_m")]
    pub primary_stroke: Vec<Vec<f64>>,
    /// Largest secondary compression stroke per leg, m.
    #[serde(rename = "secondary_compression_m")]
    pub secondary_compression: Vec<Vec<f64>>,
    /// Footpads in contact per sample (bit i set: leg i + 1).
    pub contacts: Vec<u32>,
}

struct Recorder {
    series: Series,
    up_g: nalgebra::Vector3<f64>,
    g: f64,
}

impl Observer<Simulation> for Recorder {
    fn observe(&mut self, sim: &Simulation) {
        let v = sim.vehicle();
        let s = &mut self.series;
        s.t.push(sim.time());
        // Specific force along the upward vertical: (a − G)·ẑ_G, in g.
        let specific = v.acceleration - self.up_g * (-self.g);
        s.vertical_acceleration_g
            .push(specific.dot(&self.up_g) / self.g);
        s.pitch_rate.push(v.omega_inertial().x);
        if s.primary_stroke.is_empty() {
            s.primary_stroke = vec![Vec::new(); sim.gear().len()];
            s.secondary_compression = vec![Vec::new(); sim.gear().len()];
        }
        for (i, g) in sim.gear().iter().enumerate() {
            s.primary_stroke[i].push(g.primary_stroke);
            s.secondary_compression[i].push(
                (-g.secondary_stroke[0])
                    .max(-g.secondary_stroke[1])
                    .max(0.0),
            );
        }
        let mask = sim
            .footpads()
            .iter()
            .enumerate()
            .filter(|(_, p)| p.state == ContactState::Contact)
            .fold(0u32, |m, (i, _)| m | (1 << i));
        s.contacts.push(mask);
    }
}

/// Runs a scenario recording its time histories; returns them with the summary.
pub fn record(scenario: &Scenario) -> Result<(Series, touchdown_core::Summary), ValidationError> {
    let mut sim = Simulation::new(scenario).map_err(|source| ValidationError::Run {
        scenario: scenario.source.clone(),
        source,
    })?;
    let alpha = scenario.surface.slope;
    let up_g = touchdown_frames::t_gi(alpha) * nalgebra::Vector3::z();
    let mut rec = Recorder {
        series: Series::default(),
        up_g,
        g: scenario.vehicle.gravity,
    };
    let summary = sim.run(&mut rec).map_err(|source| ValidationError::Run {
        scenario: scenario.source.clone(),
        source,
    })?;
    Ok((rec.series, summary))
}

/// The fact checks and the series of our run of the figure 25-26 landing.
pub struct FactsRun {
    /// Fact by fact.
    pub checks: Vec<FactCheck>,
    /// Our time histories.
    pub series: Series,
    /// Our summary.
    pub summary: touchdown_core::Summary,
    /// The scenario landed (its file, as the protocol names it, and hash).
    pub scenario: touchdown_record::ScenarioId,
}

/// What our run of the figure 25-26 landing gives for each fact the text states.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Measured {
    /// Free flight between the two acceleration pulses, s (0 if there is none).
    pub free_flight_s: f64,
    /// First contact of a footpad that was not down at touchdown, s (NaN if none).
    pub downhill_strike_s: f64,
    /// Pitch rate at the downhill strike, rad/s (NaN without a strike).
    pub pitch_rate_at_strike_rad_s: f64,
    /// Pitch rate at maximum stroking, rad/s.
    pub pitch_rate_after_rad_s: f64,
    /// When every strut with a significant stroke has come within 1 % of its largest over the
    /// impact phase (up to the first return, after the downhill strike, of a footpad that was
    /// down at touchdown), s.
    pub maximum_stroking_s: f64,
    /// Largest primary stroke beyond the first stage's end over the impact phase, ft (negative:
    /// short of it).
    pub second_stage_depth_ft: f64,
    /// Stability outcome.
    pub outcome: Outcome,
}

/// Measures the facts on a recorded landing: `series` and `summary` of the landing of `sc`.
pub fn measure(sc: &Scenario, series: &Series, summary: &touchdown_core::Summary) -> Measured {
    let stage_one_end = sc.primary.compression.stages[0].1;
    let s = series;
    let n = s.t.len();
    // The first acceleration pulse ends when the specific force first falls below the
    // free-flight threshold; the second begins when it rises above it again.
    let end1 = (1..n).find(|&k| {
        s.vertical_acceleration_g[k - 1] > FREE_FLIGHT_G
            && s.vertical_acceleration_g[k] <= FREE_FLIGHT_G
    });
    let start2 = end1.and_then(|e| (e..n).find(|&k| s.vertical_acceleration_g[k] > FREE_FLIGHT_G));
    let free_flight = match (end1, start2) {
        (Some(a), Some(b)) => s.t[b] - s.t[a],
        _ => 0.0,
    };
    // The downhill footpads strike at the first contact of a footpad that was not on the
    // surface at touchdown (the second pair of the 2-2 landing): an uphill footpad that hops
    // and lands again is not that strike.
    let strike_t = summary
        .first_contact_s
        .iter()
        .flatten()
        .copied()
        .filter(|t| *t > 0.0)
        .reduce(f64::min)
        .unwrap_or(f64::NAN);
    let strike = s.t.iter().position(|t| *t >= strike_t);
    // The stroking facts describe the report's analytical curve, which after the downhill
    // impact turns about the forward footpads and overturns: they are measured over the same
    // phase of ours, up to the first return to the surface, after the downhill strike, of a
    // footpad that was down at touchdown and left it (the rocking back onto the uphill legs the
    // report's curve never has; the whole run if there is none). An uphill footpad that hops
    // and lands again before the strike does not end it: the facts are of the downhill impact.
    let phase = impact_phase(s, strike.unwrap_or(0));
    // Maximum stroking: the time every strut with significant stroke (over a tenth of the
    // largest) has come within 1 % of its largest stroke (ignoring slow creep afterwards).
    let largest = s
        .primary_stroke
        .iter()
        .chain(&s.secondary_compression)
        .flat_map(|x| &x[..phase])
        .copied()
        .fold(0.0, f64::max);
    let reached = |x: &Vec<f64>| {
        let x = &x[..phase];
        let top = x.iter().copied().fold(0.0, f64::max);
        if top < 0.1 * largest {
            return 0.0;
        }
        x.iter()
            .position(|v| *v >= 0.99 * top)
            .map(|k| s.t[k])
            .unwrap_or(0.0)
    };
    let stroking_done = s
        .primary_stroke
        .iter()
        .chain(&s.secondary_compression)
        .map(reached)
        .fold(0.0, f64::max);
    let stroking_k =
        s.t.iter()
            .position(|t| *t >= stroking_done)
            .unwrap_or(n - 1);
    let before = strike.map(|k| s.pitch_rate[k]).unwrap_or(f64::NAN);
    let after = s.pitch_rate[stroking_k];
    let depth_ft = (s
        .primary_stroke
        .iter()
        .flat_map(|x| &x[..phase])
        .copied()
        .fold(0.0, f64::max)
        - stage_one_end)
        / touchdown_scenario::units::FOOT;
    Measured {
        free_flight_s: free_flight,
        downhill_strike_s: strike_t,
        pitch_rate_at_strike_rad_s: before,
        pitch_rate_after_rad_s: after,
        maximum_stroking_s: stroking_done,
        second_stage_depth_ft: depth_ft,
        outcome: summary.outcome,
    }
}

/// The number of recorded states of the landing's impact phase: up to (not including) the
/// first state from `from` on (the downhill strike's) at which a footpad that was on the
/// surface at touchdown and left it is on it again; all of them if none returns.
fn impact_phase(s: &Series, from: usize) -> usize {
    let Some(&first) = s.contacts.first() else {
        return 0;
    };
    let mut left = 0u32;
    for (k, &mask) in s.contacts.iter().enumerate() {
        if k >= from && mask & left != 0 {
            return k;
        }
        left |= first & !mask;
    }
    s.contacts.len()
}

/// Runs the figure 25-26 landing, with `overrides` (field path, value in file units: a fit's
/// parameters), and checks the facts.
pub fn check(paths: &Paths, overrides: &[(&str, f64)]) -> Result<FactsRun, ValidationError> {
    let facts: Facts = reference::read(&paths.reference("fig-25-26-facts.toml"))?;
    let path = paths.scenario(&facts.scenario);
    let sc = Scenario::load_with(&path, overrides)?;
    let (series, summary) = record(&sc)?;
    let m = measure(&sc, &series, &summary);
    let (free_flight, strike_t) = (m.free_flight_s, m.downhill_strike_s);
    let (before, after) = (m.pitch_rate_at_strike_rad_s, m.pitch_rate_after_rad_s);
    let (stroking_done, depth_ft) = (m.maximum_stroking_s, m.second_stage_depth_ft);
    let outcome = match m.outcome {
        Outcome::Stable => "stable",
        Outcome::Unstable => "unstable",
        Outcome::Undecided => "undecided",
    };
    let f = &facts;
    let checks = vec![
        fact(
            "free flight between the two acceleration pulses",
            &f.free_flight.quote.clone(),
            format!("{:.3} s", f.free_flight.value.duration_s),
            format!("{free_flight:.3} s"),
            (free_flight - f.free_flight()).abs() <= TIME_TOLERANCE_S,
            format!("±{TIME_TOLERANCE_S} s"),
        ),
        fact(
            "downhill footpads strike",
            &f.downhill_strike.quote.clone(),
            format!("{:.3} s", f.downhill_strike.value.time_s),
            format!("{strike_t:.3} s"),
            (strike_t - f.downhill_strike()).abs() <= TIME_TOLERANCE_S,
            format!("±{TIME_TOLERANCE_S} s"),
        ),
        fact(
            "pitch rate at the downhill strike",
            &f.pitch_rate_drop.quote.clone(),
            format!("{:+.1} rad/s", f.pitch_rate_drop.value.before_rad_s),
            format!("{before:+.2} rad/s"),
            (before - f.pitch_rate_drop().0).abs() <= PITCH_RATE_TOLERANCE_RAD_S,
            format!("±{PITCH_RATE_TOLERANCE_RAD_S} rad/s"),
        ),
        fact(
            "pitch rate after the downhill impact (at maximum stroking)",
            &f.pitch_rate_drop.quote.clone(),
            format!("{:+.1} rad/s", f.pitch_rate_drop.value.after_rad_s),
            format!("{after:+.2} rad/s"),
            (after - f.pitch_rate_drop().1).abs() <= PITCH_RATE_TOLERANCE_RAD_S,
            format!("±{PITCH_RATE_TOLERANCE_RAD_S} rad/s"),
        ),
        fact(
            "maximum stroking reached by",
            &f.maximum_stroking.quote.clone(),
            format!("{:.2} s", f.maximum_stroking.value.by_time_s),
            format!("{stroking_done:.3} s"),
            stroking_done <= f.maximum_stroking.value.by_time_s + 0.01,
            "by 0.12 s (+0.01 s)",
        ),
        fact(
            "primary stroke into the second stage",
            &f.second_stage.quote.clone(),
            format!("{:.3} ft", f.second_stage.value.depth_ft),
            format!("{depth_ft:+.3} ft"),
            (depth_ft - f.second_stage.value.depth_ft).abs() <= 0.01,
            "±0.01 ft",
        ),
        fact(
            "outcome",
            &f.outcome.quote.clone(),
            format!(
                "test {}, report's analysis {}",
                f.outcome.value.experiment, f.outcome.value.report_analysis
            ),
            outcome.to_string(),
            outcome == f.outcome.value.experiment,
            "same as the test",
        ),
    ];
    Ok(FactsRun {
        checks,
        series,
        summary,
        scenario: touchdown_record::ScenarioId::new(format!("scenarios/{}", facts.scenario), &sc),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Footpads 3 and 4 (bits 2 and 3) down at touchdown; they leave, hop back once before the
    /// downhill strike (footpads 1 and 2 at sample 5), and return after it at sample 7.
    fn hopping_uphill_pads() -> Series {
        let contacts = vec![0b1100, 0, 0b1100, 0, 0, 0b0011, 0b0011, 0b1111, 0b1111];
        Series {
            t: (0..contacts.len()).map(|k| 0.01 * k as f64).collect(),
            contacts,
            ..Series::default()
        }
    }

    #[test]
    fn the_impact_phase_ends_at_a_return_after_the_downhill_strike_not_a_hop_before_it() {
        let s = hopping_uphill_pads();
        assert_eq!(
            impact_phase(&s, 5),
            7,
            "the hop at sample 2 precedes the strike"
        );
        assert_eq!(
            impact_phase(&s, 0),
            2,
            "without a strike, the first return ends it"
        );
        let mut stays = s.clone();
        stays.contacts[7] = 0b0011;
        stays.contacts[8] = 0b0011;
        assert_eq!(
            impact_phase(&stays, 5),
            stays.contacts.len(),
            "no return after it"
        );
    }
}

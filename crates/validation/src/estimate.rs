//! The touchdown velocities of the figure 25-26 landing, estimated from the facts the text
//! states about it (the figure, and with it the velocities, is missing): every landing of a
//! grid of descent and horizontal speeds is run on the core and measured fact by fact as
//! `touchdown validate` measures it ([`facts::measure`]); the estimate is the grid point whose
//! facts come closest, each fact's difference counted in units of its check's tolerance. The
//! protocol (which facts, which grid) is `reference/fig-25-26-velocity-protocol.toml`; the
//! result is written to `reference/fig-25-26-velocities.toml`.

use crate::facts::{self, Facts, Measured};
use crate::reference::{self, Paths};
use crate::ValidationError;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use touchdown_scenario::units::FOOT;
use touchdown_scenario::Scenario;

/// Most landings a protocol's grid may ask for.
const MAX_LANDINGS: usize = 100_000;

/// A fact the estimate can use (`reference/fig-25-26-facts.toml`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Fact {
    /// Free flight between the two acceleration pulses, s.
    FreeFlight,
    /// Time the downhill footpads strike, s.
    DownhillStrike,
    /// Pitch rate at the downhill strike, rad/s.
    PitchRateAtStrike,
    /// Pitch rate after the downhill impact (at maximum stroking), rad/s.
    PitchRateAfter,
}

impl Fact {
    /// The report's value and our measure of this fact, and the tolerance of its check
    /// (the same as `touchdown validate` uses), in the fact's unit.
    fn compare(self, report: &Facts, ours: &Measured) -> (f64, f64, f64) {
        match self {
            Fact::FreeFlight => (
                report.free_flight(),
                ours.free_flight_s,
                facts::TIME_TOLERANCE_S,
            ),
            Fact::DownhillStrike => (
                report.downhill_strike(),
                ours.downhill_strike_s,
                facts::TIME_TOLERANCE_S,
            ),
            Fact::PitchRateAtStrike => (
                report.pitch_rate_drop().0,
                ours.pitch_rate_at_strike_rad_s,
                facts::PITCH_RATE_TOLERANCE_RAD_S,
            ),
            Fact::PitchRateAfter => (
                report.pitch_rate_drop().1,
                ours.pitch_rate_after_rad_s,
                facts::PITCH_RATE_TOLERANCE_RAD_S,
            ),
        }
    }
}

/// A range of speeds, ft/s: `from`, `from + step`, … up to `to` inclusive.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpeedRange {
    /// First speed, ft/s.
    pub from: f64,
    /// Last speed, ft/s.
    pub to: f64,
    /// Step, ft/s.
    pub step: f64,
}

impl SpeedRange {
    /// The speeds, ft/s (each computed from its index, never accumulated).
    fn values(&self, field: &str) -> Result<Vec<f64>, ValidationError> {
        let ok = self.from.is_finite() && self.to.is_finite() && self.step.is_finite();
        if !ok || self.step <= 0.0 || self.to < self.from {
            return Err(ValidationError::Reference(format!(
                "fig-25-26-velocity-protocol.toml: field `{field}`: expected finite from <= to and step > 0, got {self:?}"
            )));
        }
        let n = ((self.to - self.from) / self.step + 1e-9).floor() + 1.0;
        if n > MAX_LANDINGS as f64 {
            return Err(ValidationError::Reference(format!(
                "fig-25-26-velocity-protocol.toml: field `{field}`: {n} speeds, expected at most {MAX_LANDINGS}"
            )));
        }
        Ok((0..n as usize)
            .map(|i| self.from + i as f64 * self.step)
            .collect())
    }
}

/// `reference/fig-25-26-velocity-protocol.toml`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Protocol {
    /// Where the protocol comes from.
    pub provenance: String,
    /// The facts the objective counts.
    pub facts: Vec<Fact>,
    /// Descent speeds (downward positive), ft/s.
    pub descent_speed: SpeedRange,
    /// Horizontal speeds along the scenario's horizontal direction, ft/s.
    pub horizontal_speed: SpeedRange,
}

/// One landing of the grid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Candidate {
    /// Descent speed, ft/s (downward positive).
    pub descent_speed_ft_s: f64,
    /// Horizontal speed, ft/s.
    pub horizontal_speed_ft_s: f64,
    /// Σ ((ours − report) / tolerance)² over the protocol's facts; infinite if a fact is
    /// missing (no downhill strike).
    pub objective: f64,
    /// The facts measured on this landing.
    pub measured: Measured,
}

/// The estimate: the best landing of the grid and how sharply the facts determine it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Estimate {
    /// Landings run.
    pub landings: usize,
    /// Landings that failed to run (never candidates).
    pub failed: usize,
    /// The grid point with the lowest objective (the lowest speeds on a tie).
    pub best: Candidate,
    /// Range of descent speeds among the grid points whose objective is within 1 of the best
    /// (every fact counted in units of its tolerance), ft/s.
    pub descent_speed_within_1_ft_s: [f64; 2],
    /// Same for the horizontal speed, ft/s.
    pub horizontal_speed_within_1_ft_s: [f64; 2],
    /// Grid points within 1 of the best.
    pub within_1: usize,
}

/// The objective of a measured landing under `protocol` (see [`Candidate::objective`]).
pub fn objective(protocol: &Protocol, report: &Facts, ours: &Measured) -> f64 {
    protocol
        .facts
        .iter()
        .map(|f| {
            let (r, o, tol) = f.compare(report, ours);
            let z = (o - r) / tol;
            if z.is_finite() {
                z * z
            } else {
                f64::INFINITY
            }
        })
        .sum()
}

/// Runs the protocol's grid and picks the estimate.
pub fn estimate(paths: &Paths) -> Result<Estimate, ValidationError> {
    let report: Facts = reference::read(&paths.reference("fig-25-26-facts.toml"))?;
    let protocol: Protocol = reference::read(&paths.reference("fig-25-26-velocity-protocol.toml"))?;
    if protocol.facts.is_empty() {
        return Err(ValidationError::Reference(
            "fig-25-26-velocity-protocol.toml: field `facts`: expected at least one fact".into(),
        ));
    }
    let path = paths.scenario(&report.scenario);
    let sc = Scenario::load(&path)?;
    let [hx, hy] = sc.file.touchdown.horizontal_velocity;
    let norm = hx.hypot(hy);
    if norm == 0.0 {
        return Err(ValidationError::Reference(format!(
            "{}: touchdown.horizontal_velocity is zero, so it gives no horizontal direction",
            path.display()
        )));
    }
    // Speeds in ft/s, the file in its own length unit.
    let per_file_unit = FOOT / sc.units().velocity();
    let (dx, dy) = (hx / norm, hy / norm);
    let vvs = protocol.descent_speed.values("descent_speed")?;
    let vhs = protocol.horizontal_speed.values("horizontal_speed")?;
    if vvs.len() * vhs.len() > MAX_LANDINGS {
        return Err(ValidationError::Reference(format!(
            "fig-25-26-velocity-protocol.toml: {} landings, expected at most {MAX_LANDINGS}",
            vvs.len() * vhs.len()
        )));
    }
    let grid: Vec<(f64, f64)> = vvs
        .iter()
        .flat_map(|vv| vhs.iter().map(move |vh| (*vv, *vh)))
        .collect();
    let runs: Vec<Option<Candidate>> = grid
        .par_iter()
        .map(|&(vv, vh)| {
            let overrides = [
                ("touchdown.vertical_velocity", -vv * per_file_unit),
                ("touchdown.horizontal_velocity[0]", dx * vh * per_file_unit),
                ("touchdown.horizontal_velocity[1]", dy * vh * per_file_unit),
            ];
            let sc = Scenario::load_with(&path, &overrides).ok()?;
            let (series, summary) = facts::record(&sc).ok()?;
            let measured = facts::measure(&sc, &series, &summary);
            Some(Candidate {
                descent_speed_ft_s: vv,
                horizontal_speed_ft_s: vh,
                objective: objective(&protocol, &report, &measured),
                measured,
            })
        })
        .collect();
    let failed = runs.iter().filter(|r| r.is_none()).count();
    let candidates: Vec<Candidate> = runs.into_iter().flatten().collect();
    let best = candidates
        .iter()
        .filter(|c| c.objective.is_finite())
        .min_by(|a, b| a.objective.total_cmp(&b.objective))
        .copied()
        .ok_or_else(|| {
            ValidationError::Reference(
                "fig-25-26 velocity estimate: no landing of the grid measures every fact".into(),
            )
        })?;
    let near: Vec<&Candidate> = candidates
        .iter()
        .filter(|c| c.objective <= best.objective + 1.0)
        .collect();
    let span = |f: fn(&Candidate) -> f64| {
        near.iter()
            .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], c| {
                [lo.min(f(c)), hi.max(f(c))]
            })
    };
    Ok(Estimate {
        landings: grid.len(),
        failed,
        best,
        descent_speed_within_1_ft_s: span(|c| c.descent_speed_ft_s),
        horizontal_speed_within_1_ft_s: span(|c| c.horizontal_speed_ft_s),
        within_1: near.len(),
    })
}

/// `reference/fig-25-26-velocities.toml` as `touchdown estimate` writes it.
pub fn result_text(e: &Estimate) -> Result<String, ValidationError> {
    let mut text = String::from(
        "# Written by `touchdown estimate` from reference/fig-25-26-velocity-protocol.toml and\n\
         # reference/fig-25-26-facts.toml: the touchdown velocities of the figure 25-26 landing\n\
         # estimated from the facts the text states (never from Table I). scenarios/fig-25-26.toml\n\
         # lands at `best` (a test checks it).\n",
    );
    text.push_str(&toml::to_string(e).map_err(|e| ValidationError::Reference(e.to_string()))?);
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;
    use touchdown_core::Outcome;

    fn report() -> Facts {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../reference/fig-25-26-facts.toml"
        );
        reference::read(std::path::Path::new(path)).unwrap()
    }

    fn protocol(facts: Vec<Fact>) -> Protocol {
        let range = SpeedRange {
            from: 0.0,
            to: 1.0,
            step: 1.0,
        };
        Protocol {
            provenance: String::new(),
            facts,
            descent_speed: range,
            horizontal_speed: range,
        }
    }

    fn measured_as(report: &Facts) -> Measured {
        Measured {
            free_flight_s: report.free_flight(),
            downhill_strike_s: report.downhill_strike(),
            pitch_rate_at_strike_rad_s: report.pitch_rate_drop().0,
            pitch_rate_after_rad_s: report.pitch_rate_drop().1,
            maximum_stroking_s: 0.1,
            second_stage_depth_ft: 0.0,
            outcome: Outcome::Stable,
        }
    }

    #[test]
    fn each_fact_counts_in_units_of_its_tolerance() {
        let r = report();
        let all = protocol(vec![
            Fact::FreeFlight,
            Fact::DownhillStrike,
            Fact::PitchRateAtStrike,
            Fact::PitchRateAfter,
        ]);
        let mut m = measured_as(&r);
        assert_eq!(objective(&all, &r, &m), 0.0);
        m.downhill_strike_s += 2.0 * facts::TIME_TOLERANCE_S;
        m.pitch_rate_after_rad_s -= facts::PITCH_RATE_TOLERANCE_RAD_S;
        assert!((objective(&all, &r, &m) - 5.0).abs() < 1e-9);
        // A fact the protocol leaves out does not count.
        let strike_only = protocol(vec![Fact::PitchRateAtStrike]);
        assert_eq!(objective(&strike_only, &r, &m), 0.0);
        // A landing without a downhill strike is no candidate.
        m.downhill_strike_s = f64::NAN;
        assert_eq!(objective(&all, &r, &m), f64::INFINITY);
    }

    #[test]
    fn a_grid_is_computed_from_its_index_and_refused_when_malformed() {
        let r = SpeedRange {
            from: 4.0,
            to: 5.0,
            step: 0.1,
        };
        let v = r.values("descent_speed").unwrap();
        assert_eq!(v.len(), 11);
        assert_eq!(v[10], 4.0 + 10.0 * 0.1);
        for bad in [
            (5.0, 4.0, 0.1),
            (4.0, 5.0, 0.0),
            (4.0, f64::NAN, 0.1),
            (0.0, 1.0, 1e-9),
        ] {
            let r = SpeedRange {
                from: bad.0,
                to: bad.1,
                step: bad.2,
            };
            let e = r.values("descent_speed").unwrap_err().to_string();
            assert!(e.contains("descent_speed"), "{e}");
        }
    }
}

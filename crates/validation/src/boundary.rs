//! The report's automatic stability-boundary search (section "Stability criteria"): for each
//! vertical velocity, the horizontal velocity at which the landing turns unstable, bracketed by
//! marching Vh up from a start value and refined by bisection to a tolerance. Each landing ends
//! early on the stability decision. Vertical velocities run in parallel.

use crate::ValidationError;
use rayon::prelude::*;
use serde::Serialize;
use std::path::Path;
use touchdown_core::Outcome;
use touchdown_scenario::Scenario;

/// Search settings; velocities in the scenario's velocity unit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Settings {
    /// First horizontal velocity tried.
    pub vh_start: f64,
    /// Marching step while bracketing.
    pub vh_step: f64,
    /// Largest horizontal velocity tried.
    pub vh_max: f64,
    /// Bisection stops when the bracket is narrower than this.
    pub tolerance: f64,
}

/// The boundary at one vertical velocity.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BoundaryPoint {
    /// Descent speed (positive down), scenario velocity unit.
    pub vv: f64,
    /// Boundary horizontal velocity (middle of the final bracket); null if none was found.
    pub vh: Option<f64>,
    /// Largest horizontal velocity found stable (null if the first was unstable).
    pub stable_at: Option<f64>,
    /// Smallest horizontal velocity found unstable (null if none up to vh_max).
    pub unstable_at: Option<f64>,
    /// Landings run.
    pub landings: usize,
    /// Landings that ended undecided (counted as not overturning).
    pub undecided: usize,
}

/// Searches the boundary at each vertical velocity. `landing(vv, vh)` runs one landing;
/// `tick` is called after each landing (for a progress bar). The search assumes the outcome
/// is monotonic in Vh at fixed Vv (stable below the boundary, unstable above).
pub fn search<F>(
    vvs: &[f64],
    settings: Settings,
    landing: F,
    tick: &(dyn Fn() + Sync),
) -> Result<Vec<BoundaryPoint>, ValidationError>
where
    F: Fn(f64, f64) -> Result<Outcome, ValidationError> + Sync,
{
    vvs.par_iter()
        .map(|&vv| {
            let mut p = BoundaryPoint {
                vv,
                vh: None,
                stable_at: None,
                unstable_at: None,
                landings: 0,
                undecided: 0,
            };
            let unstable = |vh: f64, p: &mut BoundaryPoint| -> Result<bool, ValidationError> {
                let o = landing(vv, vh)?;
                tick();
                p.landings += 1;
                p.undecided += usize::from(o == Outcome::Undecided);
                Ok(o == Outcome::Unstable)
            };
            // Bracket.
            let mut vh = settings.vh_start;
            while vh <= settings.vh_max + 1e-12 {
                if unstable(vh, &mut p)? {
                    p.unstable_at = Some(vh);
                    break;
                }
                p.stable_at = Some(vh);
                vh += settings.vh_step;
            }
            // Bisect.
            if let (Some(mut lo), Some(mut hi)) = (p.stable_at, p.unstable_at) {
                while hi - lo > settings.tolerance {
                    let mid = 0.5 * (lo + hi);
                    if unstable(mid, &mut p)? {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                p.stable_at = Some(lo);
                p.unstable_at = Some(hi);
                p.vh = Some(0.5 * (lo + hi));
            }
            Ok(p)
        })
        .collect()
}

/// A landing closure for [`search`] on a scenario file: its vertical velocity set to −vv and
/// its horizontal velocity to vh along the scenario's own horizontal direction (file units),
/// landed by `land` (one engine's run of the changed scenario, to its outcome).
pub fn scenario_landing<'a, L, E>(
    path: &'a Path,
    land: L,
) -> Result<impl Fn(f64, f64) -> Result<Outcome, ValidationError> + Sync + 'a, ValidationError>
where
    L: Fn(&Scenario) -> Result<Outcome, E> + Sync + 'a,
    E: Into<Box<dyn std::error::Error + Send + Sync>>,
{
    let sc = Scenario::load(path)?;
    let [hx, hy] = sc.file.touchdown.horizontal_velocity;
    let norm = hx.hypot(hy);
    if norm == 0.0 {
        return Err(ValidationError::Reference(format!(
            "{}: touchdown.horizontal_velocity is zero, so it gives no direction to search along",
            path.display()
        )));
    }
    let (dx, dy) = (hx / norm, hy / norm);
    Ok(move |vv: f64, vh: f64| {
        let overrides = [
            ("touchdown.vertical_velocity", -vv),
            ("touchdown.horizontal_velocity[0]", dx * vh),
            ("touchdown.horizontal_velocity[1]", dy * vh),
        ];
        let sc = Scenario::load_with(path, &overrides)?;
        land(&sc).map_err(|source| ValidationError::Run {
            scenario: format!("{} at Vv = {vv}, Vh = {vh}", path.display()),
            source: source.into(),
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// By construction: a landing that overturns exactly when Vh > 3.7 + 0.1·Vv.
    #[test]
    fn bisection_finds_a_boundary_known_by_construction() {
        let settings = Settings {
            vh_start: 0.0,
            vh_step: 1.0,
            vh_max: 10.0,
            tolerance: 1e-3,
        };
        let landing = |vv: f64, vh: f64| {
            Ok(if vh > 3.7 + 0.1 * vv {
                Outcome::Unstable
            } else {
                Outcome::Stable
            })
        };
        let points = search(&[0.0, 5.0, 10.0], settings, landing, &|| {}).unwrap();
        for p in &points {
            let exact = 3.7 + 0.1 * p.vv;
            let vh = p.vh.unwrap();
            assert!(
                (vh - exact).abs() <= 0.5e-3 + 1e-12,
                "Vv {}: {vh} vs {exact}",
                p.vv
            );
            assert!(p.stable_at.unwrap() <= exact && p.unstable_at.unwrap() > exact);
        }
        // Never unstable: no boundary; unstable from the start: no stable point.
        let never = search(&[1.0], settings, |_, _| Ok(Outcome::Stable), &|| {}).unwrap();
        assert_eq!((never[0].vh, never[0].unstable_at), (None, None));
        assert_eq!(never[0].landings, 11);
        let always = search(&[1.0], settings, |_, _| Ok(Outcome::Unstable), &|| {}).unwrap();
        assert_eq!(
            (always[0].vh, always[0].stable_at, always[0].landings),
            (None, None, 1)
        );
    }
}

//! The profile of the objective along each parameter, the others fitted again at each value.

use super::checkpointing::unit;
use super::protocol::CvProtocol;
use crate::calibrate::{fit, Fit, Predict, INFEASIBLE};
use crate::checkpoint::Checkpoint;
use crate::reference::{FitParameter, Row};
use crate::ValidationError;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Points of each parameter's profile, spread evenly over its bounds.
pub const PROFILE_POINTS: usize = 9;

/// The profile of the objective along one parameter: at each value, the other parameters
/// fitted again to every row. Values at which no feasible parameter set was found (every
/// diagram tried refused by the loader) are left out.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Profile {
    /// The parameter.
    pub name: String,
    /// Its values, file units, over its bounds.
    pub value: Vec<f64>,
    /// The lowest objective (sum of squared relative errors over every row) with the
    /// parameter at each value.
    pub objective: Vec<f64>,
    /// Every parameter at each value (file units, the protocol's order): how the others move
    /// to make up for it.
    pub fitted: Vec<Vec<f64>>,
}

/// The profile of parameter `k` over its bounds ([`PROFILE_POINTS`] values): the others
/// fitted again at each, from their values in `full` (the fit to every row), with the
/// protocol's optimiser and restarts; each point a unit of `checkpoint`. Returns the profile
/// and the landings it ran.
pub(super) fn profile(
    table: &[Row],
    protocol: &CvProtocol,
    k: usize,
    full: &Fit,
    predict: &Predict,
    checkpoint: Option<&Checkpoint>,
) -> Result<(Profile, usize), ValidationError> {
    let p = &protocol.parameter[k];
    let values: Vec<f64> = (0..PROFILE_POINTS)
        .map(|i| p.lower + (p.upper - p.lower) * i as f64 / (PROFILE_POINTS - 1) as f64)
        .collect();
    // The others start at the full fit, just inside their bounds (a fit starts strictly inside).
    let others: Vec<FitParameter> = protocol
        .parameter
        .iter()
        .zip(&full.value)
        .enumerate()
        .filter(|(i, _)| *i != k)
        .map(|(_, (q, v))| {
            let edge = 1e-6 * (q.upper - q.lower);
            FitParameter {
                initial: v.clamp(q.lower + edge, q.upper - edge),
                ..q.clone()
            }
        })
        .collect();
    let points: Vec<(ProfilePoint, usize)> = values
        .par_iter()
        .enumerate()
        .map(|(j, v)| {
            unit(
                checkpoint,
                &format!("profile-{k}-{j}"),
                predict,
                |predict| {
                    let with = |y: &[f64]| {
                        let mut x = y.to_vec();
                        x.insert(k, *v);
                        x
                    };
                    let fixed = |row: &Row, y: &[f64]| predict(row, &with(y));
                    let f = fit(
                        table,
                        &others,
                        protocol.max_iterations,
                        Some(protocol.restarts()),
                        &fixed,
                    )?;
                    Ok(ProfilePoint {
                        fit: (f.objective < INFEASIBLE).then(|| (f.objective, with(&f.value))),
                    })
                },
            )
        })
        .collect::<Result<_, ValidationError>>()?;
    let landings = points.iter().map(|(_, n)| n).sum();
    let mut profile = Profile {
        name: p.name.clone(),
        value: Vec::new(),
        objective: Vec::new(),
        fitted: Vec::new(),
    };
    for (v, (point, _)) in values.into_iter().zip(points) {
        if let Some((objective, x)) = point.fit {
            profile.value.push(v);
            profile.objective.push(objective);
            profile.fitted.push(x);
        }
    }
    Ok((profile, landings))
}

/// One point of a profile: the objective and every parameter of the fit there, or `None` if
/// no feasible parameter set was found.
#[derive(Serialize, Deserialize)]
struct ProfilePoint {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    fit: Option<(f64, Vec<f64>)>,
}

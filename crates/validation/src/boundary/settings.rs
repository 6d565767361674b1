//! The search's settings: the grid of horizontal speeds, the bisection tolerance and the scan
//! step, as asked or as ratios of the vehicle's velocity scale, and their checks.

use crate::ValidationError;
use touchdown_scenario::units::Short;
use touchdown_scenario::Scenario;

/// Largest number of grid points at one vertical velocity.
pub const MAX_GRID_POINTS: usize = 10_000;

/// Largest ratio of the largest |Vh| searched (or 1 if that is smaller) to the tolerance and
/// to the step: beyond it a bisection could not narrow its bracket in floating point.
pub const MAX_RELATIVE_RESOLUTION: f64 = 1e9;

/// Search settings; velocities in the scenario's velocity unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// First grid point (`--vh-start`), scenario velocity unit.
    pub vh_start: f64,
    /// Grid step (`--vh-step`), scenario velocity unit; finite and > 0.
    pub vh_step: f64,
    /// Largest horizontal velocity tried on the grid (`--vh-max`), scenario velocity unit;
    /// ≥ `vh_start`. It is a grid point when it lies within 1e-9 (relative) of one.
    pub vh_max: f64,
    /// Bisection stops when a bracket is no wider than this (`--tol`), scenario velocity unit;
    /// finite, > 0 and at least max(|vh_start|, |vh_max|, 1) / [`MAX_RELATIVE_RESOLUTION`].
    pub tolerance: f64,
    /// Step of the finer scan around the changes of outcome the grid finds (`--scan-step`),
    /// scenario velocity unit: finite, > 0 and below `vh_step`; `None` scans nothing but the
    /// grid.
    pub scan_step: Option<f64>,
}

/// The grid step when none is asked for, as a fraction of the vehicle's velocity scale
/// ([`touchdown_scenario::scales::Scales::velocity_m_s`]): 2.11 ft/s on the 1/6-scale model
/// (velocity scale 8.45 ft/s, 2.58 m/s), whose boundary moves by about 2 ft/s per 2 ft/s of
/// descent speed.
pub const DEFAULT_VH_STEP: f64 = 0.25;

/// The grid's largest horizontal speed when none is asked for, as a fraction of the vehicle's
/// velocity scale: 29.6 ft/s on the 1/6-scale model, past its boundary at every descent speed
/// of Table I (23.6 ft/s at 8 ft/s, docs/engines.md).
pub const DEFAULT_VH_MAX: f64 = 3.5;

/// The bisection tolerance when none is asked for, as a fraction of the vehicle's velocity
/// scale: 0.051 ft/s on the 1/6-scale model, the report's 0.05 ft/s.
pub const DEFAULT_TOLERANCE: f64 = 0.006;

/// The scan step when none is asked for, as a fraction of the grid step: 0.25 ft/s on a grid
/// of 2 ft/s, 0.264 ft/s on the 1/6-scale model's default grid.
pub const DEFAULT_SCAN_STEP: f64 = 0.125;

/// A search's settings as asked (`--vh-start`, `--vh-step`, `--vh-max`, `--tol`,
/// `--scan-step`), scenario velocity unit: each one left out takes its default, a ratio of the
/// vehicle's velocity scale ([`Asked::settings`]), so that a dynamically similar vehicle is
/// searched alike whatever its size and units.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Asked {
    /// First grid point; default 0.
    pub vh_start: Option<f64>,
    /// Grid step; default [`DEFAULT_VH_STEP`] of the velocity scale.
    pub vh_step: Option<f64>,
    /// Largest grid point; default [`DEFAULT_VH_MAX`] of the velocity scale.
    pub vh_max: Option<f64>,
    /// Bisection tolerance; default [`DEFAULT_TOLERANCE`] of the velocity scale.
    pub tolerance: Option<f64>,
    /// Scan step: 0 scans nothing but the grid; default [`DEFAULT_SCAN_STEP`] of the grid
    /// step.
    pub scan_step: Option<f64>,
}

impl Asked {
    /// The settings of a search of `sc`: what is asked as asked, the rest from the vehicle's
    /// velocity scale in the scenario's velocity unit; an error for a vehicle with no velocity
    /// scale (neither gravity nor a touchdown speed) if a default needs it.
    pub fn settings(&self, sc: &Scenario) -> Result<Settings, ValidationError> {
        let scale = || -> Result<f64, ValidationError> {
            let v = touchdown_scenario::scales::Scales::of(sc)?.velocity_m_s;
            Ok(v / sc.units().velocity())
        };
        let or_scaled = |asked: Option<f64>, ratio: f64| -> Result<f64, ValidationError> {
            match asked {
                Some(v) => Ok(v),
                None => Ok(ratio * scale()?),
            }
        };
        let vh_step = or_scaled(self.vh_step, DEFAULT_VH_STEP)?;
        let scan_step = match self.scan_step {
            Some(0.0) => None,
            Some(s) => Some(s),
            None => Some(DEFAULT_SCAN_STEP * vh_step),
        };
        Ok(Settings {
            vh_start: self.vh_start.unwrap_or(0.0),
            vh_step,
            vh_max: or_scaled(self.vh_max, DEFAULT_VH_MAX)?,
            tolerance: or_scaled(self.tolerance, DEFAULT_TOLERANCE)?,
            scan_step,
        })
    }
}

pub(super) fn refuse(argument: &'static str, expected: String, got: f64) -> ValidationError {
    ValidationError::Setting {
        argument,
        expected,
        got: Short(got).to_string(),
    }
}

impl Settings {
    /// Checks the settings: an error ([`ValidationError::Setting`]) names the command-line
    /// argument at fault and what it must be.
    pub fn validate(&self) -> Result<(), ValidationError> {
        self.grid().map(|_| ())
    }

    /// The grid of horizontal velocities, scenario velocity unit: `vh_start + i·vh_step` for
    /// i = 0, 1, …, the last no more than 1e-9 (relative to the largest of |vh_start|,
    /// |vh_max| and the step) above `vh_max`. Refused as [`Settings::validate`] says.
    pub fn grid(&self) -> Result<Vec<f64>, ValidationError> {
        let &Settings {
            vh_start,
            vh_step,
            vh_max,
            tolerance,
            scan_step,
        } = self;
        if !vh_start.is_finite() {
            return Err(refuse("--vh-start", "a finite speed".into(), vh_start));
        }
        if !vh_max.is_finite() {
            return Err(refuse("--vh-max", "a finite speed".into(), vh_max));
        }
        if !(vh_step.is_finite() && vh_step > 0.0) {
            return Err(refuse("--vh-step", "a finite step > 0".into(), vh_step));
        }
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(refuse("--tol", "a finite tolerance > 0".into(), tolerance));
        }
        if let Some(scan) = scan_step {
            if !(scan.is_finite() && scan > 0.0 && scan < vh_step) {
                return Err(refuse(
                    "--scan-step",
                    format!("a finite step > 0 and below --vh-step ({})", Short(vh_step)),
                    scan,
                ));
            }
            // The scan covers at most the whole grid: as many points as a grid of its step.
            if (vh_max - vh_start) / scan > MAX_GRID_POINTS as f64 {
                return Err(refuse(
                    "--scan-step",
                    format!(
                        "a step giving at most {MAX_GRID_POINTS} points from --vh-start {} to --vh-max {}",
                        Short(vh_start),
                        Short(vh_max)
                    ),
                    scan,
                ));
            }
        }
        if vh_max < vh_start {
            return Err(refuse(
                "--vh-max",
                format!("a speed ≥ --vh-start ({})", Short(vh_start)),
                vh_max,
            ));
        }
        let scale = vh_start.abs().max(vh_max.abs()).max(1.0);
        let finest = scale / MAX_RELATIVE_RESOLUTION;
        if tolerance < finest {
            return Err(refuse(
                "--tol",
                format!(
                    "a tolerance ≥ {} (1e-9 of the largest |Vh| searched, or of 1), \
                     which bisection can reach in floating point",
                    Short(finest)
                ),
                tolerance,
            ));
        }
        if vh_step < finest {
            return Err(refuse(
                "--vh-step",
                format!(
                    "a step ≥ {} (1e-9 of the largest |Vh| searched, or of 1)",
                    Short(finest)
                ),
                vh_step,
            ));
        }
        let too_many = || {
            refuse(
                "--vh-step",
                format!(
                    "a step giving at most {MAX_GRID_POINTS} grid points from --vh-start \
                     {} to --vh-max {} (a step ≥ {})",
                    Short(vh_start),
                    Short(vh_max),
                    Short((vh_max - vh_start) / (MAX_GRID_POINTS - 1) as f64)
                ),
                vh_step,
            )
        };
        let intervals = (vh_max - vh_start) / vh_step;
        if intervals.is_nan() || intervals > MAX_GRID_POINTS as f64 {
            return Err(too_many());
        }
        let slack = vh_start.abs().max(vh_max.abs()).max(vh_step) / MAX_RELATIVE_RESOLUTION;
        let point = |i: usize| vh_start + i as f64 * vh_step;
        let mut last = intervals.floor() as usize;
        if point(last + 1) <= vh_max + slack {
            last += 1;
        } else if last > 0 && point(last) > vh_max + slack {
            last -= 1;
        }
        if last + 1 > MAX_GRID_POINTS {
            return Err(too_many());
        }
        Ok((0..=last).map(point).collect())
    }
}

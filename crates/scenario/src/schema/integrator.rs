//! The integration settings: scheme, step limits, tolerances and run budget.

use super::yes;
use serde::{Deserialize, Serialize};

/// Integration scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Scheme {
    /// The report's linear-acceleration predictor-corrector with Δt = DIST/VEL (eqs. 20-25).
    Report,
    /// The classical fourth-order Runge–Kutta method at the fixed step `dt_max` (shortened only
    /// to land an airborne footpad on its plane and to meet the end time).
    Rk4,
    /// The Dormand–Prince 5(4) embedded Runge–Kutta pair with error control (`rtol`, `atol`),
    /// its steps within [`dt_min`, `dt_max`].
    Dopri5,
    /// The report's predictor-corrector and step rule with the gear's stiff modes taken in its
    /// stride: every strut of a footpad off the surface corrected implicitly, and a step
    /// longer than `dt_max` (up to `stride` times it) where the gear's engaged stiffness
    /// allows it (not in the report; docs/errata.md, "Long strides where the gear is soft").
    Strides,
}

impl Scheme {
    /// The scheme's name as a scenario file writes it (`integrator.scheme`).
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Report => "report",
            Scheme::Rk4 => "rk4",
            Scheme::Dopri5 => "dopri5",
            Scheme::Strides => "strides",
        }
    }
}

/// How the core represents the vehicle's attitude.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum AttitudeForm {
    /// Euler angles θ (eqs. 3-9, the report): singular at θy = ±90°.
    #[default]
    Euler,
    /// A unit quaternion, q̇ = ½·q⊗ω: no singularity (not in the report; with the `rk4` and
    /// `dopri5` schemes only). The Euler angles are still reported, read from T_BI.
    Quaternion,
}

fn default_scheme() -> Scheme {
    Scheme::Report
}
fn default_energy_tolerance() -> f64 {
    0.02
}
/// Default run budget, accepted steps (`integrator.max_steps`): about 10 s of the core, a few
/// minutes of a multibody engine; a Table I landing takes about a thousand steps on the core
/// and a hundred thousand on a multibody engine at 20 µs.
pub const DEFAULT_MAX_STEPS: f64 = 1e7;
fn default_max_steps() -> f64 {
    DEFAULT_MAX_STEPS
}
fn default_rtol() -> f64 {
    1e-6
}
fn default_atol() -> f64 {
    1e-9
}
/// The longest step of the `strides` scheme as a multiple of `dt_max`, unless the file sets
/// `integrator.stride`.
pub const DEFAULT_STRIDE: f64 = 8.0;
/// The `strides` scheme's ω·Δt on the gear's stiffest engaged mode (its trace bound), unless the
/// file sets `integrator.mode_step`: the report's scheme is stable to 2.
pub const DEFAULT_MODE_STEP: f64 = 1.0;

/// How many times finer than a study's settings the runs are that state the accuracy those
/// settings give ([`Integrator::refine`] by it): a campaign's accuracy sample and a
/// calibration's rows at its fit are landed again so (docs/campaigns.md, "Accuracy";
/// docs/validation.md, "Calibrating by hand").
pub const ACCURACY_REFINEMENT: f64 = 8.0;

/// Integration settings (eqs. 20-25).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Integrator {
    /// "report" (default), "strides", "rk4" or "dopri5".
    #[serde(default = "default_scheme")]
    pub scheme: Scheme,
    /// DIST: allowed relative movement between any footpad and the centre of mass per step
    /// (the `report` scheme's step rule, eq. 25); length.
    pub dist: f64,
    /// Smallest step; time.
    pub dt_min: f64,
    /// Largest step; time. Keep it well below 2/ω of the stiffest strut mode.
    pub dt_max: f64,
    /// End time of the run (unless the stability criteria end it earlier); time.
    pub t_end: f64,
    /// Shorten a step so that an airborne footpad lands on its surface plane instead of
    /// overshooting it (not in the report; docs/errata.md, "Eq. (25): VEL and first contacts").
    #[serde(default = "yes")]
    pub contact_step_limit: bool,
    /// Divergence guard: stop when the energy residual exceeds this fraction of the energy
    /// put in (touchdown kinetic energy, potential energy released, thrust and RCS input);
    /// dimensionless.
    #[serde(default = "default_energy_tolerance")]
    pub energy_tolerance: f64,
    /// Run budget: the most accepted steps a landing takes on any engine (ten times as many
    /// force evaluations on the core); a run that reaches it stops with a diagnostic, and a
    /// multibody step that could not reach `t_end` within it is refused (default 1e7).
    #[serde(default = "default_max_steps")]
    pub max_steps: f64,
    /// "euler" (default) or "quaternion" (`rk4` and `dopri5` only).
    #[serde(default)]
    pub attitude: AttitudeForm,
    /// `dopri5`: relative error tolerance per step; dimensionless (default 1e-6).
    #[serde(default = "default_rtol")]
    pub rtol: f64,
    /// `dopri5`: absolute error tolerance per step, applied to every state component in SI
    /// units (m, m/s, rad, rad/s; whatever the file's units); default 1e-9.
    #[serde(default = "default_atol")]
    pub atol: f64,
    /// `strides`: the longest step as a multiple of `dt_max` (dimensionless, ≥ 1; default
    /// [`DEFAULT_STRIDE`]); the step goes past `dt_max` only where the gear's engaged
    /// stiffness allows it (docs/errata.md, "Long strides where the gear is soft").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stride: Option<f64>,
    /// `strides`: the largest ω·Δt the report's corrector may reach on the gear's stiffest
    /// engaged mode, ω from the trace bound of the vehicle on its struts, and past it, with
    /// the vehicle corrected implicitly, on the modes in which a maximum can be made
    /// (dimensionless, in (0, 2); default [`DEFAULT_MODE_STEP`]; docs/errata.md, "Long strides
    /// where the gear is soft").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mode_step: Option<f64>,
}

impl Integrator {
    /// The settings refined by `factor` (> 1) for the scheme they name: every step limit
    /// (`dt_max`, and `dt_min` where it would exceed it) divided by `factor`; the report's step
    /// rule also takes DIST ÷ `factor` (eq. 25: Δt = DIST/VEL), and the `strides` scheme also
    /// its `mode_step` ÷ `factor` (its step on the gear's modes, Δt = mode_step/ω, with the
    /// longest, `stride`·`dt_max`, ÷ `factor` through `dt_max`); the Dormand–Prince pair also
    /// takes `rtol` and `atol` ÷ `factor`⁵ (its local error is of fifth order in the step: the
    /// same local error as a step `factor` times shorter). The run's budget of steps,
    /// `max_steps`, grows by `factor`: a refined run is the same landing in more steps.
    pub fn refine(&mut self, factor: f64) {
        self.max_steps *= factor;
        self.dt_max /= factor;
        self.dt_min = self.dt_min.min(self.dt_max);
        match self.scheme {
            Scheme::Report => self.dist /= factor,
            Scheme::Strides => {
                self.dist /= factor;
                self.mode_step = Some(self.mode_step.unwrap_or(DEFAULT_MODE_STEP) / factor);
            }
            Scheme::Rk4 => {}
            Scheme::Dopri5 => {
                let tolerance = factor.powi(5);
                self.rtol /= tolerance;
                self.atol /= tolerance;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Scheme;

    #[test]
    fn a_schemes_name_is_the_one_its_file_writes() {
        for scheme in [Scheme::Report, Scheme::Rk4, Scheme::Dopri5, Scheme::Strides] {
            let written = toml::Value::try_from(scheme).expect("a scheme serialises");
            assert_eq!(written.as_str(), Some(scheme.name()));
        }
    }
}

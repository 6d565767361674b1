//! The multibody engines' time step and footpad contact, set from the scenario's own scales
//! (docs/engines.md, "Step and contact from the scenario's scale").
//!
//! Both engines apply the strut laws explicitly once per step, so the step must resolve the
//! stiffest gear mode: the primary strut's stiffest rate on the footpad mass, the secondaries'
//! on the gear's rotation about its trunnion (the tripod's on the footpad they meet at)
//! (eqs. 49-52). A setting the scenario states is used as stated (and checked); one it leaves
//! out is derived from that mode's angular frequency ω_max and the contact sphere's radius,
//! with the dimensionless rules below. Every rule is a ratio of like quantities, so a
//! dynamically similar vehicle (`[similarity]`, a Froude twin) gets the similar step and
//! contact, and lands as the original does within the engine's own step convergence
//! (`tests/physics.rs`, Froude twins).

use touchdown_laws::{GearLaws, Honeycomb};
use touchdown_scenario::schema::Arrangement;
use touchdown_scenario::{Scenario, ScenarioError};

/// Default ω_max·Δt: about 39 steps per period of the stiffest gear mode. The 1/6-scale
/// model's file states its validated step instead (ω_max·Δt = 0.164 there).
pub const STEP_PER_MODE: f64 = 0.16;

/// Default natural frequency of rapier's footpad contact per ω_max: the contact four times as
/// fast as the stiffest strut mode, so that footpads do not sink while the struts stroke.
pub const CONTACT_PER_MODE: f64 = 4.0;

/// Default time constant of MuJoCo's footpad contacts (`solref[0]`) per step: MuJoCo's floor,
/// the stiffest contact the step resolves.
pub const TIMECONST_PER_STEP: f64 = touchdown_scenario::model::Mujoco::MIN_TIMECONST_PER_STEP;

/// Default width of MuJoCo's contact impedance ramp (`solimp[2]`) per contact sphere radius.
pub const WIDTH_PER_CONTACT_RADIUS: f64 = 0.1;

/// ω·Δt above which a multibody engine refuses an explicit strut law (symplectic Euler is
/// stable below 2).
pub const MAX_OMEGA_DT: f64 = 1.0;

/// A gear mode the explicit step must resolve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mode {
    /// Which mode, for messages.
    pub what: &'static str,
    /// Its angular frequency, rad/s.
    pub omega: f64,
}

/// A honeycomb's stiffest rate, N/m: its backoff (rebound) rate, its stroke-out stop's rate or
/// its onset ramp's, whichever is largest (eqs. 49-52).
pub fn stiffest_rate(h: &Honeycomb) -> f64 {
    soft_rate(h).max(h.curve.stroke_out_rate())
}

/// A honeycomb's stiffest rate between its stops, N/m: its backoff (rebound) rate K_B or its
/// onset ramp's, whichever is larger (eqs. 49-52).
pub fn soft_rate(h: &Honeycomb) -> f64 {
    h.backoff_rate
        .max(h.curve.vertices().nth(1).map(|(x, f)| f / x).unwrap_or(0.0))
}

/// The two explicit gear modes of `sc` with its `laws`, each honeycomb's rate taken as `rate`
/// gives it (N/m; [`stiffest_rate`] for the modes the base step resolves): the primary's rate
/// on the footpad mass PMASS, and the secondaries': for the cantilever on the outer link's rotation
/// about its trunnion seen at point 1 (links as in `sc.links`), for the tripod on the footpad
/// they meet at, together with the primary (the footpad node on its three struts, bounded by
/// the trace of its stiffness over PMASS).
pub fn gear_modes(sc: &Scenario, laws: &GearLaws, rate: fn(&Honeycomb) -> f64) -> [Mode; 2] {
    let k_primary = rate(&laws.primary.honeycomb);
    let sec = &laws.secondary.honeycomb;
    let k_secondary = rate(&sec.tension).max(rate(&sec.compression));
    let pmass = sc.footpad.mass;
    let primary = Mode {
        what: "primary strut on the footpad mass",
        omega: (k_primary / pmass).sqrt(),
    };
    let secondaries = match sc.arrangement {
        Arrangement::Cantilever => {
            let leg = &sc.legs[0];
            let m_outer = sc.links.outer_cylinder_mass_ratio * pmass;
            let l_outer = sc
                .links
                .outer_cylinder_length(leg, &sc.primary, sc.arrangement);
            // Rotation about the trunnion seen at point 1: I_B2 / L21².
            let i_b2 = m_outer * l_outer * l_outer / 3.0 + pmass * leg.l2p * leg.l2p;
            let m_point1 = i_b2 / (leg.l21 * leg.l21);
            Mode {
                what: "secondary struts on the gear's rotation about its trunnion",
                omega: (k_secondary / m_point1).sqrt(),
            }
        }
        Arrangement::Tripod => Mode {
            what: "the three struts on the footpad mass they meet at",
            omega: ((k_primary + 2.0 * k_secondary) / pmass).sqrt(),
        },
    };
    [primary, secondaries]
}

/// A multibody engine's fixed time step: `stated` (the value of the scenario field `field`) as
/// stated, else [`STEP_PER_MODE`] over the stiffest of [`gear_modes`]; checked
/// ([`check_step`]). Returns the step, s, and the stiffest mode.
fn time_step(
    sc: &Scenario,
    stated: Option<f64>,
    field: &str,
) -> Result<(f64, Mode), ScenarioError> {
    let modes = gear_modes(sc, &GearLaws::from_scenario(sc)?, stiffest_rate);
    let stiffest = if modes[1].omega > modes[0].omega {
        modes[1]
    } else {
        modes[0]
    };
    let dt = stated.unwrap_or(STEP_PER_MODE / stiffest.omega);
    check_step(sc, &modes, dt, field, stated.is_some())?;
    Ok((dt, stiffest))
}

/// The settings of a rapier landing, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RapierSettings {
    /// Fixed time step, s.
    pub timestep: f64,
    /// Natural frequency of the footpad contact constraint, Hz.
    pub contact_frequency: f64,
    /// Damping ratio of the footpad contact constraint.
    pub contact_damping_ratio: f64,
    /// rapier's length unit, m: the primary strut length L2P of leg 1, so that its
    /// length-scaled tolerances (prediction distance, slop) scale with the vehicle.
    pub length_unit: f64,
}

impl RapierSettings {
    /// `sc`'s rapier settings: each stated one as stated, each other derived (module doc),
    /// the step checked against the run budget and the stiffest gear mode.
    pub fn new(sc: &Scenario) -> Result<RapierSettings, ScenarioError> {
        let r = &sc.rapier;
        let (timestep, mode) = time_step(sc, r.timestep, "engines.rapier.timestep")?;
        Ok(RapierSettings {
            timestep,
            contact_frequency: r
                .contact_frequency
                .unwrap_or(CONTACT_PER_MODE * mode.omega / std::f64::consts::TAU),
            contact_damping_ratio: r.contact_damping_ratio,
            length_unit: sc.legs[0].l2p,
        })
    }
}

/// The settings of a MuJoCo landing and its exported model, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MujocoSettings {
    /// Fixed time step (`option/timestep`), s.
    pub timestep: f64,
    /// Time constant of the footpad contacts (`solref[0]`), s.
    pub contact_timeconst: f64,
    /// Damping ratio of the footpad contacts (`solref[1]`).
    pub contact_damping_ratio: f64,
    /// Width of the footpad contacts' impedance ramp (`solimp[2]`), m.
    pub contact_width: f64,
}

impl MujocoSettings {
    /// `sc`'s MuJoCo settings: each stated one as stated, each other derived (module doc),
    /// the step checked against the run budget and the stiffest gear mode, the contact time
    /// constant against MuJoCo's floor of twice the step.
    pub fn new(sc: &Scenario) -> Result<MujocoSettings, ScenarioError> {
        let m = &sc.mujoco;
        let (timestep, _) = time_step(sc, m.timestep, "engines.mujoco.timestep")?;
        let contact_timeconst = m.contact_timeconst.unwrap_or(TIMECONST_PER_STEP * timestep);
        if contact_timeconst < TIMECONST_PER_STEP * timestep {
            let field = "engines.mujoco.contact_timeconst";
            return Err(ScenarioError::field(
                sc.file_of(field),
                field,
                format!(
                    "{contact_timeconst:.4e} s is below twice the time step ({timestep:.4e} s{}); expected at least {:.4e} s (MuJoCo would silently raise it)",
                    if m.timestep.is_some() { "" } else { ", derived from the stiffest gear mode" },
                    TIMECONST_PER_STEP * timestep
                ),
            ));
        }
        Ok(MujocoSettings {
            timestep,
            contact_timeconst,
            contact_damping_ratio: m.contact_damping_ratio,
            contact_width: m
                .contact_width
                .unwrap_or(WIDTH_PER_CONTACT_RADIUS * sc.links.contact_radius(&sc.legs[0])),
        })
    }
}

/// Checks a multibody engine's fixed time step `dt` (s) against the run budget
/// (`integrator.max_steps` steps to `integrator.t_end`) and the explicit gear `modes`
/// ([`gear_modes`]). (The obstacle walls are built no stiffer than the step resolves,
/// `crate::wall`, so they never refuse it; nor does an end stop's unloading, steep as it is at
/// small restitutions, which releases the stop rather than loading a stiffness.) The error, on
/// the scenario field `field` that sets the step (`stated`: the file states it; otherwise it
/// was derived), says which mode is too stiff and the largest step allowed.
fn check_step(
    sc: &Scenario,
    modes: &[Mode; 2],
    dt: f64,
    field: &str,
    stated: bool,
) -> Result<(), ScenarioError> {
    let origin = if stated {
        String::new()
    } else {
        format!(" (not stated: derived as {STEP_PER_MODE}/ω of the stiffest gear mode)")
    };
    let steps = sc.integrator.t_end / dt;
    if steps.is_nan() || steps > sc.integrator.max_steps as f64 {
        return Err(ScenarioError::field(
            sc.file_of(field),
            field,
            format!(
                "time step {dt:.3e} s{origin} needs {steps:.3e} steps to reach integrator.t_end = {:.3e} s; expected at most integrator.max_steps = {} steps (the run budget), i.e. a time step ≥ {:.3e} s",
                sc.integrator.t_end,
                sc.integrator.max_steps,
                sc.integrator.t_end / sc.integrator.max_steps as f64
            ),
        ));
    }
    for &Mode { what, omega } in modes {
        if omega * dt > MAX_OMEGA_DT {
            return Err(ScenarioError::field(
                sc.file_of(field),
                field,
                format!(
                    "time step {dt:.3e} s is too large for the stiffest explicit strut law ({what}: ω = {omega:.4e} rad/s, ω·Δt = {:.3}); expected ω·Δt ≤ {MAX_OMEGA_DT}, i.e. a time step ≤ {:.3e} s",
                    omega * dt,
                    MAX_OMEGA_DT / omega
                ),
            ));
        }
    }
    Ok(())
}

//! The engines a scenario applies to, and the settings of rapier, MuJoCo and their gear links.

use serde::{Deserialize, Serialize};

/// An engine of the testbench.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Engine {
    /// The report-faithful core.
    Core,
    /// The rapier multibody rebuild.
    Rapier,
    /// The MuJoCo model driven by the shared laws.
    Mujoco,
}

impl Engine {
    /// Every engine, in comparison order.
    pub const ALL: [Engine; 3] = [Engine::Core, Engine::Rapier, Engine::Mujoco];

    /// The engine's name, as in scenario files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Core => "core",
            Engine::Rapier => "rapier",
            Engine::Mujoco => "mujoco",
        }
    }
}

impl std::fmt::Display for Engine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Engine {
    type Err = String;
    fn from_str(s: &str) -> Result<Engine, String> {
        Engine::ALL
            .into_iter()
            .find(|e| e.name() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = Engine::ALL.iter().map(|e| e.name()).collect();
                format!("unknown engine {s:?}; expected one of {}", names.join(", "))
            })
    }
}

fn all_engines() -> Vec<Engine> {
    Engine::ALL.to_vec()
}

/// The engines that apply to the scenario, and the settings of those other than the core.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Engines {
    /// The engines that apply to this scenario (`touchdown run` refuses the others and
    /// `touchdown compare` leaves them out); default all three.
    #[serde(default = "all_engines")]
    pub applicable: Vec<Engine>,
    /// The rapier multibody rebuild (`touchdown run --engine rapier`).
    #[serde(default)]
    pub rapier: Rapier,
    /// The MuJoCo export (`touchdown export-mjcf`, `touchdown run --engine mujoco`).
    #[serde(default)]
    pub mujoco: Mujoco,
    /// The gear links the multibody engines (rapier, MuJoCo) add to the report's massless gear.
    #[serde(default)]
    pub links: GearLinks,
}

impl Default for Engines {
    fn default() -> Self {
        Engines {
            applicable: all_engines(),
            rapier: Rapier::default(),
            mujoco: Mujoco::default(),
            links: GearLinks::default(),
        }
    }
}

fn one() -> f64 {
    1.0
}
fn default_outer_cylinder_mass_ratio() -> f64 {
    0.1
}
fn default_link_radius_ratio() -> f64 {
    0.03
}

/// The rapier multibody rebuild (docs/engines.md): solver settings. A setting left out is
/// derived from the scenario's own scales (docs/engines.md, "Step and contact from the
/// scenario's scale"), so that no default depends on the vehicle's size.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rapier {
    /// Fixed time step; time. The strut laws are applied explicitly once per step, so keep
    /// ω·timestep well below 2 for the stiffest strut mode (checked at start-up). Absent: 0.16
    /// over the stiffest gear mode's angular frequency.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub timestep: Option<f64>,
    /// Natural frequency of the footpad contact constraint (rapier's contact softness, used for
    /// both its moving-body and fixed-body settings); 1/time (Hz). High, so that the footpads do
    /// not sink: the contact must be much stiffer than the stiffest strut law. Absent: four times
    /// the stiffest gear mode's frequency.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_frequency: Option<f64>,
    /// Damping ratio of the footpad contact constraint; dimensionless.
    #[serde(default = "one")]
    pub contact_damping_ratio: f64,
    /// The most time steps one step may take where no end stop is engaged or can engage
    /// within it; dimensionless, a whole number ≥ 1. The step taken there is the largest
    /// multiple up to this that keeps the honeycombs' stiffest mode at the time step's ω·Δt
    /// and that the obstacle walls and spikes resolve (docs/engines.md, "A longer step between
    /// the stops"). Absent: 1, the time step throughout.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stride: Option<f64>,
}

impl Default for Rapier {
    fn default() -> Self {
        Rapier {
            timestep: None,
            contact_frequency: None,
            contact_damping_ratio: one(),
            stride: None,
        }
    }
}

/// The gear links of the multibody engines: the masses they add to the report's massless gear
/// (stated in every multibody summary). Dimensionless.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GearLinks {
    /// Mass of each primary outer-cylinder link as a fraction of the effective footpad mass;
    /// dimensionless (the report's gear is massless; the link needs some mass).
    #[serde(default = "default_outer_cylinder_mass_ratio")]
    pub outer_cylinder_mass_ratio: f64,
    /// Radius of the gear links' solid-cylinder inertia as a fraction of the primary strut
    /// length L2P; dimensionless.
    #[serde(default = "default_link_radius_ratio")]
    pub link_radius_ratio: f64,
}

impl Default for GearLinks {
    fn default() -> Self {
        GearLinks {
            outer_cylinder_mass_ratio: default_outer_cylinder_mass_ratio(),
            link_radius_ratio: default_link_radius_ratio(),
        }
    }
}

/// The MuJoCo export (docs/engines.md). A setting left out is derived from the scenario's own
/// scales (docs/engines.md, "Step and contact from the scenario's scale").
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mujoco {
    /// Fixed time step (`option/timestep`); time. The strut laws are applied explicitly once
    /// per step, as in the rapier rebuild. Absent: 0.16 over the stiffest gear mode's angular
    /// frequency.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub timestep: Option<f64>,
    /// Time constant of the footpad contacts (`solref[0]`, on both geoms of every pair); time.
    /// Small, so that footpads do not sink; MuJoCo needs it at least twice the time step.
    /// Absent: twice the time step.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_timeconst: Option<f64>,
    /// Damping ratio of the footpad contacts (`solref[1]`); dimensionless.
    #[serde(default = "one")]
    pub contact_damping_ratio: f64,
    /// Penetration over which the footpad contacts' impedance rises from 0.99 to 0.999
    /// (`solimp[2]`); length. Absent: a tenth of the contact sphere's radius.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_width: Option<f64>,
}

impl Default for Mujoco {
    fn default() -> Self {
        Mujoco {
            timestep: None,
            contact_timeconst: None,
            contact_damping_ratio: one(),
            contact_width: None,
        }
    }
}

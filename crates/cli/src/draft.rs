//! `touchdown new`: a first vehicle and landing drafted from a handful of numbers
//! (`touchdown_scenario::draft`), written and reviewed.

use crate::args::{DraftArgs, DraftArrangement, DraftUnits, Format};
use crate::outln;
use anyhow::{bail, Context, Result};
use touchdown_scenario::draft::{Draft, UnitSystem};
use touchdown_scenario::schema::Arrangement;

/// `touchdown new`: writes `n.out`/vehicle.toml and `n.out`/landing.toml from the numbers `n`,
/// then prints their review; whether it found nothing.
pub fn new(n: DraftArgs) -> Result<bool> {
    let inertia: [f64; 3] = n.inertia.as_slice().try_into().map_err(|_| {
        anyhow::anyhow!(
            "--inertia: expected three principal moments XX,YY,ZZ, got {}",
            n.inertia.len()
        )
    })?;
    let draft = Draft {
        name: n.name,
        units: match n.units {
            DraftUnits::Si => UnitSystem::Si,
            DraftUnits::FtSlugLbf => UnitSystem::FootSlugPound,
        },
        arrangement: match n.arrangement {
            DraftArrangement::Cantilever => Arrangement::Cantilever,
            DraftArrangement::Tripod => Arrangement::Tripod,
        },
        legs: n.legs,
        mass: n.mass,
        gravity: n.gravity,
        inertia,
        footprint_radius: n.footprint_radius,
        centre_of_mass_height: n.centre_of_mass_height,
        crush_load: n.crush_load,
        stroke: n.stroke,
        vertical_velocity: n.vertical_velocity,
        horizontal_velocity: n.horizontal_velocity,
        slope: n.slope,
    };
    let out = n.out.as_path();
    let (vehicle, landing) = draft
        .files("vehicle.toml")
        .map_err(|e| anyhow::anyhow!("--{}: {}", e.field.replace('_', "-"), e.message))?;
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let (vehicle_path, landing_path) = (out.join("vehicle.toml"), out.join("landing.toml"));
    for path in [&vehicle_path, &landing_path] {
        if path.exists() {
            bail!(
                "{} exists: touchdown new never writes over a file (choose another --out, or move it away)",
                path.display()
            );
        }
    }
    for (path, text) in [(&vehicle_path, vehicle), (&landing_path, landing)] {
        std::fs::write(path, text).with_context(|| format!("cannot write {}", path.display()))?;
    }
    outln!(
        "wrote {} and {}\n",
        vehicle_path.display(),
        landing_path.display()
    )?;
    let clean = crate::check::check(&landing_path, &[], Format::Text)?;
    if clean {
        outln!(
            "\nnext: touchdown run {} (then replace each estimate, tag E, with your own values)",
            landing_path.display()
        )?;
    } else {
        outln!(
            "\nnext: the findings above first (the files are written; touchdown check {} reviews them again)",
            landing_path.display()
        )?;
    }
    Ok(clean)
}

//! Resolution of a merged, schema-checked scenario into SI (`Scenario`): every field checked
//! (`crate::check::Check`), the legs built, the engines' settings and mechanisms resolved.

use crate::check::{owner_of, Check};
use crate::error::ScenarioError;
use crate::mechanisms;
use crate::model::{self, Scenario};
use crate::ranges;
use crate::read::Merged;
use crate::schema::{self, ScenarioFile, SCHEMA_VERSION};
use crate::strict::Strict;
use crate::units::{short, Units};
use nalgebra::{Matrix3, Vector3};

/// Schema check (types, required and unknown fields, tables only as tables), then resolution.
pub(crate) fn resolve_layers(source: String, merged: Merged) -> Result<Scenario, ScenarioError> {
    let t = &merged.table;
    if !t.contains_key("surface")
        && !t.contains_key("touchdown")
        && (t.contains_key("vehicle") || t.contains_key("gear"))
    {
        return Err(ScenarioError::NotALanding { file: source });
    }
    let file: ScenarioFile =
        read_strict(toml::Value::Table(merged.table)).map_err(|m| ScenarioError::Field {
            file: owner_of(&merged.layers, &m.field).to_string(),
            field: m.field,
            message: m.message,
        })?;
    resolve(&source, merged.layers, file)
}

/// Where a TOML document does not fit a schema: the field (a path such as
/// `dispersion[2].mean`) and what is wrong with it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SchemaMismatch {
    /// The field path.
    pub field: String,
    /// What is wrong (the first line of the deserializer's message).
    pub message: String,
}

/// Reads `value` as a `T` through the strict reader of the scenario schema (tables only as
/// tables, numbers in short notation): the reader of scenario files, and of other project files
/// in TOML (campaigns). A missing field is reported at its own path, not at its table's.
pub fn read_strict<T: serde::de::DeserializeOwned>(
    value: toml::Value,
) -> Result<T, SchemaMismatch> {
    serde_path_to_error::deserialize(Strict(value)).map_err(|e| {
        let mut field = e.path().to_string();
        let message = e.inner().to_string();
        let message = message.lines().next().unwrap_or_default().to_string();
        // "missing field `x`" is about the field x, not about the table that lacks it.
        if let Some(name) = message
            .strip_prefix("missing field `")
            .and_then(|rest| rest.split('`').next())
        {
            field = if field == "." || field.is_empty() {
                name.to_string()
            } else {
                format!("{field}.{name}")
            };
        }
        SchemaMismatch { field, message }
    })
}

/// The applicable engines in comparison order: at least one, none named twice.
pub(crate) fn resolve_applicable(
    c: &Check,
    engines: &[schema::Engine],
) -> Result<Vec<schema::Engine>, ScenarioError> {
    let field = "engines.applicable";
    if engines.is_empty() {
        return Err(c.err(
            field,
            "expected at least one of \"core\", \"rapier\", \"mujoco\"",
        ));
    }
    let mut sorted = engines.to_vec();
    sorted.sort();
    if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
        return Err(c.err(
            field,
            format!("expected each engine once, {} is named twice", w[0]),
        ));
    }
    Ok(sorted)
}

/// The rapier engine's settings in SI.
pub(crate) fn resolve_rapier(
    c: &Check,
    r: &schema::Rapier,
    u: &Units,
) -> Result<model::Rapier, ScenarioError> {
    Ok(model::Rapier {
        timestep: r
            .timestep
            .map(|v| c.positive_si("engines.rapier.timestep", v, u.time()))
            .transpose()?,
        contact_frequency: r
            .contact_frequency
            .map(|v| c.positive_si("engines.rapier.contact_frequency", v, 1.0 / u.time()))
            .transpose()?,
        contact_damping_ratio: c.non_negative_si(
            "engines.rapier.contact_damping_ratio",
            r.contact_damping_ratio,
            1.0,
        )?,
        stride: c.whole("engines.rapier.stride", r.stride.unwrap_or(1.0))?,
    })
}

/// The MuJoCo export's settings in SI.
pub(crate) fn resolve_mujoco(
    c: &Check,
    m: &schema::Mujoco,
    u: &Units,
) -> Result<model::Mujoco, ScenarioError> {
    let timestep = m
        .timestep
        .map(|v| c.positive_si("engines.mujoco.timestep", v, u.time()))
        .transpose()?;
    let contact_timeconst = m
        .contact_timeconst
        .map(|v| c.positive_si("engines.mujoco.contact_timeconst", v, u.time()))
        .transpose()?;
    if let (Some(step), Some(timeconst)) = (timestep, contact_timeconst) {
        let least = model::Mujoco::MIN_TIMECONST_PER_STEP * step;
        if timeconst < least {
            return Err(c.err(
                "engines.mujoco.contact_timeconst",
                format!(
                    "expected at least twice engines.mujoco.timestep, {} in the file's time unit (MuJoCo would silently raise it)",
                    short(least / u.time())
                ),
            ));
        }
    }
    Ok(model::Mujoco {
        timestep,
        contact_timeconst,
        contact_damping_ratio: c.non_negative_si(
            "engines.mujoco.contact_damping_ratio",
            m.contact_damping_ratio,
            1.0,
        )?,
        contact_width: m
            .contact_width
            .map(|v| c.positive_si("engines.mujoco.contact_width", v, u.length()))
            .transpose()?,
    })
}

/// The touchdown conditions, SI, checked.
pub(crate) fn resolve_touchdown(
    c: &Check,
    td: &schema::Touchdown,
    u: &Units,
) -> Result<model::Touchdown, ScenarioError> {
    let vh = td.horizontal_velocity;
    let mut velocity_g = Vector3::zeros();
    for (i, v) in vh.iter().enumerate() {
        velocity_g[i] = c.finite_si(
            &format!("touchdown.horizontal_velocity[{i}]"),
            *v,
            u.velocity(),
        )?;
    }
    velocity_g.z = c.finite_si(
        "touchdown.vertical_velocity",
        td.vertical_velocity,
        u.velocity(),
    )?;
    if velocity_g.z > 0.0 {
        c.warn(
            "touchdown.vertical_velocity",
            format!(
                "{} in the file's units is upward (negative is down): the vehicle starts away from the ground and lands only if gravity brings it back",
                short(td.vertical_velocity)
            ),
        );
    }
    Ok(model::Touchdown {
        attitude: c.vec3("touchdown.attitude", td.attitude, u.angle())?,
        attitude_reference: td.attitude_reference,
        velocity_g,
        body_rates: c.vec3("touchdown.body_rates", td.body_rates, u.angular_rate())?,
        clearance: c.non_negative_si("touchdown.clearance", td.clearance, u.length())?,
    })
}

/// A setting of the `strides` scheme only (`field`, dimensionless): its value or `default`
/// with that scheme, refused with the others (1, unused, when absent).
fn strides_only(
    c: &Check,
    it: &schema::Integrator,
    field: &str,
    value: Option<f64>,
    default: f64,
) -> Result<f64, ScenarioError> {
    match (it.scheme, value) {
        (schema::Scheme::Strides, v) => c.positive_si(field, v.unwrap_or(default), 1.0),
        (_, None) => Ok(1.0),
        (_, Some(_)) => Err(c.err(
            field,
            "expected it with scheme \"strides\" only (docs/errata.md, \"Long strides where the gear is soft\"); the schemes \"report\", \"rk4\" and \"dopri5\" have no stride",
        )),
    }
}

/// The integrator settings, SI, checked, on the resolved `surface`.
pub(crate) fn resolve_integrator(
    c: &Check,
    it: &schema::Integrator,
    u: &Units,
    surface: &model::Surface,
) -> Result<model::Integrator, ScenarioError> {
    let integrator = model::Integrator {
        scheme: it.scheme,
        dist: c.positive_si("integrator.dist", it.dist, u.length())?,
        dt_min: c.positive_si("integrator.dt_min", it.dt_min, u.time())?,
        dt_max: c.positive_si("integrator.dt_max", it.dt_max, u.time())?,
        t_end: c.positive_si("integrator.t_end", it.t_end, u.time())?,
        contact_step_limit: it.contact_step_limit,
        energy_tolerance: c.positive_si("integrator.energy_tolerance", it.energy_tolerance, 1.0)?,
        max_steps: c
            .positive_si("integrator.max_steps", it.max_steps, 1.0)?
            .round() as u64,
        attitude: it.attitude,
        rtol: c.positive_si("integrator.rtol", it.rtol, 1.0)?,
        atol: c.positive_si("integrator.atol", it.atol, 1.0)?,
        stride: strides_only(
            c,
            it,
            "integrator.stride",
            it.stride,
            schema::DEFAULT_STRIDE,
        )?,
        mode_step: strides_only(
            c,
            it,
            "integrator.mode_step",
            it.mode_step,
            schema::DEFAULT_MODE_STEP,
        )?,
    };
    if integrator.dt_min > integrator.dt_max {
        return Err(c.err("integrator.dt_min", "expected dt_min ≤ dt_max"));
    }
    if integrator.scheme == schema::Scheme::Strides
        && (surface.soil.is_some() || !surface.curbs.is_empty())
    {
        return Err(c.err(
            "integrator.scheme",
            "expected \"report\", \"rk4\" or \"dopri5\" on soil or beside curbs: the long strides are derived for the struts' laws on footpads that stand or fly (docs/errata.md, \"Long strides where the gear is soft\"), not for the soil's bearing or the curbs' crushing",
        ));
    }
    let corrector = matches!(it.scheme, schema::Scheme::Report | schema::Scheme::Strides);
    if it.attitude == schema::AttitudeForm::Quaternion && corrector {
        return Err(c.err(
            "integrator.attitude",
            "expected \"euler\" with scheme \"report\" or \"strides\" (the report's predictor-corrector integrates Euler angles, eqs. 20-25); \"quaternion\" needs scheme \"rk4\" or \"dopri5\"",
        ));
    }
    Ok(integrator)
}

/// The multibody engines' gear links.
pub(crate) fn resolve_links(
    c: &Check,
    l: &schema::GearLinks,
) -> Result<model::GearLinks, ScenarioError> {
    Ok(model::GearLinks {
        outer_cylinder_mass_ratio: c.positive_si(
            "engines.links.outer_cylinder_mass_ratio",
            l.outer_cylinder_mass_ratio,
            1.0,
        )?,
        link_radius_ratio: c.positive_si(
            "engines.links.link_radius_ratio",
            l.link_radius_ratio,
            1.0,
        )?,
    })
}

/// Legs from the report's parameterisation (see [`schema::Parametric`]), body axes, m.
pub(crate) fn parametric_legs(
    c: &Check,
    p: &schema::Parametric,
    arrangement: schema::Arrangement,
    u: &Units,
) -> Result<Vec<model::Leg>, ScenarioError> {
    let l = u.length();
    let f = |name: &str, v: f64| c.positive_si(&format!("gear.parametric.{name}"), v, l);
    let (r1, r2, r3) = (f("r1", p.r1)?, f("r2", p.r2)?, f("r3", p.r3)?);
    let (z2, z3, zc) = (f("z2", p.z2)?, f("z3", p.z3)?, f("zc", p.zc)?);
    // Point 1's height: Z1 on the cantilever; the footpad's, 0, on the tripod (eqs. 29-30).
    let z1 = match (arrangement, p.z1) {
        (schema::Arrangement::Cantilever, Some(z1)) => {
            let z1_si = f("z1", z1)?;
            if z1_si >= z3 {
                return Err(c.err(
                    "gear.parametric.z1",
                    format!(
                        "expected Z1 below the primary trunnion height Z3 = {}, got {}",
                        short(p.z3),
                        short(z1)
                    ),
                ));
            }
            z1_si
        }
        (schema::Arrangement::Cantilever, None) => {
            return Err(c.conflict(
                "gear.parametric.z1",
                "gear.arrangement",
                "expected Z1 (length), the height of point 1, for the cantilever gear",
            ))
        }
        (schema::Arrangement::Tripod, None) => 0.0,
        // Named where it was set last: a tripod arrangement over a cantilever's parameters
        // is the arrangement's line.
        (schema::Arrangement::Tripod, Some(_)) => {
            return Err(c.conflict(
                "gear.parametric.z1",
                "gear.arrangement",
                "the tripod's secondaries meet the primary at the footpad: its parametric form leaves Z1 out (or give the tripod's points in gear.legs)",
            ))
        }
    };
    let beta = c.finite_si("gear.parametric.beta", p.beta, u.angle())?;
    // Point 1: on the primary axis from B2 = (R1, Z3) to BP = (R3, 0), at height Z1.
    let t1 = (z3 - z1) / z3;
    let x1 = r1 + (r3 - r1) * t1;
    let (b3, b4) = match p.beta_convention {
        schema::BetaConvention::TrunnionAzimuth => (
            Vector3::new(r2 * beta.cos(), r2 * beta.sin(), z2),
            Vector3::new(r2 * beta.cos(), -r2 * beta.sin(), z2),
        ),
        schema::BetaConvention::StrutAngle => {
            let y = (x1 - r2) * beta.tan();
            (Vector3::new(r2, y, z2), Vector3::new(r2, -y, z2))
        }
    };
    let b2 = Vector3::new(r1, 0.0, z3);
    let bp = Vector3::new(r3, 0.0, 0.0);
    let l21 = t1 * (bp - b2).norm();
    let shift = Vector3::new(0.0, 0.0, zc);
    check_leg_count(c, "gear.parametric.leg_azimuths", p.leg_azimuths.len())?;
    let mut legs = Vec::with_capacity(p.leg_azimuths.len());
    for (i, az) in p.leg_azimuths.iter().enumerate() {
        let a = c.finite_si(
            &format!("gear.parametric.leg_azimuths[{i}]"),
            *az,
            u.angle(),
        )?;
        let r = touchdown_frames::rot_z(a);
        legs.push(model::Leg::from_points(
            r * b2 - shift,
            r * b3 - shift,
            r * b4 - shift,
            r * bp - shift,
            l21,
        ));
    }
    Ok(legs)
}

pub(crate) fn explicit_legs(
    c: &Check,
    legs: &[schema::Leg],
    arrangement: schema::Arrangement,
    u: &Units,
) -> Result<Vec<model::Leg>, ScenarioError> {
    check_leg_count(c, "gear.legs", legs.len())?;
    let l = u.length();
    legs.iter()
        .enumerate()
        .map(|(i, leg)| {
            let f = |n: &str| format!("gear.legs[{i}].{n}");
            let (b2, bp) = (c.vec3(&f("b2"), leg.b2, l)?, c.vec3(&f("bp"), leg.bp, l)?);
            // eqs. (29)-(30): point 1 at L21 along the primary; the tripod's is the footpad.
            let l21 = match (arrangement, leg.l21) {
                (schema::Arrangement::Cantilever, Some(x)) => c.positive_si(&f("l21"), x, l)?,
                (schema::Arrangement::Cantilever, None) => {
                    return Err(c.err(&f("l21"), "expected L21 (length) for the cantilever gear"))
                }
                (schema::Arrangement::Tripod, None) => (bp - b2).norm(),
                (schema::Arrangement::Tripod, Some(_)) => {
                    return Err(c.err(
                        &f("l21"),
                        "the tripod's secondaries meet the primary at the footpad: leave L21 out",
                    ))
                }
            };
            Ok(model::Leg::from_points(
                b2,
                c.vec3(&f("b3"), leg.b3, l)?,
                c.vec3(&f("b4"), leg.b4, l)?,
                bp,
                l21,
            ))
        })
        .collect()
}

/// From 3 to [`ranges::MAX_LEGS`] legs.
pub(crate) fn check_leg_count(c: &Check, field: &str, n: usize) -> Result<(), ScenarioError> {
    if n < 3 {
        return Err(c.err(field, format!("expected at least 3 legs, got {n}")));
    }
    if n > ranges::MAX_LEGS {
        return Err(c.err(
            field,
            format!("expected at most {} legs, got {n}", ranges::MAX_LEGS),
        ));
    }
    Ok(())
}

/// Geometric checks common to both ways of giving the legs.
pub(crate) fn check_legs(
    c: &Check,
    field: &str,
    legs: &[model::Leg],
    arrangement: schema::Arrangement,
    lengths: f64,
) -> Result<(), ScenarioError> {
    let tiny = 1e-9;
    for (i, leg) in legs.iter().enumerate() {
        let f = format!("{field}[{i}]");
        if leg.l2p < tiny {
            return Err(c.err(&f, "the footpad BP coincides with the primary trunnion B2"));
        }
        if arrangement == schema::Arrangement::Cantilever && leg.l21 >= leg.l2p {
            return Err(c.err(
                &f,
                format!(
                    "the strut cannot reach its footpad: L21 = {} must be shorter than the primary strut |BP − B2| = {} (file length units)",
                    short(leg.l21 / lengths),
                    short(leg.l2p / lengths)
                ),
            ));
        }
        if leg.l31 < tiny || leg.l41 < tiny {
            return Err(c.err(
                &f,
                "a secondary trunnion coincides with the attachment point 1",
            ));
        }
        // A gear reaches down from the vehicle to its footpad.
        if leg.bp.z >= leg.b2.z {
            return Err(c.err(
                &f,
                format!(
                    "expected the footpad BP below its primary trunnion B2 (a gear reaches down to its footpad); BP is at z = {}, B2 at z = {} (file length units, body axes, +Z up)",
                    short(leg.bp.z / lengths),
                    short(leg.b2.z / lengths)
                ),
            ));
        }
    }
    // Counter-clockwise order seen from above: footpad azimuths strictly increasing, one turn.
    let az: Vec<f64> = legs.iter().map(|l| l.bp.y.atan2(l.bp.x)).collect();
    let mut turn = 0.0;
    for i in 0..az.len() {
        let mut d = az[(i + 1) % az.len()] - az[i];
        while d <= 0.0 {
            d += std::f64::consts::TAU;
        }
        turn += d;
    }
    if (turn - std::f64::consts::TAU).abs() > 1e-6 {
        return Err(c.err(
            field,
            "legs must be listed counter-clockwise seen from above (+Z_B), once around",
        ));
    }
    // Consecutive footpads apart by a least angle: two legs at (nearly) one azimuth are one leg
    // listed twice, and their stability wall has no direction.
    let least = ranges::MIN_LEG_SEPARATION_DEG.to_radians();
    for i in 0..az.len() {
        let j = (i + 1) % az.len();
        let d = (az[j] - az[i]).rem_euclid(std::f64::consts::TAU);
        if d < least {
            let element = if field == "gear.parametric" {
                format!("gear.parametric.leg_azimuths[{j}]")
            } else {
                format!("{field}[{j}]")
            };
            return Err(c.err(
                &element,
                format!(
                    "leg {}'s footpad is {} deg counter-clockwise from leg {}'s seen from above; expected consecutive legs at least {} deg apart",
                    j + 1,
                    short(d.to_degrees()),
                    i + 1,
                    short(ranges::MIN_LEG_SEPARATION_DEG)
                ),
            ));
        }
    }
    Ok(())
}

pub(crate) fn inertia(
    c: &Check,
    i: &schema::Inertia,
    u: &Units,
) -> Result<Matrix3<f64>, ScenarioError> {
    let s = u.inertia();
    let g = |n: &str, v: f64| c.finite_si(&format!("vehicle.inertia.{n}"), v, s);
    let (xx, yy, zz) = (g("xx", i.xx)?, g("yy", i.yy)?, g("zz", i.zz)?);
    let (xy, xz, yz) = (g("xy", i.xy)?, g("xz", i.xz)?, g("yz", i.yz)?);
    let j = Matrix3::new(xx, -xy, -xz, -xy, yy, -yz, -xz, -yz, zz);
    if j.cholesky().is_none() {
        return Err(c.err("vehicle.inertia", "expected a positive-definite inertia tensor (check the moments and the products of inertia)"));
    }
    // Every rigid body's principal moments satisfy the triangle inequalities: I₁ = ∫(y² + z²)dm
    // ≤ ∫(x² + z²)dm + ∫(x² + y²)dm = I₂ + I₃, equal only for a body with no extent along the
    // first axis (a flat plate). A tensor past that is no body's, however it integrates.
    let mut moments: Vec<f64> = j.symmetric_eigenvalues().iter().copied().collect();
    moments.sort_by(f64::total_cmp);
    if moments[2] > (moments[0] + moments[1]) * (1.0 + 1e-9) {
        return Err(c.err(
            "vehicle.inertia",
            format!(
                "expected the inertia of a rigid body: its principal moments {}, {} and {} (file units) break the triangle inequality, the largest exceeding the sum of the other two, which no distribution of mass allows (check that each moment is about its own axis, e.g. yy about Y_B)",
                short(moments[0] / s),
                short(moments[1] / s),
                short(moments[2] / s)
            ),
        ));
    }
    Ok(j)
}

pub(crate) fn resolve(
    source: &str,
    layers: Vec<(String, toml::Table)>,
    file: ScenarioFile,
) -> Result<Scenario, ScenarioError> {
    let c = Check::new(&layers);
    if file.schema_version != SCHEMA_VERSION {
        return Err(c.err(
            "schema_version",
            format!("expected {SCHEMA_VERSION}, got {}", file.schema_version),
        ));
    }
    if let Some(s) = &file.similarity {
        c.positive_si("similarity.length", s.length, 1.0)?;
        c.positive_si("similarity.mass", s.mass, 1.0)?;
        c.positive_si("similarity.time", s.time, 1.0)?;
    }
    let u = file.read_units();
    let vehicle = model::Vehicle {
        mass: c.positive_si("vehicle.mass", file.vehicle.mass, u.mass())?,
        inertia: inertia(&c, &file.vehicle.inertia, &u)?,
        gravity: c.non_negative_si("vehicle.gravity", file.vehicle.gravity, u.acceleration())?,
    };
    let arrangement = file.gear.arrangement;
    let (legs, legs_field) = match (&file.gear.legs, &file.gear.parametric) {
        (Some(l), None) => (explicit_legs(&c, l, arrangement, &u)?, "gear.legs"),
        (None, Some(p)) => (parametric_legs(&c, p, arrangement, &u)?, "gear.parametric"),
        _ => return Err(c.err("gear", "expected exactly one of `legs` or `parametric`")),
    };
    check_legs(&c, legs_field, &legs, arrangement, u.length())?;
    let n = legs.len();
    let ps = &file.primary_strut;
    let primary = model::PrimaryStrut {
        compression: c.load_stroke("primary_strut.compression", &ps.compression, 3, &u)?,
        trunnion_rate: c.trunnion("primary_strut.trunnion", ps.trunnion, &u)?,
        viscous: c.viscous("primary_strut.viscous", ps.viscous, &u)?,
        bearing_friction: c.non_negative_si(
            "primary_strut.bearing.friction",
            ps.bearing.friction,
            1.0,
        )?,
        inner_cylinder_length: c.positive_si(
            "primary_strut.bearing.inner_cylinder_length",
            ps.bearing.inner_cylinder_length,
            u.length(),
        )?,
        initial_overlap: c.positive_si(
            "primary_strut.bearing.initial_overlap",
            ps.bearing.initial_overlap,
            u.length(),
        )?,
        bending_stiffness: mechanisms::bending(&c, ps.bending, arrangement, &u)?,
    };
    if primary.initial_overlap >= primary.inner_cylinder_length {
        return Err(c.err(
            "primary_strut.bearing.initial_overlap",
            "expected the initial overlap D2 to be shorter than the inner cylinder D1",
        ));
    }
    let shortest = legs.iter().map(|l| l.l2p).fold(f64::INFINITY, f64::min);
    if primary.inner_cylinder_length >= shortest {
        return Err(c.err(
            "primary_strut.bearing.inner_cylinder_length",
            "expected the inner cylinder D1 to be shorter than the primary strut",
        ));
    }
    // The landed vehicle rests on its primaries: below its weight their first crush load would
    // crush them standing (a load in kN written as N lands without any other word).
    let weight = vehicle.mass * vehicle.gravity;
    let first_crush = primary.compression.stages.first().map_or(0.0, |s| s.0);
    if n as f64 * first_crush < weight {
        c.warn(
            "primary_strut.compression.stages[0].crush_load",
            format!(
                "the {n} primaries' first crush load, {} each (file force units), holds less than the vehicle's weight, {}: the landed vehicle would crush its gear standing still (a load meant in kN written in N?)",
                short(first_crush / u.force()),
                short(weight / u.force())
            ),
        );
    }
    let ss = &file.secondary_strut;
    let secondary = model::SecondaryStrut {
        tension: c.load_stroke("secondary_strut.tension", &ss.tension, 4, &u)?,
        compression: c.load_stroke("secondary_strut.compression", &ss.compression, 4, &u)?,
        trunnion_rate: c.trunnion("secondary_strut.trunnion", ss.trunnion, &u)?,
        viscous: c.viscous("secondary_strut.viscous", ss.viscous, &u)?,
    };
    let footpad = model::Footpad {
        mass: c.positive_si("footpad.mass", file.footpad.mass, u.mass())?,
        radius: c.positive_si("footpad.radius", file.footpad.radius, u.length())?,
        height: match file.footpad.height {
            Some(h) => Some(c.positive_si("footpad.height", h, u.length())?),
            None => None,
        },
        crush: match &file.footpad.crush {
            Some(ls) => Some(c.load_stroke("footpad.crush", ls, 4, &u)?),
            None => None,
        },
        detached: file.footpad.detached,
    };
    let sf = &file.surface;
    let slope = c.finite("surface.slope", sf.slope)? * u.angle();
    if slope.abs() >= std::f64::consts::FRAC_PI_2 {
        return Err(c.err(
            "surface.slope",
            "expected a slope strictly between −90° and 90°",
        ));
    }
    let slope = c.si("surface.slope", sf.slope, u.angle())?;
    let hole = c.per_pad("surface.hole", &sf.hole, n)?;
    let obstacle = c.per_pad("surface.obstacle", &sf.obstacle, n)?;
    let spike = c.per_pad("surface.spike_depth", &sf.spike_depth, n)?;
    for i in 0..n {
        if spike[i] < 0.0 {
            return Err(c.err(
                &format!("surface.spike_depth[{i}]"),
                format!(
                    "expected an engagement depth ≥ 0 (0: no spikes), got {}",
                    short(spike[i])
                ),
            ));
        }
        if spike[i] > 0.0 && obstacle[i] > 0.0 {
            return Err(c.conflict(
                &format!("surface.spike_depth[{i}]"),
                &format!("surface.obstacle[{i}]"),
                "a footpad held by an obstacle's wall (surface.obstacle > 0) has no spikes too: give one of the two",
            ));
        }
    }
    // What holds each footpad laterally: neither restraint goes with soil or beside a curb.
    let holds: Vec<Option<mechanisms::Hold>> = (0..n)
        .map(|i| mechanisms::Hold::of(obstacle[i], spike[i]))
        .collect();
    let friction = c.per_pad("surface.friction", &sf.friction, n)?;
    if let Some(i) = friction.iter().position(|f| *f < 0.0) {
        return Err(c.err(
            &format!("surface.friction[{i}]"),
            format!(
                "expected a friction coefficient ≥ 0, got {}",
                short(friction[i])
            ),
        ));
    }
    let hole_si = c.each_si("surface.hole", &hole, u.length())?;
    let obstacle_si = c.each_si("surface.obstacle", &obstacle, u.length())?;
    let spike_si = c.each_si("surface.spike_depth", &spike, u.length())?;
    let friction = c.each_si("surface.friction", &friction, 1.0)?;
    let pads = (0..n)
        .map(|i| model::PadSurface {
            hole: hole_si[i],
            obstacle: obstacle_si[i],
            spike_depth: spike_si[i],
            friction: friction[i],
        })
        .collect();
    // A footpad with inertia leaves when its surface would have to pull: the report's
    // stand-ins for the pressing force would make the surface pull or let go of a pressed
    // footpad (docs/errata.md, "Footpads with inertia").
    if footpad.detached == schema::Detached::Inertial
        && sf.release != schema::ReleaseRule::GearForce
    {
        return Err(c.err(
            "surface.release",
            "expected \"gear_force\" with footpad.detached = \"inertial\" (the default): a footpad with mass leaves when its surface would have to pull; the report's stand-ins \"strut_force\" and \"honeycomb_force\" go with its massless footpad, footpad.detached = \"rigid\"",
        ));
    }
    let surface = model::Surface {
        slope,
        soil: mechanisms::soil(&c, sf, &footpad, &holds, &u)?,
        curbs: mechanisms::curbs(&c, sf, &footpad, &holds, &u)?,
        pads,
        release: sf.release,
    };
    let touchdown = resolve_touchdown(&c, &file.touchdown, &u)?;
    let integrator = resolve_integrator(&c, &file.integrator, &u, &surface)?;
    let st = &file.stability;
    let frac = c.positive(
        "stability.kinetic_energy_fraction",
        st.kinetic_energy_fraction,
    )?;
    if frac > 1.0 {
        return Err(c.err(
            "stability.kinetic_energy_fraction",
            format!("expected a fraction in (0, 1], got {}", short(frac)),
        ));
    }
    let stability = model::Stability {
        kinetic_energy_fraction: c.si("stability.kinetic_energy_fraction", frac, 1.0)?,
        counted_energy: st.counted_energy,
        min_separation_velocity: c.non_negative_si(
            "stability.min_separation_velocity",
            st.min_separation_velocity,
            u.velocity(),
        )?,
        walls: st.walls,
        terminate_on_decision: st.terminate_on_decision,
        settled_tolerance: st
            .settled_tolerance
            .map(|e| c.positive_si("stability.settled_tolerance", e, u.length()))
            .transpose()?,
    };
    let comparison = file.comparison.unwrap_or_default();
    for (name, limit) in comparison.set() {
        c.positive_si(&format!("comparison.{name}"), limit, 1.0)?;
    }
    let applicable_engines = resolve_applicable(&c, &file.engines.applicable)?;
    let rapier = resolve_rapier(&c, &file.engines.rapier, &u)?;
    let mujoco = resolve_mujoco(&c, &file.engines.mujoco, &u)?;
    let links = resolve_links(&c, &file.engines.links)?;
    let thrust = mechanisms::thrust(&c, file.thrust.as_ref(), &u)?;
    let rcs = mechanisms::rcs(&c, file.rcs.as_ref(), &u)?;
    let slosh = mechanisms::slosh(&c, file.slosh.as_ref(), vehicle.mass, &u)?;
    let warnings = c.into_warnings();
    Ok(Scenario {
        source: source.to_string(),
        layers,
        file,
        vehicle,
        arrangement,
        legs,
        primary,
        secondary,
        footpad,
        surface,
        touchdown,
        integrator,
        stability,
        comparison,
        applicable_engines,
        rapier,
        mujoco,
        links,
        thrust,
        rcs,
        slosh,
        warnings,
    })
}

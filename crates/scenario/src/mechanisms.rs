//! Reading the optional mechanisms of a scene (soil, curbs, bending, thrust, RCS, sloshing):
//! each is absent unless its table is given, and each is checked against the rest of the scene
//! (a soil surface has no curbs, a curb needs a footpad crush diagram, ...).

use crate::check::Check;
use crate::error::ScenarioError;
use crate::model;
use crate::schema::{self, Arrangement, RcsMode};
use crate::units::{short, Units};
use nalgebra::Vector3;

/// What holds a footpad laterally, as the file names it: an obstacle's wall
/// (`surface.obstacle`) or spikes (`surface.spike_depth`). Neither goes with soil or beside a
/// curb, and each refusal names the field that gives it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Hold {
    /// The field under `[surface]`.
    key: &'static str,
    /// What it is, plural, for messages.
    what: &'static str,
}

impl Hold {
    /// The hold of a footpad with obstacle height `obstacle` and spike depth `spike` (file
    /// units; at most one of them positive, checked before), if any.
    pub(crate) fn of(obstacle: f64, spike: f64) -> Option<Hold> {
        if obstacle > 0.0 {
            Some(Hold {
                key: "obstacle",
                what: "obstacles",
            })
        } else if spike > 0.0 {
            Some(Hold {
                key: "spike_depth",
                what: "spikes",
            })
        } else {
            None
        }
    }

    /// The field of footpad `i`'s hold.
    fn field(self, i: usize) -> String {
        format!("surface.{}[{i}]", self.key)
    }
}

/// Primary-strut bending stiffness EI, N·m² (force·length² in the file).
pub(crate) fn bending(
    c: &Check,
    b: Option<schema::Bending>,
    arrangement: Arrangement,
    u: &Units,
) -> Result<Option<f64>, ScenarioError> {
    let Some(b) = b else { return Ok(None) };
    if arrangement == Arrangement::Tripod {
        return Err(c.err(
            "primary_strut.bending",
            "the tripod's primary is a two-force member with no side load, so it does not bend (docs/errata.md, tripod gear); remove [primary_strut.bending]",
        ));
    }
    let scale = u.force() * u.length() * u.length();
    Ok(Some(c.positive_si(
        "primary_strut.bending.stiffness",
        b.stiffness,
        scale,
    )?))
}

/// The soil of a `kind = "soil"` surface, SI.
pub(crate) fn soil(
    c: &Check,
    sf: &schema::Surface,
    footpad: &model::Footpad,
    holds: &[Option<Hold>],
    u: &Units,
) -> Result<Option<model::Soil>, ScenarioError> {
    let soil = match (sf.kind, &sf.soil) {
        (schema::SurfaceKind::Rigid, None) => return Ok(None),
        (schema::SurfaceKind::Rigid, Some(_)) => {
            return Err(c.err(
                "surface.soil",
                "soil constants on a rigid surface: set surface.kind = \"soil\" or remove [surface.soil]",
            ))
        }
        (schema::SurfaceKind::Soil, None) => {
            return Err(c.err(
                "surface.soil",
                "expected the soil constants k1..k8 for surface.kind = \"soil\"",
            ))
        }
        (schema::SurfaceKind::Soil, Some(s)) => *s,
    };
    if footpad.height.is_none() {
        return Err(c.err(
            "footpad.height",
            "expected the footpad height (length) on a soil surface: it bounds the frontal area of eq. (102)",
        ));
    }
    if let Some((i, h)) = (holds.iter().enumerate()).find_map(|(i, h)| Some((i, (*h)?))) {
        return Err(c.conflict(
            &h.field(i),
            "surface.kind",
            &format!(
                "{} are not part of the soil model (the report omits them there); give {} = 0",
                h.what, h.key
            ),
        ));
    }
    if !sf.curbs.is_empty() {
        return Err(c.err(
            "surface.curbs",
            "curbs are not part of the soil model (the report omits them there); remove them or use a rigid surface",
        ));
    }
    let (f, l, t) = (u.force(), u.length(), u.time());
    let p = f / (l * l);
    let k = |name: &str, v: f64, scale: f64| {
        c.non_negative_si(&format!("surface.soil.{name}"), v, scale)
    };
    Ok(Some(model::Soil {
        k1: k("k1", soil.k1, p)?,
        k2: k("k2", soil.k2, p / l)?,
        k3: k("k3", soil.k3, p * t / l)?,
        k4: k("k4", soil.k4, p * t * t / (l * l))?,
        k5: k("k5", soil.k5, p)?,
        k6: k("k6", soil.k6, p / l)?,
        k7: k("k7", soil.k7, p / l)?,
        k8: k("k8", soil.k8, p * t * t / (l * l))?,
    }))
}

/// The curbs of a rigid surface, SI; at most two per footpad, only beside sliding footpads.
pub(crate) fn curbs(
    c: &Check,
    sf: &schema::Surface,
    footpad: &model::Footpad,
    holds: &[Option<Hold>],
    u: &Units,
) -> Result<Vec<model::Curb>, ScenarioError> {
    let n = holds.len();
    let mut per_leg = vec![0usize; n];
    let mut out = Vec::with_capacity(sf.curbs.len());
    for (i, curb) in sf.curbs.iter().enumerate() {
        let f = |name: &str| format!("surface.curbs[{i}].{name}");
        if curb.leg == 0 || curb.leg > n {
            return Err(c.err(
                &f("leg"),
                format!(
                    "expected a leg number from 1 to {n}, got {}",
                    short(curb.leg as f64)
                ),
            ));
        }
        let leg = curb.leg - 1;
        per_leg[leg] += 1;
        if per_leg[leg] > 2 {
            return Err(c.err(
                &f("leg"),
                format!(
                    "at most two curbs per footpad (fig. 19); leg {} has more",
                    curb.leg
                ),
            ));
        }
        if let Some(h) = holds[leg] {
            return Err(c.conflict(
                &h.field(leg),
                &format!("surface.curbs[{i}]"),
                &format!(
                    "leg {}'s footpad is held by {} and has a curb (surface.curbs[{i}]): curbs apply to sliding footpads; give {} = 0 there or remove the curb",
                    curb.leg, h.what, h.key
                ),
            ));
        }
        out.push(model::Curb {
            leg,
            distance: c.positive_si(&f("distance"), curb.distance, u.length())?,
            angle: c.finite_si(&f("angle"), curb.angle, u.angle())?,
            friction: c.non_negative_si(&f("friction"), curb.friction, 1.0)?,
        });
    }
    if !out.is_empty() && footpad.crush.is_none() {
        return Err(c.err(
            "footpad.crush",
            "expected the footpad crushing diagram (fig. 18) with curbs",
        ));
    }
    Ok(out)
}

/// The descent engine, SI.
pub(crate) fn thrust(
    c: &Check,
    t: Option<&schema::Thrust>,
    u: &Units,
) -> Result<Option<model::Thrust>, ScenarioError> {
    let Some(t) = t else { return Ok(None) };
    let (f, s) = (u.force(), u.time());
    let decay_rate = match t.decay_rate {
        Some(k) => Some(c.non_negative_si("thrust.decay_rate", k, 1.0 / s)?),
        None => None,
    };
    let mut polynomial = Vec::with_capacity(t.polynomial.len());
    for (i, m) in t.polynomial.iter().enumerate() {
        polynomial.push(c.finite_si(
            &format!("thrust.polynomial[{i}]"),
            *m,
            f / s.powi(i as i32),
        )?);
    }
    let amplification = match &t.amplification {
        None => None,
        Some(a) => {
            if a.clearance.len() != a.factor.len() || a.clearance.is_empty() {
                return Err(c.err(
                    "thrust.amplification",
                    format!(
                        "expected as many factors as clearances (at least one), got {} clearances and {} factors",
                        a.clearance.len(),
                        a.factor.len()
                    ),
                ));
            }
            let mut table = Vec::with_capacity(a.clearance.len());
            for (i, (z, k)) in a.clearance.iter().zip(&a.factor).enumerate() {
                let z = c.finite_si(
                    &format!("thrust.amplification.clearance[{i}]"),
                    *z,
                    u.length(),
                )?;
                let k = c.positive_si(&format!("thrust.amplification.factor[{i}]"), *k, 1.0)?;
                table.push((z, k));
            }
            Some(table)
        }
    };
    let nozzle_crushing = match t.nozzle_crushing {
        None => None,
        Some(n) => Some((
            c.positive_si(
                "thrust.nozzle_crushing.exit_radius",
                n.exit_radius,
                u.length(),
            )?,
            c.non_negative_si("thrust.nozzle_crushing.crush_load", n.crush_load, f)?,
        )),
    };
    Ok(Some(model::Thrust {
        thrust: c.non_negative_si("thrust.thrust", t.thrust, f)?,
        tailoff_start: c.finite_si("thrust.tailoff_start", t.tailoff_start, s)?,
        clock_at_touchdown: c.finite_si("thrust.clock_at_touchdown", t.clock_at_touchdown, s)?,
        decay_rate,
        polynomial,
        nozzle_exit: c.vec3("thrust.nozzle_exit", t.nozzle_exit, u.length())?,
        amplification,
        nozzle_crushing,
    }))
}

/// The reaction control system, SI.
pub(crate) fn rcs(
    c: &Check,
    r: Option<&schema::Rcs>,
    u: &Units,
) -> Result<Option<model::Rcs>, ScenarioError> {
    let Some(r) = r else { return Ok(None) };
    let each = |name: &str, v: [f64; 3], scale: f64, positive: bool| {
        let mut out = Vector3::zeros();
        for i in 0..3 {
            let field = format!("rcs.{name}[{i}]");
            out[i] = if positive {
                c.positive_si(&field, v[i], scale)?
            } else {
                c.non_negative_si(&field, v[i], scale)?
            };
        }
        Ok::<_, ScenarioError>(out)
    };
    let attitude_gain = match r.mode {
        RcsMode::AttitudeHold => each("attitude_gain", r.attitude_gain, 1.0, false)?,
        RcsMode::RateCommand if r.attitude_gain != [0.0; 3] => {
            return Err(c.err(
                "rcs.attitude_gain",
                "rate command has no attitude gains (k11 = k21 = k31 = 0): leave them out or use mode = \"attitude_hold\"",
            ))
        }
        RcsMode::RateCommand => Vector3::zeros(),
    };
    if r.mode == RcsMode::AttitudeHold && r.commanded_rates != [0.0; 3] {
        return Err(c.err(
            "rcs.commanded_rates",
            "attitude hold commands zero rates (eq. 78); use mode = \"rate_command\" to command rates",
        ));
    }
    let downward_translation = match r.downward_translation {
        None => None,
        Some(d) => Some(model::DownwardTranslation {
            delay: c.non_negative_si("rcs.downward_translation.delay", d.delay, u.time())?,
            force: c.non_negative_si("rcs.downward_translation.force", d.force, u.force())?,
        }),
    };
    Ok(Some(model::Rcs {
        mode: match r.mode {
            RcsMode::AttitudeHold => model::RcsMode::AttitudeHold,
            RcsMode::RateCommand => model::RcsMode::RateCommand,
        },
        attitude_gain,
        rate_gain: each("rate_gain", r.rate_gain, u.time(), false)?,
        deadband: each("deadband", r.deadband, u.angle(), true)?,
        torque: each("torque", r.torque, u.force() * u.length(), false)?,
        commanded_attitude: c.vec3("rcs.commanded_attitude", r.commanded_attitude, u.angle())?,
        commanded_rates: c.vec3("rcs.commanded_rates", r.commanded_rates, u.angular_rate())?,
        downward_translation,
    }))
}

/// Propellant sloshing, SI; the slosh mass M_s = F_s/ω² (eq. 112) must be less than the
/// vehicle's mass `mass` (kg).
pub(crate) fn slosh(
    c: &Check,
    s: Option<&schema::Slosh>,
    mass: f64,
    u: &Units,
) -> Result<Option<model::Slosh>, ScenarioError> {
    let Some(s) = s else { return Ok(None) };
    let l = u.length();
    let fs = c.positive_si("slosh.force_coefficient", s.force_coefficient, u.mass() / l)?;
    let w2 = c.positive_si("slosh.frequency_parameter", s.frequency_parameter, 1.0 / l)?;
    if fs / w2 >= mass {
        return Err(c.err(
            "slosh.force_coefficient",
            format!(
                "the slosh mass F_s/ω² = {} kg (eq. 112) must be less than the vehicle mass {} kg",
                short(fs / w2),
                short(mass)
            ),
        ));
    }
    Ok(Some(model::Slosh {
        force_coefficient: fs,
        frequency_parameter: w2,
        free_surface_depth: c.finite_si("slosh.free_surface_depth", s.free_surface_depth, l)?,
        mass_depth: c.non_negative_si("slosh.mass_depth", s.mass_depth, l)?,
        initial_amplitude: [
            c.finite_si("slosh.initial_amplitude[0]", s.initial_amplitude[0], l)?,
            c.finite_si("slosh.initial_amplitude[1]", s.initial_amplitude[1], l)?,
        ],
    }))
}

//! The range of physical plausibility of every number a scenario holds: one table, [`RANGES`],
//! checked on load in SI (after the file's units are applied, so a range does not depend on
//! them) and documented in docs/scenario-format.md ("Ranges").
//!
//! A value outside its field's range is refused, naming the file, the field, the value and the
//! range. Some fields also have a narrower *usual* range: a value outside it but inside the
//! range is legal and may be meant, so it is accepted with a [`crate::Warning`]
//! ([`crate::Scenario::warnings`]).
//!
//! The ranges are generous but finite: they span landers from a 1/6-scale drop-test model (tens
//! of kg) to a heavy full-scale vehicle (tens of tonnes and more), and exist to refuse numbers
//! no lander has (an attitude of 1e300 degrees, a stiffness of 1e-300 N/m), which would
//! otherwise run, overflow or book absurd energies.

use crate::units::short;

/// One end of a range, in the range's display unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bound {
    /// The end itself is allowed: `[` or `]`.
    Closed(f64),
    /// The end itself is not allowed: `(` or `)`.
    Open(f64),
}

impl Bound {
    /// The end's value, display unit.
    pub fn value(self) -> f64 {
        match self {
            Bound::Closed(x) | Bound::Open(x) => x,
        }
    }
}

/// The plausible range of one field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Field path without indices (`gear.legs.b2` covers `gear.legs[2].b2[0]`). A leading `*.`
    /// stands for any prefix: `*.onset_rate` covers every load-stroke diagram
    /// (`primary_strut.compression`, `secondary_strut.tension`, `secondary_strut.compression`,
    /// `footpad.crush`).
    pub field: &'static str,
    /// Display unit of the bounds (SI, or degrees for angles); empty if dimensionless.
    pub unit: &'static str,
    /// SI value of one display unit (π/180 for degrees, 1 otherwise).
    pub si: f64,
    /// Lower end, display unit.
    pub lower: Bound,
    /// Upper end, display unit.
    pub upper: Bound,
    /// The usual range `[lo, hi]`, display unit: outside it (but inside the range) a value is
    /// accepted with a warning. `None`: no warning.
    pub usual: Option<(f64, f64)>,
    /// Why these ends, in one line.
    pub reason: &'static str,
}

const DEG: f64 = std::f64::consts::PI / 180.0;

/// Least angle between consecutive legs' footpads seen from above, degrees: two legs closer
/// than this are one leg listed twice (`[0, 1e-300, 180, 270]`), not a gear.
pub const MIN_LEG_SEPARATION_DEG: f64 = 1.0;

/// Most legs a gear may have: the stability walls, the laws and the output columns are per
/// leg, and no lander has more.
pub const MAX_LEGS: usize = 32;

const fn row(
    field: &'static str,
    unit: &'static str,
    lower: Bound,
    upper: Bound,
    reason: &'static str,
) -> Range {
    Range {
        field,
        unit,
        si: 1.0,
        lower,
        upper,
        usual: None,
        reason,
    }
}

const fn deg(field: &'static str, lower: Bound, upper: Bound, reason: &'static str) -> Range {
    Range {
        field,
        unit: "deg",
        si: DEG,
        lower,
        upper,
        usual: None,
        reason,
    }
}

const fn deg_per_s(field: &'static str, lower: Bound, upper: Bound, reason: &'static str) -> Range {
    Range {
        unit: "deg/s",
        ..deg(field, lower, upper, reason)
    }
}

const fn usual(r: Range, lo: f64, hi: f64) -> Range {
    Range {
        usual: Some((lo, hi)),
        ..r
    }
}

use Bound::{Closed as C, Open as O};

/// Every numeric field's range, in SI (angles in degrees). Reasons say what the ends stand for.
pub const RANGES: &[Range] = &[
    // The vehicle.
    usual(row("vehicle.mass", "kg", C(1e-3), C(1e7), "from a gram-scale model to a 10 000-tonne vehicle (the 1/6-scale LM is 29 kg, the LM about 7 t)"), 1.0, 1e6),
    usual(row("vehicle.gravity", "m/s²", C(0.0), C(100.0), "0 (free space, allowed) to ten Earth gravities; Jupiter's is 24.8 m/s²"), 0.0, 30.0),
    row("vehicle.inertia.xx", "kg·m²", C(1e-6), C(1e10), "a 1-gram body of 3 cm radius of gyration to a 10 000-tonne one of 30 m"),
    row("vehicle.inertia.yy", "kg·m²", C(1e-6), C(1e10), "a 1-gram body of 3 cm radius of gyration to a 10 000-tonne one of 30 m"),
    row("vehicle.inertia.zz", "kg·m²", C(1e-6), C(1e10), "a 1-gram body of 3 cm radius of gyration to a 10 000-tonne one of 30 m"),
    row("vehicle.inertia.xy", "kg·m²", C(-1e10), C(1e10), "products of inertia of either sign, bounded as the moments"),
    row("vehicle.inertia.xz", "kg·m²", C(-1e10), C(1e10), "products of inertia of either sign, bounded as the moments"),
    row("vehicle.inertia.yz", "kg·m²", C(-1e10), C(1e10), "products of inertia of either sign, bounded as the moments"),
    // The gear's geometry.
    row("gear.legs.b2", "m", C(-1e3), C(1e3), "body-axis coordinates within 1 km of the centre of mass"),
    row("gear.legs.b3", "m", C(-1e3), C(1e3), "body-axis coordinates within 1 km of the centre of mass"),
    row("gear.legs.b4", "m", C(-1e3), C(1e3), "body-axis coordinates within 1 km of the centre of mass"),
    row("gear.legs.bp", "m", C(-1e3), C(1e3), "body-axis coordinates within 1 km of the centre of mass"),
    row("gear.legs.l21", "m", C(1e-4), C(1e3), "a length from 0.1 mm to 1 km"),
    row("gear.parametric.r1", "m", C(1e-4), C(1e3), "a length from 0.1 mm to 1 km"),
    row("gear.parametric.r2", "m", C(1e-4), C(1e3), "a length from 0.1 mm to 1 km"),
    row("gear.parametric.r3", "m", C(1e-4), C(1e3), "a length from 0.1 mm to 1 km"),
    row("gear.parametric.z1", "m", C(1e-4), C(1e3), "a height above the footpad plane from 0.1 mm to 1 km"),
    row("gear.parametric.z2", "m", C(1e-4), C(1e3), "a height above the footpad plane from 0.1 mm to 1 km"),
    row("gear.parametric.z3", "m", C(1e-4), C(1e3), "a height above the footpad plane from 0.1 mm to 1 km"),
    row("gear.parametric.zc", "m", C(1e-4), C(1e3), "a height above the footpad plane from 0.1 mm to 1 km"),
    deg("gear.parametric.beta", O(-90.0), O(90.0), "tan β finite for strut_angle, the secondary trunnions ahead of the leg for trunnion_azimuth"),
    deg("gear.parametric.leg_azimuths", C(-360.0), C(360.0), "one turn either way; consecutive legs also at least 1° apart"),
    // Load-stroke diagrams, trunnions and dampers (every strut and the footpad crush).
    row("*.onset_rate", "N/m", C(1e2), C(1e12), "a 1/6-scale honeycomb strut is about 1e5 N/m, a full-scale one about 1e7 N/m"),
    row("*.backoff_rate", "N/m", C(1e2), C(1e12), "an elastic rebound rate, as the onset rate; 1e-300 N/m would book 1e304 J of elastic energy"),
    row("*.stroke_out_rate", "N/m", C(1e2), C(1e12), "a bottoming stop, stiffer than the onset rate, up to 1e12 N/m"),
    row("*.stages.crush_load", "N", C(1.0), C(1e8), "a 1/6-scale stage crushes at about 600 N, a full-scale one at tens of kN"),
    row("*.stages.stroke_end", "m", C(1e-4), C(10.0), "a stroke from 0.1 mm to 10 m (the LM's primary strokes about 0.8 m)"),
    row("*.stop_restitution", "", C(0.0), C(1.0), "a coefficient of restitution"),
    row("*.trunnion", "N/m", C(1e2), C(1e12), "a trunnion spring rate, bounded as the strut rates"),
    row("*.viscous.coefficient", "N/(m/s)^γ", C(0.0), C(1e9), "at most 1e9 N at 1 m/s"),
    row("*.viscous.exponent", "", C(0.1), C(5.0), "1 for a linear damper, 2 for an orifice"),
    row("primary_strut.bearing.friction", "", C(0.0), C(2.0), "a friction coefficient; the report's is 0.1"),
    row("primary_strut.bearing.inner_cylinder_length", "m", C(1e-4), C(1e3), "a length from 0.1 mm to 1 km"),
    row("primary_strut.bearing.initial_overlap", "m", C(1e-4), C(1e3), "a length from 0.1 mm to 1 km"),
    row("primary_strut.bending.stiffness", "N·m²", C(1.0), C(1e12), "EI of a strut from a thin tube to a massive beam"),
    // The footpad.
    row("footpad.mass", "kg", C(1e-4), C(1e5), "the 1/6-scale model's effective footpad is 0.19 kg, a full-scale one tens of kg"),
    row("footpad.radius", "m", C(1e-4), C(100.0), "a footpad from 0.1 mm to 100 m"),
    row("footpad.height", "m", C(1e-4), C(100.0), "a footpad from 0.1 mm to 100 m"),
    // The surface.
    usual(deg("surface.slope", O(-90.0), O(90.0), "a slope strictly between a wall and a wall; the report's are up to 15°"), -45.0, 45.0),
    row("surface.hole", "m", C(-100.0), C(100.0), "a depression (> 0) or a bump (< 0) under a footpad, within 100 m"),
    row("surface.obstacle", "m", C(-1e3), C(1e3), "a lock height (> 0) or sliding (≤ 0), within 1 km"),
    row("surface.spike_depth", "m", C(0.0), C(1.0), "an engagement depth of spikes (> 0) or none (0), within 1 m"),
    usual(row("surface.friction", "", C(0.0), C(10.0), "a friction coefficient; above about 2 a footpad is in effect locked (surface.obstacle)"), 0.0, 2.0),
    row("surface.soil.k1", "Pa", C(0.0), C(1e10), "bearing strength: loose regolith about 1e4 Pa, rock about 1e8 Pa"),
    row("surface.soil.k2", "Pa/m", C(0.0), C(1e12), "strength gradient, up to rock over a millimetre"),
    row("surface.soil.k3", "Pa·s/m", C(0.0), C(1e12), "bearing strength per penetration rate, up to rock over a millimetre per m/s"),
    row("surface.soil.k4", "Pa·s²/m²", C(0.0), C(1e12), "bearing strength per penetration rate squared, bounded as K2"),
    row("surface.soil.k5", "Pa", C(0.0), C(1e10), "lateral strength: loose regolith about 1e4 Pa, rock about 1e8 Pa"),
    row("surface.soil.k6", "Pa/m", C(0.0), C(1e12), "lateral strength gradient, up to rock over a millimetre"),
    row("surface.soil.k7", "Pa/m", C(0.0), C(1e12), "lateral strength gradient, up to rock over a millimetre"),
    row("surface.soil.k8", "Pa·s²/m²", C(0.0), C(1e12), "lateral strength per speed squared, bounded as K4"),
    row("surface.curbs.distance", "m", C(1e-4), C(100.0), "a curb from 0.1 mm to 100 m from its footpad"),
    deg("surface.curbs.angle", C(-360.0), C(360.0), "one turn either way"),
    row("surface.curbs.friction", "", C(0.0), C(10.0), "a friction coefficient"),
    // The touchdown.
    usual(deg("touchdown.attitude", C(-360.0), C(360.0), "one turn either way; beyond ±180° an angle repeats one within"), -180.0, 180.0),
    usual(row("touchdown.vertical_velocity", "m/s", C(-1e3), C(1e3), "the report's landings are below 5 m/s; beyond 30 m/s it is a crash, not a landing"), -30.0, 30.0),
    usual(row("touchdown.horizontal_velocity", "m/s", C(-1e3), C(1e3), "the report's landings are below 8 m/s horizontally; beyond 30 m/s it is a crash, not a landing"), -30.0, 30.0),
    usual(deg_per_s("touchdown.body_rates", C(-3600.0), C(3600.0), "ten turns a second; a lander at touchdown turns at a few degrees a second"), -360.0, 360.0),
    usual(row("touchdown.clearance", "m", C(0.0), C(1e3), "a free flight before contact; beyond 10 m it is a long fall"), 0.0, 10.0),
    // The integrator.
    row("integrator.dist", "m", C(1e-8), C(1.0), "the report's DIST is 2.5 mm for the LM"),
    usual(row("integrator.dt_min", "s", C(1e-12), C(1.0), "a picosecond is near the rounding of t; `touchdown compare` locates events to 1e-10 s"), 1e-9, 1.0),
    row("integrator.dt_max", "s", C(1e-9), C(1.0), "a nanosecond step to a second"),
    row("integrator.t_end", "s", C(1e-6), C(1e4), "a touchdown lasts seconds; 1e4 s bounds a run with free flight"),
    usual(row("integrator.energy_tolerance", "", C(1e-9), C(10.0), "a fraction of the energy put in; healthy runs close to 1e-4, and above 1 the guard no longer guards"), 1e-9, 1.0),
    row("integrator.max_steps", "", C(1e2), C(1e9), "a landing takes thousands of steps; a billion is hours of a multibody engine"),
    row("integrator.rtol", "", C(1e-14), C(0.1), "a relative tolerance above the rounding of f64 (2.2e-16)"),
    row("integrator.stride", "", C(1.0), C(1e3), "scheme strides: a multiple of dt_max from 1 (the report's rule) to a thousand"),
    row("integrator.mode_step", "", O(0.0), O(2.0), "scheme strides: ω·Δt on the stiffest engaged mode, below the report scheme's stability limit of 2"),
    usual(row("integrator.atol", "", C(1e-18), C(1.0), "an absolute tolerance on m, m/s, rad, rad/s; `touchdown compare` goes to 1e-16"), 1e-14, 1.0),
    // Stability criteria.
    row("similarity.length", "", C(1e-3), C(1e3), "a similar vehicle from a thousandth to a thousand times as large"),
    row("similarity.mass", "", C(1e-9), C(1e9), "a similar vehicle's mass ratio, a length ratio cubed at most"),
    row("similarity.time", "", C(1e-3), C(1e3), "a similar vehicle's time ratio, the square root of length over gravity ratios"),
    row("stability.kinetic_energy_fraction", "", C(1e-6), C(1.0), "a fraction of the touchdown kinetic energy; below 1e-6 no landing would ever end stable"),
    row("stability.min_separation_velocity", "m/s", C(0.0), C(1e3), "a speed up to 1 km/s"),
    row("stability.settled_tolerance", "m", O(0.0), C(1.0), "a stroke tolerance up to 1 m"),
    // The comparison's tolerances.
    row("comparison.primary_stroke", "", O(0.0), C(10.0), "a fraction of the larger maximum stroke: above ten times, no difference fails"),
    row("comparison.secondary_stroke", "", O(0.0), C(10.0), "a fraction of the larger maximum stroke: above ten times, no difference fails"),
    row("comparison.peak_pitch_rate", "", O(0.0), C(10.0), "a fraction of the larger peak: above ten times, no difference fails"),
    row("comparison.peak_pitch_rate_time", "", O(0.0), C(10.0), "a fraction of the vehicle's time scale: above ten times, no difference fails"),
    row("comparison.pitch_rate_history_rms_difference", "", O(0.0), C(10.0), "a fraction of the peak pitch rate: above ten times, no difference fails"),
    row("comparison.pitch_rate_history_largest_difference", "", O(0.0), C(10.0), "a fraction of the peak pitch rate: above ten times, no difference fails"),
    row("comparison.peak_vertical_acceleration", "", O(0.0), C(10.0), "a fraction of the larger peak: above ten times, no difference fails"),
    row("comparison.min_stability_distance", "", O(0.0), C(10.0), "a fraction of the footprint radius: above ten times, no difference fails"),
    row("comparison.overturn_velocity", "", O(0.0), C(10.0), "a fraction of the vehicle's velocity scale: above ten times, no difference fails"),
    row("comparison.past_capacity", "", O(0.0), C(10.0), "a fraction of the strut's capacity: above ten times, no difference fails"),
    row("comparison.energy", "", O(0.0), C(10.0), "a fraction of the touchdown kinetic energy: above ten times, no difference fails"),
    // The descent engine.
    row("thrust.thrust", "N", C(0.0), C(1e8), "the LM descent engine gives 45 kN; 1e8 N exceeds any rocket stage"),
    row("thrust.tailoff_start", "s", C(-1e4), C(1e4), "a time on the thrust-curve clock within the run bound"),
    row("thrust.clock_at_touchdown", "s", C(-1e4), C(1e4), "a time on the thrust-curve clock within the run bound"),
    row("thrust.decay_rate", "1/s", C(0.0), C(1e6), "a tailoff no faster than a microsecond"),
    row("thrust.polynomial", "N/s^i", C(-1e8), C(1e8), "each term within the thrust range over one second"),
    row("thrust.nozzle_exit", "m", C(-1e3), C(1e3), "body-axis coordinates within 1 km of the centre of mass"),
    row("thrust.amplification.clearance", "m", C(-1e3), C(1e3), "a nozzle height within 1 km"),
    row("thrust.amplification.factor", "", C(1e-3), C(100.0), "a factor on the thrust; the report's fig. 16 stays near 1"),
    row("thrust.nozzle_crushing.exit_radius", "m", C(1e-4), C(100.0), "a nozzle from 0.1 mm to 100 m"),
    row("thrust.nozzle_crushing.crush_load", "N", C(0.0), C(1e8), "a force up to 1e8 N, beyond any rocket stage"),
    // Reaction control.
    row("rcs.attitude_gain", "", C(0.0), C(1e3), "a gain on the attitude error"),
    row("rcs.rate_gain", "s", C(0.0), C(1e3), "a gain on the rate error"),
    deg("rcs.deadband", C(1e-6), C(180.0), "a deadband from a micro-degree (below, the jets chatter) to half a turn"),
    row("rcs.torque", "N·m", C(0.0), C(1e8), "the LM's jets give about 1e3 N·m"),
    deg("rcs.commanded_attitude", C(-360.0), C(360.0), "one turn either way"),
    deg_per_s("rcs.commanded_rates", C(-3600.0), C(3600.0), "ten turns a second"),
    row("rcs.downward_translation.delay", "s", C(0.0), C(1e4), "within the 1e4 s bound of a run"),
    row("rcs.downward_translation.force", "N", C(0.0), C(1e8), "a force up to 1e8 N, beyond any rocket stage"),
    // Propellant slosh.
    row("slosh.force_coefficient", "kg/m", C(1e-6), C(1e9), "F_s = M_s·ω²: a slosh mass up to the vehicle's, ω² up to 1e4 1/m"),
    row("slosh.frequency_parameter", "1/m", C(1e-4), C(1e4), "ω² per unit acceleration: a tank from 0.1 mm to 10 km across"),
    row("slosh.free_surface_depth", "m", C(-1e3), C(1e3), "within 1 km of the centre of mass"),
    row("slosh.mass_depth", "m", C(0.0), C(1e3), "within 1 km of the free surface"),
    row("slosh.initial_amplitude", "m", C(-100.0), C(100.0), "an amplitude within 100 m"),
    // The multibody engines.
    usual(row("engines.rapier.timestep", "s", O(0.0), C(0.1), "a positive step; the engine refuses one that cannot reach t_end within its run budget"), 1e-9, 0.1),
    row("engines.rapier.contact_frequency", "Hz", C(1.0), C(1e7), "a contact from 1 Hz to 10 MHz"),
    row("engines.rapier.contact_damping_ratio", "", C(0.0), C(100.0), "a damping ratio"),
    row("engines.rapier.stride", "", C(1.0), C(64.0), "a whole number of time steps"),
    usual(row("engines.mujoco.timestep", "s", O(0.0), C(0.1), "a positive step; the engine refuses one that cannot reach t_end within its run budget"), 1e-9, 0.1),
    usual(row("engines.mujoco.contact_timeconst", "s", O(0.0), C(1.0), "a contact time constant, at least twice the step"), 2e-9, 1.0),
    row("engines.mujoco.contact_width", "m", O(0.0), C(1.0), "a penetration up to a metre"),
    row("engines.mujoco.contact_damping_ratio", "", C(0.0), C(100.0), "a damping ratio"),
    row("engines.links.outer_cylinder_mass_ratio", "", C(1e-4), C(100.0), "a link mass as a fraction of the footpad's"),
    row("engines.links.link_radius_ratio", "", C(1e-4), C(1.0), "a link radius as a fraction of the strut's length"),
];

/// A field path without its indices: `gear.legs[2].b2[0]` → `gear.legs.b2`.
pub fn normalize(field: &str) -> String {
    let mut out = String::with_capacity(field.len());
    let mut depth = 0usize;
    for ch in field.chars() {
        match ch {
            '[' => depth += 1,
            ']' => depth = depth.saturating_sub(1),
            _ if depth == 0 => out.push(ch),
            _ => {}
        }
    }
    out
}

/// The range of `field` (a path such as `primary_strut.compression.stages[1].crush_load`), if
/// it has one.
pub fn lookup(field: &str) -> Option<&'static Range> {
    let path = normalize(field);
    RANGES.iter().find(|r| r.field == path).or_else(|| {
        RANGES.iter().find(|r| {
            r.field
                .strip_prefix('*')
                .is_some_and(|tail| path.ends_with(tail))
        })
    })
}

impl Range {
    /// Whether `si` (SI) is inside the range; NaN never is.
    pub fn contains(&self, si: f64) -> bool {
        let x = si / self.si;
        let above = match self.lower {
            Bound::Closed(lo) => x >= lo,
            Bound::Open(lo) => x > lo,
        };
        let below = match self.upper {
            Bound::Closed(hi) => x <= hi,
            Bound::Open(hi) => x < hi,
        };
        above && below
    }

    /// Whether `si` (SI) is inside the usual range (always, if the field has none).
    pub fn is_usual(&self, si: f64) -> bool {
        let x = si / self.si;
        self.usual.is_none_or(|(lo, hi)| x >= lo && x <= hi)
    }

    /// The range as written in messages and docs: `[0.001, 1e+07] kg`, `(-90, 90) deg`.
    pub fn interval(&self) -> String {
        let (open, lo) = match self.lower {
            Bound::Closed(x) => ('[', x),
            Bound::Open(x) => ('(', x),
        };
        let (close, hi) = match self.upper {
            Bound::Closed(x) => (']', x),
            Bound::Open(x) => (')', x),
        };
        let text = format!("{open}{}, {}{close}", short(lo), short(hi));
        with_unit(text, self.unit)
    }

    /// The usual range as written in messages and docs, if the field has one.
    pub fn usual_interval(&self) -> Option<String> {
        self.usual
            .map(|(lo, hi)| with_unit(format!("[{}, {}]", short(lo), short(hi)), self.unit))
    }
}

fn with_unit(text: String, unit: &str) -> String {
    if unit.is_empty() {
        text
    } else {
        format!("{text} {unit}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_range_is_finite_ordered_and_named_once() {
        let mut seen = std::collections::BTreeSet::new();
        for r in RANGES {
            assert!(seen.insert(r.field), "{} listed twice", r.field);
            let (lo, hi) = (r.lower.value(), r.upper.value());
            assert!(lo.is_finite() && hi.is_finite() && lo < hi, "{}", r.field);
            if let Some((ulo, uhi)) = r.usual {
                assert!(lo <= ulo && ulo < uhi && uhi <= hi, "{}", r.field);
            }
            assert!(!r.reason.is_empty() && r.si > 0.0, "{}", r.field);
        }
    }

    #[test]
    fn indices_and_wildcards_find_their_row() {
        assert_eq!(normalize("gear.legs[2].b2[0]"), "gear.legs.b2");
        assert_eq!(
            lookup("secondary_strut.tension.stages[1].crush_load").map(|r| r.field),
            Some("*.stages.crush_load")
        );
        assert_eq!(
            lookup("footpad.crush.onset_rate").map(|r| r.field),
            Some("*.onset_rate")
        );
        assert_eq!(
            lookup("primary_strut.trunnion").map(|r| r.field),
            Some("*.trunnion")
        );
        assert_eq!(
            lookup("surface.friction[3]").map(|r| r.field),
            Some("surface.friction")
        );
        assert!(lookup("nothing.here").is_none());
    }

    #[test]
    fn open_ends_and_nan_are_outside() {
        let slope = lookup("surface.slope").unwrap();
        assert!(slope.contains(89.0 * DEG) && !slope.contains(90.0 * DEG));
        assert!(!slope.contains(f64::NAN));
        assert_eq!(slope.interval(), "(-90, 90) deg");
        let mass = lookup("vehicle.mass").unwrap();
        assert_eq!(mass.interval(), "[0.001, 1e+07] kg");
        assert!(mass.contains(1e-3) && mass.contains(1e7) && !mass.contains(1.0001e7));
        assert!(!mass.is_usual(0.5) && mass.is_usual(29.0));
    }
}

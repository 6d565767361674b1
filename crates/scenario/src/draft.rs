//! A first vehicle and landing drafted from a handful of numbers (`touchdown new`): the mass and
//! inertia, the footprint, the leg count and arrangement, the primary strut's crush load and
//! stroke, the touchdown speed, in one coherent unit system. Every other value is derived by a
//! rule written beside it in the file (tag `E`, with its reasoning): the proportions and
//! ratios of the bundled robotic lander (`scenarios/vehicles/robotic-lander-4leg.toml`),
//! scaled to the numbers given. The drafted files load, and a first landing runs from them;
//! they are a start for the team's own values, not a design.
//!
//! Every rule is a ratio of the numbers given, so a draft in feet, slugs and pounds is the
//! same vehicle as its draft in metres, kilograms and newtons (tested).

use crate::units::short;

/// The coherent unit systems a draft is written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnitSystem {
    /// m, kg, N, s (angles in degrees).
    Si,
    /// ft, slug, lbf, s (angles in degrees).
    FootSlugPound,
}

impl UnitSystem {
    /// The `[units]` table's (length, mass, force) names.
    fn names(self) -> (&'static str, &'static str, &'static str) {
        match self {
            UnitSystem::Si => ("m", "kg", "N"),
            UnitSystem::FootSlugPound => ("ft", "slug", "lbf"),
        }
    }
}

/// The numbers a draft is made from, in `units` (angles in degrees, times in seconds).
#[derive(Debug, Clone, PartialEq)]
pub struct Draft {
    /// The vehicle's name.
    pub name: String,
    /// The unit system of every number here and of the files written.
    pub units: UnitSystem,
    /// The gear arrangement.
    pub arrangement: crate::schema::Arrangement,
    /// Number of legs (3 to [`crate::ranges::MAX_LEGS`]).
    pub legs: usize,
    /// Vehicle mass at touchdown, without the footpads; mass.
    pub mass: f64,
    /// Local gravity; length/time².
    pub gravity: f64,
    /// Principal moments of inertia about the centre of mass, [xx, yy, zz]; mass·length².
    pub inertia: [f64; 3],
    /// Radius of the circle through the footpads, seen from above; length.
    pub footprint_radius: f64,
    /// Height of the centre of mass above the footpads, gear undeformed; length.
    pub centre_of_mass_height: f64,
    /// The primary strut's first crush load; force.
    pub crush_load: f64,
    /// The primary strut's stroke capacity; length.
    pub stroke: f64,
    /// Touchdown vertical velocity, negative down; length/time.
    pub vertical_velocity: f64,
    /// Touchdown horizontal velocity along +Y (downhill on a slope; toward leg 2 of four),
    /// the plane the pitch rate is measured in; length/time.
    pub horizontal_velocity: f64,
    /// Surface slope, deg (about X: +Y downhill).
    pub slope: f64,
}

/// A number of a draft that cannot make a vehicle: which one (its name in [`Draft`]) and why.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{field}: {message}")]
pub struct DraftError {
    /// The number, as [`Draft`] names it (`crush_load`).
    pub field: &'static str,
    /// What a valid value is.
    pub message: String,
}

/// The proportions of the bundled robotic lander's leg (vehicles/robotic-lander-4leg.toml):
/// radii as fractions of the footprint radius, heights above the footpads as fractions of the
/// centre of mass's, β the secondary trunnions' azimuth from the leg plane.
const R1: f64 = 0.64; // primary trunnion B2: 0.80 m of 1.25 m
const R2: f64 = 0.60; // secondary trunnions B3, B4: 0.75 m of 1.25 m
const Z1: f64 = 7.0 / 18.0; // point 1: 0.35 m of 0.90 m
const Z2: f64 = 11.0 / 18.0; // secondary trunnions: 0.55 m of 0.90 m
const Z3: f64 = 10.0 / 9.0; // primary trunnion: 1.00 m of 0.90 m
const BETA_DEG: f64 = 30.0;

/// `x` rounded to four significant digits, as a TOML float (a `.` or an exponent always): what
/// the file says is exactly what runs.
fn num(x: f64) -> String {
    if x == 0.0 {
        return "0.0".into();
    }
    let e = x.abs().log10().floor() as i32;
    let scale = 10f64.powi(3 - e);
    let r = (x * scale).round() / scale;
    if (1e-3..1e5).contains(&r.abs()) {
        let s = format!("{r}");
        if s.contains('.') {
            s
        } else {
            format!("{s}.0")
        }
    } else {
        format!("{r:e}")
    }
}

impl Draft {
    /// Checks the numbers: each positive where it must be, a leg count the format takes, and
    /// a stroke the strut's length can hold.
    fn check(&self) -> Result<(), DraftError> {
        let positive = |field: &'static str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(DraftError {
                    field,
                    message: format!("expected a positive number, got {}", short(v)),
                })
            }
        };
        positive("mass", self.mass)?;
        positive("gravity", self.gravity)?;
        for m in self.inertia {
            positive("inertia", m)?;
        }
        positive("footprint_radius", self.footprint_radius)?;
        positive("centre_of_mass_height", self.centre_of_mass_height)?;
        positive("crush_load", self.crush_load)?;
        positive("stroke", self.stroke)?;
        if !(3..=crate::ranges::MAX_LEGS).contains(&self.legs) {
            return Err(DraftError {
                field: "legs",
                message: format!(
                    "expected 3 to {} legs, got {}",
                    crate::ranges::MAX_LEGS,
                    self.legs
                ),
            });
        }
        for (field, v) in [
            ("vertical_velocity", self.vertical_velocity),
            ("horizontal_velocity", self.horizontal_velocity),
            ("slope", self.slope),
        ] {
            if !v.is_finite() {
                return Err(DraftError {
                    field,
                    message: format!("expected a finite number, got {}", short(v)),
                });
            }
        }
        if self.vertical_velocity >= 0.0 {
            return Err(DraftError {
                field: "vertical_velocity",
                message: format!(
                    "expected a descent, negative (down), got {}",
                    short(self.vertical_velocity)
                ),
            });
        }
        let [a, b, c] = self.inertia;
        let largest = a.max(b).max(c);
        if largest > (a + b + c - largest) * (1.0 + 1e-9) {
            return Err(DraftError {
                field: "inertia",
                message: format!(
                    "no rigid body has principal moments {}, {}, {}: the largest exceeds the sum of the other two",
                    short(a),
                    short(b),
                    short(c)
                ),
            });
        }
        let longest = self.bearing().2;
        if self.stroke > longest {
            return Err(DraftError {
                field: "stroke",
                message: format!(
                    "a primary strut {} long (from the footprint radius and the centre-of-mass height) holds a stroke of at most {} beside its bearings, got {}",
                    short(self.primary_length()),
                    short(longest),
                    short(self.stroke)
                ),
            });
        }
        Ok(())
    }

    /// The undeformed primary's length |BP − B2|, length.
    fn primary_length(&self) -> f64 {
        let (r, h) = (self.footprint_radius, self.centre_of_mass_height);
        ((1.0 - R1) * r).hypot(Z3 * h)
    }

    /// The bearing: (D2 the initial overlap, D1 the inner cylinder, the longest stroke they
    /// hold), length. The robotic lander's D2 = 0.246·L2P and D1 = 0.597·L2P, D1 lengthened
    /// to D2 + 1.2·stroke where the stroke needs it, at most 0.9·L2P.
    fn bearing(&self) -> (f64, f64, f64) {
        let l = self.primary_length();
        let d2 = 0.27 / 1.0966 * l;
        let d1 = (0.655 / 1.0966 * l).max(d2 + 1.2 * self.stroke);
        (d2, d1.min(0.9 * l), (0.9 * l - d2) / 1.2)
    }

    /// The vehicle file, and the landing file that extends it as `vehicle_file`.
    pub fn files(&self, vehicle_file: &str) -> Result<(String, String), DraftError> {
        self.check()?;
        Ok((self.vehicle(), self.landing(vehicle_file)))
    }

    fn vehicle(&self) -> String {
        let (lu, mu, fu) = self.units.names();
        let (r, h, n) = (self.footprint_radius, self.centre_of_mass_height, self.legs);
        let tripod = self.arrangement == crate::schema::Arrangement::Tripod;
        let f1 = self.crush_load;
        let s = self.stroke;
        // Primary: two stages as the robotic lander's, the second 1.6 × the first over the
        // last third; onset after 2.5 % of stage 1; rebound 45 × onset; bottoming 100 × onset.
        let onset = f1 / (0.025 * s * 2.0 / 3.0);
        // Secondaries: 5/11 of the primary's load to 0.4 × its stroke, then twice that to 0.6 ×.
        let fs = f1 * 5.0 / 11.0;
        let onset_s = fs / (0.035 * 0.4 * s);
        let (d2, d1, _) = self.bearing();
        let l2p = self.primary_length();
        let pad_mass = self.mass * 3.0 / 700.0;
        // The stiffest mode: a footpad on a bottomed primary's stop as it unloads, along
        // K_so/e² with the default restitution e = 0.5 (docs/errata.md, "End stops");
        // ω·dt_max = 0.16, so that a landing past the capacity lands.
        let dt_max = 0.16 * (pad_mass * 0.25 / (100.0 * onset)).sqrt();
        let azimuths: Vec<String> = (0..n).map(|i| num(360.0 * i as f64 / n as f64)).collect();
        let [ixx, iyy, izz] = self.inertia;
        let z1 = if tripod {
            "# z1 left out: the tripod's secondaries meet the primary at the footpad\n".to_string()
        } else {
            format!(
                "z1 = {}                  # E: point 1, 7/18 of the centre-of-mass height\n",
                num(Z1 * h)
            )
        };
        format!(
            r#"# {name}: a first vehicle drafted by `touchdown new` from a handful of numbers (tag G:
# given), every other value derived by the rule written beside it (tag E: an estimate, from the
# proportions and ratios of the bundled robotic lander, scenarios/vehicles/robotic-lander-4leg.toml,
# scaled to the numbers given). Replace each E with the team's own value as it becomes known;
# `touchdown check` reviews the file before it lands (docs/authoring.md).
schema_version = 1
name = "{name}"
description = "Drafted by touchdown new: {n} legs, {arrangement} gear; every value not given is an estimate (E)."

[units]
length = "{lu}"
mass = "{mu}"
force = "{fu}"
angle = "deg"
time = "s"

[vehicle]
mass = {mass}              # G: at touchdown, without the footpads
gravity = {gravity}        # G
inertia = {{ xx = {ixx}, yy = {iyy}, zz = {izz}, xy = 0.0, xz = 0.0, yz = 0.0 }}  # G: principal moments about the centre of mass

[gear]
arrangement = "{arrangement}"

# The robotic lander's leg scaled to the footprint radius R = {r_} and the centre-of-mass
# height H = {h_} (G): radii as fractions of R, heights above the footpads as fractions of H.
[gear.parametric]
r1 = {r1}                  # E: primary trunnion B2 at 0.64 R
r2 = {r2}                  # E: secondary trunnions at 0.60 R
r3 = {r_}                  # G: footpads
{z1}z2 = {z2}                  # E: secondary trunnions, 11/18 H
z3 = {z3}                  # E: primary trunnion, 10/9 H
zc = {h_}                  # G: centre of mass
beta = {beta}                # E: the secondary trunnions' azimuth either side of the leg
beta_convention = "trunnion_azimuth"
leg_azimuths = [{azimuths}]   # E: evenly spaced, leg 1 along +X_B, counter-clockwise

[primary_strut]
trunnion = "rigid"
viscous = {{ coefficient = 0.0, exponent = 1.0 }}

[primary_strut.compression]
onset_rate = {onset}       # E: the first plateau reached after 2.5 % of stage 1
backoff_rate = {backoff}   # E: rebound 45 x onset (the crushed strut's axial stiffness)
stroke_out_rate = {stroke_out}   # E: bottoming, 100 x onset
stages = [
  {{ crush_load = {f1_}, stroke_end = {s1} }},   # G: the first crush load, to 2/3 of the stroke (E)
  {{ crush_load = {f2}, stroke_end = {s_} }},   # E: 1.6 x the first over the last third; G: the stroke
]

[primary_strut.bearing]
friction = {friction}            # E: {friction_note}
initial_overlap = {d2}           # E: D2 = 0.246 x the primary's length {l2p}
inner_cylinder_length = {d1}     # E: D1 = 0.597 x its length, or D2 + 1.2 x the stroke if longer

[secondary_strut]
trunnion = "rigid"
viscous = {{ coefficient = 0.0, exponent = 1.0 }}

[secondary_strut.tension]
onset_rate = {onset_s}     # E: the first plateau after 3.5 % of stage 1
backoff_rate = {backoff_s} # E: 50 x onset
stroke_out_rate = {stroke_out_s}   # E: 100 x onset
stages = [
  {{ crush_load = {fs1}, stroke_end = {ss1} }},   # E: 5/11 of the primary's first load, to 0.4 x its stroke
  {{ crush_load = {fs2}, stroke_end = {ss2} }},   # E: twice that, to 0.6 x its stroke
]

[secondary_strut.compression]
onset_rate = {onset_s}     # E: as in tension
backoff_rate = {backoff_s}
stroke_out_rate = {stroke_out_s}
stages = [
  {{ crush_load = {fs1}, stroke_end = {ss1} }},
  {{ crush_load = {fs2}, stroke_end = {ss2} }},
]

[footpad]
mass = {pad_mass}          # E: 3/700 of the vehicle's mass, the robotic lander's
radius = {pad_radius}      # E: 0.12 R

[integrator]
scheme = "report"
dist = {dist}              # E: the robotic lander's 1 mm, scaled with the primary's length
dt_min = {dt_min}
dt_max = {dt_max}          # E: 0.16 / omega of the stiffest mode, a footpad on a bottomed primary's stop unloading (K_so/e^2, e = 0.5)
t_end = {t_end}            # E: a landing runs to its end time (the decision, stable or not, is reported with its time)
"#,
            name = self.name.replace('"', "'"),
            arrangement = if tripod { "tripod" } else { "cantilever" },
            mass = num(self.mass),
            gravity = num(self.gravity),
            ixx = num(ixx),
            iyy = num(iyy),
            izz = num(izz),
            r_ = num(r),
            h_ = num(h),
            r1 = num(R1 * r),
            r2 = num(R2 * r),
            z2 = num(Z2 * h),
            z3 = num(Z3 * h),
            azimuths = azimuths.join(", "),
            beta = num(BETA_DEG),
            onset = num(onset),
            backoff = num(45.0 * onset),
            stroke_out = num(100.0 * onset),
            f1_ = num(f1),
            s1 = num(s * 2.0 / 3.0),
            f2 = num(1.6 * f1),
            s_ = num(s),
            friction = if tripod { "0.0" } else { "0.1" },
            friction_note = if tripod {
                "the tripod's primary carries no side load"
            } else {
                "the report's bearing friction coefficient"
            },
            d2 = num(d2),
            d1 = num(d1),
            l2p = num(l2p),
            onset_s = num(onset_s),
            backoff_s = num(50.0 * onset_s),
            stroke_out_s = num(100.0 * onset_s),
            fs1 = num(fs),
            ss1 = num(0.4 * s),
            fs2 = num(2.0 * fs),
            ss2 = num(0.6 * s),
            pad_mass = num(pad_mass),
            pad_radius = num(0.12 * r),
            dist = num(0.001 / 1.0966 * l2p),
            dt_min = num(dt_max / 2000.0),
            dt_max = num(dt_max),
            t_end = num(self.t_end()),
        )
    }

    /// The run's end: three times the vehicle's free-fall time scale √(H/g), at least 1 s
    /// (2.2 s for the robotic lander).
    fn t_end(&self) -> f64 {
        (3.0 * (self.centre_of_mass_height / self.gravity).sqrt()).max(1.0)
    }

    fn landing(&self, vehicle_file: &str) -> String {
        format!(
            r#"# A first landing of {name} (drafted by `touchdown new`): the touchdown given (G), on rigid
# ground, the footpads sliding on it with the friction of regolith on a metal pad (E).
schema_version = 1
extends = "{vehicle_file}"
name = "{name}: first landing"
description = "Drafted by touchdown new: vertical velocity {vv}, horizontal velocity {vh} along +Y, slope {slope} deg."

[surface]
kind = "rigid"
slope = {slope}            # G: about X, +Y downhill
hole = 0.0
obstacle = 0.0             # no restraint: the footpads slide
friction = 0.4             # E: regolith on a metal pad

[touchdown]
attitude = [0.0, 0.0, 0.0]
attitude_reference = "horizontal"
vertical_velocity = {vv}   # G: negative down
horizontal_velocity = [0.0, {vh}]   # G: along +Y (downhill; toward leg 2 of four)

[engines]
applicable = ["core", "rapier", "mujoco"]   # every engine (docs/which-engine.md)
"#,
            name = self.name.replace('"', "'"),
            vv = num(self.vertical_velocity),
            vh = num(self.horizontal_velocity),
            slope = num(self.slope),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schema::Arrangement;

    fn robotic(arrangement: Arrangement) -> Draft {
        Draft {
            name: "Drafted lander".into(),
            units: UnitSystem::Si,
            arrangement,
            legs: 4,
            mass: 700.0,
            gravity: 1.62,
            inertia: [215.25, 215.25, 262.5],
            footprint_radius: 1.25,
            centre_of_mass_height: 0.9,
            crush_load: 5500.0,
            stroke: 0.3,
            vertical_velocity: -2.0,
            horizontal_velocity: 0.5,
            slope: 0.0,
        }
    }

    fn load(draft: &Draft) -> crate::Scenario {
        let dir = tempfile::tempdir().unwrap();
        let (vehicle, landing) = draft.files("vehicle.toml").unwrap();
        std::fs::write(dir.path().join("vehicle.toml"), vehicle).unwrap();
        std::fs::write(dir.path().join("landing.toml"), landing).unwrap();
        crate::Scenario::load(dir.path().join("landing.toml")).unwrap()
    }

    #[test]
    fn numbers_are_rounded_floats_toml_reads_back() {
        for (x, text) in [
            (5500.0, "5500.0"),
            (0.2, "0.2"),
            (1.1e6, "1.1e6"),
            (0.123456, "0.1235"),
            (-2.0, "-2.0"),
            (2.5e-5, "2.5e-5"),
        ] {
            assert_eq!(num(x), text);
            let v: toml::Value = toml::from_str(&format!("x = {}", num(x))).unwrap();
            assert!(v["x"].is_float(), "{text}");
        }
    }

    #[test]
    fn the_robotic_landers_numbers_draft_its_geometry_and_load_without_warnings() {
        let sc = load(&robotic(Arrangement::Cantilever));
        assert!(sc.warnings().is_empty(), "{:?}", sc.warnings());
        let bundled = crate::Scenario::load(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../../scenarios/robotic-lander-nominal.toml"),
        )
        .unwrap();
        for (a, b) in sc.legs.iter().zip(&bundled.legs) {
            for (p, q) in [(a.b2, b.b2), (a.b3, b.b3), (a.b4, b.b4), (a.bp, b.bp)] {
                assert!((p - q).norm() < 1e-3, "{p} against {q}");
            }
            assert!((a.l21 - b.l21).abs() < 1e-3);
        }
        let (p, q) = (&sc.primary.compression, &bundled.primary.compression);
        assert_eq!((p.onset_rate, p.stages[0]), (q.onset_rate, q.stages[0]));
        assert_eq!(p.capacity(), q.capacity());
        assert_eq!(sc.integrator.dist, bundled.integrator.dist);
        // The footpad on a bottomed stop unloading: ω = √(4·100·K_o/m_pad), ω·dt_max = 0.16.
        let omega = (4.0 * 100.0 * p.onset_rate / sc.footpad.mass).sqrt();
        assert!(
            (omega * sc.integrator.dt_max - 0.16).abs() < 1e-3,
            "{}",
            sc.integrator.dt_max
        );
        let tripod = load(&robotic(Arrangement::Tripod));
        assert_eq!(tripod.arrangement, Arrangement::Tripod);
        assert!(tripod.warnings().is_empty(), "{:?}", tripod.warnings());
    }

    #[test]
    fn a_draft_in_feet_slugs_and_pounds_is_the_same_vehicle() {
        let si = robotic(Arrangement::Cantilever);
        let (ft, slug, lbf) = (0.3048, 14.593_902_937_206_364, 4.448_221_615_260_5);
        let us = Draft {
            units: UnitSystem::FootSlugPound,
            mass: si.mass / slug,
            gravity: si.gravity / ft,
            inertia: si.inertia.map(|i| i / (slug * ft * ft)),
            footprint_radius: si.footprint_radius / ft,
            centre_of_mass_height: si.centre_of_mass_height / ft,
            crush_load: si.crush_load / lbf,
            stroke: si.stroke / ft,
            vertical_velocity: si.vertical_velocity / ft,
            horizontal_velocity: si.horizontal_velocity / ft,
            ..si.clone()
        };
        let (a, b) = (load(&si), load(&us));
        // Equal to the four significant digits each file writes its numbers with.
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-3 * x.abs().max(y.abs());
        assert!(close(a.vehicle.mass, b.vehicle.mass));
        assert!(close(a.legs[1].bp.y, b.legs[1].bp.y));
        assert!(close(a.legs[1].b3.x, b.legs[1].b3.x));
        assert!(close(
            a.primary.compression.onset_rate,
            b.primary.compression.onset_rate
        ));
        assert!(close(a.integrator.dt_max, b.integrator.dt_max));
        assert!(close(a.integrator.dist, b.integrator.dist));
        assert!(close(a.touchdown.velocity_g.z, b.touchdown.velocity_g.z));
    }

    #[test]
    fn numbers_that_make_no_vehicle_are_named() {
        let bad = |change: &dyn Fn(&mut Draft)| {
            let mut d = robotic(Arrangement::Cantilever);
            change(&mut d);
            d.files("vehicle.toml").unwrap_err()
        };
        assert_eq!(bad(&|d| d.mass = -1.0).field, "mass");
        assert_eq!(bad(&|d| d.legs = 2).field, "legs");
        assert_eq!(bad(&|d| d.inertia = [1.0, 1.0, 3.0]).field, "inertia");
        assert_eq!(
            bad(&|d| d.vertical_velocity = 2.0).field,
            "vertical_velocity"
        );
        let e = bad(&|d| d.stroke = 2.0);
        assert_eq!(e.field, "stroke");
        assert!(e.message.contains("holds a stroke of at most"), "{e}");
    }
}

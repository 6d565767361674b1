//! A vehicle and its landing reviewed before they run (docs/authoring.md, "Checked before it
//! lands"): the figures a landing-gear reviewer looks at first, and the findings a landing
//! should not run past unread, each naming the file of the `extends` chain that set the value.
//!
//! | figure | what it compares |
//! |---|---|
//! | gear crush load | the primaries' first crush loads, resolved on the vertical, against the landed weight: below it the vehicle crushes its gear standing still |
//! | stroke energy | what every strut absorbs crushing to its capacity against the touchdown energy: above it, the landing ends on end stops unless friction and dampers take the rest |
//! | static tip-over angle | the angle a vehicle at rest on level ground, undeformed, tilts through before its centre of mass passes over its nearest footprint edge, against the slope |
//! | principal moments | the inertia's principal moments (the loader refuses a tensor no rigid body has) |
//!
//! The review is geometry and the laws' own load-stroke curves (`touchdown-laws`), nothing
//! integrated: it takes microseconds, and a vehicle that passes it may still fail its landing.

use nalgebra::Vector3;
use serde::Serialize;
use touchdown_laws::GearLaws;
use touchdown_scenario::{Scenario, ScenarioError};

/// The figures of a review, SI.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Figures {
    /// Legs.
    pub legs: usize,
    /// The vehicle's weight M·g at touchdown, N.
    pub weight_n: f64,
    /// The primaries' first crush loads resolved on the vertical, summed over the legs (each
    /// FP1 times the cosine of its strut's angle from −Z_B, undeformed, trunnion-modified where
    /// a trunnion spring is given), N.
    pub gear_crush_load_n: f64,
    /// `gear_crush_load_n` over `weight_n`: below 1 the landed vehicle crushes its gear
    /// (absent without gravity).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gear_crush_load_of_weight: Option<f64>,
    /// The vehicle's kinetic energy at touchdown, translation and rotation (½·M·|V|² +
    /// ½·ωᵀ·J·ω), J.
    pub touchdown_kinetic_energy_j: f64,
    /// The weight's work over the vertical travel of a primary crushed to its capacity (the
    /// most vertical leg's), J.
    pub stroke_potential_energy_j: f64,
    /// `touchdown_kinetic_energy_j` + `stroke_potential_energy_j`, J.
    pub touchdown_energy_j: f64,
    /// What one primary strut absorbs crushing from no stroke to its capacity, J.
    pub primary_stroke_energy_j: f64,
    /// What one secondary strut absorbs crushing to its capacity, on its side that absorbs
    /// more (tension or compression), J.
    pub secondary_stroke_energy_j: f64,
    /// What every strut of every leg absorbs crushing to its capacity, J.
    pub stroke_energy_j: f64,
    /// `stroke_energy_j` over `touchdown_energy_j`: below 1 the honeycomb alone cannot take the
    /// landing (absent when the touchdown carries no energy).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stroke_energy_of_touchdown: Option<f64>,
    /// Height of the centre of mass above the lowest footpad, undeformed and upright, m.
    pub centre_of_mass_height_m: f64,
    /// The least distance from the centre of mass's projection to a footprint edge (an edge
    /// joins consecutive footpads), m; negative when the projection lies outside.
    pub footprint_inner_radius_m: f64,
    /// The static tip-over angle: atan(footprint inner radius / centre-of-mass height), rad.
    pub static_tip_over_angle_rad: f64,
    /// The surface slope, its magnitude, rad.
    pub slope_rad: f64,
    /// `static_tip_over_angle_rad` less `slope_rad`: the tilt left before a vehicle standing on
    /// the slope, its nearest edge downhill, tips over, rad.
    pub tip_over_margin_rad: f64,
    /// The inertia tensor's principal moments, smallest first, kg·m².
    pub principal_moments_kg_m2: [f64; 3],
}

/// What a finding is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Concern {
    /// A value the loader accepts but warns of: outside its usual range, or against the
    /// weight (the scenario's own warnings).
    Value,
    /// The touchdown energy exceeds what every strut absorbs to its capacity.
    StrokeEnergy,
    /// The slope is at or past the static tip-over angle.
    TipOver,
    /// The centre of mass stands outside its footprint.
    Footprint,
}

/// One finding: what, the file that set the value, the field and why.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Finding {
    /// What it is about.
    pub concern: Concern,
    /// The file of the `extends` chain that sets the field (or `overrides` for a `--set`).
    pub file: String,
    /// The field path.
    pub field: String,
    /// What was found, with the figures.
    pub message: String,
}

impl std::fmt::Display for Finding {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: field `{}`: {}", self.file, self.field, self.message)
    }
}

/// A review: its figures and its findings (none when nothing needs a look).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Review {
    /// The figures.
    pub figures: Figures,
    /// The findings, the scenario's own warnings first.
    pub findings: Vec<Finding>,
}

impl Review {
    /// The review as the document `touchdown check --format json` prints
    /// (docs/schemas/check.schema.json), about `scenario`, written with `settings`.
    pub fn document(
        &self,
        scenario: &touchdown_record::ScenarioId,
        settings: &serde_json::Value,
    ) -> String {
        touchdown_record::Document::new("check", Some(scenario), settings, self).pretty()
    }
}

/// Reviews `sc`: an error only where its gear laws cannot be built (as an engine would report).
pub fn review(sc: &Scenario) -> Result<Review, ScenarioError> {
    let laws = GearLaws::from_scenario(sc)?;
    let v = &sc.vehicle;
    let n = sc.legs.len();
    let weight = v.mass * v.gravity;
    // Each primary's axis from its trunnion down to its footpad, and its cosine with −Z_B.
    let vertical: Vec<f64> = sc
        .legs
        .iter()
        .map(|l| -(l.bp - l.b2).normalize().z)
        .collect();
    let primary_curve = &laws.primary.honeycomb.curve;
    let first_crush = primary_curve
        .vertices()
        .map(|(_, f)| f)
        .find(|f| *f > 0.0)
        .unwrap_or(0.0);
    let gear_crush = vertical.iter().map(|c| first_crush * c).sum::<f64>();
    let velocity = sc.touchdown.velocity_g;
    let omega = sc.touchdown.body_rates;
    let kinetic = 0.5 * v.mass * velocity.norm_squared() + 0.5 * omega.dot(&(v.inertia * omega));
    let most_vertical = vertical.iter().copied().fold(0.0, f64::max);
    let potential = weight * primary_curve.capacity() * most_vertical;
    let touchdown = kinetic + potential;
    let primary_energy = primary_curve.energy_to_capacity();
    let h = &laws.secondary.honeycomb;
    let secondary_energy = h
        .tension
        .curve
        .energy_to_capacity()
        .max(h.compression.curve.energy_to_capacity());
    let stroke = n as f64 * (primary_energy + 2.0 * secondary_energy);
    let height = sc
        .legs
        .iter()
        .map(|l| -l.bp.z)
        .fold(f64::NEG_INFINITY, f64::max);
    let inner = footprint_inner_radius(sc.legs.iter().map(|l| l.bp));
    let tip = inner.atan2(height);
    let slope = sc.surface.slope.abs();
    let mut moments = [0.0; 3];
    moments.copy_from_slice(v.inertia.symmetric_eigenvalues().as_slice());
    moments.sort_by(f64::total_cmp);
    let figures = Figures {
        legs: n,
        weight_n: weight,
        gear_crush_load_n: gear_crush,
        gear_crush_load_of_weight: (weight > 0.0).then(|| gear_crush / weight),
        touchdown_kinetic_energy_j: kinetic,
        stroke_potential_energy_j: potential,
        touchdown_energy_j: touchdown,
        primary_stroke_energy_j: primary_energy,
        secondary_stroke_energy_j: secondary_energy,
        stroke_energy_j: stroke,
        stroke_energy_of_touchdown: (touchdown > 0.0).then(|| stroke / touchdown),
        centre_of_mass_height_m: height,
        footprint_inner_radius_m: inner,
        static_tip_over_angle_rad: tip,
        slope_rad: slope,
        tip_over_margin_rad: tip - slope,
        principal_moments_kg_m2: moments,
    };
    let mut findings: Vec<Finding> = sc
        .warnings()
        .iter()
        .map(|w| Finding {
            concern: Concern::Value,
            file: w.file.clone(),
            field: w.field.clone(),
            message: w.message.clone(),
        })
        .collect();
    let finding = |concern, field: &str, message: String| Finding {
        concern,
        file: sc.file_of(field).to_string(),
        field: field.to_string(),
        message,
    };
    if touchdown > stroke {
        findings.push(finding(
            Concern::StrokeEnergy,
            "touchdown.vertical_velocity",
            format!(
                "the touchdown energy, {touchdown:.4e} J (kinetic {kinetic:.4e} J, and the weight over a primary's vertical travel at capacity {potential:.4e} J), exceeds what every strut of all {n} legs absorbs crushing to its capacity, {stroke:.4e} J: the honeycomb alone cannot take this landing, and what friction and dampers do not take goes into the end stops or stays as motion, an overturn (the crush loads and strokes of primary_strut and secondary_strut, or the touchdown speed)"
            ),
        ));
    }
    let gear = if sc.file.gear.legs.is_some() {
        "gear.legs"
    } else {
        "gear.parametric"
    };
    if inner <= 0.0 {
        findings.push(finding(
            Concern::Footprint,
            gear,
            format!(
                "the centre of mass stands {:.4e} m outside its footprint (the polygon of the footpads, seen from above): the vehicle cannot stand on its gear",
                -inner
            ),
        ));
    } else if slope >= tip {
        findings.push(finding(
            Concern::TipOver,
            "surface.slope",
            format!(
                "the slope, {:.2} deg, is at or past the static tip-over angle, {:.2} deg (footprint inner radius {inner:.4} m under a centre of mass {height:.4} m high): a vehicle at rest on it, its nearest footprint edge downhill, tips over",
                slope.to_degrees(),
                tip.to_degrees()
            ),
        ));
    }
    Ok(Review { figures, findings })
}

/// The least signed distance from the origin's projection to an edge of the polygon through
/// `points` (seen from above, in the order given, counter-clockwise), m: positive inside.
fn footprint_inner_radius(points: impl Iterator<Item = Vector3<f64>>) -> f64 {
    let p: Vec<Vector3<f64>> = points.collect();
    (0..p.len())
        .map(|i| {
            let (a, b) = (p[i].xy(), p[(i + 1) % p.len()].xy());
            let e = b - a;
            // (b − a) × (0 − a), z component, over |b − a|: positive with the origin on the left.
            (e.x * -a.y - e.y * -a.x) / e.norm()
        })
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bundled(name: &str) -> Scenario {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenarios")
            .join(name);
        Scenario::load(path).unwrap()
    }

    #[test]
    fn a_square_footprint_has_its_half_side_as_inner_radius() {
        let square = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)]
            .map(|(x, y)| Vector3::new(x, y, -1.0));
        let r = footprint_inner_radius(square.into_iter());
        assert!((r - 0.5f64.sqrt()).abs() < 1e-15);
        // Off-centre past an edge: outside, negative.
        let shifted = square.map(|p| p + Vector3::new(2.0, 0.0, 0.0));
        assert!(footprint_inner_radius(shifted.into_iter()) < 0.0);
    }

    #[test]
    fn the_lm_model_passes_and_its_figures_follow_from_its_file() {
        let sc = bundled("flat-drop.toml");
        let r = review(&sc).unwrap();
        let f = &r.figures;
        assert!(r.findings.is_empty(), "{:?}", r.findings);
        assert_eq!(f.legs, 4);
        assert!((f.weight_n - sc.vehicle.mass * sc.vehicle.gravity).abs() < 1e-12);
        // Four primaries on a footprint symmetric about the centre of mass: the inner radius
        // is the footpad radius over √2.
        let r3 = sc.legs[0].bp.xy().norm();
        assert!((f.footprint_inner_radius_m - r3 / 2f64.sqrt()).abs() < 1e-9 * r3);
        assert!(f.stroke_energy_of_touchdown.unwrap() > 1.0);
        assert!(f.static_tip_over_angle_rad > 0.5 && f.tip_over_margin_rad > 0.0);
    }

    #[test]
    fn a_slope_past_the_tip_over_angle_and_a_hard_landing_are_found_naming_their_files() {
        let dir = tempfile::tempdir().unwrap();
        let base = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenarios/flat-drop.toml")
            .canonicalize()
            .unwrap();
        let path = dir.path().join("steep.toml");
        std::fs::write(
            &path,
            format!(
                "schema_version = 1\nextends = {:?}\nname = \"steep\"\n[surface]\nslope = 70.0\n[touchdown]\nvertical_velocity = -60.0\n",
                base.display()
            ),
        )
        .unwrap();
        let sc = Scenario::load(&path).unwrap();
        let r = review(&sc).unwrap();
        let concerns: Vec<Concern> = r.findings.iter().map(|f| f.concern).collect();
        assert!(concerns.contains(&Concern::TipOver), "{:?}", r.findings);
        assert!(
            concerns.contains(&Concern::StrokeEnergy),
            "{:?}",
            r.findings
        );
        for f in r.findings.iter().filter(|f| f.concern != Concern::Value) {
            assert_eq!(f.file, path.display().to_string(), "{f}");
        }
        assert!(r.figures.stroke_energy_of_touchdown.unwrap() < 1.0);
        assert!(r.figures.tip_over_margin_rad < 0.0);
    }

    #[test]
    fn the_review_does_not_depend_on_the_units_or_the_scale() {
        let sc = bundled("fig-25-26.toml");
        let si = review(&sc).unwrap().figures;
        // The same vehicle six times larger, 216 times heavier, its clock six times slower:
        // lengths scale, the tip-over angle and the ratios do not.
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/fig-25-26.toml");
        let scaled = Scenario::load_with(
            &path,
            &[
                ("similarity.length", 6.0),
                ("similarity.mass", 216.0),
                ("similarity.time", 6.0),
            ],
        )
        .unwrap();
        let big = review(&scaled).unwrap().figures;
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
        assert!(close(
            big.static_tip_over_angle_rad,
            si.static_tip_over_angle_rad
        ));
        assert!(close(
            big.stroke_energy_of_touchdown.unwrap(),
            si.stroke_energy_of_touchdown.unwrap()
        ));
        assert!(close(
            big.gear_crush_load_of_weight.unwrap(),
            si.gear_crush_load_of_weight.unwrap()
        ));
        assert!(close(
            big.footprint_inner_radius_m,
            6.0 * si.footprint_inner_radius_m
        ));
    }
}

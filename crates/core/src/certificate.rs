//! The settled end's certificate (docs/errata.md, "Settled landings: an early end with a
//! proof"): once the landing is decided stable, an energy certificate checked at accepted
//! states that no maximum stroke can grow by more than the scenario's tolerance ε, that the
//! least stability distance cannot fall by more than ε, that no peak strut force, specific
//! force or pitch rate (in either sense) can grow at all, and that no overturn is reachable. The run ends at the
//! first state where it holds.
//!
//! The certificate bounds the energy the vehicle and its footpads can still spend on any of
//! these, A = KE + Σ_struts [E_j(s_j) − f_j·s_j + Ê_j*(f_j)], where E_j is a strut's stored
//! energy, Ê_j* the conjugate of the least energy it takes to reach a stroke
//! ([`touchdown_laws::StrutReach`]) and f_j a set of strut loads that holds the vehicle at rest
//! on its footpads in contact (found by reweighted least squares). By the
//! Fenchel–Young inequality and the virtual work of those loads, the potential energy cancels:
//! no state the landing can reach has a strut's gap above A, nor a kinetic energy above A.

use crate::model::Model;
use crate::settling::{LegTerms, Motion, Settling, MAX_LEGS};
use crate::state::State;
use crate::surface::ContactState;
use nalgebra::{Matrix3, Matrix6, SMatrix, Vector3, Vector6};
use touchdown_record::Outcome;
use touchdown_scenario::model::Leg;

/// The certificate holds only while the energy it bounds is at most this fraction κ of the
/// least energy that tips the vehicle over a wall: the bound is exact to first order in the
/// displacements it allows, and κ bounds the neglected second-order terms (the rotation's
/// change of the lever arms) relative to it; the bound is raised by the same fraction.
const LINEAR_MARGIN: f64 = 0.1;

/// Directions of the motion whose weight in AᵀWA is below this fraction of the largest are
/// free: the rows do not bound them (rounding is 1e-16 of it).
const FREE_MOTION: f64 = 1e-12;

/// Rounds of the reweighted balance.
const BALANCE_ROUNDS: usize = 4;

/// The weight of a slack strut's compliance against a loaded one's in the first balance: a
/// slack strut (no load, between its permanent sets) takes a load only by stroking across its
/// band, so it starts as all but free.
const SLACK: f64 = 1e-9;

/// Why the certificate does not hold at a state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Unsettled {
    /// The landing is not decided stable.
    Undecided,
    /// A footpad in contact is not held laterally.
    Sliding,
    /// A strut is on its bottoming stop.
    Stop,
    /// The footpads in contact cannot hold the vehicle at rest.
    Unbalanced,
    /// Holding the vehicle at rest would crush a strut on a plateau.
    Crushing,
    /// The energy left is not small against the least energy that tips the vehicle.
    Tipping,
    /// The least stability distance could fall by more than ε.
    Distance,
    /// A footpad could rise out of what holds it.
    Lift,
    /// A maximum stroke could grow by more than ε.
    Stroke,
    /// A peak strut force could grow.
    Force,
    /// The peak specific force could grow.
    SpecificForce,
    /// The pitch rate's extreme in either sense could grow.
    PitchRate,
}

/// The strokes' gradient in the footpad's body-frame position for the cantilever leg `leg`
/// with its footpad at `bp` (m, body axes), rows c, S31, S41 (eqs. 27-34 differentiated): the
/// primary shortens along its axis, and point 1, at L21 along it, moves the secondaries.
pub(crate) fn stroke_jacobian(leg: &Leg, bp: &Vector3<f64>) -> Matrix3<f64> {
    let v2p = bp - leg.b2;
    let len = v2p.norm();
    let e = v2p / len;
    let swing = (Matrix3::identity() - e * e.transpose()) * (leg.l21 / len);
    let b1 = leg.b2 + e * leg.l21;
    let row = |b: &Vector3<f64>| (b1 - b).normalize().transpose() * swing;
    let mut j = Matrix3::zeros();
    j.set_row(0, &(-e.transpose()));
    j.set_row(1, &row(&leg.b3));
    j.set_row(2, &row(&leg.b4));
    j
}

impl State {
    /// Checks the certificate at the accepted state once the check is due, and ends the
    /// landing where it holds.
    pub(crate) fn check_settled(&mut self, model: &Model, settling: &Settling) {
        if self.settled.is_some() || self.t < self.next_settling_check {
            return;
        }
        self.next_settling_check = self.t + settling.interval;
        let mut terms = std::mem::take(&mut self.settling_terms);
        if self.certify(model, settling, &mut terms).is_ok() {
            self.settled = Some(self.t);
        }
        self.settling_terms = terms;
    }

    /// The certificate at the accepted state: the energy bound A (J) where it holds.
    pub(crate) fn certify(
        &self,
        model: &Model,
        settling: &Settling,
        terms: &mut [LegTerms],
    ) -> Result<f64, Unsettled> {
        if self.stability.decision().map(|d| d.0) != Some(Outcome::Stable) {
            return Err(Unsettled::Undecided);
        }
        let eps = settling.tolerance;
        let v = &self.vehicle;
        let t_ib = v.t_bi.transpose();
        let g_b = t_ib * model.gravity;
        let up_b = t_ib * Vector3::z();
        let (m, mp) = (model.mass.mass, model.footpad_mass);
        // Each leg's geometry, strokes and laws' minorants.
        for (i, term) in terms.iter_mut().enumerate() {
            let pad = &self.pads[i];
            let contact = pad.state == ContactState::Contact;
            if contact && !pad.walled {
                return Err(Unsettled::Sliding);
            }
            let g = &self.gear[i];
            term.bp = if model.inertial || contact {
                t_ib * (pad.position - v.position)
            } else {
                pad.bp_attached
            };
            term.jacobian = stroke_jacobian(&model.legs[i], &term.bp);
            term.strokes = Vector3::new(
                g.primary_stroke,
                g.secondary_stroke[0],
                g.secondary_stroke[1],
            );
            term.bearing = contact;
            (term.forces, term.rates, term.stored) = self.strut_state(model, i);
            term.reach = Some(
                model
                    .laws
                    .reach(&self.memory[i], eps)
                    .ok_or(Unsettled::Stop)?,
            );
        }
        // The energy the landing can still spend, at the loads that bound it best.
        let mut kinetic = self.kinetic_energy(model);
        for p in &self.pads {
            if model.inertial || p.state == ContactState::Contact {
                kinetic += 0.5 * mp * p.velocity.norm_squared();
            }
        }
        let available = self.least_available(model, terms, kinetic, &g_b, &up_b)?;
        let budget = available * (1.0 + LINEAR_MARGIN);
        let weight = m * model.gravity.norm();
        if weight <= 0.0 {
            return Err(Unsettled::Tipping);
        }
        // Strokes: each strut's reach alone, then the slack struts' through the vehicle's
        // motion, which the loaded struts and the bearing footpads' lifts bound together.
        for (i, term) in terms.iter_mut().enumerate() {
            let r = term.reach.ok_or(Unsettled::Stop)?;
            for (j, strut) in r.iter().enumerate() {
                let (lo, hi) = strut.limits(eps);
                let (s, f) = (term.strokes[j], term.loads[j]);
                term.intervals[j] = strut.reach(s, f, budget, (lo.max(s - model.legs[i].l2p), hi));
            }
            let moved = Vector3::from_fn(|j, _| {
                let (lo, hi) = term.intervals[j];
                (term.strokes[j] - lo).max(hi - term.strokes[j])
            });
            let inverse = term.jacobian.try_inverse().ok_or(Unsettled::Unbalanced)?;
            term.give = inverse.norm() * moved.norm();
        }
        couple(terms, &up_b, budget);
        for term in terms.iter() {
            let r = term.reach.ok_or(Unsettled::Stop)?;
            for (j, strut) in r.iter().enumerate() {
                let (lo, hi) = strut.limits(eps);
                let (reach_lo, reach_hi) = term.intervals[j];
                if reach_hi >= hi || (j > 0 && reach_lo <= lo) {
                    return Err(Unsettled::Stroke);
                }
            }
        }
        // Walls: the energy to tip over each, the least distance it can come to, the rotation
        // it allows.
        let rise = budget / weight;
        let up = -model.gravity.normalize();
        let n = terms.len();
        let mut rotation: f64 = 0.0;
        for i in 0..n {
            let k = (i + 1) % n;
            let (a, b) = (self.pad_views[i].position, self.pad_views[k].position);
            let u = (b - a).normalize();
            let w = v.position - a;
            let rho = w - u * w.dot(&u);
            let r = rho.norm();
            let s = (1.0 - u.dot(&up).powi(2)).max(0.0).sqrt();
            if r * s <= 0.0 {
                return Err(Unsettled::Tipping);
            }
            let top = (up - u * u.dot(&up)) / s;
            let cos0 = (rho.dot(&top) / r).clamp(-1.0, 1.0);
            let barrier = weight * r * s * (1.0 - cos0);
            if available > LINEAR_MARGIN * barrier {
                return Err(Unsettled::Tipping);
            }
            let cos_min = cos0 + rise / (r * s);
            let (theta0, theta_min) = (cos0.acos(), cos_min.min(1.0).acos());
            rotation = rotation.max(theta0 - theta_min);
            let floor = r * theta_min.sin() - terms[i].give - terms[k].give;
            if floor <= 0.0 || floor < self.stability.min_distance() - eps {
                return Err(Unsettled::Distance);
            }
        }
        // Footpads held by a wall or spikes stay within them.
        for (i, term) in terms.iter().enumerate() {
            let pad = &self.pads[i];
            if !pad.walled {
                continue;
            }
            let surface = &model.surfaces[i];
            let height = pad.position.z - surface.plane();
            let lift = rise + term.bp.norm() * rotation + term.give;
            if height + lift >= surface.hold_height() {
                return Err(Unsettled::Lift);
            }
        }
        // Forces, the specific force and the pitch rate.
        let speed = |mass: f64| (2.0 * budget / mass).sqrt();
        let spin = speed(settling.inertia_min);
        // Each sense's extreme of the pitch rate (|q| ≤ spin from here on).
        let [low, high] = self.extremes.pitch_rate_extremes();
        if spin > high.0.min(-low.0) {
            return Err(Unsettled::PitchRate);
        }
        let mut on_vehicle = 0.0;
        for (i, term) in terms.iter().enumerate() {
            let pad_speed = if model.inertial { speed(mp) } else { 0.0 };
            let relative = pad_speed + speed(m) + spin * term.bp.norm();
            let bounds = self.strut_force_bounds(model, i, term, relative)?;
            let (primary, tension, compression) = self.extremes.peak_forces(i);
            if bounds[0].1 > primary
                || (0..2).any(|j| bounds[j + 1].1 > tension[j] || -bounds[j + 1].0 > compression[j])
            {
                return Err(Unsettled::Force);
            }
            let largest = Vector3::from_fn(|j, _| bounds[j].0.abs().max(bounds[j].1.abs()));
            on_vehicle += term.jacobian.norm() * largest.norm();
        }
        if on_vehicle / m > self.extremes.specific_force() {
            return Err(Unsettled::SpecificForce);
        }
        Ok(available)
    }

    /// The energy bound A = KE + Σ gaps (J) at the loads that make it least, found by
    /// iteratively reweighted least squares: a loaded strut's gap is ½·(f − F)²/K_B near its
    /// state, a slack strut's grows as |f| times the stroke to the side f loads, so each round
    /// weighs a slack strut by the compliance |f|/d that gives its gap at the last round's load
    /// (every round's loads hold the vehicle at rest, so each gives a valid bound; the least is
    /// kept). Leaves the terms at the loads kept.
    fn least_available(
        &self,
        model: &Model,
        terms: &mut [LegTerms],
        kinetic: f64,
        g_b: &Vector3<f64>,
        up_b: &Vector3<f64>,
    ) -> Result<f64, Unsettled> {
        for term in terms.iter_mut() {
            term.slack = term.forces.map(|f| f == 0.0).into();
            term.compliance =
                term.rates
                    .zip_map(&term.forces, |k, f| if f == 0.0 { k * SLACK } else { k });
        }
        let mut best: Option<f64> = None;
        let mut contact = [false; MAX_LEGS];
        for (c, term) in contact.iter_mut().zip(terms.iter()) {
            *c = term.bearing;
        }
        for _ in 0..BALANCE_ROUNDS {
            for (c, term) in contact.iter().zip(terms.iter_mut()) {
                term.bearing = *c;
            }
            self.balance(model, terms, g_b, up_b)?;
            let mut available = kinetic;
            for term in terms.iter() {
                let r = term.reach.ok_or(Unsettled::Stop)?;
                for (j, strut) in r.iter().enumerate() {
                    let (s, f) = (term.strokes[j], term.loads[j]);
                    available +=
                        term.stored[j] - f * s + strut.conjugate(f).ok_or(Unsettled::Crushing)?;
                }
            }
            if best.is_none_or(|b| available < b) {
                best = Some(available);
                for term in terms.iter_mut() {
                    term.kept = (term.loads, term.bearing, term.pressing);
                }
            }
            for term in terms.iter_mut() {
                let r = term.reach.ok_or(Unsettled::Stop)?;
                for (j, strut) in r.iter().enumerate() {
                    let (s, f) = (term.strokes[j], term.loads[j]);
                    term.compliance[j] = if f * term.forces[j] > 0.0 {
                        term.rates[j]
                    } else {
                        // Loading the other side (or a slack strut) strokes across the band.
                        let (a, b) = strut.band();
                        let distance = if f >= 0.0 { b - s } else { s - a };
                        f.abs().max(f64::MIN_POSITIVE) / distance.max(f64::MIN_POSITIVE)
                    };
                }
            }
        }
        for term in terms.iter_mut() {
            (term.loads, term.bearing, term.pressing) = term.kept;
        }
        best.ok_or(Unsettled::Unbalanced)
    }

    /// Sets each leg's loads f to the least-squares set (in the struts' compliances) that holds
    /// the vehicle at rest with the bearing footpads pressing on their surfaces (eqs. 10-15 at
    /// rest; a footpad that would have to pull bears nothing); the others carry their footpad's
    /// weight (with inertia) or nothing.
    fn balance(
        &self,
        model: &Model,
        terms: &mut [LegTerms],
        g_b: &Vector3<f64>,
        up_b: &Vector3<f64>,
    ) -> Result<(), Unsettled> {
        let mp = model.footpad_mass;
        let hanging = if model.inertial {
            g_b * mp
        } else {
            Vector3::zeros()
        };
        loop {
            let mut stiffness = Matrix6::zeros();
            let mut residual = Vector6::zeros();
            residual
                .fixed_rows_mut::<3>(0)
                .copy_from(&(-g_b * model.mass.mass));
            for term in terms.iter_mut() {
                let jt = term.jacobian.transpose();
                let c = coupling(&term.bp, &jt);
                if term.bearing {
                    let k = Matrix3::from_diagonal(&term.compliance);
                    stiffness += c * k * c.transpose();
                    term.loads = term.forces;
                } else {
                    // B = Jᵀ·f carries the hanging footpad's weight.
                    term.loads = jt.try_inverse().ok_or(Unsettled::Unbalanced)? * hanging;
                }
                residual -= c * term.loads;
            }
            let multipliers = stiffness
                .cholesky()
                .ok_or(Unsettled::Unbalanced)?
                .solve(&residual);
            let mut pulling: Option<(usize, f64)> = None;
            for (i, term) in terms.iter_mut().enumerate() {
                if !term.bearing {
                    continue;
                }
                let c = coupling(&term.bp, &term.jacobian.transpose());
                term.loads +=
                    Matrix3::from_diagonal(&term.compliance) * c.transpose() * multipliers;
                let reaction = term.jacobian.transpose() * term.loads - g_b * mp;
                let pressing = reaction.dot(up_b);
                term.pressing = pressing;
                if pressing < 0.0 && pulling.is_none_or(|(_, p)| pressing < p) {
                    pulling = Some((i, pressing));
                }
            }
            match pulling {
                None => return Ok(()),
                Some((i, _)) => terms[i].bearing = false,
            }
        }
    }

    /// Leg `i`'s honeycomb forces (c, S31, S41 senses, N) at the accepted state, the rebound
    /// rates K_B of the sides they are on (N/m; the compliances the balance weighs them by)
    /// and the stored energies (J).
    fn strut_state(&self, model: &Model, i: usize) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let g = &self.gear[i];
        let memory = &self.memory[i];
        let (p, h) = (&model.laws.primary, &model.laws.secondary.honeycomb);
        let s = g.secondary_stroke;
        (
            Vector3::new(g.fcp, g.fc_secondary[0], g.fc_secondary[1]),
            Vector3::new(
                p.honeycomb.backoff_rate,
                h.side(s[0]).backoff_rate,
                h.side(s[1]).backoff_rate,
            ),
            Vector3::new(
                p.stored_energy(g.primary_stroke, memory.primary),
                h.stored_energy(s[0], memory.secondary[0]),
                h.stored_energy(s[1], memory.secondary[1]),
            ),
        )
    }

    /// Bounds (least, largest) of leg `i`'s axial strut forces, N (F2P compression positive,
    /// F31 and F41 tension positive), over the strokes the energy allows (`term`), its
    /// footpad moving relative to the vehicle at most at `relative` m/s: the honeycomb's force at
    /// the interval's ends, the viscous force at the fastest stroking, and for the primary the
    /// bearing friction of the largest side load the secondaries can put on it (eqs. 49-63).
    fn strut_force_bounds(
        &self,
        model: &Model,
        i: usize,
        term: &LegTerms,
        relative: f64,
    ) -> Result<[(f64, f64); 3], Unsettled> {
        let laws = &model.laws;
        let memory = &self.memory[i];
        let h = &laws.secondary.honeycomb;
        let rate = |j: usize| term.jacobian.row(j).norm() * relative;
        let mut bounds = [(0.0, 0.0); 3];
        for j in 0..2 {
            let (lo, hi) = term.intervals[j + 1];
            let viscous = laws.secondary.viscous.force(rate(j + 1)).abs();
            bounds[j + 1] = (
                h.force(lo, memory.secondary[j]) - viscous,
                h.force(hi, memory.secondary[j]) + viscous,
            );
        }
        let (lo, hi) = term.intervals[0];
        let p = &laws.primary;
        let side =
            bounds[1].0.abs().max(bounds[1].1.abs()) + bounds[2].0.abs().max(bounds[2].1.abs());
        let leg = &model.legs[i];
        let side_load = side * leg.l21 / (leg.l2p - hi);
        let friction = p
            .bearing
            .loads(side_load, lo.max(0.0))
            .map_err(|_| Unsettled::Force)?;
        let friction = p.bearing.friction_coefficient * (friction.f1 + friction.f2);
        let viscous = p.viscous.force(rate(0)).abs();
        bounds[0] = (
            p.stroke_force(lo, memory.primary) - viscous - friction,
            p.stroke_force(hi, memory.primary) + viscous + friction,
        );
        Ok(bounds)
    }
}

/// Tightens the slack struts' reach and the bearing footpads' give through the vehicle's
/// motion (docs/errata.md, "Settled landings: an early end with a proof"): to first order
/// every stroke of a bearing leg is a linear function aᵀ·y of the motion y (the vehicle's
/// translation and rotation and the footpads' lifts), and the loaded struts' strokes and the
/// lifts lie within their reach. Where those rows determine y (weighted least squares, W
/// the inverse squared half-widths), any other linear function φᵀ·y equals gᵀ·(their values)
/// with g = W·A·(AᵀWA)⁻¹·φ, so it lies within Σ g_r·[lo_r, hi_r].
fn couple(terms: &mut [LegTerms], up_b: &Vector3<f64>, budget: f64) {
    let mut lifts = 0;
    let mut rows = [(Motion::zeros(), 0.0, 0.0); 4 * MAX_LEGS];
    let mut count = 0;
    for term in terms.iter_mut() {
        if !term.bearing {
            continue;
        }
        term.lift = 6 + lifts;
        lifts += 1;
        for j in 0..3 {
            if !term.slack[j] {
                let (lo, hi) = term.intervals[j];
                rows[count] = (
                    term.row(j, up_b),
                    lo - term.strokes[j],
                    hi - term.strokes[j],
                );
                count += 1;
            }
        }
        let mut lift = Motion::zeros();
        lift[term.lift] = 1.0;
        rows[count] = (lift, 0.0, budget / term.pressing.max(f64::MIN_POSITIVE));
        count += 1;
    }
    let rows = &rows[..count];
    let mut normal = SMatrix::<f64, { 6 + MAX_LEGS }, { 6 + MAX_LEGS }>::zeros();
    for k in 6 + lifts..6 + MAX_LEGS {
        normal[(k, k)] = 1.0;
    }
    let weight = |lo: f64, hi: f64| 1.0 / (0.5 * (hi - lo)).max(f64::MIN_POSITIVE).powi(2);
    for (a, lo, hi) in rows {
        normal += a * a.transpose() * weight(*lo, *hi);
    }
    // The rows may leave part of the motion free (slack struts let the vehicle move without
    // load): a function of the motion is bounded only where it lies in the rows' span, which
    // the eigen-decomposition of AᵀWA tells (its part along the free directions is zero).
    let eigen = normal.symmetric_eigen();
    let largest = eigen.eigenvalues.max();
    let range = |phi: &Motion| -> Option<(f64, f64)> {
        let mut z = Motion::zeros();
        let mut free = 0.0;
        for (k, lambda) in eigen.eigenvalues.iter().enumerate() {
            let v = eigen.eigenvectors.column(k);
            let along = v.dot(phi);
            if *lambda > FREE_MOTION * largest {
                z += v * (along / lambda);
            } else {
                free += along * along;
            }
        }
        if free > (FREE_MOTION * phi.norm_squared()).max(0.0) {
            return None;
        }
        Some(rows.iter().fold((0.0, 0.0), |(low, high), (a, lo, hi)| {
            let g = weight(*lo, *hi) * a.dot(&z);
            (low + (g * lo).min(g * hi), high + (g * lo).max(g * hi))
        }))
    };
    for term in terms.iter_mut().filter(|t| t.bearing) {
        for j in 0..3 {
            if !term.slack[j] {
                continue;
            }
            if let Some((low, high)) = range(&term.row(j, up_b)) {
                let (lo, hi) = term.intervals[j];
                let s = term.strokes[j];
                term.intervals[j] = (lo.max(s + low), hi.min(s + high));
            }
        }
        let mut give = Vector3::zeros();
        for k in 0..3 {
            let mut phi = Motion::zeros();
            phi[k] = -1.0;
            phi.fixed_rows_mut::<3>(3)
                .copy_from(&term.bp.cross_matrix().row(k).transpose());
            phi[term.lift] = up_b[k];
            match range(&phi) {
                Some((low, high)) => give[k] = low.abs().max(high.abs()),
                None => give[k] = f64::INFINITY,
            }
        }
        term.give = term.give.min(give.norm());
    }
}

/// The map from a leg's strut loads to its force and moment on the vehicle about the centre
/// of mass (body axes), 6×3: B = Jᵀ·f, M = BP × B.
fn coupling(bp: &Vector3<f64>, jt: &Matrix3<f64>) -> SMatrix<f64, 6, 3> {
    let mut c = SMatrix::<f64, 6, 3>::zeros();
    c.fixed_rows_mut::<3>(0).copy_from(jt);
    c.fixed_rows_mut::<3>(3)
        .copy_from(&(bp.cross_matrix() * jt));
    c
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gear::{GearOptions, GearState};
    use touchdown_laws::GearMemory;
    use touchdown_scenario::schema::Arrangement;
    use touchdown_scenario::Scenario;

    /// The bundled scenario `name` (under scenarios/).
    fn bundled(name: &str) -> Scenario {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios");
        Scenario::load(root.join(name)).unwrap()
    }

    /// Table I's 2-2 landing at 10 ft/s settles before its end time: the run ends there, after
    /// its stable decision, with every outcome and maximum of the run to the end time (the
    /// strokes and the least stability distance within ε, the rest exactly).
    #[test]
    fn a_landing_proved_settled_ends_with_the_maxima_of_the_full_run() {
        let scenario = bundled("table-i-2-2-vv10.toml");
        let full = crate::run(&scenario).unwrap();
        let eps = 0.001 * 0.3048; // 0.001 ft, as docs/errata.md measures it
        let mut settled = scenario.clone();
        settled.stability.settled_tolerance = Some(eps);
        let early = crate::run(&settled).unwrap();
        let t = early.settled_time_s.expect("it settles");
        assert_eq!(early.t_end_s, t);
        assert!(t < full.t_end_s && t > early.decision_time_s.unwrap());
        assert_eq!(full.settled_time_s, None);
        assert_eq!(early.outcome, full.outcome);
        let strokes = |s: &touchdown_record::Summary| {
            let mut v = s.max_primary_stroke_m.clone();
            for (c, t) in s
                .max_secondary_compression_m
                .iter()
                .zip(&s.max_secondary_tension_m)
            {
                v.extend(c.iter().chain(t));
            }
            v.push(s.min_stability_distance_m);
            v
        };
        for (a, b) in strokes(&full).iter().zip(strokes(&early)) {
            assert!((a - b).abs() <= eps, "{a} vs {b}");
        }
        assert_eq!(early.peak_primary_force_n, full.peak_primary_force_n);
        assert_eq!(
            early.peak_secondary_tension_force_n,
            full.peak_secondary_tension_force_n
        );
        assert_eq!(
            early.peak_secondary_compression_force_n,
            full.peak_secondary_compression_force_n
        );
        assert_eq!(
            early.peak_specific_force_m_s2,
            full.peak_specific_force_m_s2
        );
        assert_eq!(early.peak_pitch_rate_rad_s, full.peak_pitch_rate_rad_s);
        assert_eq!(
            [early.min_pitch_rate_rad_s, early.max_pitch_rate_rad_s],
            [full.min_pitch_rate_rad_s, full.max_pitch_rate_rad_s]
        );
        assert!(early.steps < full.steps);
    }

    /// The closed-form stroke gradient is the gear's own strokes differentiated.
    #[test]
    fn the_stroke_jacobian_differentiates_the_gears_strokes() {
        let scenario = bundled("table-i-2-2-vv8.toml");
        let laws = touchdown_laws::GearLaws::from_scenario(&scenario).unwrap();
        let leg = &scenario.legs[0];
        let options = GearOptions {
            arrangement: Arrangement::Cantilever,
            bending: None,
        };
        let strokes = |bp: &Vector3<f64>| {
            let mut g = GearState::default();
            crate::gear::evaluate(
                leg,
                &laws,
                &GearMemory::default(),
                bp,
                &Vector3::zeros(),
                &options,
                &mut g,
            )
            .unwrap();
            Vector3::new(
                g.primary_stroke,
                g.secondary_stroke[0],
                g.secondary_stroke[1],
            )
        };
        let bp = leg.bp + Vector3::new(0.003, -0.002, 0.01);
        let j = stroke_jacobian(leg, &bp);
        let h = 1e-6 * leg.l2p;
        for k in 0..3 {
            let mut d = Vector3::zeros();
            d[k] = h;
            let numeric = (strokes(&(bp + d)) - strokes(&(bp - d))) / (2.0 * h);
            assert!(
                (numeric - j.column(k)).norm() < 1e-7,
                "{numeric} vs {}",
                j.column(k)
            );
        }
    }
}

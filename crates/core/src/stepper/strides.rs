//! The `strides` scheme's corrector of the vehicle: the struts of every footpad on its surface
//! taken implicitly, so that the vehicle's modes on its gear bound no step (docs/errata.md,
//! "Long strides where the gear is soft", item 2).
//!
//! The vehicle's displacement from its prediction, y = (δR, δφ) (inertial metres, inertial
//! radians, δφ = T_BI·T_EB·δθ), moves a footpad fixed on its surface by
//! δBP = −T_IB·δR + BP×(T_IB·δφ) in body axes, and strut j's stroke by g_jᵀ·y with
//! g_j = (−T_BI·ŵ_j, T_BI·(ŵ_j×BP)), ŵ_j the stroke's gradient in BP
//! ([`gear::stroke_gradients`]). Linearised about the prediction, each strut's force changes
//! by k_j·g_jᵀ·y (k_j its law's secant over the step), and the vehicle's accelerations by
//! −M_y⁻¹·K·y with K = Σ_j k_j·g_jg_jᵀ, M_y = diag(M·I, T_BI·J·T_IB). Both halves of y are in
//! inertial axes so that a landing's mirror image, which may swap body axes (the 2-2 landing's
//! plane of symmetry is a diagonal of them), only changes signs of y: the factorisation below
//! then mirrors bit for bit (docs/errata.md, "Decisions at rounding level"). The report's
//! corrector (eqs. 22-24) q₁ = q_k + q̇_k·Δt + (q̈_k/3 + q̈₁/6)·Δt², q̇₁ = q̇_k + (q̈_k + q̈₁)·Δt/2
//! with q̈₁ the acceleration at the corrected state, so linearised, gives for δq = q₁ − q*
//!
//!   (M_y + Δt²/6·K)·y = M_y·(q̈* − q̈_k)·Δt²/6   (in y's axes),
//!
//! symmetric positive definite, solved by Cholesky; q̇₁ = q̇_k + q̈_k·Δt + 3·δq/Δt. With K = 0
//! it is the report's corrector (q̈₁ = q̈*); on linear laws it is Newmark's linear-acceleration
//! rule (β = 1/6, γ = 1/2), stable on an undamped mode for ω·Δt ≤ √12 and without numerical
//! damping below it (`tests::the_corrector_is_newmarks_linear_acceleration_rule`). Each
//! strut's force changes by k_j·g_jᵀ·y in the trial's forces, so that the ledger books what
//! the vehicle felt.

use super::secant::strut_secants;
use super::Scratch;
use crate::gear::{self, GearState};
use crate::model::Model;
use crate::state::State;
use crate::surface::ContactState;
use crate::vehicle::VehicleState;
use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};

/// One footpad on its surface linearised about the prediction: its body-frame position BP (m),
/// its struts' stroke gradients in BP (body axes, primary compression and the secondaries'
/// tension) and their laws' secants over the step (N/m).
#[derive(Debug, Clone, Copy)]
pub(super) struct Engaged {
    bp: Vector3<f64>,
    gradients: [Vector3<f64>; 3],
    rates: [f64; 3],
}

impl Engaged {
    /// Leg `i` of `state` with the vehicle predicted at `pred`, if its footpad is on its
    /// surface; its gear at the start of the step and at the trial in `gear`.
    fn new(
        model: &Model,
        state: &State,
        (previous, trial): (&[GearState], &[GearState]),
        pred: &VehicleState,
        i: usize,
    ) -> Option<Engaged> {
        let pad = &state.pads[i];
        if pad.state != ContactState::Contact {
            return None;
        }
        let leg = &model.legs[i];
        let bp = pred.t_bi.transpose() * (pad.position - pred.position);
        let gradients = gear::stroke_gradients(leg, model.arrangement, &bp);
        let rates = strut_secants(leg, &model.laws, &previous[i], &trial[i]);
        Some(Engaged {
            bp,
            gradients,
            rates,
        })
    }

    /// Strut j's gradient g_j in y = (δR, δφ), with `t_bi` the predicted T_BI.
    fn generalised(&self, t_bi: &Matrix3<f64>, j: usize) -> Vector6<f64> {
        generalised(t_bi, &self.bp, &self.gradients[j])
    }

    /// K's share of this footpad, Σ_j k_j·g_jg_jᵀ, its lower triangle (the upper is zero): the
    /// primary's term and the two secondaries' sum, which a mirror that swaps them leaves the
    /// same.
    fn stiffness(&self, t_bi: &Matrix3<f64>) -> Matrix6<f64> {
        let term = |j: usize| {
            let mut k = Matrix6::zeros();
            if self.rates[j] > 0.0 {
                let g = self.generalised(t_bi, j);
                let kg = g * self.rates[j];
                for c in 0..6 {
                    for r in c..6 {
                        k[(r, c)] = kg[r] * g[c];
                    }
                }
            }
            k
        };
        term(0) + (term(1) + term(2))
    }
}

/// Step 5 of the `strides` scheme for the vehicle (the module's documentation): from the
/// accepted state `old` and the prediction `pred` with its trial accelerations, the corrected
/// vehicle written into `scratch.new` (slosh aside: the caller corrects it) and each engaged
/// strut's force change put into the trial's forces (`scratch.trial`).
pub(super) fn correct_vehicle(
    model: &Model,
    state: &State,
    scratch: &mut Scratch,
    pred: &VehicleState,
    old: &VehicleState,
    dt: f64,
) {
    let t_bi = &pred.t_bi;
    let gear = (&scratch.previous[..], &scratch.trial[..]);
    for (i, e) in scratch.engaged.iter_mut().enumerate() {
        *e = Engaged::new(model, state, gear, pred, i);
    }
    let engaged = &scratch.engaged;
    let stiffness = (model.sum_order).sum_by(Matrix6::zeros(), |i| {
        engaged[i].map_or(Matrix6::zeros(), |e| e.stiffness(t_bi))
    });
    let mut inertia = Matrix6::zeros();
    let mass = &model.mass;
    inertia
        .fixed_view_mut::<3, 3>(0, 0)
        .fill_diagonal(mass.mass);
    inertia
        .fixed_view_mut::<3, 3>(3, 3)
        .copy_from(&(t_bi * mass.inertia * t_bi.transpose()));
    let translation = pred.acceleration - old.acceleration;
    let rotation = t_bi * (pred.euler.t_eb() * (pred.theta_ddot - old.theta_ddot));
    let change = Vector6::new(
        translation.x,
        translation.y,
        translation.z,
        rotation.x,
        rotation.y,
        rotation.z,
    );
    let y = correction(&inertia, &stiffness, &change, dt);
    let d_r = Vector3::new(y[0], y[1], y[2]);
    let d_phi = t_bi.transpose() * Vector3::new(y[3], y[4], y[5]);
    let d_theta = pred.euler.t_be() * d_phi;
    let new = &mut scratch.new;
    *new = *old;
    new.position = pred.position + d_r;
    new.velocity = old.velocity + old.acceleration * dt + d_r * (3.0 / dt);
    new.set_attitude(
        pred.euler.theta + d_theta,
        old.theta_dot + old.theta_ddot * dt + d_theta * (3.0 / dt),
    );
    // The trial's forces changed as the vehicle's did: the ledger books the struts' work with
    // them (eq. 24's trapezoid), and the gear's force on each footpad changes by
    // −Σ_j ŵ_j·ΔF_j (virtual work on the massless gear).
    for (e, slot) in scratch.engaged.iter().zip(scratch.trial.iter_mut()) {
        let Some(e) = e else { continue };
        let d_bp = -(t_bi.transpose() * d_r) + e.bp.cross(&d_phi);
        let df = [0, 1, 2].map(|j| e.rates[j] * e.gradients[j].dot(&d_bp));
        slot.fcp += df[0];
        slot.f2p += df[0];
        slot.fc_secondary[0] += df[1];
        slot.fc_secondary[1] += df[2];
        slot.fp -= e.gradients[0] * df[0] + e.gradients[1] * df[1] + e.gradients[2] * df[2];
    }
}

/// The gradient g = (−T_BI·ŵ, T_BI·(ŵ×BP)) in y = (δR, δφ) of a stroke whose gradient in the
/// footpad's body-frame position `bp` (m) is `w`, the footpad fixed on its surface and the
/// vehicle's attitude `t_bi` (T_BI): a displacement y moves the footpad by
/// δBP = −T_IB·δR + BP×(T_IB·δφ) relative to the body.
fn generalised(t_bi: &Matrix3<f64>, bp: &Vector3<f64>, w: &Vector3<f64>) -> Vector6<f64> {
    let r = -(t_bi * w);
    let phi = t_bi * w.cross(bp);
    Vector6::new(r.x, r.y, r.z, phi.x, phi.y, phi.z)
}

/// The corrected state's displacement from the prediction y (m and rad, in y's axes) of a
/// body of inertia `inertia` (kg and kg·m²) on springs of stiffness `stiffness` (its lower
/// triangle, N/m and N·m/rad) over a step of `dt` (s), its accelerations changed by `change`
/// (q̈* − q̈_k in y's axes) from the start of the step to the prediction: the solution of
/// (M_y + Δt²/6·K)·y = M_y·(q̈* − q̈_k)·Δt²/6 (the module's documentation).
fn correction(
    inertia: &Matrix6<f64>,
    stiffness: &Matrix6<f64>,
    change: &Vector6<f64>,
    dt: f64,
) -> Vector6<f64> {
    let h = dt * dt / 6.0;
    let uncorrected = change * h;
    // M_y plus a positive semi-definite matrix (its lower triangle is what the factorisation
    // reads): it fails only on a NaN, which the step's divergence guard then reports.
    (inertia + stiffness * h)
        .cholesky()
        .map_or(uncorrected, |c| c.solve(&(inertia * uncorrected)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One undamped mode ẍ = −ω²·x in each of y's six axes, stepped as the `strides` scheme
    /// steps the vehicle on its engaged struts: predicted, evaluated, corrected through
    /// [`correction`], evaluated again at the corrected state. Returns the largest energy
    /// ½·(ẋ² + ω²·x²) reached over `steps` steps of ω·Δt = `h`, from 1 at the start.
    fn largest_energy(h: f64, steps: usize) -> f64 {
        let (omega, mass) = (50.0, 3.0);
        let dt = h / omega;
        let inertia = Matrix6::identity() * mass;
        let mut stiffness = Matrix6::zeros();
        stiffness.fill_diagonal(mass * omega * omega);
        let (mut x, mut v) = (Vector6::repeat(1.0 / omega), Vector6::zeros());
        let mut a = -x * omega * omega;
        let energy =
            |x: &Vector6<f64>, v: &Vector6<f64>| 0.5 * (v[0] * v[0] + omega * omega * x[0] * x[0]);
        let mut largest: f64 = energy(&x, &v);
        for _ in 0..steps {
            let predicted = x + v * dt + a * (0.5 * dt * dt);
            let trial = -predicted * omega * omega;
            let y = correction(&inertia, &stiffness, &(trial - a), dt);
            x = predicted + y;
            v += a * dt + y * (3.0 / dt);
            a = -x * omega * omega;
            largest = largest.max(energy(&x, &v));
        }
        largest
    }

    /// Newmark's linear-acceleration rule on an undamped mode: its energy stays within a
    /// bounded band (no growth, no numerical damping to speak of) for ω·Δt below √12 ≈ 3.46,
    /// the bound `IMPLICIT_MODE_STEP` = 3 keeps every mode under, and grows without bound
    /// past it; the report's explicit corrector is unstable past ω·Δt = 2.
    #[test]
    fn the_corrector_is_newmarks_linear_acceleration_rule() {
        for h in [0.5, 1.0, 2.0, 3.0, 3.4] {
            let e = largest_energy(h, 20_000);
            assert!(e < 10.0, "ω·Δt = {h}: energy reached {e}");
        }
        assert!(largest_energy(3.6, 2_000) > 1e6);
        assert!(3.0 < 12f64.sqrt());
    }

    /// The gradient in y of a primary's compression stroke c = L2P − |BP − B2| against
    /// central differences of the stroke with the vehicle moved by δR (inertial) and turned
    /// by δφ (inertial axes) and the footpad held where it is.
    #[test]
    fn a_strokes_gradient_in_the_vehicles_displacement_is_its_central_difference() {
        use nalgebra::Rotation3;
        let t_bi = *Rotation3::from_euler_angles(0.3, -0.2, 0.7).matrix();
        let position = Vector3::new(0.4, -1.1, 2.0);
        let pad = Vector3::new(1.9, 0.3, -0.1);
        let (b2, l2p) = (Vector3::new(0.8, 0.2, 0.5), 1.6);
        let stroke = |y: &Vector6<f64>| {
            let turn = Rotation3::from_scaled_axis(Vector3::new(y[3], y[4], y[5]));
            let t = turn.matrix() * t_bi;
            let bp = t.transpose() * (pad - position - Vector3::new(y[0], y[1], y[2]));
            l2p - (bp - b2).norm()
        };
        let bp = t_bi.transpose() * (pad - position);
        let w = -(bp - b2).normalize();
        let g = generalised(&t_bi, &bp, &w);
        let eps = 1e-6;
        for i in 0..6 {
            let mut d = Vector6::zeros();
            d[i] = eps;
            let numeric = (stroke(&d) - stroke(&-d)) / (2.0 * eps);
            assert!(
                (numeric - g[i]).abs() < 1e-8,
                "axis {i}: {numeric} against {}",
                g[i]
            );
        }
    }

    /// With no engaged strut the correction is the report's corrector, δq = (q̈* − q̈_k)·Δt²/6,
    /// to rounding (the factorisation divides by √M twice).
    #[test]
    fn with_no_stiffness_the_correction_is_the_reports() {
        let inertia = Matrix6::from_diagonal(&Vector6::new(2.0, 2.0, 2.0, 0.3, 0.4, 0.5));
        let change = Vector6::new(1.0, -2.0, 3.0, 0.25, -0.5, 7.0);
        let dt = 1.7e-4;
        let y = correction(&inertia, &Matrix6::zeros(), &change, dt);
        let h = dt * dt / 6.0;
        for i in 0..6 {
            let expected = change[i] * h;
            assert!(
                (y[i] - expected).abs() <= 4.0 * f64::EPSILON * expected.abs(),
                "axis {i}"
            );
        }
    }
}

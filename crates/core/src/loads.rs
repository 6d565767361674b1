//! Net loads on the vehicle and its accelerations: each gear evaluated at its footpad
//! (eqs. 26-65), the gear's force and moment on the vehicle (eqs. 66-68), the
//! vehicle-level mechanisms' loads added (eqs. 83-84), and the rigid-vehicle accelerations
//! (eqs. 9-15, slosh eq. 109).

use crate::gear::{self, GearOptions, GearState, PrimaryAxis};
use crate::mechanisms::Power;
use crate::model::Model;
use crate::state::State;
use crate::stiction::{held_friction, Held};
use crate::surface::{ContactState, Footpad};
use crate::vehicle::VehicleState;
use nalgebra::Vector3;
use touchdown_frames::GIMBAL_LOCK_COS;
use touchdown_record::{Law, RunError};
use touchdown_scenario::model::Mechanism;
use touchdown_scenario::schema::{Arrangement, AttitudeForm};

/// Net loads on the vehicle (eqs. 66-68, 83-84): force in inertial axes excluding gravity,
/// torque in body axes, and the power of the vehicle-level mechanisms (thrust, nozzle, RCS,
/// slosh) on the vehicle.
pub(crate) struct Loads {
    /// Net force, inertial axes, N.
    pub(crate) force: Vector3<f64>,
    /// Net torque about the centre of mass, body axes, N·m.
    pub(crate) torque: Vector3<f64>,
    /// Power of the vehicle-level mechanisms on the vehicle, W.
    pub(crate) applied_power: Power,
}

/// Time of the first contact of any of `pads`, s.
fn first_contact(pads: &[Footpad]) -> Option<f64> {
    pads.iter().filter_map(|p| p.first_contact).reduce(f64::min)
}

impl State {
    /// Gear forces and net loads on the vehicle at `v` with the footpads as they are now,
    /// written into `out` (eqs. 26-68, 83-84). A gear carries its footpad's load in contact and,
    /// with inertia, off the surface (docs/errata.md, "Eq. (66): only pads in contact —
    /// interpreted"); a rigid footpad off the surface carries none.
    pub(crate) fn loads(
        &mut self,
        model: &Model,
        t: f64,
        v: &VehicleState,
        out: &mut [GearState],
    ) -> Result<Loads, RunError> {
        self.loads_at(model, t, v, 1.0, out)
    }

    /// [`State::loads`] with each sliding footpad a fraction `blend` of the way from its
    /// start of step to where it is now (a Runge–Kutta stage; 1 is now); the footpads off the
    /// surface are where the stage put them.
    pub(crate) fn loads_at(
        &mut self,
        model: &Model,
        t: f64,
        v: &VehicleState,
        blend: f64,
        out: &mut [GearState],
    ) -> Result<Loads, RunError> {
        // Each leg's load, summed below in the order of crate::summation.
        let (mut leg_force, mut leg_torque) = std::mem::take(&mut self.leg_loads);
        let mut held = std::mem::take(&mut self.held);
        held.clear();
        let friction = model.arrangement == Arrangement::Cantilever
            && model.laws.primary.bearing.friction_coefficient > 0.0;
        for (i, slot) in out.iter_mut().enumerate() {
            let pad = &self.pads[i];
            let free = pad.state != ContactState::Contact;
            if free && !model.inertial {
                // The report's rigid footpad off the surface: its massless gear carries nothing.
                let prev = &self.gear[i];
                *slot = GearState {
                    primary_stroke: prev.primary_stroke,
                    secondary_stroke: prev.secondary_stroke,
                    ..GearState::default()
                };
                leg_force[i] = Vector3::zeros();
                leg_torque[i] = Vector3::zeros();
                continue;
            }
            let (position, velocity) = if blend >= 1.0 || free {
                (pad.position, pad.velocity)
            } else {
                let (p0, v0) = self.pad_start[i];
                (p0.lerp(&pad.position, blend), v0.lerp(&pad.velocity, blend))
            };
            let (bp, bp_dot, primary) =
                self.evaluate_leg(model, i, v, &position, &velocity, slot)?;
            if free && friction {
                // Off the surface the bearing friction is set below, once the vehicle's
                // acceleration without it is known (crate::stiction).
                let h = Held {
                    leg: i,
                    bp,
                    bp_dot,
                    primary,
                };
                slot.f2p -= slot.fbr;
                slot.fp -= h.primary.axis * slot.fbr;
                slot.fbr = 0.0;
                held.push(h);
            }
            leg_torque[i] = bp.cross(&(-slot.fp)); // eq. (66)
            leg_force[i] = -(v.t_bi * slot.fp); // eqs. (67)-(68)
        }
        // eqs. (72)-(74), (80)-(82), (115)-(117): the scene's vehicle-level mechanisms, if any.
        let (mut applied_force, mut applied_torque) = (Vector3::zeros(), Vector3::zeros());
        let mut applied_power = Power::default();
        let pads = &self.pads;
        if let Some(a) =
            (model.mechanisms).vehicle_loads(&mut self.mechanisms, t, || first_contact(pads), v)
        {
            (applied_force, applied_torque) = (v.t_bi * a.force, a.torque);
            applied_power = Power {
                applied: applied_force.dot(&v.velocity) + a.torque.dot(&v.omega),
                driving: a.driving_power(&(v.t_bi.transpose() * v.velocity), &v.omega),
            };
        }
        // eqs. (83)-(84): the legs' loads in the order of crate::summation, and the mechanisms'.
        let order = &model.sum_order;
        let total = |f: &[Vector3<f64>], q: &[Vector3<f64>]| {
            let (force, torque) = order.sum_loads(f, q);
            (force + applied_force, torque + applied_torque)
        };
        let (mut force, mut torque) = total(&leg_force, &leg_torque);
        if !held.is_empty() {
            let acceleration = model.mass.linear_acceleration(&force, &model.gravity);
            let omega_dot = model.mass.angular_acceleration(&torque, &v.omega);
            for h in &held {
                let slot = &mut out[h.leg];
                let walled = self.pads[h.leg].walled;
                let fbr = held_friction(model, walled, h, slot, v, &acceleration, &omega_dot)
                    .map_err(|e| {
                        self.diverged(v, e.to_string(), Law::BearingFriction, Some(h.leg))
                    })?;
                let on_pad = h.primary.axis * fbr;
                slot.fbr = fbr;
                slot.f2p += fbr;
                slot.fp += on_pad;
                leg_torque[h.leg] += h.bp.cross(&(-on_pad)); // eq. (66)
                leg_force[h.leg] -= v.t_bi * on_pad; // eqs. (67)-(68)
            }
            (force, torque) = total(&leg_force, &leg_torque);
        }
        self.leg_loads = (leg_force, leg_torque);
        self.held = held;
        Ok(Loads {
            force,
            torque,
            applied_power,
        })
    }

    /// Evaluates gear `i` (eqs. 26-65) into `slot` with the vehicle at `v` and its footpad at
    /// `position` moving at `velocity` (inertial, m and m/s); returns the footpad's body-frame
    /// position BP and its velocity relative to the body ḂP in body axes, m and m/s, and the
    /// primary strut's axis and length there.
    pub(crate) fn evaluate_leg(
        &mut self,
        model: &Model,
        i: usize,
        v: &VehicleState,
        position: &Vector3<f64>,
        velocity: &Vector3<f64>,
        slot: &mut GearState,
    ) -> Result<(Vector3<f64>, Vector3<f64>, PrimaryAxis), RunError> {
        let t_ib = v.t_bi.transpose();
        let bp = t_ib * (position - v.position);
        let bp_dot = t_ib * (velocity - v.velocity) - v.omega.cross(&bp);
        if model.arrangement == Arrangement::Tripod {
            self.mechanisms.tick(Mechanism::Tripod);
        }
        if model.mechanisms.bending.is_some() {
            self.mechanisms.tick(Mechanism::Bending);
        }
        let options = GearOptions {
            arrangement: model.arrangement,
            bending: (model.mechanisms.bending.as_ref()).map(|b| (b, self.bending_lag[i])),
        };
        let primary = gear::evaluate(
            &model.legs[i],
            &model.laws,
            &self.memory[i],
            &bp,
            &bp_dot,
            &options,
            slot,
        )
        .map_err(|f| self.diverged(v, f.error.to_string(), f.law, Some(i)))?;
        Ok((bp, bp_dot, primary))
    }

    /// Accelerations of `v` under `loads`: eqs. (10)-(12), (13)-(15) and (9a)-(9c); the slosh
    /// amplitude's by eq. (109), corrected.
    pub(crate) fn accelerate(
        &self,
        model: &Model,
        v: &mut VehicleState,
        loads: &Loads,
    ) -> Result<(), RunError> {
        let euler = model.integrator.attitude == AttitudeForm::Euler;
        // θy stays within ±90° unless it crossed the singularity (cos θy < 0 beyond).
        if euler && v.euler.cos.y < GIMBAL_LOCK_COS {
            return Err(self.diverged(v,
                "Euler-angle singularity: θy reached or crossed ±90° (eqs. 5 and 9a divide by cos θy); integrator.attitude = \"quaternion\" (schemes rk4, dopri5) goes through it".into(),
                Law::Kinematics,
                None,
            ));
        }
        v.acceleration = model.mass.linear_acceleration(&loads.force, &model.gravity);
        v.omega_dot = model.mass.angular_acceleration(&loads.torque, &v.omega);
        if euler {
            v.theta_ddot = (v.euler).euler_acceleration(&v.theta_dot, &v.omega, &v.omega_dot);
        }
        v.slosh_q_ddot = (model.mechanisms).slosh_acceleration(&self.mechanisms, v); // eq. (109), corrected
        Ok(())
    }
}

//! Steps 6-8 of a step, the same for every scheme (see [`crate::stepper`]): the new state is
//! evaluated and accepted, the contact logic runs, the honeycomb memories are committed, the
//! work of the step is booked, the divergence checks run and the stability criteria (eqs.
//! 105-107) and the running extremes are updated.

use crate::gear::GearState;
use crate::ledger::Quadrature;
use crate::mechanisms::Power;
use crate::model::Model;
use crate::state::State;
use crate::stepper::{Advance, Scratch};
use crate::surface::ContactState;
use crate::vehicle::VehicleState;
use nalgebra::{Vector2, Vector3};
use touchdown_record::{EnergyReport, PadView, RunError};

impl State {
    /// Evaluates the accepted state `v` into `spare`, which then becomes the accepted gear
    /// states (the ones they replace go to `spare`), and sets its accelerations.
    pub(crate) fn accept(
        &mut self,
        model: &Model,
        v: &mut VehicleState,
        spare: &mut Vec<GearState>,
    ) -> Result<(), RunError> {
        let loads = self.loads(model, self.t, v, spare);
        self.evaluations += 1;
        let loads = loads?;
        self.accelerate(model, v, &loads)?;
        self.applied_power = loads.applied_power;
        std::mem::swap(&mut self.gear, spare);
        Ok(())
    }

    /// Steps 6-8 for every scheme: the new state (in the stepper's `scratch`) after `step` (its
    /// length, quadrature and footpad work) from `old` is evaluated, the contact logic runs, the
    /// hysteresis is committed, the work of the step booked (`power_old` the mechanisms' power
    /// at `old`, W), the divergence checks and the stability criteria run.
    pub(crate) fn finish_step(
        &mut self,
        model: &Model,
        old: &VehicleState,
        step: &Advance,
        power_old: Power,
        scratch: &mut Scratch,
    ) -> Result<(), RunError> {
        let Advance {
            dt,
            quadrature,
            pads,
        } = step;
        let dt = *dt;
        let Scratch {
            new,
            previous,
            trial,
            spare,
            ..
        } = scratch;
        // The curbs' work on the footpads with inertia off the surface, their force frozen over
        // the step (the footpads' energy change is in the footpad energy).
        if model.inertial && model.mechanisms.curbs.is_some() {
            let mut curbs_off_surface = 0.0;
            for (p, (p0, _)) in self.pads.iter().zip(&self.pad_start) {
                if p.state != ContactState::Contact {
                    curbs_off_surface += p.curb_xy.dot(&(p.position - p0).xy());
                }
            }
            self.ledger.mechanisms -= curbs_off_surface;
        }
        // 6. evaluate (unless the last stage did), contact logic, re-evaluate on a change
        self.t += dt;
        match quadrature {
            Quadrature::Stages {
                evaluated: Some(power),
                ..
            } => {
                std::mem::swap(&mut self.gear, trial);
                self.applied_power = *power;
            }
            _ => self.accept(model, new, spare)?,
        }
        self.vehicle = *new;
        let mut pads_energy = self.footpad_energy(model);
        if self.contact_logic(model)? {
            // The impacts' loss (and the footpads put on their planes) is a contact event.
            let pads_before = pads_energy;
            pads_energy = self.footpad_energy(model);
            self.ledger.events += pads_energy - pads_before;
            self.accept(model, new, spare)?;
            self.vehicle = *new;
        }
        self.update_pad_accelerations(model);
        // 7. commit hysteresis at the accepted state: every gear with inertial footpads (they
        // stroke on the surface or off it), the gears in contact with rigid ones
        if !model.inertial {
            for (n, p) in self.contact_steps.iter_mut().zip(&self.pads) {
                *n = if p.state == ContactState::Contact {
                    n.saturating_add(1)
                } else {
                    0
                };
            }
        }
        for i in 0..model.legs.len() {
            let pad = &self.pads[i];
            if !model.inertial && pad.state != ContactState::Contact {
                continue;
            }
            let g = &self.gear[i];
            model
                .laws
                .commit(g.primary_stroke, g.secondary_stroke, &mut self.memory[i]);
            self.bending_lag[i] = g.point1_deflection;
            // A curb is crushed by a footpad on the surface, and by one with inertia off it.
            let crushing = pad.state == ContactState::Contact
                || (model.inertial && pad.first_contact.is_some());
            if let (Some(curbs), true) = (&model.mechanisms.curbs, crushing) {
                let xy = Vector2::new(pad.position.x, pad.position.y);
                curbs.commit(
                    &mut self.mechanisms.curb_memory,
                    i,
                    pad.touchdown_xy,
                    xy,
                    model.footpad_radius,
                );
            }
        }
        (model.mechanisms).commit(&mut self.mechanisms, new, &model.gravity);
        // Work of the vehicle-level mechanisms on the vehicle with the forces the step used
        // (the report: trapezoid of their power), and of the soil and curbs on the footpads.
        let applied_work = match quadrature {
            Quadrature::Trapezoid { trial_power } => 0.5 * (power_old.applied + trial_power) * dt,
            Quadrature::Stages { work, .. } => work.applied,
        };
        self.ledger.mechanisms += -applied_work - pads.soil - pads.curbs;
        // The energy the driving mechanisms put in (a trapezoid of their positive power at the
        // accepted states): the balance's scale, not the balance (docs/errata.md, "Energy guard").
        let driving = 0.5 * (power_old.driving.max(0.0) + self.applied_power.driving.max(0.0));
        self.ledger.driving_input += driving * dt;
        self.ledger.sliding += pads.gear + pads.curbs + pads.soil - pads.energy_change;
        self.book_strut_work(dt, quadrature, previous, trial);
        self.steps += 1;
        // The footpads have not moved since the contact logic: their energy is the same.
        let energy = self.energy_with_footpads(model, pads_energy);
        self.check_divergence(model, &energy)?;
        self.update_stability(model, Some(old), &energy);
        self.update_extremes();
        self.extremes.update_acceleration(
            &old.velocity,
            &self.vehicle.velocity,
            dt,
            &model.gravity,
        );
        self.extremes.follow(&self.stability);
        Ok(())
    }

    /// Stability distances, the unstable crossing and the four stable conditions
    /// (eqs. 105-107, `touchdown_record::stability`). `old` is the previous accepted vehicle
    /// state, `energy` the energy report of this state.
    pub(crate) fn update_stability(
        &mut self,
        model: &Model,
        old: Option<&VehicleState>,
        energy: &EnergyReport,
    ) {
        for i in 0..self.pads.len() {
            let p = &self.pads[i];
            self.pad_views[i] = PadView {
                position: self.pad_position(model, i),
                in_contact: p.state == ContactState::Contact,
                touched: p.first_contact.is_some(),
            };
        }
        let v = &self.vehicle;
        self.stability.update(
            self.t,
            &v.position,
            &v.velocity,
            old.map(|o| &o.velocity),
            energy,
            &self.pad_views,
        );
    }

    /// Inertial position of footpad `i`, m: a rigid footpad off the surface where its gear
    /// holds it.
    fn pad_position(&self, model: &Model, i: usize) -> Vector3<f64> {
        let p = &self.pads[i];
        if model.inertial || p.state == ContactState::Contact {
            p.position
        } else {
            self.vehicle.point(&p.bp_attached)
        }
    }

    /// The accelerations of the footpads with inertia off the surface at the accepted state
    /// (eqs. 16-18), their gears evaluated there.
    pub(crate) fn update_pad_accelerations(&mut self, model: &Model) {
        if !model.inertial {
            return;
        }
        for i in 0..self.pads.len() {
            if self.pads[i].state != ContactState::Contact {
                self.pads[i].acceleration =
                    self.pad_acceleration(model, i, &self.vehicle, &self.gear[i]);
            }
        }
    }

    /// Running maxima of strokes, strut forces and the pitch rate (angular velocity about the
    /// inertial X axis).
    pub(crate) fn update_extremes(&mut self) {
        for (i, g) in self.gear.iter().enumerate() {
            self.extremes.update_leg(
                self.t,
                i,
                g.primary_stroke,
                g.secondary_stroke,
                g.f2p,
                g.f_secondary(),
            );
        }
        self.extremes
            .update_pitch_rate(self.t, self.vehicle.omega_inertial().x);
    }
}

//! Footpads on the surface: the contact logic (text before eq. 85, after eq. 100;
//! docs/errata.md, "Footpads with inertia (eqs. 16-19, 85-100) — extended"): a footpad with
//! inertia lands as a plastic impact of its own mass, stays while the surface pushes it and
//! leaves when the surface would have to pull (the report's rigid detached footpad is in
//! `core::release`); the frozen in-plane forces on a sliding footpad
//! (eqs. 85, 96-99 corrected) and its advance over a step (eq. 97, soil eqs. 101-104, curbs
//! eqs. 86-95), and the location of landings by the adaptive scheme.

use crate::gear::GearState;
use crate::ledger::PadWork;
use crate::model::Model;
use crate::state::SlidingStart;
use crate::state::State;
use crate::surface::{advance_sliding, touch_down, ContactState, Footpad, SlidingForces};
use crate::vehicle::VehicleState;
use nalgebra::{Vector2, Vector3};
use touchdown_laws::sliding::VELOCITY_ROUNDING;
use touchdown_laws::sliding_friction;
use touchdown_record::RunError;
use touchdown_scenario::model::Mechanism;
use touchdown_scenario::schema::ReleaseRule;

/// The load footpad presses its surface with, N: the gear's FZI (eq. 67, positive pressing it
/// in) and the footpad's own weight normal to the surface, PMASS·(−g_z) (docs/errata.md,
/// "Eq. (85): FDRAG is FDRAGP"): the surface's normal reaction on a footpad resting on it, the
/// normal load of its friction and the soil's vertical load (eq. 103).
fn surface_reaction(model: &Model, fzi: f64) -> f64 {
    fzi - model.footpad_mass * model.gravity.z
}

/// How far past its plane a footpad off the surface may be at the end of an adaptive step
/// before the step is shortened to locate its landing, m.
pub const CONTACT_EVENT_DEPTH: f64 = 1e-9;

impl State {
    /// Contact logic of the surface (text before eq. 85) at the accepted state, the gear
    /// evaluated there, for the scene's footpads: with inertia ([`State::inertial_contact`]) or
    /// the report's rigid detached footpad ([`State::rigid_contact`]). Returns whether any
    /// footpad changed state or was moved.
    pub(crate) fn contact_logic(&mut self, model: &Model) -> Result<bool, RunError> {
        let mut changed = false;
        for i in 0..self.pads.len() {
            changed |= if model.inertial {
                self.inertial_contact(model, i)?
            } else {
                self.rigid_contact(model, i)?
            };
        }
        Ok(changed)
    }

    /// The contact logic of footpad `i` with inertia (docs/errata.md, "Footpads with inertia"):
    /// off the surface, once it has reached its plane (below it, or within
    /// [`Model::contact_tolerance`] and approaching) it meets it in a plastic impact of its
    /// own mass: it is put on the plane and loses its normal velocity on the rigid surface (the
    /// energy lost is a contact event), and stays in contact unless the surface would have to
    /// pull it there at once. In contact it leaves as soon as the surface would have to pull it
    /// ([`State::leaves`]), keeping its position and velocity: its gear keeps its strokes and
    /// loads. Returns whether it changed state or was moved.
    fn inertial_contact(&mut self, model: &Model, i: usize) -> Result<bool, RunError> {
        let soil = model.mechanisms.soil.is_some();
        let s = model.surfaces[i];
        let plane = s.plane();
        if self.pads[i].state == ContactState::Contact {
            if self.leaves(model, i, &self.vehicle, &self.gear[i]) {
                let pad = &mut self.pads[i];
                pad.state = ContactState::Detached;
                pad.stuck = false;
                return Ok(true);
            }
            return Ok(false);
        }
        let pad = &mut self.pads[i];
        if pad.walled && pad.position.z > plane + s.hold_height() {
            pad.walled = false; // above its obstacle's wall, or its spikes out of the ground
        }
        let pad = *pad;
        // Decisions at rounding level: a footpad within the contact tolerance of its plane
        // lands if it approaches it faster than rounding (docs/errata.md, "Decisions at
        // rounding level").
        let tol = model.contact_tolerance;
        let v_cm = self.vehicle.velocity;
        let speed = (pad.velocity - v_cm).norm() + v_cm.norm();
        let below = pad.position.z < plane - tol;
        let touching = pad.position.z <= plane + tol && pad.velocity.z < -VELOCITY_ROUNDING * speed;
        if !(below || touching) {
            return Ok(false);
        }
        let vel = pad.velocity;
        // The landing (rare) evaluates the gear through `&mut self`: the vehicle is copied.
        let v = self.vehicle;
        self.put_down(model, i, &pad.position, &vel);
        // Its gear on the plane after the impact: a rigid surface that would have to pull it
        // there at once takes the impact and lets it go (on soil it penetrates, and leaves by
        // the soil's rule).
        let landed = self.pads[i];
        let mut g = GearState::default();
        self.evaluate_leg(model, i, &v, &landed.position, &landed.velocity, &mut g)?;
        if !soil && self.pressing(model, &v, &g) < -model.force_rounding {
            self.pads[i] = Footpad {
                position: Vector3::new(pad.position.x, pad.position.y, plane),
                velocity: Vector3::new(landed.velocity.x, landed.velocity.y, vel.z.max(0.0)),
                first_contact: landed.first_contact,
                touchdown_xy: landed.touchdown_xy,
                walled: landed.walled,
                ..pad
            };
        }
        Ok(true)
    }

    /// Puts footpad `i`, reaching its plane at `position` with velocity `velocity` (inertial,
    /// m and m/s), into contact (text before eq. 86): against a curb's face if it lands again
    /// inside a curb's crushed zone (`laws::curb::Curbs::landing`: it does not crush the curb
    /// without work), with its normal velocity lost on the rigid surface and kept on soil,
    /// where it penetrates (eq. 103).
    pub(crate) fn put_down(
        &mut self,
        model: &Model,
        i: usize,
        position: &Vector3<f64>,
        velocity: &Vector3<f64>,
    ) {
        let pad = self.pads[i];
        let v_normal = if model.mechanisms.soil.is_some() {
            velocity.z
        } else {
            0.0
        };
        let mut xy = Vector2::new(position.x, position.y);
        if let (Some(curbs), true) = (&model.mechanisms.curbs, pad.first_contact.is_some()) {
            xy = curbs.landing(
                &self.mechanisms.curb_memory,
                i,
                pad.touchdown_xy,
                xy,
                model.footpad_radius,
            );
        }
        let v_xy = Vector2::new(velocity.x, velocity.y);
        touch_down(
            &mut self.pads[i],
            &model.surfaces[i],
            xy,
            v_xy,
            v_normal,
            self.t,
        );
    }

    /// The force that keeps a footpad on its surface under the release rule, with the vehicle
    /// at `v` and its gear in state `g`, N (positive pressing): the surface's normal reaction on
    /// the footpad at rest on it, FZI (the normal component of the gear's force on it, eqs. 67,
    /// 85) plus its weight PMASS·g_n (a footpad is lifted only by a pull larger than its own
    /// weight), or, for the rigid footpad, the report's stand-ins F2P or FCP.
    pub(crate) fn pressing(&self, model: &Model, v: &VehicleState, g: &GearState) -> f64 {
        match model.release {
            ReleaseRule::GearForce => -(v.t_bi * g.fp).z - model.footpad_mass * model.gravity.z,
            ReleaseRule::StrutForce => g.f2p,
            ReleaseRule::HoneycombForce => g.fcp,
        }
    }

    /// Whether footpad `i` with inertia, in contact, leaves its surface with the vehicle in
    /// state `v` and its gear in state `g`: the surface would have to pull it (its reaction
    /// negative beyond rounding). On soil, a footpad leaves once it is no longer pressed and
    /// has risen out of the soil (docs/errata.md, "Eq. (101)").
    fn leaves(&self, model: &Model, i: usize, v: &VehicleState, g: &GearState) -> bool {
        let pressing = self.pressing(model, v, g);
        let tol = model.force_rounding;
        if model.mechanisms.soil.is_some() {
            return pressing <= tol && self.pads[i].position.z > model.surfaces[i].plane();
        }
        pressing < -tol
    }

    /// The acceleration of footpad `i` off the surface (eqs. 16-18): its gear's and its curbs'
    /// forces on it over its mass, plus gravity, with the vehicle at `v` and the gear in state `g`, m/s²;
    /// vertical only while its obstacle's wall holds it ([`Footpad::walled`]: the wall
    /// produces "a force equal and opposite to the strut forces resolved at the footpad").
    pub(crate) fn pad_acceleration(
        &self,
        model: &Model,
        i: usize,
        v: &VehicleState,
        g: &GearState,
    ) -> Vector3<f64> {
        let a = self.free_pad_acceleration(model, i, v, g);
        if self.pads[i].walled {
            Vector3::new(0.0, 0.0, a.z)
        } else {
            a
        }
    }

    /// The acceleration footpad `i` off the surface would have with nothing holding it
    /// laterally: its gear's and its curbs' forces on it over its mass, plus gravity, m/s².
    fn free_pad_acceleration(
        &self,
        model: &Model,
        i: usize,
        v: &VehicleState,
        g: &GearState,
    ) -> Vector3<f64> {
        let pad = &self.pads[i];
        let curbs = Vector3::new(pad.curb_xy.x, pad.curb_xy.y, 0.0);
        (v.t_bi * g.fp + curbs) / model.footpad_mass + model.gravity
    }

    /// The lateral force of footpad `i`'s restraint (its obstacle's wall or its spikes) on it
    /// at the accepted state, N (magnitude): while it is held ([`Footpad::walled`]), in contact
    /// or off the surface, the lateral force that keeps it from moving sideways, PMASS times
    /// the in-plane part of its free acceleration; zero once it is free.
    pub(crate) fn restraint_force(&self, model: &Model, i: usize) -> f64 {
        let pad = &self.pads[i];
        // The report's rigid footpad off the surface moves with its gear: nothing holds it.
        let rigid_off = !model.inertial && pad.state != ContactState::Contact;
        if !pad.walled || rigid_off {
            return 0.0;
        }
        let free = self.free_pad_acceleration(model, i, &self.vehicle, &self.gear[i]);
        model.footpad_mass * free.xy().norm()
    }

    /// Frozen in-plane forces on footpad `i` at the accepted state `v` (eqs. 85, 96-99
    /// corrected: the footpad receives −FPI = T_BI·FP), and the soil's lateral drag FDRAG
    /// in them (N; 0 off soil).
    fn sliding_forces(
        &mut self,
        model: &Model,
        i: usize,
        v: &VehicleState,
    ) -> (SlidingForces, f64) {
        if model.mechanisms.soil.is_some() {
            self.mechanisms.tick(Mechanism::Soil);
        }
        if model.mechanisms.curbs.is_some() {
            self.mechanisms.tick(Mechanism::Curbs);
        }
        let on_pad = v.t_bi * self.gear[i].fp; // −FPI, eq. (67) reversed
        let fzi = -on_pad.z; // FZI = (FPI)_z, positive pressing into the surface
        let pad = &self.pads[i];
        let xy = Vector2::new(pad.position.x, pad.position.y);
        let v_xy = Vector2::new(pad.velocity.x, pad.velocity.y);
        let mut soil_drag = 0.0;
        if let Some(soil) = &model.mechanisms.soil {
            // eqs. (102), (104): FGRND = FDRAG + FDRAGP, both along −v̂
            let depth = model.surfaces[i].plane() - pad.position.z;
            let sp = (xy - pad.touchdown_xy).norm();
            soil_drag = soil.lateral_drag(depth, sp, v_xy.norm());
        }
        let curb_xy = match &model.mechanisms.curbs {
            Some(curbs) => curbs.force(
                &self.mechanisms.curb_memory,
                i,
                pad.touchdown_xy,
                xy,
                v_xy,
                model.footpad_radius,
            ),
            None => Vector2::zeros(),
        };
        let forces = SlidingForces {
            gear_xy: Vector2::new(on_pad.x, on_pad.y),
            curb_xy,
            drag: sliding_friction(model.surfaces[i].friction, surface_reaction(model, fzi)) // eq. (85)
                + soil_drag,
            gravity_xy: Vector2::new(model.gravity.x, model.gravity.y),
            fzi,
            mass: model.footpad_mass,
            rounding: model.force_rounding,
        };
        (forces, soil_drag)
    }

    /// Step 2: the sliding footpads advance over `dt` (s) with their forces frozen at the
    /// accepted state `old` (eq. 97); their start is kept for the stages, and with their
    /// forces for [`State::correct_sliding_pads`].
    pub(crate) fn advance_pads(&mut self, model: &Model, dt: f64, old: &VehicleState) -> PadWork {
        let mut w = PadWork::default();
        for i in 0..self.pads.len() {
            self.pad_start[i] = (self.pads[i].position, self.pads[i].velocity);
            self.sliding_start[i] = None;
            if self.pads[i].state != ContactState::Contact {
                self.pads[i].curb_xy = self.curbs_off_surface(model, i);
                continue;
            }
            if model.surfaces[i].locked() {
                continue;
            }
            let (f, soil_drag) = self.sliding_forces(model, i, old);
            self.sliding_start[i] = Some(SlidingStart {
                stuck: self.pads[i].stuck,
                forces: f,
                soil_drag,
            });
            self.advance_pad(model, i, &f, dt, &mut w);
        }
        w
    }

    /// Step 5 for the footpads on the surface: each sliding footpad advanced again over `dt`
    /// (s) from the start of the step with the forces the vehicle's corrector uses (eq. 24),
    /// the gear's ½(F_k + F*) in the plane and FZI likewise, F* the gear's at the trial
    /// `trial` with the vehicle predicted at `pred`; the Coulomb drag on that FZI, the soil's
    /// and the curbs' forces as frozen. The footpad and the vehicle then feel the same gear
    /// force over the step, and the work it does on each is booked with it (docs/errata.md,
    /// "Sliding footpads corrected with the vehicle").
    pub(crate) fn correct_sliding_pads(
        &mut self,
        model: &Model,
        dt: f64,
        pred: &VehicleState,
        trial: &[GearState],
    ) -> PadWork {
        let mut w = PadWork::default();
        for (i, gear) in trial.iter().enumerate() {
            let Some(start) = self.sliding_start[i] else {
                continue;
            };
            let on_pad = pred.t_bi * gear.fp; // −FPI at the trial, eq. (67) reversed
            let f0 = &start.forces;
            let fzi = 0.5 * (f0.fzi + -on_pad.z);
            let f = SlidingForces {
                gear_xy: (f0.gear_xy + Vector2::new(on_pad.x, on_pad.y)) * 0.5,
                drag: sliding_friction(model.surfaces[i].friction, surface_reaction(model, fzi))
                    + start.soil_drag,
                fzi,
                ..*f0
            };
            // back to the start of the step: the advance changes nothing else of the footpad
            let pad = &mut self.pads[i];
            (pad.position, pad.velocity) = self.pad_start[i];
            pad.stuck = start.stuck;
            self.advance_pad(model, i, &f, dt, &mut w);
        }
        w
    }

    /// Footpad `i` on the surface advanced over `dt` (s) under the constant forces `f`
    /// (eq. 97; on soil eq. 103), the work of the step added to `w`.
    fn advance_pad(
        &mut self,
        model: &Model,
        i: usize,
        f: &SlidingForces,
        dt: f64,
        w: &mut PadWork,
    ) {
        let m = model.footpad_mass;
        let (p0, v0) = (self.pads[i].position, self.pads[i].velocity);
        advance_sliding(&mut self.pads[i], f, dt);
        if let Some(soil) = &model.mechanisms.soil {
            // eq. (103) with constant forces over the step; the soil only resists
            // penetration and holds a resting footpad rigid-plastically (eq. 101 row).
            let load = surface_reaction(model, f.fzi); // FZI + weight, downward positive
            let plane = model.surfaces[i].plane();
            let step = soil.advance_vertical(plane - p0.z, -v0.z, load, m, dt);
            let pad = &mut self.pads[i];
            pad.position.z = plane - step.depth;
            pad.velocity.z = -step.rate;
            w.gear -= f.fzi * (pad.position.z - p0.z);
            w.soil += step.work;
        }
        let (p1, v1) = (self.pads[i].position, self.pads[i].velocity);
        let dp = Vector2::new(p1.x - p0.x, p1.y - p0.y);
        w.gear += f.gear_xy.dot(&dp);
        w.curbs += f.curb_xy.dot(&dp);
        w.energy_change +=
            0.5 * m * (v1.norm_squared() - v0.norm_squared()) - m * model.gravity.dot(&(p1 - p0));
    }

    /// The in-plane force of its curbs on footpad `i` with inertia off the surface, after its
    /// first contact, with its forces frozen at the accepted state (eqs. 91-96), N: a curb
    /// stands on the surface beside the footpad's first contact point, and a footpad that flies
    /// into it crushes it as one that slides into it does. Zero for a rigid footpad, which does
    /// not move on its own off the surface.
    fn curbs_off_surface(&mut self, model: &Model, i: usize) -> Vector2<f64> {
        let pad = &self.pads[i];
        let Some(curbs) = &model.mechanisms.curbs else {
            return Vector2::zeros();
        };
        if !model.inertial || pad.first_contact.is_none() {
            return Vector2::zeros();
        }
        let xy = Vector2::new(pad.position.x, pad.position.y);
        let v_xy = Vector2::new(pad.velocity.x, pad.velocity.y);
        let f = curbs.force(
            &self.mechanisms.curb_memory,
            i,
            pad.touchdown_xy,
            xy,
            v_xy,
            model.footpad_radius,
        );
        self.mechanisms.tick(Mechanism::Curbs);
        f
    }

    /// Whether a footpad's contact changes within the step just taken to `v` (the gear's
    /// forces there in the trial states) so that the adaptive scheme must locate it: with
    /// inertia, a footpad off the surface that crossed its plane by more than
    /// [`CONTACT_EVENT_DEPTH`]; a footpad in contact that would leave at the step's end (the
    /// contact logic lets it go only at an accepted state, so over the rest of a long step the
    /// surface would pull it, an error first order in the step: on the Table I 2-2 landing at
    /// 8 ft/s Dormand–Prince at 1e-6 left leg 3's primary 0.09 mm short of the fine step's as
    /// its footpad lifted at 0.015 s); or a held footpad that rose past its hold (its
    /// obstacle's wall, its spikes' depth: its lateral motion starts there, a discontinuity a
    /// step must end at, as the fixed steps' contact update ends it); for the rigid footpad,
    /// [`State::rigid_contact_event`].
    pub(crate) fn contact_event(
        &self,
        model: &Model,
        v: &VehicleState,
        trial: &[GearState],
    ) -> bool {
        if !model.inertial {
            return self.rigid_contact_event(model, v, trial);
        }
        self.pads.iter().enumerate().any(|(i, p)| {
            let s = model.surfaces[i];
            let (start, end) = (self.pad_start[i].0.z, p.position.z);
            let depth = s.plane() - CONTACT_EVENT_DEPTH;
            let hold = s.plane() + s.hold_height();
            if p.state == ContactState::Contact {
                return self.leaves(model, i, v, &trial[i]);
            }
            (start >= depth && end < depth) || (p.walled && start <= hold && end > hold)
        })
    }
}

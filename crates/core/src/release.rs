//! The report's detached footpad (`footpad.detached = "rigid"`; text before eq. 85 and after
//! eq. 100; docs/errata.md, "Contact and release (text before eq. 85, after eq. 100) —
//! reinterpreted"): an airborne footpad rides rigidly with the vehicle on its gear, touches down
//! where its tentative rigid position reaches its plane, leaves as soon as its gear no longer
//! presses it (`surface.release`), and its massless gear then relaxes to strokes at which no
//! strut carries a force. Kept for teaching what a massless gear does; the footpad with inertia
//! ([`crate::contact`]) does not need any of it.

use crate::gear::{self, GearState};
use crate::model::Model;
use crate::state::{Relaxation, State};
use crate::surface::ContactState;
use crate::vehicle::VehicleState;
use nalgebra::Vector3;
use touchdown_record::{Law, RunError};
use touchdown_scenario::schema::Arrangement;

impl State {
    /// The contact logic of footpad `i` (the rigid detached footpad) at the current vehicle
    /// state, the gear evaluated there: an airborne footpad whose tentative rigid position
    /// reaches its plane (within [`Model::contact_tolerance`]) touches down unless its gear
    /// would pull it there; a footpad in contact leaves as soon as its gear no longer presses it
    /// onto the surface ([`State::rigid_leaves`]), and its gear relaxes. Returns whether the
    /// footpad changed state.
    pub(crate) fn rigid_contact(&mut self, model: &Model, i: usize) -> Result<bool, RunError> {
        let v = self.vehicle;
        let s = model.surfaces[i];
        match self.pads[i].state {
            ContactState::Free | ContactState::Detached => {
                let attached = self.pads[i].bp_attached;
                let tentative = v.point(&attached);
                let vel = v.point_velocity(&attached);
                self.pads[i].position = tentative;
                self.pads[i].velocity = vel;
                if tentative.z > s.plane() + model.contact_tolerance {
                    return Ok(false);
                }
                let airborne = self.pads[i];
                self.put_down(model, i, &tentative, &vel);
                // A (re)contact whose first evaluation would pull the footpad, load its
                // primary's extension stop (a footpad put on its plane from just above it) or
                // stretch its strut past its bearings is no contact.
                let pad = self.pads[i];
                let mut g = GearState::default();
                let fits = self
                    .evaluate_leg(model, i, &v, &pad.position, &pad.velocity, &mut g)
                    .is_ok();
                let tol = model.force_rounding;
                if !fits || self.pressing(model, &v, &g) < -tol || g.fcp < -tol {
                    self.pads[i] = airborne;
                    return Ok(false);
                }
                Ok(true)
            }
            ContactState::Contact => {
                if self.rigid_leaves(model, i, &v, &self.gear[i]) {
                    self.release(model, i, &v)?;
                    return Ok(true);
                }
                Ok(false)
            }
        }
    }

    /// Whether footpad `i`, in contact, leaves its surface with the vehicle in state `v` and its
    /// gear in state `g`: its gear pulls it (beyond rounding), or its primary strut's extension
    /// stop is loaded (the vehicle is lifting it: no stop is loaded through a contact); a slack
    /// gear (no force either way, within rounding) lets it go when the point of the vehicle it
    /// hangs from moves away from the surface, and leaves it resting there otherwise (a massless
    /// footpad between a slack gear and its surface is held by neither; its lightest-mass limit
    /// rests). On soil, a footpad leaves once it is no longer pressed and has risen out of the
    /// soil (docs/errata.md, "Eq. (101)").
    pub(crate) fn rigid_leaves(
        &self,
        model: &Model,
        i: usize,
        v: &VehicleState,
        g: &GearState,
    ) -> bool {
        let pressing = self.pressing(model, v, g);
        let tol = model.force_rounding;
        if model.mechanisms.soil.is_some() {
            return pressing <= tol && self.pads[i].position.z > model.surfaces[i].plane();
        }
        if pressing < -tol || g.fcp < -tol {
            return true;
        }
        if pressing > tol {
            return false;
        }
        let bp = v.t_bi.transpose() * (self.pads[i].position - v.position);
        v.point_velocity(&bp).z > 0.0
    }

    /// Footpad `i`, no longer pressed, leaves its surface at the accepted state `v`: its leaving
    /// strokes are committed, its massless gear relaxes to strokes at which no strut carries a
    /// force (the stored energy it releases counts as dissipated by the honeycombs, whose work
    /// the ledger already holds) and the footpad is attached rigidly where the relaxed struts
    /// put it. A relaxed gear that cannot be assembled is an error.
    fn release(&mut self, model: &Model, i: usize, v: &VehicleState) -> Result<(), RunError> {
        let g = self.gear[i];
        let (c, s) = (g.primary_stroke, g.secondary_stroke);
        model.laws.commit(c, s, &mut self.memory[i]);
        let bp = v.t_bi.transpose() * (self.pads[i].position - v.position);
        let relaxed = gear::relax(
            &model.legs[i],
            &model.laws,
            &self.memory[i],
            model.arrangement,
            &bp,
            c,
            s,
        )
        .ok_or_else(|| {
            self.diverged(
                v,
                "the struts of a leaving gear, relaxed to zero force, no longer meet".into(),
                Law::GearRelaxation,
                Some(i),
            )
        })?;
        let relaxed = self.above_plane(model, i, v, relaxed, c);
        self.relaxation[i] = Relaxation {
            primary: c - relaxed.primary_stroke,
            secondary: [0, 1].map(|j| s[j] - relaxed.secondary_stroke[j]),
            bending: g.bending_lengthening,
        };
        self.gear[i].primary_stroke = relaxed.primary_stroke;
        self.gear[i].secondary_stroke = relaxed.secondary_stroke;
        self.bending_lag[i] = Vector3::zeros();
        let pad = &mut self.pads[i];
        pad.state = ContactState::Detached;
        pad.stuck = false;
        pad.bp_attached = relaxed.bp;
        pad.position = v.point(&relaxed.bp);
        pad.velocity = v.point_velocity(&relaxed.bp);
        Ok(())
    }

    /// A leaving cantilever gear relaxed from primary stroke `c` (m) whose footpad would end
    /// below its plane (relaxing a primary strut extends it toward the surface) keeps its
    /// primary as compressed as puts the footpad on the plane: a footpad cannot leave through
    /// its surface. That primary stroke's small load stays in the detached gear, stored and
    /// counted, until the footpad lands again.
    fn above_plane(
        &self,
        model: &Model,
        i: usize,
        v: &VehicleState,
        relaxed: gear::Relaxed,
        c: f64,
    ) -> gear::Relaxed {
        let plane = model.surfaces[i].plane();
        let leg = &model.legs[i];
        let axis = (relaxed.bp - leg.b2).normalize();
        let down = (v.t_bi * axis).z;
        if model.arrangement != Arrangement::Cantilever
            || v.point(&relaxed.bp).z >= plane
            || down >= 0.0
        {
            return relaxed;
        }
        // (R + T_BI·(B2 + V̂2P·(L2P − c')))_z = plane
        let length = (plane - v.point(&leg.b2).z) / down;
        let held = (leg.l2p - length).clamp(relaxed.primary_stroke, c.max(relaxed.primary_stroke));
        gear::Relaxed {
            bp: leg.b2 + axis * (leg.l2p - held),
            primary_stroke: held,
            ..relaxed
        }
    }

    /// Whether a rigid footpad's contact changes within the step just taken to `v`, the gear's
    /// forces there in the trial states (the Dormand–Prince pair's last stage is the new
    /// state): a footpad that has stayed in contact and leaves ([`State::contact_steps`]), or
    /// an airborne one that crossed its plane in the step by more than
    /// [`crate::contact::CONTACT_EVENT_DEPTH`] (one already below it at the start, kept off by a
    /// gear that would pull it, is no event).
    pub(crate) fn rigid_contact_event(
        &self,
        model: &Model,
        v: &VehicleState,
        trial: &[GearState],
    ) -> bool {
        self.pads.iter().enumerate().any(|(i, p)| match p.state {
            ContactState::Contact => {
                self.contact_steps[i] > 1 && self.rigid_leaves(model, i, v, &trial[i])
            }
            ContactState::Free | ContactState::Detached => {
                let depth = model.surfaces[i].plane() - crate::contact::CONTACT_EVENT_DEPTH;
                self.pad_start[i].0.z >= depth && v.point(&p.bp_attached).z < depth
            }
        })
    }
}

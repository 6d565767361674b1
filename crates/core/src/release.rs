//! The report's detached footpad (`footpad.detached = "rigid"`; text before eq. 85 and after
//! eq. 100; docs/errata.md, "Contact and release (text before eq. 85, after eq. 100) —
//! reinterpreted"): an airborne footpad rides rigidly with the vehicle on its gear, touches down
//! where its tentative rigid position reaches its plane, leaves as soon as its gear no longer
//! presses it (`surface.release`), and its massless gear then relaxes to strokes at which no
//! strut carries a force. Kept for teaching what a massless gear does; the footpad with inertia
//! ([`crate::contact`]) does not need any of it.

use crate::gear::{self, GearState};
use crate::simulation::Physics;
use crate::state::VehicleState;
use crate::surface::ContactState;
use nalgebra::Vector3;
use touchdown_record::{Law, RunError};
use touchdown_scenario::schema::Arrangement;

impl Physics {
    /// The contact logic of footpad `i` (the rigid detached footpad) at the current vehicle
    /// state, the gear evaluated there: an airborne footpad whose tentative rigid position
    /// reaches its plane (within [`Physics::contact_tolerance`]) touches down unless its gear
    /// would pull it there; a footpad in contact leaves as soon as its gear no longer presses it
    /// onto the surface ([`Physics::rigid_leaves`]), and its gear relaxes. Returns whether the
    /// footpad changed state.
    pub(crate) fn rigid_contact(&mut self, i: usize) -> Result<bool, RunError> {
        let v = self.vehicle;
        let s = self.surfaces[i];
        match self.pads[i].state {
            ContactState::Free | ContactState::Detached => {
                let attached = self.pads[i].bp_attached;
                let tentative = v.point(&attached);
                let vel = v.point_velocity(&attached);
                self.pads[i].position = tentative;
                self.pads[i].velocity = vel;
                if tentative.z > s.plane() + self.contact_tolerance {
                    return Ok(false);
                }
                let airborne = self.pads[i];
                self.put_down(i, &tentative, &vel);
                // A (re)contact whose first evaluation would pull the footpad, load its
                // primary's extension stop (a footpad put on its plane from just above it) or
                // stretch its strut past its bearings is no contact.
                let pad = self.pads[i];
                let mut g = GearState::default();
                let fits = self
                    .evaluate_leg(i, &v, &pad.position, &pad.velocity, &mut g)
                    .is_ok();
                let tol = self.force_rounding;
                if !fits || self.pressing(&v, &g) < -tol || g.fcp < -tol {
                    self.pads[i] = airborne;
                    return Ok(false);
                }
                Ok(true)
            }
            ContactState::Contact => {
                if self.rigid_leaves(i, &v, &self.gear[i]) {
                    self.release(i, &v)?;
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
    pub(crate) fn rigid_leaves(&self, i: usize, v: &VehicleState, g: &GearState) -> bool {
        let pressing = self.pressing(v, g);
        let tol = self.force_rounding;
        if self.mechanisms.soil.is_some() {
            return pressing <= tol && self.pads[i].position.z > self.surfaces[i].plane();
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
    fn release(&mut self, i: usize, v: &VehicleState) -> Result<(), RunError> {
        let g = self.gear[i];
        let (c, s) = (g.primary_stroke, g.secondary_stroke);
        self.laws.commit(c, s, &mut self.memory[i]);
        let bp = v.t_bi.transpose() * (self.pads[i].position - v.position);
        let relaxed = gear::relax(
            &self.legs[i],
            &self.laws,
            &self.memory[i],
            self.arrangement,
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
        let relaxed = self.above_plane(i, v, relaxed, c);
        self.relaxation[i] = (
            c - relaxed.primary_stroke,
            [0, 1].map(|j| s[j] - relaxed.secondary_stroke[j]),
        );
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
        i: usize,
        v: &VehicleState,
        relaxed: gear::Relaxed,
        c: f64,
    ) -> gear::Relaxed {
        let plane = self.surfaces[i].plane();
        let leg = &self.legs[i];
        let axis = (relaxed.bp - leg.b2).normalize();
        let down = (v.t_bi * axis).z;
        if self.arrangement != Arrangement::Cantilever
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
    /// state): a footpad that has stayed in contact and leaves ([`Physics::contact_steps`]), or
    /// an airborne one that crossed its plane in the step by more than
    /// [`crate::contact::CONTACT_EVENT_DEPTH`] (one already below it at the start, kept off by a
    /// gear that would pull it, is no event).
    pub(crate) fn rigid_contact_event(&self, v: &VehicleState, trial: &[GearState]) -> bool {
        self.pads.iter().enumerate().any(|(i, p)| match p.state {
            ContactState::Contact => {
                self.contact_steps[i] > 1 && self.rigid_leaves(i, v, &trial[i])
            }
            ContactState::Free | ContactState::Detached => {
                let depth = self.surfaces[i].plane() - crate::contact::CONTACT_EVENT_DEPTH;
                self.pad_start[i].0.z >= depth && v.point(&p.bp_attached).z < depth
            }
        })
    }
}

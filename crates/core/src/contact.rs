//! Footpads on the surface: the contact logic (text before eq. 85, after eq. 100;
//! docs/errata.md, "Contact and release (text before eq. 85, after eq. 100) — reinterpreted"):
//! touchdown, pressing and leaving, the release of a leaving gear (kept above its plane); the
//! frozen in-plane forces on a sliding footpad (eqs. 85, 96-99 corrected) and its advance over
//! a step (eq. 97, soil eqs. 101-104, curbs eqs. 86-95), and the location of contact events by
//! the adaptive scheme.

use crate::gear::{self, GearState};
use crate::ledger::PadWork;
use crate::simulation::Physics;
use crate::state::VehicleState;
use crate::surface::{advance_sliding, touch_down, ContactState, SlidingForces};
use nalgebra::{Vector2, Vector3};
use touchdown_laws::sliding_friction;
use touchdown_record::{Law, RunError};
use touchdown_scenario::model::Mechanism;
use touchdown_scenario::schema::{Arrangement, ReleaseRule};

/// How far past its plane a footpad may be at the end of an adaptive step (an airborne one
/// below, a leaving one above) before the step is shortened to locate the event, m.
pub const CONTACT_EVENT_DEPTH: f64 = 1e-9;

impl Physics {
    /// Contact logic of the surface (text before eq. 85; docs/errata.md, "Contact and release")
    /// at the current vehicle state, the gear evaluated there: an airborne footpad whose
    /// tentative rigid position reaches its plane (within [`Physics::contact_tolerance`])
    /// touches down unless its gear would pull it there; a footpad in contact leaves as soon as
    /// its gear no longer presses it onto the surface, and its gear relaxes. Returns whether any
    /// footpad changed state.
    pub(crate) fn contact_logic(&mut self) -> Result<bool, RunError> {
        let v = self.vehicle;
        let soil = self.mechanisms.soil.is_some();
        let mut changed = false;
        for i in 0..self.pads.len() {
            let s = self.surfaces[i];
            match self.pads[i].state {
                ContactState::Free | ContactState::Detached => {
                    let attached = self.pads[i].bp_attached;
                    let tentative = v.point(&attached);
                    let vel = v.point_velocity(&attached);
                    self.pads[i].position = tentative;
                    self.pads[i].velocity = vel;
                    if tentative.z > s.plane() + self.contact_tolerance {
                        continue;
                    }
                    let airborne = self.pads[i];
                    let v_normal = if soil { vel.z } else { 0.0 };
                    let mut xy = Vector2::new(tentative.x, tentative.y);
                    if let (Some(curbs), true) =
                        (&self.mechanisms.curbs, airborne.first_contact.is_some())
                    {
                        xy = curbs.landing(i, airborne.touchdown_xy, xy, self.footpad_radius);
                    }
                    touch_down(
                        &mut self.pads[i],
                        &s,
                        xy,
                        Vector2::new(vel.x, vel.y),
                        v_normal,
                        self.t,
                    );
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
                    } else {
                        changed = true;
                    }
                }
                ContactState::Contact => {
                    if self.leaves(i, &v, &self.gear[i]) {
                        self.release(i, &v)?;
                        changed = true;
                    }
                }
            }
        }
        Ok(changed)
    }

    /// The force that keeps a footpad on its surface under the release rule, with the vehicle
    /// at `v` and its gear in state `g`, N (positive pressing): the surface's normal reaction on
    /// the footpad at rest on it, FZI (the normal component of the gear's force on it, eqs. 67,
    /// 85) plus its weight PMASS·g_n (a footpad is lifted only by a pull larger than its own
    /// weight), or the report's stand-ins F2P or FCP.
    fn pressing(&self, v: &VehicleState, g: &GearState) -> f64 {
        match self.release {
            ReleaseRule::GearForce => -(v.t_bi * g.fp).z - self.footpad_mass * self.gravity.z,
            ReleaseRule::StrutForce => g.f2p,
            ReleaseRule::HoneycombForce => g.fcp,
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
    pub(crate) fn leaves(&self, i: usize, v: &VehicleState, g: &GearState) -> bool {
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

    /// Frozen in-plane forces on footpad `i` at the accepted state `v` (eqs. 85, 96-99
    /// corrected: the footpad receives −FPI = T_BI·FP).
    fn sliding_forces(&mut self, i: usize, v: &VehicleState) -> SlidingForces {
        if self.mechanisms.soil.is_some() {
            self.mechanisms.tick(Mechanism::Soil);
        }
        if self.mechanisms.curbs.is_some() {
            self.mechanisms.tick(Mechanism::Curbs);
        }
        let on_pad = v.t_bi * self.gear[i].fp; // −FPI, eq. (67) reversed
        let fzi = -on_pad.z; // FZI = (FPI)_z, positive pressing into the surface
        let pad = &self.pads[i];
        let xy = Vector2::new(pad.position.x, pad.position.y);
        let v_xy = Vector2::new(pad.velocity.x, pad.velocity.y);
        let mut drag = sliding_friction(self.surfaces[i].friction, fzi); // eq. (85)
        if let Some(soil) = &self.mechanisms.soil {
            // eqs. (102), (104): FGRND = FDRAG + FDRAGP, both along −v̂
            let depth = self.surfaces[i].plane() - pad.position.z;
            let sp = (xy - pad.touchdown_xy).norm();
            drag += soil.lateral_drag(depth, sp, v_xy.norm());
        }
        let curb_xy = match &self.mechanisms.curbs {
            Some(curbs) => curbs.force(i, pad.touchdown_xy, xy, v_xy, self.footpad_radius),
            None => Vector2::zeros(),
        };
        SlidingForces {
            gear_xy: Vector2::new(on_pad.x, on_pad.y),
            curb_xy,
            drag,
            gravity_xy: Vector2::new(self.gravity.x, self.gravity.y),
            fzi,
            mass: self.footpad_mass,
            rounding: self.force_rounding,
        }
    }

    /// Step 2: the sliding footpads advance over `dt` (s) with their forces frozen at the
    /// accepted state `old` (eq. 97); their start is kept for the stages.
    pub(crate) fn advance_pads(&mut self, dt: f64, old: &VehicleState) -> PadWork {
        let mut w = PadWork::default();
        for i in 0..self.pads.len() {
            self.pad_start[i] = (self.pads[i].position, self.pads[i].velocity);
            if self.pads[i].state != ContactState::Contact || self.surfaces[i].locked() {
                continue;
            }
            let f = self.sliding_forces(i, old);
            let m = self.footpad_mass;
            let (p0, v0) = (self.pads[i].position, self.pads[i].velocity);
            advance_sliding(&mut self.pads[i], &f, dt);
            if let Some(soil) = &self.mechanisms.soil {
                // eq. (103) with constant forces over the step; the soil only resists
                // penetration and holds a resting footpad rigid-plastically (eq. 101 row).
                let load = f.fzi - m * self.gravity.z; // FZI + weight, downward positive
                let plane = self.surfaces[i].plane();
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
            w.energy_change += 0.5 * m * (v1.norm_squared() - v0.norm_squared())
                - m * self.gravity.dot(&(p1 - p0));
        }
        w
    }

    /// Whether a footpad's contact changes within the step just taken to `v`, the gear's forces
    /// there in the trial states (the Dormand–Prince pair's last stage is the new state): a
    /// footpad that has stayed in contact and leaves ([`Physics::contact_steps`]), or an
    /// airborne one that crossed its plane in the step by
    /// more than [`CONTACT_EVENT_DEPTH`] (one already below it at the start, kept off by a gear
    /// that would pull it, is no event).
    pub(crate) fn contact_event(&self, v: &VehicleState, trial: &[GearState]) -> bool {
        self.pads.iter().enumerate().any(|(i, p)| match p.state {
            ContactState::Contact => self.contact_steps[i] > 1 && self.leaves(i, v, &trial[i]),
            ContactState::Free | ContactState::Detached => {
                let depth = self.surfaces[i].plane() - CONTACT_EVENT_DEPTH;
                self.pad_start[i].0.z >= depth && v.point(&p.bp_attached).z < depth
            }
        })
    }
}

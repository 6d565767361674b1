//! The shared strut laws (`touchdown_multibody::strut`) applied to the rapier multibody's joints
//! and links.
//!
//! - Primary strut, along the prismatic joint: the honeycomb's elastic branches (onset, rebound,
//!   bottoming, extension stop) and the viscous force are explicit forces, equal and opposite on
//!   the inner and outer cylinders along the strut axis; a honeycomb crushing on a plateau
//!   (compressing on its virgin curve) is a velocity motor with target 0 whose force bound is
//!   the crush load, engaged only while the strut compresses, so that it can stop the stroke but
//!   never drive it (one-sided); bearing friction is the joint's dry friction (rapier's
//!   per-DOF `frictionloss`) bounded by μB·(F1 + F2) from the report's statics (eqs. 53-63),
//!   with the side load FM of the massless-strut closed form.
//! - Secondary struts: massless two-force members between their trunnions on the vehicle and
//!   point 1, on the outer cylinder (cantilever) or at the footpad (tripod), with the
//!   double-acting honeycomb and viscous laws; explicit.

use crate::assembly::{body_state, to_na, to_rapier, GearBodies};
use nalgebra::Vector3;
use rapier3d_f64::prelude::*;
use touchdown_multibody::{StrutForces, StrutKinematics};
use touchdown_scenario::model::Leg;

/// Reads a gear's strokes and rates from the world.
pub fn kinematics(
    world: &PhysicsWorld,
    vehicle: RigidBodyHandle,
    gear: &GearBodies,
    leg: &Leg,
) -> StrutKinematics {
    let v = body_state(world, vehicle);
    let outer = body_state(world, gear.outer);
    let pad = body_state(world, gear.footpad);
    let (q, q_dot) = match world.multibody_joints.get(gear.stroke_joint) {
        Some((mb, link)) => (
            mb.link(link).map(|l| l.joint().coords()[0]).unwrap_or(0.0),
            mb.generalized_velocity()[gear.stroke_dof],
        ),
        None => (0.0, 0.0),
    };
    // Point 1 is on the outer link or the footpad body, both read above.
    let attached = if gear.point1_body == gear.footpad {
        pad
    } else {
        outer
    };
    let point1 = attached.point(&gear.point1_local);
    let point1_velocity = attached.velocity_at(&point1);
    let mut k = StrutKinematics {
        c: -q,
        c_dot: -q_dot,
        point1,
        axis: outer.rotation() * gear.axis_local,
        footpad: to_na(pad.pose.translation),
        ..Default::default()
    };
    for (j, (b, l0)) in [(leg.b3, leg.l31), (leg.b4, leg.l41)]
        .into_iter()
        .enumerate()
    {
        let trunnion = v.point(&b);
        let d = point1 - trunnion;
        let len = d.norm();
        let u = d / len;
        k.trunnion[j] = trunnion;
        k.u[j] = u;
        k.s[j] = len - l0;
        k.s_dot[j] = u.dot(&(point1_velocity - v.velocity_at(&trunnion)));
    }
    k
}

/// Applies a gear's forces for the coming step: explicit forces on the links and the vehicle,
/// the plateau motor's bound and the bearing-friction bound on the stroke joint.
pub fn apply(
    world: &mut PhysicsWorld,
    vehicle: RigidBodyHandle,
    gear: &GearBodies,
    k: &StrutKinematics,
    f: &StrutForces,
) {
    // Primary: compression-positive force pushes the footpad away from the trunnion.
    let primary = k.axis * (f.honeycomb + f.viscous);
    push(world, gear.footpad, &primary, &k.footpad);
    push(world, gear.outer, &-primary, &k.footpad);
    // Secondaries: a tension pulls the trunnion and point 1 together.
    for (j, force) in f.secondary().into_iter().enumerate() {
        let on_vehicle = k.u[j] * force;
        push(world, vehicle, &on_vehicle, &k.trunnion[j]);
        push(world, gear.point1_body, &-on_vehicle, &k.point1);
    }
    if let Some((mb, link)) = world.multibody_joints.get_mut(gear.stroke_joint) {
        mb.frictions_mut()[gear.stroke_dof] = f.bearing_bound;
        if let Some(l) = mb.link_mut(link) {
            l.joint
                .data
                .set_motor_max_force(JointAxis::LinX, f.crush_load);
        }
    }
}

/// Adds a force `f` (N) acting at the inertial point `at` (m) to `body`, with its moment about
/// the body's current centre of mass (rapier's own conversion would use the centre of mass of
/// the previous step for multibody links).
fn push(world: &mut PhysicsWorld, body: RigidBodyHandle, f: &Vector3<f64>, at: &Vector3<f64>) {
    let com = to_na(body_state(world, body).pose.translation);
    let rb = &mut world.bodies[body];
    rb.add_force(to_rapier(f), false);
    rb.add_torque(to_rapier(&(at - com).cross(f)), false);
}

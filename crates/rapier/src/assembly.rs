//! The lander as a rapier multibody, built from a scenario.
//!
//! - Vehicle: the multibody root (free joint), mass M and the full inertia tensor J at its centre
//!   of mass, no collider, sleeping off.
//! - Per gear: a universal joint at the primary trunnion B2 to the outer-cylinder link (two
//!   revolute joints about `hinge_axes` joined by a massless yoke at B2); a
//!   prismatic joint along the undeformed strut axis V̂2P to the inner cylinder, whose origin is
//!   the footpad ball joint BP (joint coordinate q = extension, so the compression stroke is
//!   c = −q); the inner body carries the effective footpad mass PMASS and a ball collider of the
//!   footpad radius PR. The secondaries attach at point 1 on the outer link (cantilever) or at
//!   BP on the footpad body (tripod).
//! - Ground: one fixed body with one half-space per footpad, lowered by PR below the footpad's
//!   plane Z = −HOLE so that the ball joint BP sits on the plane when the ball touches;
//!   collision groups pair each footpad with its own plane only.
//! - The multibody's default joint damping is removed.

use nalgebra::{Matrix3, Vector3};
use rapier3d_f64::prelude::*;
use touchdown_frames::gravity_inertial;
use touchdown_multibody::{hinge_axes, RapierSettings};
use touchdown_record::RunError;
use touchdown_scenario::initial::initial_state;
use touchdown_scenario::schema::{Arrangement, Engine};
use touchdown_scenario::Scenario;

/// Damping of the plateau velocity motor, N/(m/s): large enough that the motor is a hard
/// velocity constraint up to its force bound.
const MOTOR_DAMPING: f64 = 1.0e12;

/// nalgebra → rapier vector.
pub(crate) fn to_rapier(v: &Vector3<f64>) -> Vector {
    Vector::new(v.x, v.y, v.z)
}

/// rapier → nalgebra vector.
pub(crate) fn to_na(v: Vector) -> Vector3<f64> {
    Vector3::new(v.x, v.y, v.z)
}

/// nalgebra → rapier 3×3 matrix.
fn matrix(m: &Matrix3<f64>) -> Matrix {
    Matrix::from_cols(
        to_rapier(&m.column(0).into()),
        to_rapier(&m.column(1).into()),
        to_rapier(&m.column(2).into()),
    )
}

/// Pose and velocity of a body of the multibody, read from the multibody itself (rapier writes
/// its links' rigid-body poses and velocities back lazily, at the start of the next step).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyState {
    /// Pose of the body frame (origin at the centre of mass).
    pub pose: Pose,
    /// Velocity of the centre of mass, m/s.
    pub linvel: Vector3<f64>,
    /// Angular velocity, rad/s, inertial axes.
    pub angvel: Vector3<f64>,
}

impl BodyState {
    /// Inertial position of a point given in the body frame, m.
    pub fn point(&self, local: &Vector3<f64>) -> Vector3<f64> {
        to_na(self.pose.transform_point(to_rapier(local)))
    }

    /// Inertial velocity of an inertial point `p` moving with the body, m/s.
    pub fn velocity_at(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.linvel + self.angvel.cross(&(p - to_na(self.pose.translation)))
    }

    /// Rotation body → inertial.
    pub fn rotation(&self) -> Matrix3<f64> {
        let r = Matrix::from_quat(self.pose.rotation);
        Matrix3::from_columns(&[to_na(r.x_axis), to_na(r.y_axis), to_na(r.z_axis)])
    }
}

/// The current state of `body`, a link of the lander's multibody.
pub fn body_state(world: &PhysicsWorld, body: RigidBodyHandle) -> BodyState {
    let link = world.multibody_joints.rigid_body_link(body).and_then(|id| {
        let mb = world.multibody_joints.get_multibody(id.multibody)?;
        Some((mb, mb.link(id.id)?))
    });
    match link {
        Some((mb, link)) => {
            let v = mb.body_jacobian(link.link_id()) * mb.generalized_velocity();
            BodyState {
                pose: *link.local_to_world(),
                linvel: Vector3::new(v[0], v[1], v[2]),
                angvel: Vector3::new(v[3], v[4], v[5]),
            }
        }
        None => {
            let rb = &world.bodies[body];
            BodyState {
                pose: *rb.position(),
                linvel: to_na(rb.linvel()),
                angvel: to_na(rb.angvel()),
            }
        }
    }
}

/// Mass, kg, and inertia tensor about the centre of mass in the body frame, kg·m², of a body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inertia {
    /// Mass, kg.
    pub mass: f64,
    /// Inertia tensor, body frame, kg·m².
    pub tensor: Matrix3<f64>,
}

impl Inertia {
    /// Kinetic energy of a body in state `s`, J.
    pub fn kinetic_energy(&self, s: &BodyState) -> f64 {
        let w = s.rotation().transpose() * s.angvel;
        0.5 * self.mass * s.linvel.norm_squared() + 0.5 * w.dot(&(self.tensor * w))
    }
}

/// One gear's bodies, joints and fixed geometry.
#[derive(Debug, Clone, Copy)]
pub struct GearBodies {
    /// Outer-cylinder link.
    pub outer: RigidBodyHandle,
    /// Inner cylinder with the footpad (origin at BP).
    pub footpad: RigidBodyHandle,
    /// Footpad ball collider.
    pub footpad_collider: ColliderHandle,
    /// The footpad's ground plane.
    pub plane_collider: ColliderHandle,
    /// Prismatic (stroke) joint.
    pub stroke_joint: MultibodyJointHandle,
    /// Index of the stroke degree of freedom in the multibody's generalised coordinates.
    pub stroke_dof: usize,
    /// The body the secondaries attach to at point 1: `outer` (cantilever) or `footpad`
    /// (tripod, point 1 at BP), never another.
    pub point1_body: RigidBodyHandle,
    /// Point 1 (secondary attachment) in that body's local frame, m.
    pub point1_local: Vector3<f64>,
    /// Strut axis V̂2P in the outer link's local frame (unit).
    pub axis_local: Vector3<f64>,
    /// Outer link's mass and inertia.
    pub outer_inertia: Inertia,
    /// Footpad body's mass and inertia.
    pub footpad_inertia: Inertia,
}

/// Masses the rebuild adds to the report's massless gear, kg.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkMasses {
    /// Each outer-cylinder link, kg.
    pub outer_cylinder: f64,
    /// Each inner cylinder with footpad (the effective footpad mass PMASS), kg.
    pub footpad: f64,
    /// Length of the outer-cylinder link (trunnion to gland bearing), m.
    pub outer_cylinder_length: f64,
    /// Radius of the links' solid-cylinder inertia, m.
    pub link_radius: f64,
    /// Radius of the footpad's contact sphere, m.
    pub contact_radius: f64,
}

/// The built world.
pub struct Assembly {
    /// rapier's world.
    pub world: PhysicsWorld,
    /// Vehicle (multibody root).
    pub vehicle: RigidBodyHandle,
    /// Per gear.
    pub gears: Vec<GearBodies>,
    /// Added masses.
    pub masses: LinkMasses,
}

/// rapier's cap on the speed at which a contact's penetration is corrected, m/s (its default
/// with a length unit of 1 m).
const MAX_CORRECTIVE_VELOCITY: f64 = 3.0;

/// Builds the multibody, ground planes and solver settings of a scenario at its touchdown
/// state (eq. 19 as corrected, shared with the core through `touchdown_scenario::initial`).
/// `rs` are the settings it runs with ([`RapierSettings::new`]).
pub fn build(sc: &Scenario, rs: &RapierSettings) -> Result<Assembly, RunError> {
    let init = initial_state(sc);
    let r_bi = init.t_bi;
    let rotation = Rotation::from_mat3(&matrix(&r_bi));
    let pose_of = |body_point: &Vector3<f64>| {
        Pose::from_parts(to_rapier(&(init.position + r_bi * body_point)), rotation)
    };
    let omega_world = r_bi * init.omega;
    let velocity_of = |body_point: &Vector3<f64>| {
        to_rapier(&(init.velocity + omega_world.cross(&(r_bi * body_point))))
    };

    let mut world = PhysicsWorld::new();
    world.gravity = to_rapier(&gravity_inertial(sc.vehicle.gravity, sc.surface.slope));
    let p = &mut world.integration_parameters;
    p.dt = rs.timestep;
    // One solver substep per step: rapier reports a contact's friction impulse of a whole step
    // only in a tangent basis it does not keep, so the energy ledger can book it exactly only
    // with one substep (and the strut laws are applied once per step anyway).
    p.num_solver_iterations = 1;
    p.contact_softness = SpringCoefficients::new(rs.contact_frequency, rs.contact_damping_ratio);
    p.static_contact_softness = p.contact_softness;
    // Lengths of rapier's tolerances (prediction distance, slop) in units of the vehicle's
    // strut, so that they scale with it; its cap on the contacts' corrective velocity stays 3
    // m/s (a velocity: the same on a Froude twin; it does not bind on the bundled landings).
    p.length_unit = rs.length_unit;
    p.normalized_max_corrective_velocity = MAX_CORRECTIVE_VELOCITY / rs.length_unit;

    let vehicle = world.bodies.insert(
        RigidBodyBuilder::dynamic()
            .pose(pose_of(&Vector3::zeros()))
            .additional_mass_properties(MassProperties::with_inertia_matrix(
                Vector::ZERO,
                sc.vehicle.mass,
                matrix(&sc.vehicle.inertia),
            ))
            .linvel(to_rapier(&init.velocity))
            .angvel(to_rapier(&omega_world))
            .can_sleep(false),
    );
    let ground = world.bodies.insert(RigidBodyBuilder::fixed());

    let pmass = sc.footpad.mass;
    let prim = &sc.primary;
    let m_outer = sc.links.outer_cylinder_mass_ratio * pmass;
    let mut masses = LinkMasses {
        outer_cylinder: m_outer,
        footpad: pmass,
        outer_cylinder_length: 0.0,
        link_radius: 0.0,
        contact_radius: 0.0,
    };
    let mut gears = Vec::with_capacity(sc.legs.len());
    for (i, (leg, surface)) in sc.legs.iter().zip(&sc.surface.pads).enumerate() {
        let axis = (leg.bp - leg.b2) / leg.l2p;
        // Outer cylinder: trunnion B2 to the gland bearing at D1 − D2 above the footpad.
        let l_outer = sc.links.outer_cylinder_length(leg, prim, sc.arrangement);
        let radius = sc.links.radius(leg);
        let pr = sc.links.contact_radius(leg);
        masses.contact_radius = pr;
        masses.outer_cylinder_length = l_outer;
        masses.link_radius = radius;
        let outer_com = leg.b2 + axis * (0.5 * l_outer);
        let outer_inertia = Inertia {
            mass: m_outer,
            tensor: Matrix3::identity() * sc.links.moment(leg, m_outer, l_outer),
        };
        let footpad_inertia = Inertia {
            mass: pmass,
            tensor: Matrix3::identity() * sc.links.moment(leg, pmass, prim.inner_cylinder_length),
        };
        let outer = world.bodies.insert(
            RigidBodyBuilder::dynamic()
                .pose(pose_of(&outer_com))
                .additional_mass_properties(MassProperties::with_inertia_matrix(
                    Vector::ZERO,
                    m_outer,
                    matrix(&outer_inertia.tensor),
                ))
                .linvel(velocity_of(&outer_com))
                .angvel(to_rapier(&omega_world))
                .can_sleep(false),
        );
        let footpad = world.bodies.insert(
            RigidBodyBuilder::dynamic()
                .pose(pose_of(&leg.bp))
                .additional_mass_properties(MassProperties::with_inertia_matrix(
                    Vector::ZERO,
                    pmass,
                    matrix(&footpad_inertia.tensor),
                ))
                .linvel(velocity_of(&leg.bp))
                .angvel(to_rapier(&omega_world))
                .can_sleep(false),
        );
        let group = Group::from_bits_truncate(1 << i);
        let groups = InteractionGroups::new(group, group, InteractionTestMode::And);
        // The contact's friction is the surface's, U, on a locked surface too: the restraint
        // holds a locked footpad laterally (`touchdown_multibody::wall`, at BP); a lock by
        // contact friction as well held the contact point, PR below BP, and the two fought
        // as the footpad turned with its gear (docs/engines.md, "The footpad's lateral
        // restraint").
        let friction = surface.friction;
        let footpad_collider = world.colliders.insert_with_parent(
            ColliderBuilder::ball(pr)
                .density(0.0)
                .friction(friction)
                .friction_combine_rule(CoefficientCombineRule::Max)
                .restitution(0.0)
                .restitution_combine_rule(CoefficientCombineRule::Min)
                .collision_groups(groups),
            footpad,
            &mut world.bodies,
        );
        let plane_collider = world.colliders.insert_with_parent(
            ColliderBuilder::halfspace(nalgebra::Unit::new_unchecked(Vector::Z))
                .translation(Vector::new(0.0, 0.0, surface.plane() - pr))
                .friction(0.0)
                .friction_combine_rule(CoefficientCombineRule::Max)
                .restitution(0.0)
                .collision_groups(groups),
            ground,
            &mut world.bodies,
        );
        // The universal joint at B2: rapier's multibody joints turn about one axis or all
        // three, so it is two revolute joints about the hinges both engines take
        // (`hinge_axes`), the first fixed in the vehicle, joined by a massless yoke at B2.
        let (e1, e2) = hinge_axes(&axis, &leg.b2);
        let yoke = world.bodies.insert(
            RigidBodyBuilder::dynamic()
                .pose(pose_of(&leg.b2))
                .linvel(velocity_of(&leg.b2))
                .angvel(to_rapier(&omega_world))
                .can_sleep(false),
        );
        // (parent, child, hinge, anchor on the parent, anchor on the child): every body's
        // frame starts in the vehicle's attitude, so a hinge in body axes is one in each
        let hinges = [
            (vehicle, yoke, e1, leg.b2, Vector3::zeros()),
            (yoke, outer, e2, Vector3::zeros(), leg.b2 - outer_com),
        ];
        for (parent, child, hinge, on_parent, on_child) in hinges {
            let joint = RevoluteJointBuilder::new(to_rapier(&hinge))
                .local_anchor1(to_rapier(&on_parent))
                .local_anchor2(to_rapier(&on_child));
            world
                .multibody_joints
                .insert(parent, child, joint, true)
                .ok_or_else(|| not_built("the trunnion joint could not be inserted"))?;
        }
        let stroke = PrismaticJointBuilder::new(to_rapier(&axis))
            .local_anchor1(to_rapier(&(leg.bp - outer_com)))
            .local_anchor2(Vector::ZERO)
            .motor_model(MotorModel::ForceBased)
            .motor_velocity(0.0, MOTOR_DAMPING)
            .motor_max_force(0.0);
        let stroke_joint = world
            .multibody_joints
            .insert(outer, footpad, stroke, true)
            .ok_or_else(|| not_built("the stroke joint could not be inserted"))?;
        let (point1_body, point1_local) = match sc.arrangement {
            Arrangement::Cantilever => (outer, leg.b1() - outer_com),
            Arrangement::Tripod => (footpad, Vector3::zeros()),
        };
        gears.push(GearBodies {
            outer,
            footpad,
            footpad_collider,
            plane_collider,
            stroke_joint,
            stroke_dof: 0, // set below, once every link is in
            point1_body,
            point1_local,
            axis_local: axis,
            outer_inertia,
            footpad_inertia,
        });
    }
    // Remove rapier's default joint damping; start every joint at rest relative to the vehicle,
    // and the root with the touchdown velocity.
    let handle = gears[0].stroke_joint;
    if let Some((mb, _)) = world.multibody_joints.get_mut(handle) {
        mb.damping_mut().fill(0.0);
        let mut v = mb.generalized_velocity_mut();
        v.fill(0.0);
        let (lin, ang) = (init.velocity, omega_world);
        for k in 0..3 {
            v[k] = lin[k];
            v[3 + k] = ang[k];
        }
    }
    // A step of zero length applies the set-up (mass properties, contacts) without moving
    // anything.
    let dt = world.integration_parameters.dt;
    world.integration_parameters.dt = 0.0;
    world.step();
    world.integration_parameters.dt = dt;
    // The stroke DOF index into the generalised coordinates, final once every link is in.
    for g in &mut gears {
        if let Some((mb, link)) = world.multibody_joints.get(g.stroke_joint) {
            if let Some(l) = mb.link(link) {
                g.stroke_dof = l.assembly_id();
            }
        }
    }
    Ok(Assembly {
        world,
        vehicle,
        gears,
        masses,
    })
}

fn not_built(message: &str) -> RunError {
    RunError::setup(Engine::Rapier, message)
}

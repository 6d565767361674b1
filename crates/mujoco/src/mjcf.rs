//! The MJCF document of a scenario's lander.
//!
//! - Vehicle: a free body with its inertial frame at the centre of mass (mass M, full inertia
//!   tensor J), posed and moving as at touchdown through the keyframe `touchdown` (eq. 19 as
//!   corrected, shared with the other engines through `touchdown_scenario::initial`).
//! - Per gear n: body `legN_outer` at the primary trunnion B2 with a universal joint (two hinges
//!   `legN_trunnion_1`, `legN_trunnion_2`, both normal to the strut axis V̂2P, so the strut
//!   cannot spin about itself), the outer-cylinder link's mass; body `legN_footpad` at the
//!   footpad ball joint BP on the slide joint `legN_stroke` along V̂2P (joint coordinate
//!   q = extension, so the compression stroke is c = −q), with the effective footpad mass PMASS
//!   and a small contact sphere; the secondary struts are massless spatial tendons
//!   `legN_s31`, `legN_s41` from the trunnions B3, B4 on the vehicle to point 1 (site
//!   `legN_point1`), on the outer cylinder for the cantilever and at BP on the footpad body for
//!   the tripod (two-force members: a tendon carries force along itself only).
//! - Actuators, all driven by the runner from the shared laws: `legN_primary` (force along the
//!   stroke joint, N, positive extends), `legN_s31`, `legN_s41` (tendon forces, N, positive
//!   lengthens). The stroke joint's dry friction is the bearing friction bound, solved by
//!   MuJoCo's constraint solver as stiff as the step allows (time constant 2Δt, MuJoCo's
//!   floor). The runner writes it into the joint's friction row of each step
//!   ([`FRICTION_ROW_PLACEHOLDER`]), with constraint islands off so that the solver reads it.
//! - Sensors for the runner, per gear: `legN_contact` (the net force of the plane on the
//!   footpad, world axes, and the number of contacts), `legN_pad_velocity`, `legN_pad_rate`
//!   (the footpad's velocity and angular velocity, world axes); MuJoCo's energy computation is
//!   enabled for the runner's energy balance.
//! - One ground plane per footpad at its HOLE depth (lowered by the contact radius), paired
//!   with its footpad only by collision bitmasks (bit n on both), with the same contact
//!   settings on both geoms of the pair; a footpad bears from a margin of a millionth of the
//!   contact width above its plane ([`CONTACT_MARGIN_PER_WIDTH`]).
//!
//! Only what the scene needs is written: a frictionless footpad gets a frictionless contact
//! (`condim` 1).

use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
use std::fmt::Write;
use touchdown_frames::gravity_inertial;
use touchdown_multibody::{hinge_axes, MujocoSettings};
use touchdown_scenario::initial::initial_state;
use touchdown_scenario::schema::Arrangement;
use touchdown_scenario::{Scenario, ScenarioError};

/// `solimp[0..2]` of the footpad contacts: impedance 0.99 at zero penetration rising to 0.999
/// over the contact width (`solimp[2]`, `MujocoSettings::contact_width`), i.e. nearly a hard
/// contact, so that footpads do not sink.
pub const CONTACT_IMPEDANCE: [f64; 2] = [0.99, 0.999];

/// `margin` of the footpad contacts per contact width (`solimp[2]`): a footpad bears on its
/// plane from 1e-6 of the width above it (0.1 nm on the 1/6-scale model). The touchdown state
/// puts the first footpad on its plane, where MuJoCo (which takes a contact only below its
/// margin) would otherwise let the rounding of the vehicle's pose decide whether it bears in
/// the first step: on `fig-25-26` the model missed its first step's contact (56 µm deep at the
/// next) while its Froude twin, 1e-16 lower, took it. A ratio of the width, so a similar
/// vehicle gets the similar margin (docs/engines.md, "Froude twins"; `tests/integration/mujoco.rs`,
/// `footpads_on_their_planes_at_touchdown_bear_from_the_first_step_on_mujoco`).
pub const CONTACT_MARGIN_PER_WIDTH: f64 = 1e-6;

/// The stroke joint's `frictionloss` in the model, N: a placeholder, not a force. MuJoCo builds a
/// joint's dry-friction row in `mj_step1`, only where the model's `dof_frictionloss` is not zero,
/// and copies that value into it as the row's bound (`efc_frictionloss`). The bound of a step is
/// known only after `mj_step1` (the laws read the state it computes), and it may be zero; so the
/// model keeps a non-zero placeholder that makes the row exist every step, and the runner writes
/// the step's bound into the row before `mj_step2`. Written into the model instead, the bound
/// would act a step late: the bearing friction would follow its load a step behind
/// (docs/engines.md, "Energy ledger"). The least positive double, so that the model loaded without the runner (MuJoCo's
/// viewer) has no friction to speak of, whatever the vehicle's scale.
pub const FRICTION_ROW_PLACEHOLDER: f64 = f64::MIN_POSITIVE;

/// Version of this generator, written into every exported file.
pub const GENERATOR: &str = concat!("touchdown-mujoco ", env!("CARGO_PKG_VERSION"));

/// Space-separated numbers (shortest round-trip form).
fn nums(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{}", if *x == 0.0 { 0.0 } else { *x }))
        .collect::<Vec<_>>()
        .join(" ")
}

fn vec3(v: &Vector3<f64>) -> String {
    nums(&[v.x, v.y, v.z])
}

/// The MJCF document of `sc`'s lander, standalone (loads in MuJoCo and opens in its viewer),
/// or why its settings are refused ([`MujocoSettings::new`]).
pub fn export(sc: &Scenario) -> Result<String, ScenarioError> {
    let mj = MujocoSettings::new(sc)?;
    let init = initial_state(sc);
    let gravity = gravity_inertial(sc.vehicle.gravity, sc.surface.slope);
    let pmass = sc.footpad.mass;
    let m_outer = sc.links.outer_cylinder_mass_ratio * pmass;
    let solref = nums(&[mj.contact_timeconst, mj.contact_damping_ratio]);
    let [i0, i1] = CONTACT_IMPEDANCE;
    let solimp = nums(&[i0, i1, mj.contact_width]);
    // The stroke joint's dry friction holds the bearing friction as stiff as the step allows
    // (MuJoCo's floor, twice the step), whatever the contacts' time constant.
    let solref_friction = nums(&[
        touchdown_scenario::model::Mujoco::MIN_TIMECONST_PER_STEP * mj.timestep,
        mj.contact_damping_ratio,
    ]);
    let margin = nums(&[CONTACT_MARGIN_PER_WIDTH * mj.contact_width]);
    let friction_placeholder = format!("{FRICTION_ROW_PLACEHOLDER:e}");
    let quat = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(init.t_bi));
    let j: &Matrix3<f64> = &sc.vehicle.inertia;

    let mut x = String::new();
    let w = &mut x;
    let _ = writeln!(
        w,
        "<!-- Touchdown MJCF export of the scenario \"{}\".\n     scenario sha256 (resolved scenario TOML): {}\n     generator: {GENERATOR}\n     Units: SI (m, kg, s, N, rad). World frame: the report's inertial (surface) frame, Z normal\n     to the surface; the slope is in the gravity vector. Load the keyframe \"touchdown\" for the\n     touchdown state (docs/engines.md). -->",
        xml_text(&sc.file.name),
        sc.sha256()
    );
    let _ = writeln!(
        w,
        "<mujoco model=\"touchdown: {}\">",
        xml_text(&sc.file.name)
    );
    let _ = writeln!(
        w,
        "  <compiler angle=\"radian\" autolimits=\"true\" inertiafromgeom=\"false\"/>"
    );
    let _ = writeln!(
        w,
        "  <!-- implicitfast: velocity-dependent forces (none: the strut laws are explicit forces set by the runner); elliptic cones: isotropic Coulomb friction -->"
    );
    let _ = writeln!(
        w,
        "  <!-- energy: MuJoCo's kinetic and potential energies, for the runner's energy balance; island: off, so that the solver reads the stroke joints' friction rows the runner writes after mj_step1 (with islands, mj_step1 copies them into island arrays first) -->\n  <option timestep=\"{}\" gravity=\"{}\" integrator=\"implicitfast\" cone=\"elliptic\">\n    <flag energy=\"enable\" island=\"disable\"/>\n  </option>",
        nums(&[mj.timestep]),
        vec3(&gravity)
    );
    let _ = writeln!(
        w,
        "  <default>\n    <!-- Geoms collide only where a bitmask says so; the links' inertias are given explicitly. -->\n    <geom contype=\"0\" conaffinity=\"0\" mass=\"0\"/>\n    <joint damping=\"0\" armature=\"0\" frictionloss=\"0\"/>\n  </default>"
    );
    let _ = writeln!(w, "  <worldbody>");
    for (i, (leg, pad)) in sc.legs.iter().zip(&sc.surface.pads).enumerate() {
        let r = sc.links.contact_radius(leg);
        let _ = writeln!(
            w,
            "    <!-- leg {n}'s ground plane: Z = -HOLE = {} m, lowered by the contact radius so that BP is on it when the sphere touches -->\n    <geom name=\"leg{n}_plane\" type=\"plane\" pos=\"0 0 {}\" size=\"0 0 1\" contype=\"{bit}\" conaffinity=\"{bit}\" solref=\"{solref}\" solimp=\"{solimp}\" margin=\"{margin}\"{}/>",
            nums(&[pad.plane()]),
            nums(&[pad.plane() - r]),
            contact_friction(pad.friction),
            n = i + 1,
            bit = 1u32 << i,
        );
    }
    let _ = writeln!(
        w,
        "    <body name=\"vehicle\" pos=\"{}\" quat=\"{}\">\n      <freejoint name=\"vehicle\"/>\n      <!-- mass M, kg; inertia J about the centre of mass, body axes, kg m^2 (fullinertia: Ixx Iyy Izz Ixy Ixz Iyz entries of the tensor) -->\n      <inertial pos=\"0 0 0\" mass=\"{}\" fullinertia=\"{}\"/>",
        vec3(&init.position),
        nums(&[quat.w, quat.i, quat.j, quat.k]),
        nums(&[sc.vehicle.mass]),
        nums(&[j[(0, 0)], j[(1, 1)], j[(2, 2)], j[(0, 1)], j[(0, 2)], j[(1, 2)]])
    );
    for (i, (leg, pad)) in sc.legs.iter().zip(&sc.surface.pads).enumerate() {
        let n = i + 1;
        let axis = (leg.bp - leg.b2) / leg.l2p;
        let (e1, e2) = hinge_axes(&axis, &leg.b2);
        let prim = &sc.primary;
        let l_outer = sc.links.outer_cylinder_length(leg, prim, sc.arrangement);
        let radius = sc.links.radius(leg);
        let i_outer = sc.links.moment(leg, m_outer, l_outer);
        let i_pad = sc.links.moment(leg, pmass, prim.inner_cylinder_length);
        let r = sc.links.contact_radius(leg);
        // Point 1, where the secondaries' tendons end: on the outer cylinder (cantilever), at
        // the footpad ball joint BP (tripod).
        let site =
            |pos: &Vector3<f64>| format!("<site name=\"leg{n}_point1\" pos=\"{}\"/>", vec3(pos));
        let (point1_on_outer, point1_on_footpad) = match sc.arrangement {
            Arrangement::Cantilever => (
                format!("{}\n        ", site(&(leg.b1() - leg.b2))),
                String::new(),
            ),
            Arrangement::Tripod => (
                String::new(),
                format!("{}\n          ", site(&Vector3::zeros())),
            ),
        };
        let _ = writeln!(
            w,
            "      <site name=\"leg{n}_b3\" pos=\"{}\"/>\n      <site name=\"leg{n}_b4\" pos=\"{}\"/>\n      <body name=\"leg{n}_outer\" pos=\"{}\">\n        <joint name=\"leg{n}_trunnion_1\" type=\"hinge\" pos=\"0 0 0\" axis=\"{}\"/>\n        <joint name=\"leg{n}_trunnion_2\" type=\"hinge\" pos=\"0 0 0\" axis=\"{}\"/>\n        <!-- outer cylinder, trunnion to gland bearing ({} m): {} kg, solid-cylinder inertia about its centre -->\n        <inertial pos=\"{}\" mass=\"{}\" diaginertia=\"{}\"/>\n        <geom name=\"leg{n}_outer\" type=\"capsule\" fromto=\"0 0 0 {}\" size=\"{}\" rgba=\"0.7 0.7 0.7 1\"/>\n        {point1_on_outer}<body name=\"leg{n}_footpad\" pos=\"{}\">\n          <!-- q = extension along V2P; compression stroke c = -q. Dry friction: the bearing friction, as stiff as the step allows, written by the runner into this joint's friction row every step; the model's frictionloss is a placeholder that makes MuJoCo build the row -->\n          <joint name=\"leg{n}_stroke\" type=\"slide\" pos=\"0 0 0\" axis=\"{}\" frictionloss=\"{friction_placeholder}\" solreffriction=\"{solref_friction}\" solimpfriction=\"{solimp}\"/>\n          <inertial pos=\"0 0 0\" mass=\"{}\" diaginertia=\"{}\"/>\n          {point1_on_footpad}<geom name=\"leg{n}_footpad\" type=\"sphere\" size=\"{}\" contype=\"{bit}\" conaffinity=\"{bit}\" solref=\"{solref}\" solimp=\"{solimp}\" margin=\"{margin}\"{} rgba=\"0.9 0.6 0.1 1\"/>\n        </body>\n      </body>",
            vec3(&leg.b3),
            vec3(&leg.b4),
            vec3(&leg.b2),
            vec3(&e1),
            vec3(&e2),
            nums(&[l_outer]),
            nums(&[m_outer]),
            vec3(&(axis * (0.5 * l_outer))),
            nums(&[m_outer]),
            nums(&[i_outer, i_outer, i_outer]),
            vec3(&(axis * l_outer)),
            nums(&[radius]),
            vec3(&(leg.bp - leg.b2)),
            vec3(&axis),
            nums(&[pmass]),
            nums(&[i_pad, i_pad, i_pad]),
            nums(&[r]),
            contact_friction(pad.friction),
            bit = 1u32 << i,
        );
    }
    let _ = writeln!(w, "    </body>\n  </worldbody>");
    let _ = writeln!(w, "  <tendon>");
    for n in 1..=sc.legs.len() {
        for (name, trunnion) in [("s31", "b3"), ("s41", "b4")] {
            let _ = writeln!(
                w,
                "    <spatial name=\"leg{n}_{name}\" width=\"0.002\"><site site=\"leg{n}_{trunnion}\"/><site site=\"leg{n}_point1\"/></spatial>"
            );
        }
    }
    let _ = writeln!(w, "  </tendon>");
    let _ = writeln!(
        w,
        "  <actuator>\n    <!-- Forces in N set every step by the runner from the shared laws. -->"
    );
    for n in 1..=sc.legs.len() {
        let _ = writeln!(
            w,
            "    <motor name=\"leg{n}_primary\" joint=\"leg{n}_stroke\"/>\n    <motor name=\"leg{n}_s31\" tendon=\"leg{n}_s31\"/>\n    <motor name=\"leg{n}_s41\" tendon=\"leg{n}_s41\"/>"
        );
    }
    let _ = writeln!(w, "  </actuator>");
    let _ = writeln!(
        w,
        "  <sensor>\n    <!-- For the runner's contact states and energy ledger: the net force of each plane on its footpad (N, world axes; found = number of contacts), and the footpad's velocity (m/s) and angular velocity (rad/s), world axes. -->"
    );
    for n in 1..=sc.legs.len() {
        let _ = writeln!(
            w,
            "    <contact name=\"leg{n}_contact\" geom1=\"leg{n}_plane\" geom2=\"leg{n}_footpad\" data=\"found force\" reduce=\"netforce\"/>\n    <framelinvel name=\"leg{n}_pad_velocity\" objtype=\"body\" objname=\"leg{n}_footpad\"/>\n    <frameangvel name=\"leg{n}_pad_rate\" objtype=\"body\" objname=\"leg{n}_footpad\"/>"
        );
    }
    let _ = writeln!(w, "  </sensor>");
    let mut qpos = vec![
        init.position.x,
        init.position.y,
        init.position.z,
        quat.w,
        quat.i,
        quat.j,
        quat.k,
    ];
    qpos.extend(std::iter::repeat_n(0.0, 3 * sc.legs.len()));
    // Free joint: linear velocity in world axes, angular velocity in body axes.
    let mut qvel = vec![
        init.velocity.x,
        init.velocity.y,
        init.velocity.z,
        init.omega.x,
        init.omega.y,
        init.omega.z,
    ];
    qvel.extend(std::iter::repeat_n(0.0, 3 * sc.legs.len()));
    let _ = writeln!(
        w,
        "  <keyframe>\n    <!-- the touchdown state: the first footpad on its plane, the gear at rest relative to the vehicle -->\n    <key name=\"touchdown\" qpos=\"{}\" qvel=\"{}\"/>\n  </keyframe>\n</mujoco>",
        nums(&qpos),
        nums(&qvel)
    );
    Ok(x)
}

/// `condim` and `friction` attributes of a footpad contact: frictionless (condim 1) on a
/// frictionless surface, Coulomb friction U otherwise. A locked footpad's contact has the
/// surface's friction too: its restraint is the obstacle wall or spikes
/// (`touchdown_multibody::wall`), not the contact (docs/engines.md, "The footpad's lateral
/// restraint").
fn contact_friction(friction: f64) -> String {
    if friction == 0.0 {
        " condim=\"1\"".into()
    } else {
        format!(" condim=\"3\" friction=\"{} 0 0\"", nums(&[friction]))
    }
}

/// Text safe inside an XML attribute or comment.
fn xml_text(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace("--", "- -")
}

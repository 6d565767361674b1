//! The frames and the Euler-angle kinematics of NASA TN D-7045, eqs. (1)-(9), shared by the
//! scenario format (the initial state, eq. 19), the laws (the RCS attitude errors, eq. 77) and
//! every engine:
//!
//! | module | report |
//! |---|---|
//! | `frames` | the inertial, gravity and body frames and the rotations between them, eqs. (1)-(4) |
//! | `euler` | Euler-angle kinematics, eqs. (5)-(9) |
//!
//! Frames: I (inertial) has its X-Y plane on the sloped surface and Z up its normal; G (gravity)
//! shares X with I and has Z_G up along −g; B (body) has its origin at the rigid-vehicle centre
//! of mass and Z_B up the vehicle centre line. `v_I = T_BI·v_B`. Angles in rad.

mod euler;
mod frames;

pub use euler::{t_be, t_eb, GIMBAL_LOCK_COS};
pub use frames::{
    euler_from_t_bi, gravity_inertial, rot_x, rot_y, rot_z, t_bi, t_gi, t_ig, EulerTrig,
};

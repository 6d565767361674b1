//! Coulomb sliding friction on the footpad bottom, eq. (85) (printed as FDRAG; it is FDRAGP).

/// Velocities within this fraction of their scale (a footpad's speed, and the speed its forces
/// give it in a step) count as zero wherever a friction law decides a direction or a stop from
/// them: a footpad at rest whose velocity is zero only to rounding neither slides nor reverses
/// (docs/errata.md, "Decisions at rounding level").
pub const VELOCITY_ROUNDING: f64 = 1e-9;

/// Magnitude of the sliding-friction drag on a footpad, N (report FDRAGP):
/// `U·max(N, 0)`, where `normal_load` N is the surface's normal reaction on the footpad: the
/// gear's load FZI pressing it in (the inertial Z component of the gear force on the vehicle)
/// and the footpad's own weight normal to the surface (eq. (85), corrected label, the weight
/// added; docs/errata.md, "Eq. (85): FDRAG is FDRAGP"). The caller applies it against the
/// sliding direction.
#[inline]
pub fn sliding_friction(friction_coefficient: f64, normal_load: f64) -> f64 {
    friction_coefficient * normal_load.max(0.0)
}

#[cfg(test)]
mod tests {
    #[test]
    fn no_drag_without_pressure() {
        assert_eq!(super::sliding_friction(0.4, 100.0), 40.0);
        assert_eq!(super::sliding_friction(0.4, -5.0), 0.0);
    }
}

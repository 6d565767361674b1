//! The energy ledger every engine keeps: the accounts since touchdown (`EnergyReport`), the
//! work exchanged with each mechanism (`EnergyLedger`), and the imbalance that stops a run
//! whose balance no longer closes (`Imbalance`).

use serde::{Deserialize, Serialize};

/// Energy bookkeeping since touchdown, J. The balance
/// `kinetic + potential_change + footpad + honeycomb_stored + honeycomb_dissipated + viscous +
/// bearing_friction + sliding_friction + mechanisms − contact_events − kinetic_initial` is
/// `residual`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct EnergyReport {
    /// Vehicle kinetic energy at first contact, J.
    pub kinetic_initial_j: f64,
    /// Vehicle kinetic energy now, J.
    pub kinetic_j: f64,
    /// Change of the vehicle's potential energy since touchdown, J.
    pub potential_change_j: f64,
    /// Energy of the gear's own masses, J: kinetic + potential of the footpads in contact (core,
    /// rigid footpads), its change since touchdown for every footpad (core, footpads with
    /// inertia) or for every gear link (multibody engines).
    pub footpad_j: f64,
    /// Elastic energy stored in the honeycombs (recoverable), J.
    pub honeycomb_stored_j: f64,
    /// Energy dissipated by crushing honeycomb, J.
    pub honeycomb_dissipated_j: f64,
    /// Energy dissipated by the viscous strut forces, J.
    pub viscous_j: f64,
    /// Energy dissipated by primary-strut bearing friction, J.
    pub bearing_friction_j: f64,
    /// Energy dissipated by footpad sliding friction (and sliding footpads stopping), J.
    pub sliding_friction_j: f64,
    /// Energy given to the footpads by contact events, J: velocity set at touchdown and removed
    /// at lift-off (core), or the work of the surface's normal contact impulses and obstacle
    /// locks (multibody engines; negative, the impacts absorb energy).
    pub contact_events_j: f64,
    /// Work done by the vehicle and footpads on the scene's optional mechanisms, J: soil,
    /// curbs, nozzle crushing and the slosh mass absorb it; the descent engine and the RCS
    /// drive the vehicle, so their work counts negative. Zero without such mechanisms.
    #[serde(default)]
    pub mechanisms_j: f64,
    /// Energy put in by the driving mechanisms (the descent engine's thrust and the RCS), J:
    /// their power on the vehicle integrated over the intervals where it is positive. Part of
    /// the balance's energy scale, not of the balance (`mechanisms_j` holds their net work).
    #[serde(default)]
    pub driving_input_j: f64,
    /// Balance residual (integration error), J.
    pub residual_j: f64,
}

/// Work exchanged with each mechanism since touchdown, J: the accounts every engine books,
/// step by step, in its own way.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EnergyLedger {
    /// Work done on the honeycombs (stored + dissipated), J.
    pub honeycomb: f64,
    /// Dissipated by the viscous strut forces, J.
    pub viscous: f64,
    /// Dissipated by primary-strut bearing friction, J.
    pub bearing: f64,
    /// Dissipated by footpad sliding friction (and sliding footpads stopping), J.
    pub sliding: f64,
    /// Given to the footpads by contact events, J (`EnergyReport::contact_events_j`).
    pub events: f64,
    /// Done on the scene's optional mechanisms, J (`EnergyReport::mechanisms_j`).
    pub mechanisms: f64,
    /// Put in by the driving mechanisms, J (`EnergyReport::driving_input_j`).
    pub driving_input: f64,
}

impl EnergyReport {
    /// The energy scale of the balance, J: the energy put into the landing so far, that is the
    /// touchdown kinetic energy, the vehicle's potential energy released since touchdown (if
    /// it is lower now) and the driving mechanisms' input (docs/errata.md, "Energy guard").
    /// The exchanges (honeycombs, friction, contact events, gear masses, passive mechanisms)
    /// are not in it: a pair of large opposing exchanges, which a diverging law produces,
    /// cannot hide its residual.
    pub fn scale(&self) -> f64 {
        self.kinetic_initial_j + (-self.potential_change_j).max(0.0) + self.driving_input_j
    }

    /// What the energy guard judges the residual against, J: the energy scale, or `floor_j`
    /// (J, the scenario's resolution, `Scenario::energy_floor_j`) while the energy put in is
    /// smaller (docs/errata.md, "Energy guard").
    pub fn guard_scale(&self, floor_j: f64) -> f64 {
        self.scale().max(floor_j)
    }
}

impl EnergyLedger {
    /// The energy report of a state with vehicle kinetic energy `kinetic` (J; `kinetic_initial`
    /// at first contact), potential-energy change `potential_change` (J), gear energy
    /// `footpad` (J, `EnergyReport::footpad_j`) and honeycomb elastic energy `honeycomb_stored`
    /// (J), with this ledger's accounts and the balance's residual.
    pub fn report(
        &self,
        kinetic_initial: f64,
        kinetic: f64,
        potential_change: f64,
        footpad: f64,
        honeycomb_stored: f64,
    ) -> EnergyReport {
        let absorbed =
            self.honeycomb + self.viscous + self.bearing + self.sliding + self.mechanisms;
        EnergyReport {
            kinetic_initial_j: kinetic_initial,
            kinetic_j: kinetic,
            potential_change_j: potential_change,
            footpad_j: footpad,
            honeycomb_stored_j: honeycomb_stored,
            honeycomb_dissipated_j: self.honeycomb - honeycomb_stored,
            viscous_j: self.viscous,
            bearing_friction_j: self.bearing,
            sliding_friction_j: self.sliding,
            contact_events_j: self.events,
            mechanisms_j: self.mechanisms,
            driving_input_j: self.driving_input,
            residual_j: kinetic + potential_change + footpad + absorbed
                - self.events
                - kinetic_initial,
        }
    }

    /// The divergence guard on the balance: the imbalance if the residual of `e` (this ledger's
    /// report) exceeds `tolerance` of its guard scale ([`EnergyReport::guard_scale`] with the
    /// floor `floor_j`, J). `hint` names the likely cause for this engine.
    pub fn check_balance(
        &self,
        e: &EnergyReport,
        tolerance: f64,
        floor_j: f64,
        hint: &'static str,
    ) -> Result<(), Imbalance> {
        let scale = e.guard_scale(floor_j);
        if e.residual_j.abs() <= tolerance * scale.max(f64::MIN_POSITIVE) {
            return Ok(());
        }
        Err(Imbalance {
            residual_j: e.residual_j,
            tolerance,
            scale_j: scale,
            hint,
            ledger: *self,
        })
    }
}

/// An energy balance off by more than its guard allows (docs/errata.md, "Energy guard").
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error(
    "energy balance residual {residual_j:.4e} J exceeds {tolerance} of the energy scale {scale_j:.4e} J ({hint}); \
     exchanged so far: honeycomb {:.4e} J, viscous {:.4e} J, bearing friction {:.4e} J, sliding friction {:.4e} J, contact events {:.4e} J, mechanisms {:.4e} J",
    ledger.honeycomb, ledger.viscous, ledger.bearing, ledger.sliding, ledger.events, ledger.mechanisms
)]
pub struct Imbalance {
    /// The residual, J.
    pub residual_j: f64,
    /// The guard, a fraction of the energy scale.
    pub tolerance: f64,
    /// The energy scale, J.
    pub scale_j: f64,
    /// The likely cause for this engine.
    pub hint: &'static str,
    /// Work exchanged with each mechanism so far.
    pub ledger: EnergyLedger,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ledger_closes_a_balanced_state_and_flags_a_drifting_one() {
        // 100 J at touchdown: 10 J left, 5 J of potential released, 80 J into the honeycombs
        // (3 J of it stored), 10 J viscous, 4 J bearing friction, 1 J taken by an impact.
        let l = EnergyLedger {
            honeycomb: 80.0,
            viscous: 10.0,
            bearing: 4.0,
            sliding: 0.0,
            events: -1.0,
            mechanisms: 0.0,
            driving_input: 0.0,
        };
        let e = l.report(100.0, 10.0, -5.0, 0.0, 3.0);
        assert_eq!(e.residual_j, 0.0);
        assert_eq!(e.honeycomb_dissipated_j, 77.0);
        assert!(l.check_balance(&e, 0.01, 0.0, "hint").is_ok());
        let drifting = l.report(100.0, 13.0, -5.0, 0.0, 3.0);
        assert_eq!(drifting.residual_j, 3.0);
        let imbalance = l
            .check_balance(&drifting, 0.01, 0.0, "step too large")
            .unwrap_err();
        assert_eq!(imbalance.residual_j, 3.0);
        let message = imbalance.to_string();
        assert!(message.contains("step too large") && message.contains("honeycomb 8.0000e1 J"));
    }

    #[test]
    fn opposing_exchanges_do_not_inflate_the_energy_scale() {
        // A diverging curb law: 135 J at touchdown, the footpads gain 1.49 MJ that the
        // mechanisms "give" (-1.49 MJ), and the balance is off by 487 J: judged on the 135 J
        // put in, not on the megajoules exchanged.
        let l = EnergyLedger {
            mechanisms: -1.49e6,
            ..Default::default()
        };
        let e = l.report(135.0, 112.0, 10.0, 1.49e6 + 500.0, 0.0);
        assert!((e.residual_j - 487.0).abs() < 1e-6, "{}", e.residual_j);
        assert_eq!(e.scale(), 135.0);
        assert!(l.check_balance(&e, 0.02, 0.0, "hint").is_err());
        // A floor below the energy put in changes nothing; one above it is the yardstick.
        assert!(l.check_balance(&e, 0.02, 100.0, "hint").is_err());
        assert!(l.check_balance(&e, 0.02, 1e5, "hint").is_ok());
        // The energy put in: potential released and the driving mechanisms' positive work.
        let driven = EnergyLedger {
            driving_input: 40.0,
            ..Default::default()
        };
        assert_eq!(driven.report(100.0, 0.0, -25.0, 0.0, 0.0).scale(), 165.0);
        assert_eq!(driven.report(100.0, 0.0, 25.0, 0.0, 0.0).scale(), 140.0);
    }
}

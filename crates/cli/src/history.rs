//! `history.csv` as the engines run: each engine's observer fills the shared
//! [`touchdown_record::History`] row after every accepted step.

use touchdown_record::History;

/// A history file fed by an engine's observer.
pub struct Recorder(pub History);

impl touchdown_core::Observer for Recorder {
    fn observe(&mut self, sim: &touchdown_core::Simulation) {
        sim.sample(self.0.sample_mut());
        self.0.write();
    }
}

impl touchdown_rapier::Observer for Recorder {
    fn observe(&mut self, sim: &touchdown_rapier::RapierSimulation) {
        sim.sample(self.0.sample_mut());
        self.0.write();
    }
}

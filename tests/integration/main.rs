//! Workspace-level tests, one binary. What lives where:
//!
//! * `scenario_errors`: the catalogue of malformed scenarios in `tests/data/malformed/`, each
//!   producing its own specific error (file, field, what was expected);
//! * `footpad`: footpads with inertia stay above their planes, are only pushed, land as
//!   impacts of their own mass, leave with their gears loaded and are held by their walls;
//! * `decisions`: no stability decision cuts a maximum, on any engine;
//! * `physics`: checks of the core against analytic results (vertical drop energy balance,
//!   torque-free tumbling, a lander at rest carrying its weight, energy closure on Table I);
//! * `allocation`: the core's step loop does not allocate;
//! * `docs`: docs/scenario-format.md documents every scenario field;
//! * `layering`: the crate dependency layers (engines never depend on each other);
//! * `module_cycles`: no import circle between the modules of any crate;
//! * `mechanisms`: each optional mechanism (soil, curbs, bending, trunnion springs, thrust,
//!   RCS, slosh, tripod) against an analytic or limiting case; absent ones never evaluated;
//! * `plots`: the validation plots regenerate from the committed data with the project's venv;
//! * `rapier`: the rapier rebuild against the core: start state, energy balance, outcomes, and
//!   the two mechanisms that part them;
//! * `mujoco`: every scenario exports to MJCF that the pinned MuJoCo loads, in the touchdown
//!   state;
//! * `similarity`: Froude twins (`[similarity]`) land as their model does on every engine,
//!   within its step convergence;
//! * `symmetry`: every landing against its mirror image and its legs renumbered;
//! * `campaign`: campaigns give the same bytes on any threads and shards, extend without
//!   change, resume, apply what they draw, state their accuracy, meet a closed-form probability,
//!   keep each landing's energy within the guard, refuse bad files, merges and hostile folders,
//!   pair engines with a multi-fidelity interval that covers, and write Parquet that pandas,
//!   polars and DuckDB read;
//! * `fuzz`: mutated scenarios are refused naming a field or run to a clean end (proptest).
//!
//! Determinism and the command line are tested against the `touchdown` binary in
//! `crates/cli/tests/`; the robustness catalogue and the work-precision study, which live in the
//! comparison crate, in `crates/compare/tests/robustness.rs`.

mod allocation;
mod campaign;
mod decisions;
mod docs;
mod footpad;
mod fuzz;
mod integrators;
mod layering;
mod mechanisms;
mod module_cycles;
mod mujoco;
mod physics;
mod plots;
mod public_surface;
mod rapier;
mod scenario_errors;
mod similarity;
mod symmetry;
mod trajectory;

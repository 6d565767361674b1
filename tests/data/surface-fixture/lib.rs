//! A crate root as text for `tests/integration/public_surface.rs`: one module, one type
//! exported, one not. (Never compiled.)

mod model;

pub use model::Shown;

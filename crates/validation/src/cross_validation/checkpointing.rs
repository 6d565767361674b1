//! The checkpointing of the run: each unit of work kept, or taken back, as it ends.

use crate::calibrate::Predict;
use crate::checkpoint::{counted, Checkpoint};
use crate::ValidationError;
use serde::de::DeserializeOwned;
use serde::Serialize;

/// The unit of work `name`, kept in `checkpoint` if there is one (computed with `predict`
/// unless the checkpoint holds it), and the landings it ran.
pub(super) fn unit<T: Serialize + DeserializeOwned>(
    checkpoint: Option<&Checkpoint>,
    name: &str,
    predict: &Predict,
    compute: impl FnOnce(&Predict) -> Result<T, ValidationError>,
) -> Result<(T, usize), ValidationError> {
    match checkpoint {
        Some(c) => c.unit(name, predict, compute),
        None => counted(predict, compute),
    }
}

//! Johnson-Cook parameter identification, by concept: the parameter space (`params`) and
//! the objective (`objective`); model levels (`levels`); experiment sets (`sets`);
//! optimizers and staged, multi-start fits (`optimize`); statistics (`statistics`);
//! reports (`reports`); synthetic data (`synthetic`).

pub mod evaluations;
pub mod levels;
pub mod objective;
pub mod optimize;
pub mod params;
pub mod reports;
pub mod sets;
pub mod statistics;
pub mod synthetic;

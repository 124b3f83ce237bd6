//! The `mpw` program on the `materials`, `mpm-core`, `fitting`, `cutting` and `runs`
//! libraries: one module per subcommand (`cli`), the run kinds of its executors (`tasks`),
//! the verification catalogue (`verify`), the charts (`charts`) and the cutting forces as
//! the thesis filters them (`cut_forces`). The libraries know nothing of this crate.

// Input checks are written `!(x > lower)` on purpose: the negation also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord, clippy::nonminimal_bool)]

pub mod charts;
pub mod cli;
pub mod cut_forces;
pub mod tasks;
pub mod verify;

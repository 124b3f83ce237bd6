//! Many runs, one interface: a run is described by a file (`RunDescription`), executed by
//! `mpw run-one DESCRIPTION DIR` or in this process, and leaves in its task folder an
//! outcome (`Outcome`, the named results) and a manifest (`Manifest`: program, commit,
//! description hash, seed, threads, wall time, status), each written atomically (a
//! temporary file renamed into place), the manifest last: a task is finished when its
//! manifest exists.
//!
//! A batch (`Batch`) is a folder of task folders, `task-0`, `task-1`, ...; an executor
//! (`Executor`) runs a batch and reports each task from the files it left, whichever
//! executor ran it:
//!
//! - `InProcess`: one task after another in this process, each on this process's threads;
//! - `ProcessPool`: N `run-one` subprocesses at a time, N from the CPUs this process may use;
//! - `Slurm`: one job array per round through `sbatch --parsable --array=...%M`, its state
//!   from `squeue`, results from the task files (Slurm forgets finished jobs); cancelled
//!   with `scancel`.
//!
//! The numbers of a run do not depend on its executor or thread count: the outcome is read
//! back from the same file in every case, and floating-point values are written in Rust's
//! shortest round-trip form, so a value read back is the value computed, bit for bit.
//!
//! What a description's `kind` means (an MPM scene, a fit's model prediction, a cut) is
//! the program's business: executors receive it as an `Execute` function (in process) or a
//! program path (subprocesses), and this crate knows no mechanics.

pub mod atomic;
pub mod batch;
pub mod changes;
pub mod description;
pub mod executor;
pub mod manifest;
pub mod outcome;
pub mod task;

pub use batch::{Batch, TaskFailure, TaskReport};
pub use description::RunDescription;
pub use executor::{BatchState, Executor, InProcess, ProcessPool, Slurm, SlurmConfig};
pub use manifest::{Manifest, Program, Status};
pub use outcome::{Outcome, OutcomeSeries, OutcomeValue};
pub use task::Execute;

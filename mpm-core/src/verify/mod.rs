//! The thesis verification benchmarks, each as a function that runs the case and returns
//! the measured numbers; `verify_cases` turns them into `mpw verify` table rows.

pub mod rigid_contact;
pub mod vibration;

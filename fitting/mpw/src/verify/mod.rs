//! The verification catalogue of `mpw verify`: every case the project checks against an
//! analytic solution, a published value or an independent implementation, by library.

pub mod case_result;
pub mod data;
pub mod fit;
pub mod materials;
pub mod mpm;
pub mod shpb;
pub mod shpb_model;

//! Verification studies of the material models that produce both numbers (as
//! `verify::CaseResult` rows) and data for charts.

pub mod figure_4_5;
pub mod iso_error;

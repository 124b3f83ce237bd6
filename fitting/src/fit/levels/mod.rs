//! Model levels: how an experiment's measured channels are predicted from material
//! parameters, cheapest first: one material point (`single_point`: tensile tests,
//! `tensile`; SHPB specimens, `shpb_specimen`, from the face signals of `shpb_input`) and
//! the SHPB test as an MPM model (`mpm_shpb`), all behind `model::ExperimentModel`.

pub mod jacobian_check;
pub mod model;
pub mod mpm_shpb;
pub mod shpb_input;
pub mod shpb_specimen;
pub mod single_point;
pub mod tensile;

//! Finite-strain material models of thesis chapter 4, written once in generic scalar code
//! so that dual numbers (`dual::Dual`, and `num-dual`'s where its helpers are used) give
//! consistent tangents and parameter sensitivities from the same source, plus a
//! homogeneous single-material-point driver (MTest-like).
//!
//! Units are SI throughout (Pa, K, kg/m³, s). Stress is Cauchy `sigma` unless named
//! otherwise (`tau` Kirchhoff).

pub mod ad;
pub mod any_model;
pub mod conformance;
pub mod driver;
pub mod dual;
pub mod elastic;
pub mod elementary;
pub mod error;
pub mod expm;
pub mod flow_stress;
pub mod lanes;
pub mod limits;
pub mod local_newton;
pub mod material;
pub mod near_one;
pub mod neo_hooke;
pub mod param_file;
pub mod parameters;
pub mod params;
pub mod plasticity;
pub mod preheated;
pub mod scalar;
pub mod seeded;
pub mod signal;
pub mod sym_eigen;
pub mod tensor;
pub mod toml_place;

pub use any_model::AnyModel;
pub use error::MaterialError;
pub use flow_stress::FlowStress;
pub use material::{Material, Model, State};
pub use neo_hooke::NeoHooke;
pub use param_file::{load_elasto_plastic, load_material, MaterialFile};
pub use plasticity::{ElastoPlastic, ReturnMap};
pub use scalar::Scalar;

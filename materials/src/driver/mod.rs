//! Homogeneous single-material-point driver (MTest-like, DESIGN section 5).
//!
//! Each of the nine components of F is either prescribed (`Control::Kinematic`, a value
//! of F_ij) or stress-controlled (`Control::Stress`, a value of the Cauchy stress σ_ij
//! [Pa]); the unknown F components are found each step by Newton with the AD tangent.
//! Temperature is adiabatic (the model's own heating) or prescribed.
//!
//! The driver is generic over the scalar: with dual parameters it returns the
//! sensitivities of the whole stress history. The Newton solve runs in `f64`, then one
//! Newton step in dual arithmetic with the converged tangent gives du/dp = −T⁻¹ ∂r/∂p
//! (implicit function theorem), as in the local return mapping.

mod load_path;
mod output;
mod solve;

pub use load_path::{Control, LoadPath, Ramp, RateKind, Temperature};
pub use output::{write_csv, Record};
pub use solve::{run, DriverError};

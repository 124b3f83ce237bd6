//! Split-Hopkinson-Pressure-Bar signal processing (DESIGN 7.1): baseline removal, pulse
//! detection, optional Savitzky-Golay filtering, time shift of each pulse to the specimen
//! faces (c0 = √(E_b/ρ_b) and the gauge distances, or calibrated delays; optionally with
//! the Pochhammer-Chree dispersion of that travel; aligned geometrically, by measured
//! arrival or by force balance), face velocities and forces, 1-, 2- and 3-wave stress,
//! strain rate, strain, true stress and strain, equilibrium ratio, and the strain-rate
//! plateau.
//!
//! Inputs are raw gauge strains as recorded (compression negative); every output is
//! compression positive. [`analyze`] is the entry point; the relative face velocity and
//! the face forces F1, F2 it returns drive and check the fitting models of the specimen.

pub mod alignment;
mod analysis;
pub mod dispersion;
mod error;
pub mod filter;
mod gauges;
pub mod plateau;
pub mod pulses;
pub mod round_trip;
pub mod signal;
pub mod synthetic;

pub use alignment::{Alignment, Shifts};
pub use analysis::{analyze, analyze_with, Processing, ShpbAnalysis};
pub use error::ShpbError;
pub use plateau::Plateau;
pub use pulses::{detect_pulses, PulseWindows};
pub use round_trip::{
    record_with_late_gauges, synthetic_round_trip, synthetic_round_trip_with, RoundTrip,
};

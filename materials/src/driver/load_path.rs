//! Load paths: piecewise-linear histories of F or σ components, and canned paths
//! (uniaxial tension/compression at constant true or engineering rate with a hold,
//! simple shear, the SHPB specimen under a prescribed length history).

use crate::limits::LOAD_PATH_STEPS;
use crate::signal::{SignalError, TimeSignal};

/// A piecewise-linear function of time through the points (t_k, v_k), constant beyond
/// its ends (module `signal`).
pub type Ramp = TimeSignal<f64>;

/// Why a ramp or a load path cannot be made.
pub type RampError = SignalError;

/// How one component of the deformation is controlled.
#[derive(Debug, Clone, PartialEq)]
pub enum Control {
    /// Prescribed deformation-gradient component F_ij(t).
    Kinematic(Ramp),
    /// Prescribed Cauchy stress component σ_ij(t) [Pa]; F_ij is unknown.
    Stress(Ramp),
}

#[derive(Debug, Clone, PartialEq)]
pub enum Temperature {
    /// The model's own adiabatic heating (Taylor-Quinney).
    Adiabatic,
    /// θ(t) [K] imposed before every step.
    Prescribed(Ramp),
}

/// Constant true (logarithmic) or engineering strain rate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RateKind {
    True,
    Engineering,
}

/// A complete load path: controls of the 9 components of F (row-major), the step times
/// and the temperature.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadPath {
    pub controls: [[Control; 3]; 3],
    /// Times of the steps [s], strictly increasing; the state at `times[0]` is the
    /// initial one (F = I unless prescribed otherwise).
    pub times: Vec<f64>,
    pub temperature: Temperature,
}

fn fixed(v: f64) -> Control {
    Control::Kinematic(Ramp::constant(v))
}

fn free() -> Control {
    Control::Stress(Ramp::constant(0.0))
}

fn even_times(t_end: f64, steps: usize) -> Vec<f64> {
    (0..=steps)
        .map(|k| t_end * k as f64 / steps as f64)
        .collect()
}

impl LoadPath {
    /// Uniaxial stress along x with F_xx(t) given at the step `times`; σ_yy = σ_zz = 0 and
    /// all shear components of F fixed at zero.
    pub fn uniaxial_stretch(
        times: Vec<f64>,
        stretch: Vec<f64>,
        temperature: Temperature,
    ) -> Result<Self, RampError> {
        let f_xx = Ramp::new(times.clone(), stretch)?;
        Ok(LoadPath {
            controls: [
                [Control::Kinematic(f_xx), fixed(0.0), fixed(0.0)],
                [fixed(0.0), free(), fixed(0.0)],
                [fixed(0.0), fixed(0.0), free()],
            ],
            times,
            temperature,
        })
    }

    /// Uniaxial tension (`strain_end` > 0) or compression (< 0) at a constant true or
    /// engineering strain rate `rate` [1/s] up to `strain_end` (true or engineering, as
    /// `kind`), then a hold of `hold` seconds at constant strain. `steps` steps for the
    /// ramp, and the hold with the same step size.
    pub fn uniaxial(
        kind: RateKind,
        strain_end: f64,
        rate: f64,
        hold: f64,
        steps: usize,
        temperature: Temperature,
    ) -> Result<Self, RampError> {
        let t_ramp = strain_end.abs() / rate.abs();
        let dt = t_ramp / steps as f64;
        let total = LOAD_PATH_STEPS.check(steps as f64 + (hold / dt).round(), || {
            format!("{steps} ramp steps of {dt:e} s and a hold of {hold:e} s at that step")
        })?;
        let times: Vec<f64> = (0..=total).map(|k| k as f64 * dt).collect();
        let stretch = times
            .iter()
            .map(|&t| {
                let strain = strain_end * (t / t_ramp).min(1.0);
                match kind {
                    RateKind::True => strain.exp(),
                    RateKind::Engineering => 1.0 + strain,
                }
            })
            .collect();
        Self::uniaxial_stretch(times, stretch, temperature)
    }

    /// Simple shear F = I + γ(t) e_x ⊗ e_y at constant rate γ̇ up to `gamma_end`, fully
    /// kinematic.
    pub fn simple_shear(
        gamma_end: f64,
        gamma_rate: f64,
        steps: usize,
        temperature: Temperature,
    ) -> Result<Self, RampError> {
        let t_end = gamma_end.abs() / gamma_rate.abs();
        LOAD_PATH_STEPS.check(steps as f64, || format!("{steps} shear steps"))?;
        let gamma = Ramp::new(vec![0.0, t_end], vec![0.0, gamma_end])?;
        Ok(LoadPath {
            controls: [
                [fixed(1.0), Control::Kinematic(gamma), fixed(0.0)],
                [fixed(0.0), fixed(1.0), fixed(0.0)],
                [fixed(0.0), fixed(0.0), fixed(1.0)],
            ],
            times: even_times(t_end, steps),
            temperature,
        })
    }

    /// SHPB specimen: uniaxial stress along the bar axis x under the specimen length
    /// history L(t)/L0 at the step `times` (adiabatic). The force on the specimen is
    /// F = σ_xx A0 L0 / L (plastically incompressible, elastic volume change neglected).
    pub fn shpb_specimen(times: Vec<f64>, length_ratio: Vec<f64>) -> Result<Self, RampError> {
        Self::uniaxial_stretch(times, length_ratio, Temperature::Adiabatic)
    }
}

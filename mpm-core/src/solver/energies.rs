//! Energy bookkeeping and the conserved measures the checks and outputs read: kinetic
//! energy, momentum, per-body measures. Sums are in a fixed order (`parallel::fixed_sum`), so they
//! do not depend on the thread count.

use super::Solver;
use crate::failure::{Cause, SimulationError};
use crate::parallel::fixed_sum;
use nalgebra::SVector;

/// Energy bookkeeping [J]: K + W_int = K0 + W_ext + W_bc for an exact integrator.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Energies {
    /// Kinetic energy Σ ½ m v².
    pub kinetic: f64,
    /// Stress work ∫ σ : D dv dt (stored elastic energy plus plastic dissipation).
    pub internal: f64,
    /// Work of body forces, applied (traction) forces, contact and spring forces, and
    /// artificial damping.
    pub external: f64,
    /// Work of prescribed grid velocities.
    pub boundary: f64,
    /// Initial kinetic energy.
    pub initial: f64,
    /// K0 plus the integral of the absolute power of every external source.
    pub supplied: f64,
}

impl Energies {
    /// Energy not accounted for: K + W_int − (K0 + W_ext + W_bc).
    pub fn error(&self) -> f64 {
        self.kinetic + self.internal - (self.initial + self.external + self.boundary)
    }
}

impl<const D: usize> Solver<D> {
    pub fn kinetic_energy(&self) -> f64 {
        let p = &self.particles;
        fixed_sum(p.len(), 0.0, |i| {
            0.5 * p.mass[i] * p.velocity[i].norm_squared()
        })
    }

    /// Total linear momentum Σ m v [kg m/s].
    pub fn momentum(&self) -> SVector<f64, D> {
        let p = &self.particles;
        fixed_sum(p.len(), SVector::zeros(), |i| p.velocity[i] * p.mass[i])
    }

    /// Linear momentum of one body [kg m/s].
    pub fn body_momentum(&self, block: usize) -> SVector<f64, D> {
        let p = &self.particles;
        let r = self.blocks[block].range.clone();
        fixed_sum(r.len(), SVector::zeros(), |i| {
            p.velocity[r.start + i] * p.mass[r.start + i]
        })
    }

    /// Kinetic energy ½ Σ m v² of one body [J].
    pub fn body_kinetic_energy(&self, block: usize) -> f64 {
        let p = &self.particles;
        let r = self.blocks[block].range.clone();
        fixed_sum(r.len(), 0.0, |i| {
            0.5 * p.mass[r.start + i] * p.velocity[r.start + i].norm_squared()
        })
    }

    pub(super) fn check_energy(&mut self) -> Result<(), SimulationError> {
        self.energies.kinetic = self.kinetic_energy();
        let e = self.energies;
        let total = e.kinetic + e.internal;
        let limit = self.settings.blowup_factor * e.supplied.max(f64::MIN_POSITIVE);
        if !total.is_finite() {
            return Err(self.failure(None, Cause::NonFinite { what: "energy" }));
        }
        if total > limit && e.supplied > 0.0 {
            return Err(self.failure(
                None,
                Cause::EnergyBlowUp {
                    energy: total,
                    limit,
                },
            ));
        }
        if let Some(w) = &self.watchdog {
            if let Some(cause) = w.check_energy(e.error(), e.supplied) {
                return Err(self.failure(None, cause));
            }
        }
        Ok(())
    }
}

//! Preparing a run: Δt from the CFL estimate and spring stability (module `solver::time_step`), the
//! node mass cutoff, scratch arrays, the watchdog and the initial energy.

use super::time_step::{self, TimeStep};
use super::{Energies, Solver};
use crate::shape::{Hex, ShapeFunction};
use crate::watchdog::Watchdog;
use nalgebra::SVector;

impl<const D: usize> Solver<D> {
    /// Choose Δt (eq. 7.22-7.23 and spring stability) and prepare the run.
    pub fn initialize(&mut self) -> TimeStep {
        let n = self.particles.len();
        if (0..self.blocks.len()).any(|b| self.kernel_of(b) == ShapeFunction::CpdiHex) {
            self.box_domains_without_hex();
        }
        let speed = self.max_signal_speed();
        let lightest = self
            .particles
            .mass
            .iter()
            .cloned()
            .fold(f64::INFINITY, f64::min);
        let stiffest = self
            .rigid
            .iter()
            .map(|r| r.body.penalty_of(lightest))
            .chain(self.conditions.iter().map(|c| c.stiffness()))
            .fold(0.0, f64::max);
        let spring = (stiffest > 0.0).then_some((stiffest, lightest));
        let ts = time_step::choose(
            self.grid.min_spacing(),
            speed,
            spring,
            self.settings.safety,
            self.settings.dt,
        );
        self.set_time_step(ts.dt, speed);
        self.scratch.force = vec![SVector::zeros(); n];
        self.scratch.grid_velocity = vec![SVector::zeros(); n];
        self.scratch.work = vec![0.0; n];
        let v_ref = self
            .particles
            .velocity
            .iter()
            .map(|v| v.norm())
            .chain(self.velocity_bcs.iter().map(|b| b.peak_speed()))
            .fold(0.0, f64::max);
        let c_max = self
            .blocks
            .iter()
            .map(|b| b.wave_speed())
            .fold(0.0, f64::max);
        self.watchdog = Some(Watchdog::new(
            &self.particles.position,
            self.grid.min_spacing(),
            (v_ref, c_max, self.settings.body_force.norm()),
            self.settings.energy_error_fraction,
        ));
        let k0 = self.kinetic_energy();
        self.energies = Energies {
            kinetic: k0,
            initial: k0,
            supplied: k0,
            ..Energies::default()
        };
        ts
    }

    /// Every point without a hexahedral domain gets its box (`cpdi-hex`).
    fn box_domains_without_hex(&mut self) {
        let p = &mut self.particles;
        p.hex.resize(p.len(), Hex::none());
        for (hex, half) in p.hex.iter_mut().zip(&p.half_size) {
            if hex.is_none() {
                *hex = Hex::boxed(half);
            }
        }
    }
}

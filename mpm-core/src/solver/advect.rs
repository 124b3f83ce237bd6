//! The last motion stage: x ← x + ṽ Δt, the work of external and body forces on the
//! grid velocity, and the domain and watchdog checks on every point.

use super::gather::Failure;
use super::Solver;
use crate::failure::{Cause, SimulationError};
use crate::parallel;
use crate::parallel::fixed_sum;
use nalgebra::SVector;
use rayon::prelude::*;

impl<const D: usize> Solver<D> {
    /// x ← x + ṽ Δt, external work, domain and watchdog checks.
    pub(super) fn advect(&mut self) -> Result<(), SimulationError> {
        let dt = self.dt;
        let b = self.settings.body_force;
        let domain = self.settings.domain;
        let watchdog = self.watchdog.as_ref();
        let bounds = watchdog.map(|w| w.bounds_at(self.time));
        let p = &mut self.particles;
        let s = &self.scratch;
        let cut = parallel::light(p.len());
        let points = (p.position.par_iter_mut())
            .zip(s.grid_velocity.par_iter())
            .zip(p.velocity.par_iter())
            .enumerate();
        let cause = |x: &SVector<f64, D>, v| {
            if !x.iter().all(|c| c.is_finite()) {
                return Some(Cause::NonFinite { what: "position" });
            }
            if let Some(cause) = watchdog
                .zip(bounds)
                .and_then(|(w, b)| w.check_point(x, v, b))
            {
                return Some(cause);
            }
            let (lo, hi) = domain?;
            (0..D)
                .any(|k| x[k] < lo[k] || x[k] > hi[k])
                .then(|| Cause::LeftDomain {
                    position: x.iter().cloned().collect(),
                })
        };
        // a failure travels boxed, so the fold's state stays two words wide
        let check = |(i, ((x, vg), v)): (usize, ((&mut SVector<f64, D>, _), _))| -> Failure {
            *x += vg * dt;
            cause(x, v).map(|c| (i, Box::new(c)))
        };
        let failure = parallel::fold(
            points,
            cut,
            None,
            // every point moves, also past a failing one: the run's last state is written
            |first, point| {
                let found = check(point);
                first.or(found)
            },
            Option::or,
        );
        if let Some((i, cause)) = failure {
            return Err(self.failure(Some(i), *cause));
        }
        let p = &self.particles;
        let power = |i: usize| (s.force[i] + b * p.mass[i]).dot(&s.grid_velocity[i]) * dt;
        let ext = fixed_sum(p.len(), 0.0, power);
        let abs = fixed_sum(p.len(), 0.0, |i| power(i).abs());
        let (contact, contact_abs) = self.surface_load_work();
        self.energies.external += ext + contact;
        self.energies.supplied += abs + contact_abs;
        Ok(())
    }
}

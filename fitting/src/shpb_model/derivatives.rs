//! The face forces of an SHPB model run with their exact derivatives along free material
//! parameters (forward mode, `mpm_core::solver::Tangent`): dF1/dp and dF2/dp at every
//! step, from the derivatives of each face's contact force, which the pass carries
//! through the specimen's points, the CPDI weights and the penalty contact with friction.
//!
//! Both drives: faces of prescribed motion (measured velocity) and faces on elastic bars
//! (incident pulse), whose displacements carry the derivatives of the contact forces
//! that drive them. The material
//! starts at the test temperature (`Preheated`); free parameters that change ρ0 or the
//! wave speed are refused (Δt is held).

use super::{run::one_thread, Discretized, ShpbModel, ShpbRun, INCIDENT, SPECIMEN, TRANSMITTER};
use anyhow::{anyhow, Result};
use materials::plasticity::ElastoPlastic;
use materials::preheated::Preheated;
use materials::seeded::{for_directions, seeded, ForDirections};
use mpm_core::parallel::LARGE_MODEL_FROM;
use mpm_core::solver::observer::CONTINUE;
use mpm_core::solver::Tangent;
use mpm_core::{Solver, Template};
use std::sync::Arc;

/// dF1/dp (`incident`) and dF2/dp (`transmitted`) at every row of the run's
/// `FaceHistory`, one entry per free parameter [N per unit of the parameter].
#[derive(Debug, Clone, Default)]
pub struct ForceDerivatives {
    pub incident: Vec<Vec<f64>>,
    pub transmitted: Vec<Vec<f64>>,
}

impl ShpbModel {
    /// Run the model with `material` starting at `theta_start` [K] from t = 0 to `end`
    /// [s], carrying the derivatives of the face forces along the parameters `free` (1 to
    /// 6), on one thread unless the model is large (as `run_until`).
    pub fn run_with_derivatives(
        &self,
        material: &ElastoPlastic,
        theta_start: f64,
        free: &[&str],
        end: f64,
    ) -> Result<(ShpbRun, ForceDerivatives)> {
        let material = Preheated {
            inner: *material,
            theta_start,
        };
        let job = Job {
            model: self,
            material,
            end: end.min(self.end_s()),
        };
        let run = || for_directions(free, job).map_err(|why| anyhow!("exact Jacobian: {why}"))?;
        match self.particles() < LARGE_MODEL_FROM {
            true => one_thread(run),
            false => run(),
        }
    }
}

/// What `run_with_derivatives` hands to `for_directions`.
struct Job<'a> {
    model: &'a ShpbModel,
    material: Preheated<ElastoPlastic>,
    end: f64,
}

impl ForDirections for Job<'_> {
    type Output = Result<(ShpbRun, ForceDerivatives)>;

    fn run<const P: usize>(self, free: [&str; P]) -> Self::Output {
        match &self.model.template {
            Discretized::Axisymmetric(t) => self.run_on::<2, P>(t, free),
            Discretized::Solid(t) => self.run_on::<3, P>(t, free),
        }
    }
}

impl Job<'_> {
    fn run_on<const D: usize, const P: usize>(
        &self,
        template: &Template<D>,
        free: [&str; P],
    ) -> Result<(ShpbRun, ForceDerivatives)> {
        let model = self.model;
        let mut solver = template.instantiate(&[(SPECIMEN, Arc::new(self.material))])?;
        solver.initialize();
        let seeded =
            seeded(&self.material, &free).map_err(|why| anyhow!("exact Jacobian: {why}"))?;
        let mut tangent = Tangent::new(&solver, vec![seeded])?;
        let mut d = ForceDerivatives::default();
        let mut record = |s: &Solver<D>, tangent: &Tangent<D, P>| {
            d.incident
                .push(model.face_force_derivative(s, tangent, INCIDENT));
            d.transmitted
                .push(model.face_force_derivative(s, tangent, TRANSMITTER));
        };
        record(&solver, &tangent);
        let run = model.run_solver(solver, self.end, &mut |_| CONTINUE, |s| {
            s.step_with(&mut tangent)?;
            record(s, &tangent);
            Ok(())
        })?;
        Ok((run, d))
    }
}

impl ShpbModel {
    /// The derivatives of the compressive force on face `face` (of the whole specimen)
    /// [N per unit of each parameter].
    fn face_force_derivative<const D: usize, const P: usize>(
        &self,
        s: &Solver<D>,
        tangent: &Tangent<D, P>,
        face: usize,
    ) -> Vec<f64> {
        let axis = s.rigid[face].body.planes[0].normal;
        let force = tangent.contact_force(s, face);
        let along = (0..D).fold(0.0 * force[0].eps, |sum, k| sum - force[k].eps * axis[k]);
        along.iter().map(|d| d * self.copies).collect()
    }
}

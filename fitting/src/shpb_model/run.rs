//! One run of an SHPB model with one material: the histories at both faces, recorded
//! every step in memory (no files).

use super::{Discretized, Drive, ShpbModel, INCIDENT, SPECIMEN, TRANSMITTER};
use crate::shpb::signal::interpolate;
use materials::Material;
use mpm_core::melting::{Melting, MeltingWatch};
use mpm_core::parallel::LARGE_MODEL_FROM;
use mpm_core::solver::observer::{observe_all, Observer, Verdict};
use mpm_core::solver::{RigidContact, RunError};
use mpm_core::{Solver, Template};
use std::sync::Arc;
use std::time::Instant;

/// Histories at the faces, one row per step. Forces and strains compression positive,
/// velocities along each face's axis into the specimen.
#[derive(Debug, Clone, Default)]
pub struct FaceHistory {
    pub time_s: Vec<f64>,
    /// Contact force on s_i (model F1) and s_t (model F2) [N].
    pub force_incident_n: Vec<f64>,
    pub force_transmitted_n: Vec<f64>,
    /// Face velocities [m/s].
    pub velocity_incident_m_per_s: Vec<f64>,
    pub velocity_transmitted_m_per_s: Vec<f64>,
    /// Gauge strains the model's forces imply at the faces: ε_r = F1/(E_b A_b) − ε_i and
    /// ε_t = F2/(E_b A_b) [-] (with the `IncidentPulse` drive, the model's prediction of
    /// the measured pulses).
    pub reflected: Vec<f64>,
    pub transmitted: Vec<f64>,
    /// Distance between the faces [m].
    pub length_m: Vec<f64>,
}

/// A finished run.
#[derive(Debug, Clone)]
pub struct ShpbRun {
    pub history: FaceHistory,
    pub steps: usize,
    pub dt_s: f64,
    pub particles: usize,
    pub wall_s: f64,
    /// The specimen's points that reached the melting temperature, if any.
    pub melting: Vec<Melting>,
}

/// `run` on one thread, inside its own pool: a model of a few thousand points runs the
/// parallel loops of a step inline instead of waking threads.
pub(super) fn one_thread<R: Send>(
    run: impl FnOnce() -> anyhow::Result<R> + Send,
) -> anyhow::Result<R> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    pool.install(run)
}

/// An observer of the solver at every level (2D and 3D), e.g. `SnapshotWriter`.
pub trait AnyObserver: Observer<2> + Observer<3> + Send {}

impl<T: Observer<2> + Observer<3> + Send> AnyObserver for T {}

/// Compressive force on a face (of the model, not of its copies) and its velocity into
/// the specimen.
fn face_state<const D: usize>(rc: &RigidContact<D>, drive_velocity: f64) -> (f64, f64) {
    let axis = rc.body.planes[0].normal;
    let force = -rc.contact.force.dot(&axis);
    let velocity = rc
        .body
        .motion
        .bar
        .as_ref()
        .map_or(drive_velocity, |b| b.velocity);
    (force, velocity)
}

impl ShpbModel {
    /// Run the model with `material` over the signals' time span.
    pub fn run(&self, material: Arc<dyn Material>) -> anyhow::Result<ShpbRun> {
        self.run_until(material, self.end_s())
    }

    /// Run the model with `material` from t = 0 to `end` [s] (at most the signals' end), as
    /// one of several run side by side (a fit's evaluation): a large model
    /// (`LARGE_MODEL_FROM` points or more, e.g. the 3D quarter at 40 points along, 51 720)
    /// uses the caller's pool, a smaller one runs on one thread. A run alone
    /// (`run_observed`: `mpw simulate`) always uses the caller's pool. The results are the
    /// same either way; the run is explicit, so its history up to `end` is that of the
    /// whole run.
    pub fn run_until(&self, material: Arc<dyn Material>, end: f64) -> anyhow::Result<ShpbRun> {
        let run = || self.run_observed(material, end, &mut []);
        match self.particles() < LARGE_MODEL_FROM {
            true => one_thread(run),
            false => run(),
        }
    }

    /// `run_until` as a run alone, on the caller's pool, also reporting every step (and
    /// the initial state) to `observers` (VTK snapshots, progress).
    pub fn run_observed(
        &self,
        material: Arc<dyn Material>,
        end: f64,
        observers: &mut [&mut dyn AnyObserver],
    ) -> anyhow::Result<ShpbRun> {
        let end = end.min(self.end_s());
        match &self.template {
            Discretized::Axisymmetric(t) => self.run_inline(t, material, end, &mut |s| {
                let mut each = observers
                    .iter_mut()
                    .map(|o| &mut **o as &mut dyn Observer<2>);
                observe_all(&mut each.by_ref().collect::<Vec<_>>(), s)
            }),
            Discretized::Solid(t) => self.run_inline(t, material, end, &mut |s| {
                let mut each = observers
                    .iter_mut()
                    .map(|o| &mut **o as &mut dyn Observer<3>);
                observe_all(&mut each.by_ref().collect::<Vec<_>>(), s)
            }),
        }
    }

    fn run_inline<const D: usize>(
        &self,
        template: &Template<D>,
        material: Arc<dyn Material>,
        end: f64,
        observe: &mut dyn FnMut(&Solver<D>) -> Verdict,
    ) -> anyhow::Result<ShpbRun> {
        let mut solver = template.instantiate(&[(SPECIMEN, material)])?;
        solver.initialize();
        self.run_solver(solver, end, observe, |s| Ok(s.step()?))
    }

    /// Run `solver` (initialized) to `end`, each step taken by `step`.
    pub(super) fn run_solver<const D: usize>(
        &self,
        mut solver: Solver<D>,
        end: f64,
        observe: &mut dyn FnMut(&Solver<D>) -> Verdict,
        step: impl FnMut(&mut Solver<D>) -> Result<(), RunError>,
    ) -> anyhow::Result<ShpbRun> {
        let start = Instant::now();
        let mut h = FaceHistory::default();
        let mut melting = MeltingWatch::default();
        let mut each = |s: &Solver<D>| -> Verdict {
            self.record(s, &mut h);
            melting.check(s);
            observe(s)
        };
        let first = each(&solver)?;
        if first.is_break() || solver.run_until_by(end, &mut [&mut each], step)?.is_break() {
            anyhow::bail!(
                "the SHPB run was stopped by its caller at step {} (t = {:.4e} s)",
                solver.step,
                solver.time
            );
        }
        Ok(ShpbRun {
            history: h,
            steps: solver.step,
            dt_s: solver.dt,
            particles: solver.particles.len(),
            wall_s: start.elapsed().as_secs_f64(),
            melting: melting.melted(),
        })
    }

    fn record<const D: usize>(&self, s: &Solver<D>, h: &mut FaceHistory) {
        let t = s.time;
        let at = |values: &[f64]| interpolate(&self.signals.time_s, values, t);
        let drive = match self.settings.drive {
            Drive::MeasuredVelocity => at(&self.signals.relative_velocity_m_per_s),
            Drive::IncidentPulse => 0.0,
        };
        let (f_i, v_i) = face_state(&s.rigid[INCIDENT], drive);
        let (f_t, v_t) = face_state(&s.rigid[TRANSMITTER], 0.0);
        let (f_i, f_t) = (f_i * self.copies, f_t * self.copies);
        let ea = self.bars.axial_stiffness;
        // axial position of face k: its plane in the body frame, moved by its motion
        let z = |k: usize| {
            let body = &s.rigid[k].body;
            body.planes[0].point[D - 1] + body.motion.pose(t).translation[D - 1]
        };
        h.time_s.push(t);
        h.force_incident_n.push(f_i);
        h.force_transmitted_n.push(f_t);
        h.velocity_incident_m_per_s.push(v_i);
        h.velocity_transmitted_m_per_s.push(v_t);
        h.reflected.push(f_i / ea - at(&self.signals.incident));
        h.transmitted.push(f_t / ea);
        h.length_m.push(z(INCIDENT) - z(TRANSMITTER));
    }
}

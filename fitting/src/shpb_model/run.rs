//! One run of an SHPB model with one material: the histories at both faces, recorded
//! every step in memory (no files).

use super::{Drive, ShpbModel, INCIDENT, SPECIMEN, TRANSMITTER};
use crate::shpb::signal::interpolate;
use materials::Material;
use mpm_core::observer::Observer;
use mpm_core::solver::RigidContact;
use mpm_core::Solver;
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
}

/// `run` on one thread, inside its own pool: a model of a few thousand points runs the
/// parallel loops of a step inline instead of waking threads (issue 15).
fn one_thread(run: impl FnOnce() -> anyhow::Result<ShpbRun> + Send) -> anyhow::Result<ShpbRun> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    pool.install(run)
}

/// Compressive force on a face and its velocity into the specimen.
fn face_state(rc: &RigidContact<2>, drive_velocity: f64) -> (f64, f64) {
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

    /// Run the model with `material` from t = 0 to `end` [s] (at most the signals' end):
    /// the run is explicit, so its history up to `end` is that of the whole run.
    pub fn run_until(&self, material: Arc<dyn Material>, end: f64) -> anyhow::Result<ShpbRun> {
        one_thread(|| self.run_inline(material, end.min(self.end_s()), &mut []))
    }

    /// `run`, also reporting every step (and the initial state) to `observers` (VTK
    /// snapshots, progress).
    pub fn run_observed(
        &self,
        material: Arc<dyn Material>,
        observers: &mut [&mut (dyn Observer<2> + Send)],
    ) -> anyhow::Result<ShpbRun> {
        one_thread(|| self.run_inline(material, self.end_s(), observers))
    }

    fn run_inline(
        &self,
        material: Arc<dyn Material>,
        end: f64,
        observers: &mut [&mut (dyn Observer<2> + Send)],
    ) -> anyhow::Result<ShpbRun> {
        let start = Instant::now();
        let mut solver = self.template.instantiate(&[(SPECIMEN, material)])?;
        solver.initialize();
        let mut h = FaceHistory::default();
        let mut each = |s: &Solver<2>| -> std::io::Result<()> {
            self.record(s, &mut h);
            observers.iter_mut().try_for_each(|o| o.observe(s))
        };
        each(&solver)?;
        solver.run_until(end, &mut [&mut each])?;
        Ok(ShpbRun {
            history: h,
            steps: solver.step,
            dt_s: solver.dt,
            particles: solver.particles.len(),
            wall_s: start.elapsed().as_secs_f64(),
        })
    }

    fn record(&self, s: &Solver<2>, h: &mut FaceHistory) {
        let t = s.time;
        let at = |values: &[f64]| interpolate(&self.signals.time_s, values, t);
        let drive = match self.settings.drive {
            Drive::MeasuredVelocity => at(&self.signals.relative_velocity_m_per_s),
            Drive::IncidentPulse => 0.0,
        };
        let (f_i, v_i) = face_state(&s.rigid[INCIDENT], drive);
        let (f_t, v_t) = face_state(&s.rigid[TRANSMITTER], 0.0);
        let ea = self.bars.axial_stiffness;
        // axial position of face k: its plane in the body frame, moved by its motion
        let z = |k: usize| {
            let body = &s.rigid[k].body;
            body.planes[0].point[1] + body.motion.pose(t).translation[1]
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

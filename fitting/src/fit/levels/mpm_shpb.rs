//! The axisymmetric MPM model of an SHPB record as an experiment model of the fit
//! (`level = "mpm-axisymmetric"` in a set file): the specimen between the two faces
//! with Coulomb friction, barrelling and radial inertia (`crate::shpb_model`), driven as
//! the single-point level is, by the measured relative face velocity v1 − v2, so the two
//! levels differ only in what the MPM model adds; or (`drive = "incident-pulse"`) by the
//! incident pulse alone, both faces on elastic bars, so that F1 − F1,meas =
//! E_b A_b (ε_r − ε_r,meas) and F2 − F2,meas = E_b A_b (ε_t − ε_t,meas) compare the
//! predicted gauge signals with the measured ones. The prediction is the model's contact
//! force on the incident face (F1) and on the transmitter face (F2) at the experiment's
//! samples [N, compression positive], stacked as the single-point level stacks them.
//! Each sample is the model force's mean over `GAUGE_WINDOW` around it: the bars carry
//! nothing that fast to their gauges (a 1 µs box has its first zero at 1 MHz, while
//! Pochhammer-Chree dispersion of a 12-20 mm bar already acts from ≈ 100 kHz, and the
//! record's processing smooths at the same width), and the single steps at which a ring
//! of points touches or leaves a face or a node plane (spikes of a few per cent, 20 ns
//! wide) would otherwise decide, sample by sample, whether a small parameter change
//! moves the prediction.
//!
//! Shape functions: CPDI unless the set file names another kernel (`fit_set`). On the
//! real record (945 test 01, incident-pulse drive, `mpw simulate --refine 10,20,40,80`,
//! the CPDI MPM-level fit's parameters) the RMS difference of F2 over the plateau against
//! the 80-point run is 1.98 / 0.59 / 0.39 % at 10 / 20 / 40 points along with CPDI,
//! 3.51 / 2.44 / 1.97 % with uGIMP, and 11.45 / 8.44 / 8.73 % with linear shape functions,
//! which do not converge (the count of cell crossings grows with the resolution). Driven
//! at 12 m/s (10 µs ramp, 80 µs, 8 × 4 mm, 945 material without rate term, μ = 0) the mean
//! F2 at 10 / 20 / 40 / 80 points along is 27.63 / 27.96 / 28.10 / 28.17 kN with uGIMP,
//! towards the homogeneous single-point answer, 28.34 kN; with linear shape functions
//! 28.68 / 28.30 / 28.20 / 28.00 kN, drifting below it.
//!
//! The model is discretized once per experiment (a template); every trial material
//! instantiates it and runs it on one thread, so the objective runs experiments and
//! finite-difference columns in parallel. A run ends a window after the last sample, not
//! at the record's end (945 test 01: 80 of 120 µs). A trial whose run fails (a diverged material)
//! is an error the optimizer treats as a rejected step.
//!
//! Jacobian (`Jacobian`): the exact derivatives of the window means, carried through one
//! run (`jacobian = "exact"`, measured-velocity drive), or by default forward finite
//! differences with the relative step `FD_STEP`, chosen from the
//! measured noise (945 test 01, 20 layers, linear shape functions, 198 samples, around the
//! single-point fit):
//! d(mean F2)/d ln p is the same to 0.3 % from steps of 1e-6 to 3e-2 for A, N and C, but
//! the largest single-sample derivative, 46, 32 and 15 kN for A, C and N at steps of
//! 1e-6-1e-5, jumps to 87, 93 and 26 kN at steps of 1e-4-1e-3, where a sample's window
//! catches a contact event that moved by a step; at 1e-2 it is back to 47, 33 and 17 kN
//! while the curvature error of the mean is still below 0.5 %.

use crate::fit::levels::model::{finite_difference, ExperimentModel, Material};
use crate::shpb::pulses::SMOOTHING_S;
use crate::shpb::signal::{cumulative_integral, interpolate};
use crate::shpb_model::record::preheated;
use crate::shpb_model::{ContactChange, ShpbModel};
use anyhow::Result;
use nalgebra::DMatrix;

/// Relative forward-difference step of an MPM level.
pub const FD_STEP: f64 = 1e-2;

/// Width of the mean a sample takes of the model force [s]: the smoothing width of the
/// record's processing.
pub const GAUGE_WINDOW: f64 = SMOOTHING_S;

/// Means of the piecewise-linear `values(time)` over `width` around each of `at`,
/// (I(t + w/2) − I(t − w/2)) / w with I the trapezoidal integral (the window clipped to
/// the record).
pub fn window_means(time: &[f64], values: &[f64], at: &[f64], width: f64) -> Vec<f64> {
    let integral = cumulative_integral(time, values);
    let (first, last) = (time[0], time[time.len() - 1]);
    at.iter()
        .map(|&t| {
            let (a, b) = ((t - 0.5 * width).max(first), (t + 0.5 * width).min(last));
            if b > a {
                (interpolate(time, &integral, b) - interpolate(time, &integral, a)) / (b - a)
            } else {
                interpolate(time, values, t)
            }
        })
        .collect()
}

/// Which face forces an SHPB experiment is compared with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FaceForces {
    Both,
    F1,
    F2,
}

impl FaceForces {
    /// Number of force channels.
    pub fn count(self) -> usize {
        match self {
            FaceForces::Both => 2,
            FaceForces::F1 | FaceForces::F2 => 1,
        }
    }
}

/// How an MPM level gives its Jacobian.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Jacobian {
    /// Forward differences at the relative step `FD_STEP`, one run per free parameter.
    #[default]
    FiniteDifference,
    /// Exact derivatives of the run carried beside it (`ShpbModel::run_with_derivatives`).
    Exact,
}

impl std::str::FromStr for Jacobian {
    type Err = String;

    /// The name in set files.
    fn from_str(name: &str) -> Result<Jacobian, String> {
        match name {
            "finite-difference" => Ok(Jacobian::FiniteDifference),
            "exact" => Ok(Jacobian::Exact),
            other => Err(format!(
                "\"{other}\", expected \"finite-difference\" or \"exact\""
            )),
        }
    }
}

pub struct MpmShpb {
    model: ShpbModel,
    /// Model times of the samples [s].
    sample_times: Vec<f64>,
    forces: FaceForces,
    theta_start: f64,
    jacobian: Jacobian,
}

impl MpmShpb {
    /// `model` (measured-velocity drive) compared at `sample_times` [s, model time] with
    /// `forces`; the specimen starts at `theta_start` [K].
    pub fn new(
        model: ShpbModel,
        sample_times: Vec<f64>,
        forces: FaceForces,
        theta_start: f64,
    ) -> Self {
        MpmShpb {
            model,
            sample_times,
            forces,
            theta_start,
            jacobian: Jacobian::default(),
        }
    }

    /// This model giving its Jacobian by `jacobian`.
    pub fn with_jacobian(self, jacobian: Jacobian) -> Self {
        MpmShpb { jacobian, ..self }
    }

    /// The compared channels of a run's face forces `(F1, F2)` at the samples, each the
    /// mean over `GAUGE_WINDOW` (F1 before F2 when both are compared).
    fn at_samples(&self, time: &[f64], incident: &[f64], transmitted: &[f64]) -> Vec<f64> {
        let at = |force: &[f64]| window_means(time, force, &self.sample_times, GAUGE_WINDOW);
        match self.forces {
            FaceForces::F1 => at(incident),
            FaceForces::F2 => at(transmitted),
            FaceForces::Both => [at(incident), at(transmitted)].concat(),
        }
    }

    /// The end of a run that covers every sample's window [s].
    fn end(&self) -> f64 {
        let last = self.sample_times.iter().copied().fold(0.0, f64::max);
        last + GAUGE_WINDOW
    }
}

impl ExperimentModel for MpmShpb {
    fn level(&self) -> &'static str {
        self.model.settings().level.description()
    }

    fn len(&self) -> usize {
        self.sample_times.len() * self.forces.count()
    }

    fn predict(&self, material: &Material) -> Result<Vec<f64>> {
        Ok(self.predict_with_warnings(material)?.0)
    }

    fn predict_with_warnings(&self, material: &Material) -> Result<(Vec<f64>, Vec<String>)> {
        let run = self
            .model
            .run_until(preheated(material, self.theta_start), self.end())?;
        let h = &run.history;
        let prediction = self.at_samples(&h.time_s, &h.force_incident_n, &h.force_transmitted_n);
        Ok((
            prediction,
            run.melting.iter().map(|m| m.to_string()).collect(),
        ))
    }

    /// Finite differences (`finite_difference`) or, with `Jacobian::Exact`, one run with
    /// the derivatives of the face forces carried along; the window means are linear, so
    /// a sample's derivative is the window mean of the force's derivative.
    fn predict_with_jacobian(
        &self,
        material: &Material,
        free: &[&str],
    ) -> Result<(Vec<f64>, DMatrix<f64>)> {
        if self.jacobian == Jacobian::FiniteDifference {
            return finite_difference(self, material, free);
        }
        let (run, d) =
            self.model
                .run_with_derivatives(material, self.theta_start, free, self.end())?;
        let h = &run.history;
        let prediction = self.at_samples(&h.time_s, &h.force_incident_n, &h.force_transmitted_n);
        let columns: Vec<Vec<f64>> = (0..free.len())
            .map(|k| {
                let column = |rows: &[Vec<f64>]| rows.iter().map(|r| r[k]).collect::<Vec<f64>>();
                self.at_samples(&h.time_s, &column(&d.incident), &column(&d.transmitted))
            })
            .collect();
        let jacobian = DMatrix::from_fn(prediction.len(), free.len(), |i, k| columns[k][i]);
        Ok((prediction, jacobian))
    }

    fn fd_step(&self) -> f64 {
        FD_STEP
    }

    fn has_own_jacobian(&self) -> bool {
        self.jacobian == Jacobian::Exact
    }

    fn with_contact(&self, change: &ContactChange) -> Result<Option<Box<dyn ExperimentModel>>> {
        Ok(Some(Box::new(MpmShpb {
            model: self.model.with_contact(change)?,
            sample_times: self.sample_times.clone(),
            ..*self
        })))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The window mean of a line is its value at the centre, of a parabola the value
    /// plus w²/12 times its curvature over 2, and a spike of one step counts by its area.
    #[test]
    fn window_means_are_exact_for_lines_and_parabolas() {
        let time: Vec<f64> = (0..=1000).map(|k| k as f64 * 1e-3).collect();
        let line: Vec<f64> = time.iter().map(|t| 3.0 * t + 1.0).collect();
        let m = window_means(&time, &line, &[0.5, 0.2005], 0.1);
        assert!(
            (m[0] - 2.5).abs() < 1e-12 && (m[1] - 1.6015).abs() < 1e-12,
            "{m:?}"
        );
        let parabola: Vec<f64> = time.iter().map(|t| t * t).collect();
        let m = window_means(&time, &parabola, &[0.5], 0.1)[0];
        // trapezoids on steps of 1e-3 add Δt²/6 · (1/2)·2 = 1.7e-7
        assert!((m - (0.25 + 0.01 / 12.0)).abs() < 2e-7, "{m}");
        let mut spike = vec![0.0; time.len()];
        spike[500] = 1.0;
        let m = window_means(&time, &spike, &[0.5], 0.1)[0];
        assert!((m - 1e-3 / 0.1).abs() < 1e-12, "{m}");
    }
}

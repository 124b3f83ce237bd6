//! Nelder-Mead (argmin 0.11) on S(u) = rᵀr in the unbounded coordinates u; works with any
//! model level since it needs no derivatives. Initial simplex: u0 and u0 + `step` e_k.
//! Stops when the standard deviation of S over the simplex is below `sd_tolerance` or
//! after `max_iterations`, or when the progress callback asks it to stop (then at the best
//! point evaluated so far, `interrupted`). A failed model run counts as S = +∞ (the point
//! is rejected).

use crate::fit::objective::{cost, Objective};
use crate::fit::optimize::trace::{OptimResult, Progress, Recorder, INTERRUPTED};
use anyhow::{anyhow, Result};
use argmin::core::{CostFunction, Executor, State, TerminationReason, TerminationStatus};
use argmin::solver::neldermead::NelderMead;
use std::sync::Mutex;

#[derive(Debug, Clone, Copy)]
pub struct NmOptions {
    pub max_iterations: u64,
    pub sd_tolerance: f64,
    /// Edge of the initial simplex in u.
    pub step: f64,
}

impl Default for NmOptions {
    fn default() -> Self {
        NmOptions {
            max_iterations: 3000,
            sd_tolerance: 1e-13,
            step: 0.25,
        }
    }
}

struct Problem<'a, 'r, 'p> {
    objective: &'a Objective<'a>,
    recorder: &'r Mutex<Recorder<'p>>,
}

impl CostFunction for Problem<'_, '_, '_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, u: &Vec<f64>) -> Result<f64, argmin::core::Error> {
        let s = self
            .objective
            .residuals(u)
            .map(|r| cost(&r))
            .unwrap_or(f64::INFINITY);
        let counts = self.objective.counts();
        let mut recorder = self.recorder.lock().unwrap();
        recorder.record(counts, s, u);
        match recorder.stopped() {
            true => Err(anyhow!("{INTERRUPTED}")),
            false => Ok(s),
        }
    }
}

pub fn nelder_mead(
    objective: &Objective,
    u0: &[f64],
    options: &NmOptions,
    progress: Progress,
) -> Result<OptimResult> {
    let mut simplex = vec![u0.to_vec()];
    for k in 0..u0.len() {
        let mut v = u0.to_vec();
        v[k] += options.step;
        simplex.push(v);
    }
    let solver = NelderMead::new(simplex)
        .with_sd_tolerance(options.sd_tolerance)
        .map_err(|e| anyhow!("Nelder-Mead setup: {e}"))?;
    let recorder = Mutex::new(Recorder::new(progress));
    let problem = Problem {
        objective,
        recorder: &recorder,
    };
    let run = Executor::new(problem, solver)
        .configure(|s| s.max_iters(options.max_iterations))
        .run()
        .map(|result| {
            let state = result.state();
            let u = state.get_best_param().cloned();
            let (termination, converged) = match state.get_termination_status() {
                TerminationStatus::Terminated(TerminationReason::SolverConverged) => (
                    format!(
                        "simplex standard deviation of S below {:.0e}",
                        options.sd_tolerance
                    ),
                    true,
                ),
                TerminationStatus::Terminated(reason) => (reason.text().to_string(), false),
                TerminationStatus::NotTerminated => ("not terminated".to_string(), false),
            };
            let end = (state.get_best_cost(), state.get_iter() as usize);
            (u, end, termination, converged)
        });
    let recorder = recorder.into_inner().unwrap();
    let (u, (cost, iterations), termination, converged, interrupted) = match run {
        Err(_) if recorder.stopped() => {
            let (u, cost) = recorder.best();
            let u = Some(u.to_vec());
            (u, (cost, 0), INTERRUPTED.to_string(), false, true)
        }
        Err(e) => return Err(anyhow!("Nelder-Mead: {e}")),
        Ok((u, end, termination, converged)) => (u, end, termination, converged, false),
    };
    Ok(OptimResult {
        optimizer: "Nelder-Mead".into(),
        u: u.ok_or_else(|| anyhow!("Nelder-Mead returned no parameters"))?,
        cost,
        iterations,
        termination,
        converged,
        interrupted,
        wall_s: recorder.elapsed(),
        history: recorder.history,
    })
}

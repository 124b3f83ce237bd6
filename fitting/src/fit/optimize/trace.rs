//! What an optimizer run leaves behind: the convergence history (best objective value
//! against model evaluations and wall time) and the termination reason.

use std::time::Instant;

/// One point of the convergence history.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HistoryPoint {
    /// Real model passes over all experiments so far (finite-difference columns count).
    pub evaluations: usize,
    /// AD Jacobian passes over all experiments so far.
    pub jacobians: usize,
    /// Wall time since the optimizer started [s].
    pub wall_s: f64,
    /// Best objective value S so far [-].
    pub cost: f64,
}

/// Result of one optimizer run, in the unbounded coordinates u.
#[derive(Debug, Clone)]
pub struct OptimResult {
    pub optimizer: String,
    pub u: Vec<f64>,
    pub cost: f64,
    pub iterations: usize,
    pub termination: String,
    /// True if the run stopped on a convergence criterion (not an iteration limit or a
    /// failure).
    pub converged: bool,
    pub history: Vec<HistoryPoint>,
    pub wall_s: f64,
}

/// Records the history as an optimizer runs and reports progress.
pub struct Recorder<'p> {
    start: Instant,
    best: f64,
    pub history: Vec<HistoryPoint>,
    progress: &'p dyn Fn(&HistoryPoint),
}

impl<'p> Recorder<'p> {
    pub fn new(progress: &'p dyn Fn(&HistoryPoint)) -> Self {
        Recorder {
            start: Instant::now(),
            best: f64::INFINITY,
            history: Vec::new(),
            progress,
        }
    }

    pub fn elapsed(&self) -> f64 {
        self.start.elapsed().as_secs_f64()
    }

    /// Note an objective value after `counts` = (evaluations, jacobians).
    pub fn record(&mut self, counts: (usize, usize), cost: f64) {
        if cost < self.best {
            self.best = cost;
        }
        let point = HistoryPoint {
            evaluations: counts.0,
            jacobians: counts.1,
            wall_s: self.elapsed(),
            cost: self.best,
        };
        (self.progress)(&point);
        self.history.push(point);
    }
}

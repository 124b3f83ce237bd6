//! What an optimizer run leaves behind (the convergence history: best objective value
//! against iterations, model evaluations and wall time; the termination reason), and the
//! way a caller watches a run and stops it: the progress callback sees every objective
//! evaluation and answers `ControlFlow::Break` to stop the run at the best point so far
//! (Ctrl-C in `mpw fit`). A stopped run is `interrupted`, never `converged`.

use std::ops::ControlFlow;
use std::time::Instant;

/// One point of the convergence history.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HistoryPoint {
    /// Optimizer iterations begun so far (Levenberg-Marquardt: steps tried; `None` for
    /// Nelder-Mead, whose iterations the evaluations do not reveal).
    pub iteration: Option<usize>,
    /// Real model passes over all experiments so far (finite-difference columns count).
    pub evaluations: usize,
    /// AD Jacobian passes over all experiments so far.
    pub jacobians: usize,
    /// Wall time since the optimizer started [s].
    pub wall_s: f64,
    /// Best objective value S so far [-].
    pub cost: f64,
}

/// A progress callback: sees each history point, answers whether the run goes on.
pub type Progress<'p> = &'p dyn Fn(&HistoryPoint) -> ControlFlow<()>;

/// A progress callback that shows nothing and never stops a run.
pub fn unwatched(_: &HistoryPoint) -> ControlFlow<()> {
    ControlFlow::Continue(())
}

/// The termination reason of a run stopped by its caller.
pub const INTERRUPTED: &str =
    "interrupted (Ctrl-C or a termination signal): the best point so far, not an optimum";

/// Result of one optimizer run, in the unbounded coordinates u.
#[derive(Debug, Clone)]
pub struct OptimResult {
    pub optimizer: String,
    pub u: Vec<f64>,
    pub cost: f64,
    pub iterations: usize,
    pub termination: String,
    /// True if the run stopped on a convergence criterion (not an iteration limit, a
    /// failure or an interrupt).
    pub converged: bool,
    /// True if the caller stopped the run (`termination` is `INTERRUPTED`).
    pub interrupted: bool,
    pub history: Vec<HistoryPoint>,
    pub wall_s: f64,
}

/// Records the history as an optimizer runs, reports progress and keeps the best point.
pub struct Recorder<'p> {
    start: Instant,
    iteration: Option<usize>,
    /// Best objective value so far and where it was found.
    best: (f64, Vec<f64>),
    stopped: bool,
    pub history: Vec<HistoryPoint>,
    progress: Progress<'p>,
}

impl<'p> Recorder<'p> {
    pub fn new(progress: Progress<'p>) -> Self {
        Recorder {
            start: Instant::now(),
            iteration: None,
            best: (f64::INFINITY, Vec::new()),
            stopped: false,
            history: Vec::new(),
            progress,
        }
    }

    pub fn elapsed(&self) -> f64 {
        self.start.elapsed().as_secs_f64()
    }

    /// The optimizer begins iteration `k` (1-based).
    pub fn begin_iteration(&mut self, k: usize) {
        self.iteration = Some(k);
    }

    /// Note the objective value `cost` at `u` after `counts` = (evaluations, jacobians).
    pub fn record(&mut self, counts: (usize, usize), cost: f64, u: &[f64]) {
        if cost < self.best.0 || self.best.1.is_empty() {
            self.best = (cost.min(self.best.0), u.to_vec());
        }
        let point = HistoryPoint {
            iteration: self.iteration,
            evaluations: counts.0,
            jacobians: counts.1,
            wall_s: self.elapsed(),
            cost: self.best.0,
        };
        if (self.progress)(&point).is_break() {
            self.stopped = true;
        }
        self.history.push(point);
    }

    /// Whether the caller asked the run to stop.
    pub fn stopped(&self) -> bool {
        self.stopped
    }

    /// The best point so far and its objective value.
    pub fn best(&self) -> (&[f64], f64) {
        (&self.best.1, self.best.0)
    }
}

//! Observers: what a run reports to after every step. The CSV history, the VTK
//! snapshots, the rest tracker and the in-memory records a fit reads (contact force per
//! rigid body, control-point paths) all read the solver through `Observer::observe`, so a
//! fitting loop gets a rigid body's force history without files.
//!
//! Units as the solver's: time [s], force [N] (plane strain: per metre of thickness;
//! axisymmetric: the full ring), position [m].

use crate::solver::Solver;
use nalgebra::SVector;
use std::io;
use std::ops::ControlFlow;

/// What an observer answers: go on, or stop the run after this step (`Break`); an
/// output error stops it too.
pub type Verdict = io::Result<ControlFlow<()>>;

/// Go on.
pub const CONTINUE: Verdict = Ok(ControlFlow::Continue(()));

pub trait Observer<const D: usize> {
    /// Called with the initial state before the first step and after every step.
    fn observe(&mut self, s: &Solver<D>) -> Verdict;
}

impl<const D: usize, F: FnMut(&Solver<D>) -> Verdict> Observer<D> for F {
    fn observe(&mut self, s: &Solver<D>) -> Verdict {
        self(s)
    }
}

/// Every observer sees the state (in order, whatever the others answer); `Break` if any
/// of them asks to stop.
pub fn observe_all<const D: usize>(
    observers: &mut [&mut dyn Observer<D>],
    s: &Solver<D>,
) -> Verdict {
    let mut verdict = ControlFlow::Continue(());
    for o in observers.iter_mut() {
        if o.observe(s)?.is_break() {
            verdict = ControlFlow::Break(());
        }
    }
    Ok(verdict)
}

/// An observer that sees only every `every`-th step (and the initial state).
pub struct Every<O> {
    pub every: usize,
    pub inner: O,
}

impl<const D: usize, O: Observer<D>> Observer<D> for Every<O> {
    fn observe(&mut self, s: &Solver<D>) -> Verdict {
        match s.step.is_multiple_of(self.every) {
            true => self.inner.observe(s),
            false => CONTINUE,
        }
    }
}

/// Named series sampled at the observed times, in memory.
#[derive(Debug, Clone)]
pub struct Recording<T> {
    /// Observed times [s].
    pub time: Vec<f64>,
    /// Series names, in the solver's order.
    pub names: Vec<String>,
    /// Each series (outer index as `names`) at each time.
    pub values: Vec<Vec<T>>,
}

impl<T> Default for Recording<T> {
    fn default() -> Self {
        Recording {
            time: Vec::new(),
            names: Vec::new(),
            values: Vec::new(),
        }
    }
}

impl<T> Recording<T> {
    /// The series `name`.
    pub fn of(&self, name: &str) -> Option<&[T]> {
        let k = self.names.iter().position(|n| n == name)?;
        Some(&self.values[k])
    }

    /// Append one sample of every series at time `t`; `names` is asked for once.
    fn record(
        &mut self,
        t: f64,
        names: impl FnOnce() -> Vec<String>,
        values: impl Iterator<Item = T>,
    ) {
        if self.time.is_empty() {
            self.names = names();
            self.values = self.names.iter().map(|_| Vec::new()).collect();
        }
        self.time.push(t);
        for (series, v) in self.values.iter_mut().zip(values) {
            series.push(v);
        }
    }
}

/// Contact force on every rigid body [N] (series named by the body), in memory.
#[derive(Debug, Clone, Default)]
pub struct ForceHistory<const D: usize>(pub Recording<SVector<f64, D>>);

impl<const D: usize> Observer<D> for ForceHistory<D> {
    fn observe(&mut self, s: &Solver<D>) -> Verdict {
        let names = || s.rigid.iter().map(|r| r.body.name.clone()).collect();
        self.0
            .record(s.time, names, s.rigid.iter().map(|r| r.contact.force));
        CONTINUE
    }
}

/// Position of every control point [m] (series named by the point), in memory.
#[derive(Debug, Clone, Default)]
pub struct ControlPointPaths<const D: usize>(pub Recording<SVector<f64, D>>);

impl<const D: usize> Observer<D> for ControlPointPaths<D> {
    fn observe(&mut self, s: &Solver<D>) -> Verdict {
        let names = || s.control_points.iter().map(|(n, _)| n.clone()).collect();
        let x = s
            .control_points
            .iter()
            .map(|(_, p)| s.particles.position[*p]);
        self.0.record(s.time, names, x);
        CONTINUE
    }
}

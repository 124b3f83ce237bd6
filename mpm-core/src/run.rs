//! Run a loaded scene to its end time, writing `history.csv` every `history_every` steps
//! and `snapshots` evenly spaced VTK snapshots (plus the first and the last state). A
//! failure stops the run; what was written stays on disk and the failure is returned in
//! the summary as a result. The named results of the last state (module `results`) are
//! written to `results.csv`, also after a failure. A run that would take more than
//! `limits::TIME_STEPS` steps fails at step 0 (after the first history row). A run stopped
//! by its caller (`progress` breaks, e.g. on Ctrl-C) ends like a failure with cause
//! `Interrupted`: its last state written, its results collected. Points that reach their
//! melting temperature are reported in the summary (`melting`), not stopped.

use crate::derivative_history::{self, Stepper};
use crate::failure::{Cause, SimulationError};
use crate::limits::TIME_STEPS;
use crate::melting::{Melting, MeltingWatch};
use crate::output::{HistoryWriter, SnapshotWriter};
use crate::results::{self, NamedResult, RestTracker};
use crate::scene::{OutputSpec, Scene, Simulation};
use crate::solver::observer::{Every, Observer};
use crate::solver::TimeStep;
use crate::solver::{RunError, Solver, TimeStepChange};
use materials::AnyModel;
use std::ops::ControlFlow;
use std::path::Path;

#[derive(Debug)]
pub struct RunSummary {
    pub time_step: TimeStep,
    /// Δt changes during the run (`solver::TimeStepChange`).
    pub time_step_changes: Vec<TimeStepChange>,
    pub steps: usize,
    pub particles: usize,
    pub failure: Option<SimulationError>,
    pub results: Vec<NamedResult>,
    /// Bodies with points that reached their melting temperature.
    pub melting: Vec<Melting>,
}

/// Run `scene` writing into `dir`; `start(time_step)` is called once Δt is chosen (to warn
/// about a risky one, `TimeStep::risk`), `progress(t, t_end)` after every step (breaking
/// stops the run).
pub fn run_scene(
    scene: Scene,
    dir: &Path,
    start: impl FnOnce(&TimeStep),
    progress: impl FnMut(f64, f64) -> ControlFlow<()>,
) -> std::io::Result<RunSummary> {
    std::fs::create_dir_all(dir)?;
    match scene.simulation {
        Simulation::Planar(s) => run(
            s,
            &scene.models,
            &scene.output,
            scene.end,
            dir,
            start,
            progress,
        ),
        Simulation::Solid(s) => run(
            s,
            &scene.models,
            &scene.output,
            scene.end,
            dir,
            start,
            progress,
        ),
    }
}

fn run<const D: usize>(
    mut solver: Solver<D>,
    models: &[AnyModel],
    output: &OutputSpec,
    end: f64,
    dir: &Path,
    start: impl FnOnce(&TimeStep),
    mut progress: impl FnMut(f64, f64) -> ControlFlow<()>,
) -> std::io::Result<RunSummary> {
    let (history_every, snapshots) = (output.history_every, output.snapshots);
    let mut step: Stepper<'_, D> = match output.derivatives.is_empty() {
        true => Box::new(|s: &mut Solver<D>| Ok(s.step()?)),
        false => {
            derivative_history::stepper(&solver, models, &output.derivatives, (dir, history_every))
                .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidInput, e))?
        }
    };
    let time_step = solver.initialize();
    start(&time_step);
    let mut history = Every {
        every: history_every,
        inner: HistoryWriter::create(&dir.join("history.csv"), &solver)?,
    };
    let mut rest = Every {
        every: history_every,
        inner: RestTracker::default(),
    };
    let mut snapshot = SnapshotWriter::new(dir, end, snapshots);
    // the initial state
    history.inner.write(&solver)?;
    rest.inner.sample(&solver);
    snapshot.write_next(&solver)?;
    let mut melting = MeltingWatch::default();
    melting.check(&solver);
    let mut report = |s: &Solver<D>| Ok(progress(s.time, end));
    let mut observers: [&mut dyn Observer<D>; 5] = [
        &mut history,
        &mut rest,
        &mut snapshot,
        &mut melting,
        &mut report,
    ];
    let too_long = TIME_STEPS.check(end / time_step.dt, || {
        format!("time.end = {end:e} s at {time_step}")
    });
    let result = match too_long {
        Err(e) => Err(RunError::Simulation(SimulationError {
            step: 0,
            time: 0.0,
            particle: None,
            cause: Cause::TooManySteps(e),
        })),
        Ok(_) => solver.run_until_by(end, &mut observers, &mut step),
    };
    let result = match result {
        Ok(ControlFlow::Break(())) => Err(RunError::Simulation(SimulationError {
            step: solver.step,
            time: solver.time,
            particle: None,
            cause: Cause::Interrupted,
        })),
        Ok(ControlFlow::Continue(())) => Ok(()),
        Err(e) => Err(e),
    };
    let failure = match result {
        Ok(()) => None,
        Err(RunError::Io(e)) => return Err(e),
        Err(RunError::Simulation(e)) => {
            history.inner.write(&solver)?;
            snapshot.write_next(&solver)?;
            Some(e)
        }
    };
    rest.inner.sample(&solver);
    let results = results::collect(&solver, &rest.inner);
    results::write_csv(&dir.join("results.csv"), &results)?;
    Ok(RunSummary {
        time_step,
        time_step_changes: solver.time_step_changes.clone(),
        steps: solver.step,
        particles: solver.particles.len(),
        failure,
        results,
        melting: melting.melted(),
    })
}

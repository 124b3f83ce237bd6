//! A fit its caller interrupts (the progress callback answers `Break`, as Ctrl-C does in
//! `mpw fit`) ends at once with the best point evaluated so far: that stage has no
//! statistics, no later stage or start runs, and the result says so.

use fitting::fit::optimize::run::{run_fit, FitProgress, Optimizer};
use fitting::fit::sets::fit_set::FitSet;
use materials::material::Model;
use std::ops::ControlFlow;
use std::path::Path;
use std::sync::Mutex;

fn default_set() -> FitSet {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/experiments/default.toml");
    let mut set = FitSet::load(&file).unwrap();
    set.starts = 3;
    set
}

/// Stop after `after` history points; returns the fit and the objective values seen.
fn interrupted_fit(
    optimizer: Optimizer,
    after: usize,
) -> (fitting::fit::optimize::run::FitResult, Vec<f64>) {
    let set = default_set();
    let seen = Mutex::new(Vec::new());
    let progress = |f: &FitProgress| {
        let mut seen = seen.lock().unwrap();
        seen.push(f.point.cost);
        match seen.len() >= after {
            true => ControlFlow::Break(()),
            false => ControlFlow::Continue(()),
        }
    };
    let result = run_fit(&set, optimizer, &progress).unwrap();
    (result, seen.into_inner().unwrap())
}

#[test]
fn levenberg_marquardt_stops_at_its_best_point_so_far() {
    let (result, seen) = interrupted_fit(Optimizer::LmExact, 3);
    assert!(result.interrupted);
    assert_eq!(seen.len(), 3, "no evaluation is reported after the stop");
    assert_eq!(result.stages.len(), 1, "later stages do not run");
    let stage = &result.stages[0];
    assert_eq!(stage.runs.len(), 1, "later starts do not run");
    let run = &stage.runs[0];
    assert!(run.interrupted && !run.converged, "{}", run.termination);
    assert!(run.termination.starts_with("interrupted"));
    // The best objective so far (the history keeps the running minimum).
    assert_eq!(stage.cost, seen[2]);
    assert!(stage.std_errors.iter().all(|s| s.is_nan()) && stage.correlation.is_empty());
    // The material carries the stage's values.
    for (name, v) in stage.free.iter().zip(&stage.values) {
        assert_eq!(result.material.param(name), Some(*v), "{name}");
    }
    assert_eq!(
        result.predictions.len(),
        3,
        "every experiment is predicted once"
    );
}

#[test]
fn nelder_mead_stops_at_its_best_point_so_far() {
    let (result, seen) = interrupted_fit(Optimizer::NelderMead, 12);
    assert!(result.interrupted);
    assert_eq!(seen.len(), 12);
    let run = &result.stages[0].runs[0];
    assert!(run.interrupted && !run.converged);
    let best = seen.iter().copied().fold(f64::INFINITY, f64::min);
    assert_eq!(run.cost, best);
    // The point kept reproduces its objective.
    let set = default_set();
    let blocks: Vec<_> = set.blocks.iter().collect();
    let cost: f64 = blocks
        .iter()
        .zip(&result.predictions)
        .flat_map(|(b, p)| b.residuals(p))
        .map(|r| r * r)
        .sum();
    assert!((cost - best).abs() <= 1e-9 * best, "{cost} vs {best}");
}

//! Fits side by side: when a set's evaluations take several fits at once (an executor
//! whose runs go to a cluster), the starts of a multi-start fit, the refits of a bootstrap
//! and the folds of a cross-validation run concurrently. Their results are those of one fit after another, to the
//! bit.

use fitting::fit::evaluations::{Evaluations, InProcess, Prediction, Request};
use fitting::fit::optimize::run::{run_fit, FitProgress, Optimizer};
use fitting::fit::sets::fit_set::FitSet;
use fitting::fit::statistics::bootstrap::bootstrap;
use fitting::fit::statistics::cross_validation::leave_one_group_out;
use std::ops::ControlFlow;
use std::path::Path;
use std::sync::Arc;

/// In-process predictions that let three fits run at once.
struct ThreeAtOnce;

impl Evaluations for ThreeAtOnce {
    fn describe(&self) -> String {
        "three fits at once".into()
    }

    fn predict(&self, requests: &[Request]) -> anyhow::Result<Vec<Prediction>> {
        InProcess.predict(requests)
    }

    fn fits_at_once(&self) -> usize {
        3
    }
}

/// The shipped synthetic set with three starts.
fn default_set() -> FitSet {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/experiments/default.toml");
    let mut set = FitSet::load(&file).unwrap();
    set.starts = 3;
    set
}

fn bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|v| v.to_bits()).collect()
}

#[test]
fn starts_side_by_side_give_the_fit_of_starts_one_after_another() {
    let go = |_: &FitProgress| ControlFlow::Continue(());
    let mut set = default_set();
    let one = run_fit(&set, Optimizer::LmExact, &go).unwrap();
    set.evaluations = Arc::new(ThreeAtOnce);
    let three = run_fit(&set, Optimizer::LmExact, &go).unwrap();
    for (a, b) in one.stages.iter().zip(&three.stages) {
        assert_eq!(a.runs.len(), 3);
        assert_eq!(a.runs.len(), b.runs.len());
        for (x, y) in a.runs.iter().zip(&b.runs) {
            assert_eq!(bits(&x.u), bits(&y.u));
            assert_eq!(x.cost.to_bits(), y.cost.to_bits());
        }
        assert_eq!(a.best, b.best);
        assert_eq!(bits(&a.values), bits(&b.values));
    }
}

#[test]
fn refits_side_by_side_give_the_bootstrap_of_refits_one_after_another() {
    let go = |_: &FitProgress| ControlFlow::Continue(());
    let mut set = default_set();
    set.starts = 1;
    let fit = run_fit(&set, Optimizer::LmExact, &go).unwrap();
    let one = bootstrap(&set, &fit.material, 8, &|_| {}).unwrap();
    set.evaluations = Arc::new(ThreeAtOnce);
    let three = bootstrap(&set, &fit.material, 8, &|_| {}).unwrap();
    assert_eq!((one.samples, one.failed), (three.samples, three.failed));
    for (a, b) in one.params.iter().zip(&three.params) {
        let of = |p: &fitting::fit::statistics::bootstrap::ParamInterval| {
            bits(&[p.mean, p.sd, p.lo95, p.hi95])
        };
        assert_eq!(of(a), of(b), "{}", a.name);
    }
    assert!(
        one.params.iter().any(|p| p.sd > 0.0),
        "a bootstrap with spread"
    );
}

#[test]
fn folds_side_by_side_give_the_cross_validation_of_folds_one_after_another() {
    let go = |_: &FitProgress| ControlFlow::Continue(());
    let mut set = default_set();
    set.starts = 1;
    let fit = run_fit(&set, Optimizer::LmExact, &go).unwrap();
    let one = leave_one_group_out(&set, &fit.material, &|_, _| {}).unwrap();
    set.evaluations = Arc::new(ThreeAtOnce);
    let three = leave_one_group_out(&set, &fit.material, &|_, _| {}).unwrap();
    assert!(one.len() >= 3, "{} folds", one.len());
    for (a, b) in one.iter().zip(&three) {
        assert_eq!(a.left_out, b.left_out);
        assert_eq!(bits(&a.values), bits(&b.values), "{}", a.left_out);
        assert_eq!(
            a.out_of_sample.rms_vs_mean.to_bits(),
            b.out_of_sample.rms_vs_mean.to_bits()
        );
    }
}

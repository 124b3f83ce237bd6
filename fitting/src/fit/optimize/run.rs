//! Running a fit: the stages in order (each starts from the previous stage's values, the
//! parameters not free in a stage stay fixed), multi-start within a stage (the stated
//! start plus `starts − 1` starts drawn uniformly in u over the logistic images of the
//! central 90 % of each bound interval, seeded), and the statistics at the optimum:
//!
//! Cov(p) = s² (J_pᵀ J_p)⁻¹, s² = S/(n − P), standard error √Cov_kk, correlation
//! Cov_kl/√(Cov_kk Cov_ll), with J_p = dr/dp the exact Jacobian at the optimum.
//!
//! A fit its caller interrupts (the progress callback answers `Break`) ends at once: the
//! stage under way keeps its best point so far without statistics, later starts and stages
//! do not run, and the result says `interrupted`.

use crate::fit::levels::model::{with_values, Material};
use crate::fit::objective::{predict_with_warnings, Block, JacobianKind, Objective};
use crate::fit::optimize::lm::{levenberg_marquardt, LmOptions};
use crate::fit::optimize::nelder_mead::{nelder_mead, NmOptions};
use crate::fit::optimize::trace::{unwatched, HistoryPoint, OptimResult};
use crate::fit::params::ParamSpace;
use crate::fit::sets::fit_set::FitSet;
use crate::fit::statistics::assumptions::{contact_shifts, AssumptionShift};
use anyhow::{bail, Result};
use materials::material::Model;
use nalgebra::DMatrix;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rayon::prelude::*;
use std::ops::ControlFlow;

/// Which optimizer a stage uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Optimizer {
    LmExact,
    LmFiniteDifference,
    NelderMead,
}

impl Optimizer {
    pub fn parse(name: &str) -> Result<Self> {
        Ok(match name {
            "lm" => Optimizer::LmExact,
            "lm-fd" => Optimizer::LmFiniteDifference,
            "nelder-mead" => Optimizer::NelderMead,
            other => bail!("optimizer \"{other}\": expected lm, lm-fd or nelder-mead"),
        })
    }
}

/// Result of one stage.
#[derive(Debug, Clone)]
pub struct StageResult {
    pub free: Vec<String>,
    pub experiments: Vec<usize>,
    pub values: Vec<f64>,
    pub std_errors: Vec<f64>,
    pub correlation: Vec<Vec<f64>>,
    /// Linearized refit shifts under changed contact assumptions (MPM levels; else empty).
    pub contact: Vec<AssumptionShift>,
    pub cost: f64,
    pub samples: usize,
    /// Every start's run; `best` indexes the one kept.
    pub runs: Vec<OptimResult>,
    pub best: usize,
    pub evaluations: usize,
    pub jacobians: usize,
    pub wall_s: f64,
}

impl StageResult {
    /// Whether the caller stopped this stage before its optimizer ended.
    pub fn interrupted(&self) -> bool {
        self.runs.iter().any(|r| r.interrupted)
    }
}

/// Where a fit is, for its progress callback: stage and start (0-based) of how many, and
/// the optimizer's latest history point.
pub struct FitProgress<'a> {
    pub stage: usize,
    pub stages: usize,
    pub start: usize,
    pub starts: usize,
    pub point: &'a HistoryPoint,
}

/// Fit result: stages and the final material.
#[derive(Debug, Clone)]
pub struct FitResult {
    pub stages: Vec<StageResult>,
    pub material: Material,
    /// Final predictions of every experiment of the set, and what each model's run warned
    /// about at the final parameters (points that reached the melting temperature).
    pub predictions: Vec<Vec<f64>>,
    pub warnings: Vec<Vec<String>>,
    pub wall_s: f64,
    /// The caller stopped the fit: the last stage is its best point so far, later stages
    /// did not run.
    pub interrupted: bool,
}

fn random_start(space: &ParamSpace, rng: &mut Pcg64) -> Vec<f64> {
    space
        .params
        .iter()
        .map(|p| {
            let x = if p.lower.is_finite() && p.upper.is_finite() {
                p.lower + (p.upper - p.lower) * rng.gen_range(0.05..0.95)
            } else {
                p.start * rng.gen_range(0.5..2.0)
            };
            p.to_unbounded(x)
        })
        .collect()
}

/// Fit `set` with `optimizer`; `progress` sees every objective evaluation and may stop the
/// fit.
pub fn run_fit(
    set: &FitSet,
    optimizer: Optimizer,
    progress: &(dyn Fn(&FitProgress) -> ControlFlow<()> + Sync),
) -> Result<FitResult> {
    if set.params.is_empty() {
        bail!(
            "{}: the set has no [[parameter]], nothing to fit; `mpw predict` evaluates it",
            set.file.display()
        );
    }
    let t0 = std::time::Instant::now();
    let mut material = set.base;
    let mut stages = Vec::new();
    let mut rng = Pcg64::seed_from_u64(set.seed);
    for (si, stage) in set.stages.iter().enumerate() {
        // Start values: the stated start for the first stage a parameter is free in,
        // afterwards the current value (clamped inside its bounds).
        let params = stage
            .free
            .iter()
            .map(|&k| {
                let p = &set.params[k];
                let seen = set.stages[..si].iter().any(|s| s.free.contains(&k));
                match seen {
                    true => p.starting_at(material.param(&p.name).unwrap()),
                    false => p.clone(),
                }
            })
            .collect();
        let space = ParamSpace::new(params)?;
        let blocks = stage.experiments.iter().map(|&e| &set.blocks[e]).collect();
        let objective = Objective::new(material, blocks, space.clone())?
            .with_evaluations(set.evaluations.as_ref());
        let mut runs = Vec::new();
        let options = LmOptions {
            ftol: set.ftol,
            ..LmOptions::default()
        };
        let starts: Vec<Vec<f64>> = (0..set.starts)
            .map(|start| match start {
                0 => space.to_unbounded(&space.starts()),
                _ => random_start(&space, &mut rng),
            })
            .collect();
        let one_start = |start: usize| {
            let report = |point: &HistoryPoint| {
                progress(&FitProgress {
                    stage: si,
                    stages: set.stages.len(),
                    start,
                    starts: set.starts,
                    point,
                })
            };
            let u0 = &starts[start];
            match optimizer {
                Optimizer::LmExact => {
                    levenberg_marquardt(&objective, u0, JacobianKind::Exact, &options, &report)
                }
                Optimizer::LmFiniteDifference => levenberg_marquardt(
                    &objective,
                    u0,
                    JacobianKind::FiniteDifference,
                    &options,
                    &report,
                ),
                Optimizer::NelderMead => {
                    nelder_mead(&objective, u0, &NmOptions::default(), &report)
                }
            }
        };
        // starts side by side when the runs go to an executor that takes several fits at
        // once; else one after another, the next one only if the last was not interrupted
        let at_once = set.evaluations.fits_at_once().min(set.starts);
        let mut results = Vec::new();
        if at_once > 1 {
            results = rayon::ThreadPoolBuilder::new()
                .num_threads(at_once)
                .build()?
                .install(|| (0..set.starts).into_par_iter().map(one_start).collect());
        } else {
            for start in 0..set.starts {
                let run = one_start(start);
                let interrupted = run.as_ref().is_ok_and(|r| r.interrupted);
                results.push(run);
                if interrupted {
                    break;
                }
            }
        }
        for (start, run) in results.into_iter().enumerate() {
            match run {
                Ok(r) => runs.push(r),
                Err(e) if start > 0 => eprintln!("stage {}: start {start} failed: {e:#}", si + 1),
                Err(e) => return Err(e),
            }
        }
        let best = (0..runs.len())
            .min_by(|&a, &b| runs[a].cost.total_cmp(&runs[b].cost))
            .unwrap();
        let u = runs[best].u.clone();
        let values = space.to_bounded(&u);
        let interrupted = runs.iter().any(|r| r.interrupted);
        let (std_errors, correlation, contact) = match interrupted {
            true => (vec![f64::NAN; values.len()], Vec::new(), Vec::new()),
            false => {
                let (r, jp) = residuals_and_jacobian_in_p(&objective, &u)?;
                let (std_errors, correlation) = covariance(&r, &jp);
                let contact = contact_shifts(&objective, &values, &r, &jp)?;
                (std_errors, correlation, contact)
            }
        };
        let (evaluations, jacobians) = objective.counts();
        let names: Vec<String> = space.names().iter().map(|s| s.to_string()).collect();
        material = with_values(&material, &space.names(), &values);
        stages.push(StageResult {
            free: names,
            experiments: stage.experiments.clone(),
            values,
            std_errors,
            correlation,
            contact,
            cost: runs[best].cost,
            samples: objective.len(),
            best,
            evaluations,
            jacobians,
            wall_s: runs.iter().map(|r| r.wall_s).sum(),
            runs,
        });
        if interrupted {
            break;
        }
    }
    let (predictions, warnings) = predict_with_warnings(
        set.evaluations.as_ref(),
        &set.blocks.iter().collect::<Vec<_>>(),
        &material,
    )?;
    Ok(FitResult {
        warnings,
        interrupted: stages.iter().any(StageResult::interrupted),
        stages,
        material,
        predictions,
        wall_s: t0.elapsed().as_secs_f64(),
    })
}

/// A refit on part of the data (a bootstrap resample, a cross-validation fold).
#[derive(Debug, Clone)]
pub struct Refit {
    /// Bounded values of `set.params`, in order.
    pub values: Vec<f64>,
    pub converged: bool,
    pub termination: String,
}

/// Fit every free parameter of `set` at once on `blocks` (which may repeat a block), one
/// Levenberg-Marquardt run with the exact Jacobian from `start` (bounded values of
/// `set.params`, or their stated starts when `None`); the other parameters as in `base`.
pub fn refit(
    set: &FitSet,
    base: Material,
    blocks: Vec<&Block>,
    start: Option<&[f64]>,
) -> Result<Refit> {
    let params = match start {
        Some(x) => set
            .params
            .iter()
            .zip(x)
            .map(|(p, &x)| p.starting_at(x))
            .collect(),
        None => set.params.clone(),
    };
    let space = ParamSpace::new(params)?;
    let objective =
        Objective::new(base, blocks, space.clone())?.with_evaluations(set.evaluations.as_ref());
    let u0 = space.to_unbounded(&space.starts());
    let run = levenberg_marquardt(
        &objective,
        &u0,
        JacobianKind::Exact,
        &LmOptions::default(),
        &unwatched,
    )?;
    Ok(Refit {
        values: space.to_bounded(&run.u),
        converged: run.converged,
        termination: run.termination,
    })
}

/// Evaluate every experiment of `set` with `material`: a result without stages.
pub fn run_predict(set: &FitSet, material: Material) -> Result<FitResult> {
    let t0 = std::time::Instant::now();
    let (predictions, warnings) = predict_with_warnings(
        set.evaluations.as_ref(),
        &set.blocks.iter().collect::<Vec<_>>(),
        &material,
    )?;
    Ok(FitResult {
        warnings,
        stages: Vec::new(),
        material,
        predictions,
        wall_s: t0.elapsed().as_secs_f64(),
        interrupted: false,
    })
}

/// Standard errors and correlation matrix at `u` from the exact Jacobian in p.
pub fn statistics(objective: &Objective, u: &[f64]) -> Result<(Vec<f64>, Vec<Vec<f64>>)> {
    let (r, jp) = residuals_and_jacobian_in_p(objective, u)?;
    Ok(covariance(&r, &jp))
}

/// Residuals r and their exact Jacobian dr/dp in the bounded parameters, at `u`.
pub fn residuals_and_jacobian_in_p(
    objective: &Objective,
    u: &[f64],
) -> Result<(Vec<f64>, DMatrix<f64>)> {
    let (r, mut jp) = objective.residuals_and_jacobian(u, JacobianKind::Exact)?;
    for (k, dpdu) in objective.space.derivatives(u).iter().enumerate() {
        jp.column_mut(k).scale_mut(1.0 / dpdu);
    }
    Ok((r, jp))
}

/// Standard errors and correlation matrix from residuals `r` and J_p = dr/dp.
fn covariance(r: &[f64], jp: &DMatrix<f64>) -> (Vec<f64>, Vec<Vec<f64>>) {
    let p = jp.ncols();
    let n = r.len();
    let s2 = r.iter().map(|x| x * x).sum::<f64>() / (n.saturating_sub(p).max(1)) as f64;
    let jtj = jp.transpose() * jp;
    let Some(inv) = jtj.clone().try_inverse() else {
        return (vec![f64::INFINITY; p], vec![vec![f64::NAN; p]; p]);
    };
    let cov = inv * s2;
    let se: Vec<f64> = (0..p).map(|k| cov[(k, k)].max(0.0).sqrt()).collect();
    let corr = (0..p)
        .map(|i| (0..p).map(|j| cov[(i, j)] / (se[i] * se[j])).collect())
        .collect();
    (se, corr)
}

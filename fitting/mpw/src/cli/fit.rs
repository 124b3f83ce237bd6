//! `mpw fit [SET]`: fit an experiment set (default `data/experiments/default.toml`), print
//! the report, write `report.toml`, per-experiment CSVs and charts to `--out`.
//! `--compare` also runs Nelder-Mead, LM with the exact Jacobian and LM with finite
//! differences on the same set and charts objective against evaluations and wall time.
//! Progress shows stage, start, iteration, objective, elapsed time and an estimate of the
//! iterations left; Ctrl-C (or SIGTERM) stops at the next evaluation and writes a partial
//! report marked interrupted.

use crate::charts::fit as fit_charts;
use crate::cli::progress::ProgressLine;
use anyhow::Result;
use fitting::fit::evaluations::executor::ExecutorEvaluations;
use fitting::fit::objective::Block;
use fitting::fit::optimize::estimate::remaining_iterations;
use fitting::fit::optimize::run::{run_fit, FitProgress, FitResult, Optimizer};
use fitting::fit::reports::report::{read_parameters, table, write_files};
use fitting::fit::reports::study_report::{
    bootstrap_table, cross_validation_table, write_bootstrap, write_cross_validation,
};
use fitting::fit::sets::fit_set::FitSet;
use fitting::fit::statistics::bootstrap::bootstrap;
use fitting::fit::statistics::cross_validation::leave_one_group_out;
use fitting::fit::statistics::scatter::scatter;
use materials::material::Model;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Experiment-set file.
    #[arg(default_value = "data/experiments/default.toml")]
    pub set: PathBuf,
    /// Override the set's optimizer: lm, lm-fd or nelder-mead.
    #[arg(long)]
    pub optimizer: Option<String>,
    /// Override the set's number of starts.
    #[arg(long)]
    pub starts: Option<usize>,
    /// Start from the parameters of this fit report or material file (e.g. the
    /// single-point fit before an MPM-level fit), clamped into the set's bounds.
    #[arg(long, value_name = "REPORT")]
    pub start: Option<PathBuf>,
    /// Output folder for report and charts.
    #[arg(long, default_value = "out/fit")]
    pub out: PathBuf,
    /// Also compare Nelder-Mead, LM (exact) and LM (finite differences).
    #[arg(long)]
    pub compare: bool,
    /// Validation run: fail unless every stage converged and every group's RMS error
    /// against its mean measured curve (a single record: its own samples) is at most 5 %
    /// of the mean measured magnitude.
    #[arg(long)]
    pub validate: bool,
    /// Bootstrap over records: this many resamples (records drawn with replacement within
    /// each group), each refitted from the optimum; intervals, correlation, bands.
    #[arg(long, value_name = "SAMPLES")]
    pub bootstrap: Option<usize>,
    /// Leave one group out: fit on the other groups, predict the one left out.
    #[arg(long)]
    pub cross_validate: bool,
    /// Exit 0 even when a group's RMS against its mean curve exceeds 50 % (a poor fit,
    /// usually a unit mistake).
    #[arg(long)]
    pub allow_poor_fit: bool,
    /// Where the MPM-level runs go (every run of a pass or a Jacobian at once): in this
    /// process, a local pool of `mpw run-one` processes, or Slurm job arrays; single-point
    /// runs stay in this process.
    #[command(flatten)]
    pub executor: super::executor_args::ExecutorArgs,
}

/// RMS against a group's mean curve above which a fit is poor: no parameter set of the
/// model describes the data, which usually means a unit or column mistake.
pub const POOR_FIT_RMS: f64 = 0.5;

/// Fail if a group of `result` is fitted worse than `POOR_FIT_RMS`, naming the likely causes.
fn refuse_poor_fit(file: &Path, set: &FitSet, result: &FitResult) -> Result<()> {
    let blocks: Vec<&Block> = set.blocks.iter().collect();
    let poor: Vec<String> = scatter(&blocks, &result.predictions)
        .iter()
        .filter(|g| !(g.rms_vs_mean <= POOR_FIT_RMS))
        .map(|g| format!("{} ({:.0} %)", g.group.label, 100.0 * g.rms_vs_mean))
        .collect();
    if poor.is_empty() {
        return Ok(());
    }
    anyhow::bail!(
        "{}: poor fit: RMS against the mean measured curve above {:.0} % for {}. Check the column units first (a strain in % declared as \"1\" or the reverse, a stress in Pa declared as MPa), then the window and the model level. The report is written; --allow-poor-fit exits 0",
        file.display(),
        100.0 * POOR_FIT_RMS,
        poor.join(", ")
    )
}

/// Largest RMS error of a validated fit against a group's mean curve, as a fraction of
/// the mean measured magnitude.
pub const VALIDATION_RMS: f64 = 0.05;

/// Fail unless every group's RMS against its mean curve is at most `VALIDATION_RMS` and
/// every stage (none for a prediction) converged.
pub fn validate(file: &Path, set: &FitSet, result: &FitResult) -> Result<()> {
    let mut failures = Vec::new();
    for (i, s) in result.stages.iter().enumerate() {
        if !s.runs[s.best].converged {
            failures.push(format!(
                "stage {} did not converge: {}",
                i + 1,
                s.runs[s.best].termination
            ));
        }
    }
    let blocks: Vec<&Block> = set.blocks.iter().collect();
    for g in scatter(&blocks, &result.predictions) {
        if !(g.rms_vs_mean <= VALIDATION_RMS) {
            failures.push(format!(
                "{}: RMS {:.2} % of the mean measured value (against the mean of its {} record(s)) exceeds {:.0} %",
                g.group.label,
                100.0 * g.rms_vs_mean,
                g.group.members.len(),
                100.0 * VALIDATION_RMS
            ));
        }
    }
    if !failures.is_empty() {
        anyhow::bail!(
            "validation of {} failed:\n  {}",
            file.display(),
            failures.join("\n  ")
        );
    }
    println!("validation passed");
    Ok(())
}

/// One progress line of a fit: where it is, the objective, the time, and (Levenberg-
/// Marquardt) an estimate of the iterations left from the best objective after each
/// iteration so far (`costs`).
fn progress_text(f: &FitProgress, costs: &[f64], ftol: f64) -> String {
    let p = f.point;
    let step = match p.iteration {
        Some(k) => format!("iteration {k}"),
        None => format!("evaluation {}", p.evaluations),
    };
    let estimate = match (p.iteration, remaining_iterations(costs, ftol)) {
        (Some(_), Some(0)) => "; at the tolerance".to_string(),
        (Some(k), Some(left)) if k > 0 => format!(
            "; about {left} more iteration(s), ~{:.0} s, to the tolerance",
            left as f64 * p.wall_s / k as f64
        ),
        _ => String::new(),
    };
    format!(
        "  stage {}/{} start {}/{}: {step}, S = {:.6e}, {:.1} s, {} evaluations + {} Jacobians{estimate}",
        f.stage + 1,
        f.stages,
        f.start + 1,
        f.starts,
        p.cost,
        p.wall_s,
        p.evaluations,
        p.jacobians,
    )
}

/// Fit a set with progress on standard error; `stop` ends the fit at its next evaluation.
pub fn fit_with_progress(
    set: &FitSet,
    optimizer: Optimizer,
    stop: &AtomicBool,
) -> Result<FitResult> {
    let line = ProgressLine::default();
    // Best objective at the end of each iteration of the current stage and start.
    let costs: Mutex<(String, Vec<f64>)> = Mutex::default();
    let progress = |f: &FitProgress| {
        let key = format!("{}/{}", f.stage, f.start);
        let mut c = costs.lock().unwrap();
        if c.0 != key {
            *c = (key.clone(), Vec::new());
        }
        let k = f.point.iteration.unwrap_or(0);
        c.1.resize(k + 1, f.point.cost);
        c.1[k] = f.point.cost;
        line.show(&key, &progress_text(f, &c.1, set.ftol));
        match stop.load(Ordering::Relaxed) {
            true => ControlFlow::Break(()),
            false => ControlFlow::Continue(()),
        }
    };
    let result = run_fit(set, optimizer, &progress);
    line.finish();
    result
}

/// What the models warned about at the final parameters, on standard error.
pub fn warn_about_models(set: &FitSet, result: &FitResult) {
    for (block, warnings) in set.blocks.iter().zip(&result.warnings) {
        for w in warnings {
            eprintln!("warning: {}: {w}", block.name);
        }
    }
}

/// After the fit's report is written, an interrupt during a study ends the process: the
/// study has no partial form.
fn quit_if_stopped(stop: &AtomicBool, study: &str, out: &Path) {
    if stop.load(Ordering::Relaxed) {
        eprintln!(
            "interrupted during the {study}: the fit's report is in {}, the {study} is not written",
            out.display()
        );
        std::process::exit(130);
    }
}

pub fn run(args: Args) -> Result<()> {
    let sets = FitSet::load_candidates(&args.set)?;
    if sets.len() > 1 {
        anyhow::ensure!(
            !(args.compare || args.bootstrap.is_some() || args.cross_validate || args.start.is_some()),
            "{}: a set with [[candidate]] laws fits and cross-validates each law; --compare, --bootstrap, --cross-validate and --start apply to one law (fit it from a set without candidates)",
            args.set.display()
        );
        anyhow::ensure!(
            args.executor.executor == super::executor_args::Kind::InProcess,
            "{}: a set with [[candidate]] laws runs in this process (--executor in-process)",
            args.set.display()
        );
        return super::fit_choice::run(&args, sets);
    }
    let (_, mut set) = sets.into_iter().next().expect("the set as written");
    if let Some(s) = args.starts {
        set.starts = s.max(1);
    }
    if let Some(file) = &args.start {
        let start = read_parameters(&set.base, file)?;
        for p in &mut set.params {
            *p = p.starting_at(start.param(&p.name).expect("a free parameter of the base"));
        }
    }
    let optimizer = Optimizer::parse(args.optimizer.as_deref().unwrap_or(&set.optimizer))?;
    let stop = crate::cli::interrupt::interrupt_flag()?;
    eprintln!(
        "fitting {} ({} experiments)",
        args.set.display(),
        set.blocks.len()
    );
    let name = args
        .set
        .file_stem()
        .map_or("set".into(), |s| s.to_string_lossy().into_owned());
    let job_name = format!("mpw-fit-{name}");
    if let Some((executor, dir)) = args
        .executor
        .subprocesses(&job_name, args.out.join("runs"))?
    {
        eprintln!(
            "MPM-level runs: {} in {}",
            executor.describe(),
            dir.display()
        );
        let mut evaluations =
            ExecutorEvaluations::new(executor, args.set.clone(), dir, stop.clone())?;
        // bootstrap refits side by side, as many as keep a Jacobian pass of each in flight
        let pass = set.blocks.len() * (1 + set.params.len());
        evaluations.fits_at_once = (args.executor.runs_at_once()? / pass.max(1)).max(1);
        set.evaluations = std::sync::Arc::new(evaluations);
    }
    let result = fit_with_progress(&set, optimizer, &stop)?;
    print!("{}", table(&set, &result));
    write_files(&args.out, &set, &result)?;
    fit_charts::fit_charts(&args.out, &set, &result)?;
    warn_about_models(&set, &result);
    if result.interrupted {
        anyhow::bail!(
            "{}: the fit was interrupted; the partial report (best values so far, marked interrupted) is in {}",
            args.set.display(),
            args.out.display()
        );
    }
    if !args.allow_poor_fit {
        refuse_poor_fit(&args.set, &set, &result)?;
    }
    if let Some(samples) = args.bootstrap {
        let line = ProgressLine::default();
        let report = |b: usize| {
            quit_if_stopped(&stop, "bootstrap", &args.out);
            let text = format!("  bootstrap sample {}/{samples}", b + 1);
            line.show(&(10 * b / samples).to_string(), &text);
        };
        let b = bootstrap(&set, &result.material, samples, &report);
        line.finish();
        let b = b?;
        print!("{}", bootstrap_table(&b));
        write_bootstrap(&args.out, &set, &b)?;
        fit_charts::scatter_charts(&args.out, &set, &result.predictions, Some(&b))?;
    }
    if args.cross_validate {
        let report = |k: usize, g: &str| {
            quit_if_stopped(&stop, "cross-validation", &args.out);
            eprintln!("  fold {}: without {g}", k + 1)
        };
        let folds = leave_one_group_out(&set, &result.material, &report)?;
        print!("{}", cross_validation_table(&set, &folds));
        write_cross_validation(&args.out, &set, &folds)?;
    }
    if args.compare {
        let mut runs = Vec::new();
        for opt in [
            Optimizer::NelderMead,
            Optimizer::LmExact,
            Optimizer::LmFiniteDifference,
        ] {
            eprintln!("comparison: {opt:?}");
            let mut single = FitSet::load(&args.set)?;
            single.starts = 1;
            let r = fit_with_progress(&single, opt, &stop)?;
            if r.interrupted {
                anyhow::bail!("the comparison was interrupted during {opt:?}");
            }
            runs.push(r);
        }
        let summary = fit_charts::comparison(&args.out, &runs)?;
        print!("{summary}");
    }
    println!("report, CSVs and charts in {}", args.out.display());
    if args.validate {
        validate(&args.set, &set, &result)?;
    }
    Ok(())
}

//! `mpw design SET --test KIND:RATE:TEMPERATURE ...`: which candidate test would shrink the
//! fitted parameters' joint uncertainty most (`fitting::fit::statistics::design`). The set
//! is fitted first, or its parameters are read from a fit report (`--params`).

use anyhow::Result;
use fitting::fit::objective::Block;
use fitting::fit::optimize::run::{run_fit, Optimizer};
use fitting::fit::reports::report::{read_parameters, show};
use fitting::fit::sets::fit_set::FitSet;
use fitting::fit::statistics::design::{rank, CandidateTest, Uncertainty};
use materials::material::Model;
use std::fmt::Write as _;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Experiment-set file: its records and free parameters.
    pub set: PathBuf,
    /// A candidate test, `tensile:RATE:TEMPERATURE` or `shpb:RATE:TEMPERATURE` (1/s, K);
    /// repeat for each.
    #[arg(long = "test", required = true, value_name = "KIND:RATE:TEMPERATURE")]
    pub tests: Vec<String>,
    /// The fitted parameters, from this fit report (default: fit the set first).
    #[arg(long, value_name = "REPORT")]
    pub params: Option<PathBuf>,
}

pub fn run(args: Args) -> Result<()> {
    let tests: Vec<CandidateTest> = (args.tests.iter())
        .map(|t| t.parse())
        .collect::<Result<_>>()?;
    let set = FitSet::load(&args.set)?;
    let material = match &args.params {
        Some(report) => read_parameters(&set.base, report)?,
        None => {
            eprintln!("fitting {} first", args.set.display());
            run_fit(&set, Optimizer::LmExact, &|_| {
                std::ops::ControlFlow::Continue(())
            })?
            .material
        }
    };
    let free: Vec<&str> = set.params.iter().map(|p| p.name.as_str()).collect();
    let blocks: Vec<&Block> = set.blocks.iter().collect();
    let (now, ranked) = rank(&blocks, &material, &free, &tests)?;
    let mut out = String::new();
    let values: Vec<String> = (free.iter())
        .map(|n| {
            format!(
                "{n} = {}",
                show(n, material.param(n).expect("a free parameter"))
            )
        })
        .collect();
    let _ = writeln!(out, "{} at {}", args.set.display(), values.join(", "));
    let _ = writeln!(
        out,
        "Which test to run next (linearized at these values, with the noise of the set's records; shrink: geometric mean of the standard errors after / now, smaller is better):"
    );
    let _ = write!(out, "  {:<34} {:>7}", "test", "shrink");
    for n in &free {
        let _ = write!(out, " {:>13}", format!("se {n}"));
    }
    let _ = writeln!(out, "  largest correlation");
    let row = |out: &mut String, label: &str, shrink: f64, u: &Uncertainty| {
        let _ = write!(out, "  {label:<34} {shrink:>7.3}");
        for (n, se) in free.iter().zip(&u.std_errors) {
            let _ = write!(out, " {:>13}", show(n, *se));
        }
        let (i, j, r) = u.worst_pair;
        let _ = writeln!(out, "  {}-{} r = {r:.3}", free[i], free[j]);
    };
    row(&mut out, "(now)", 1.0, &now);
    for r in &ranked {
        row(&mut out, &r.test.to_string(), r.shrink, &r.after);
    }
    if let Some(first) = ranked.first() {
        let _ = writeln!(out, "best next test: {}", first.test);
    }
    print!("{out}");
    Ok(())
}

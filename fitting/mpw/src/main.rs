//! `mpw`: the material-point workbench command line.

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "mpw",
    version = concat!(env!("CARGO_PKG_VERSION"), " (", env!("MPW_COMMIT"), ")"),
    about = "Johnson-Cook parameters you can trust: material models, single-point driver, MPM, fitting"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Drive one material point along a load path; write CSV and a stress-strain chart.
    Drive(mpw::cli::drive::Args),
    /// Run the verification cases and print one table row per case.
    Verify(mpw::cli::verify::Args),
    /// Measure the cost of material updates (ns per update).
    Bench(mpw::cli::bench::Args),
    /// Process an SHPB record: face forces, strain rate, stress-strain curve, equilibrium.
    Shpb(mpw::cli::shpb::Args),
    /// Fit material parameters to an experiment set (default: the synthetic 42CrMo4 set); with [[candidate]] laws, choose the law that predicts best
    Fit(mpw::cli::fit::Args),
    /// Write a Johnson-Cook card for another code (Abaqus, LS-DYNA, JSON) in a stated unit system.
    Export(mpw::cli::export::Args),
    /// Rank candidate tests (tensile or SHPB at a rate and temperature) by how much each would shrink the fitted parameters' joint uncertainty
    Design(mpw::cli::design::Args),
    /// Evaluate an experiment set with given parameters (fit report or material file), no optimizer.
    Predict(mpw::cli::predict::Args),
    /// Write a synthetic experiment set from a stated parameter set, noise level and seed.
    Synth(mpw::cli::synth::Args),
    /// Run an MPM scene (TOML): progress bar, CSV history, VTK snapshots, energy chart.
    Simulate(mpw::cli::simulate::Args),
    /// Metal cutting (thesis chapter 12): the vertical cut at a set of table 12.2, the
    /// punch force against relative feed and the feed reached.
    #[command(subcommand)]
    Cut(mpw::cli::cut::Cut),
    /// A study over one or two fields of a scene and over seeds, through an executor
    /// (in process, a local process pool or Slurm); one CSV of results.
    Sweep(mpw::cli::sweep::Args),
    /// Run one task (a run description) into its folder: outcome and manifest. The
    /// executors start it.
    RunOne(mpw::cli::run_one::Args),
    /// Measure MPM throughput (particle-steps/s with 1 and 2 threads) and bytes per particle.
    BenchMpm(mpw::cli::bench_mpm::Args),
    /// What exact parameter derivatives through an MPM run cost: the Taylor bar plain and
    /// with 4 and 5 Johnson-Cook derivatives, against a finite-difference Jacobian.
    BenchDerivatives(mpw::cli::bench_derivatives::Args),
    /// What an executor costs: overhead per one-second run in process, in the local pool
    /// and through Slurm, and the pool's speed-up on a 16-run sweep.
    BenchRuns(mpw::cli::bench_runs::Args),
    /// Every shape function on the truss and the Taylor bar: error against wall time.
    Kernels(mpw::cli::kernels::Args),
    /// Print the shell completions of mpw (source them, or save them where the shell looks).
    Completions {
        /// The shell.
        shell: clap_complete::Shell,
    },
}

fn main() {
    let cli = Cli::parse();
    // Every command runs on a worker of one pool, so that a parallel loop starts where it
    // is called instead of being handed from the main thread to the pool and back (a
    // futex round trip per loop, tens per MPM step). The stack is the main thread's usual
    // 8 MiB.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(pool_threads())
        .stack_size(8 << 20)
        .build()
        .expect("the thread pool starts");
    let result = pool.install(|| dispatch(cli.command));
    if let Err(e) = result {
        let message = format!("{e:#}");
        eprintln!("error: {message}");
        // a default path (`data/...`, relative) that the current folder does not have
        let default_path = message
            .split(|c: char| c.is_whitespace() || "`'\"(".contains(c))
            .any(|word| word.starts_with("data/"));
        if default_path && !std::path::Path::new("data").is_dir() {
            eprintln!(
                "hint: the default files (data/...) are found from the current folder, which has no data/ folder: \
run mpw from the repository root, or name the files (mpw fit SET.toml, mpw verify --data DIR, mpw drive --material FILE)"
            );
        }
        std::process::exit(1);
    }
}

/// RAYON_NUM_THREADS if set (0: unset), else the CPUs this process may use
/// (`mpm_core::parallel::cpus`: affinity, cgroup quota, SLURM_CPUS_PER_TASK); never more
/// than those CPUs, since a thread beyond them only waits for a CPU and makes the others
/// wait for it (the results are the same on any thread count).
fn pool_threads() -> usize {
    let cpus = mpm_core::parallel::cpus();
    let asked = std::env::var("RAYON_NUM_THREADS").ok();
    match asked.as_deref().map(str::trim).map(str::parse::<usize>) {
        Some(Ok(n)) if n > cpus => {
            eprintln!("note: RAYON_NUM_THREADS={n}, but this process may use {cpus} CPUs: running {cpus} threads");
            cpus
        }
        Some(Ok(n)) if n > 0 => n,
        Some(Ok(_)) | None => cpus,
        Some(Err(_)) => {
            eprintln!("note: RAYON_NUM_THREADS is not a count: running {cpus} threads");
            cpus
        }
    }
}

fn dispatch(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Drive(a) => mpw::cli::drive::run(a),
        Command::Verify(a) => mpw::cli::verify::run(a),
        Command::Bench(a) => mpw::cli::bench::run(a),
        Command::Shpb(a) => mpw::cli::shpb::run(a),
        Command::Fit(a) => mpw::cli::fit::run(a),
        Command::Export(a) => mpw::cli::export::run(a),
        Command::Design(a) => mpw::cli::design::run(a),
        Command::Predict(a) => mpw::cli::predict::run(a),
        Command::Synth(a) => mpw::cli::synth::run(a),
        Command::Simulate(a) => mpw::cli::simulate::run(a),
        Command::Cut(c) => mpw::cli::cut::run(c),
        Command::Sweep(a) => mpw::cli::sweep::run(a),
        Command::RunOne(a) => mpw::cli::run_one::run(a),
        Command::BenchMpm(a) => mpw::cli::bench_mpm::run(a),
        Command::BenchDerivatives(a) => mpw::cli::bench_derivatives::run(a),
        Command::BenchRuns(a) => mpw::cli::bench_runs::run(a),
        Command::Kernels(a) => mpw::cli::kernels::run(a),
        Command::Completions { shell } => {
            let mut cli = <Cli as clap::CommandFactory>::command();
            clap_complete::generate(shell, &mut cli, "mpw", &mut std::io::stdout());
            Ok(())
        }
    }
}

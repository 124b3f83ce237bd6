//! `mpw`: the material-point workbench command line.

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "mpw",
    version,
    about = "Johnson-Cook parameters you can trust: material models, single-point driver, MPM, fitting"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Drive one material point along a load path; write CSV and a stress-strain chart.
    Drive(fitting::cli::drive::Args),
    /// Run the verification cases and print one table row per case.
    Verify(fitting::cli::verify::Args),
    /// Measure the cost of material updates (ns per update).
    Bench(fitting::cli::bench::Args),
    /// Process an SHPB record: face forces, strain rate, stress-strain curve, equilibrium.
    Shpb(fitting::cli::shpb::Args),
    /// Fit Johnson-Cook parameters to an experiment set (default: the synthetic 42CrMo4 set).
    Fit(fitting::cli::fit::Args),
    /// Write a Johnson-Cook card for another code (Abaqus, JSON) in a stated unit system.
    Export(fitting::cli::export::Args),
    /// Evaluate an experiment set with given parameters (fit report or material file), no optimizer.
    Predict(fitting::cli::predict::Args),
    /// Write a synthetic experiment set from a stated parameter set, noise level and seed.
    Synth(fitting::cli::synth::Args),
    /// Run an MPM scene (TOML): progress bar, CSV history, VTK snapshots, energy chart.
    Simulate(fitting::cli::simulate::Args),
    /// Measure MPM throughput (particle-steps/s with 1 and 2 threads) and bytes per particle.
    BenchMpm(fitting::cli::bench_mpm::Args),
    /// Every shape function on the truss and the Taylor bar: error against wall time.
    Kernels(fitting::cli::kernels::Args),
}

fn main() {
    let cli = Cli::parse();
    // Every command runs on a worker of one pool (RAYON_NUM_THREADS, default: the cores),
    // so that a parallel loop starts where it is called instead of being handed from the
    // main thread to the pool and back: a futex round trip per loop, tens per MPM step,
    // which cost a small run more system time than compute (issue 15). The stack is the
    // main thread's usual 8 MiB.
    let pool = rayon::ThreadPoolBuilder::new()
        .stack_size(8 << 20)
        .build()
        .expect("the thread pool starts");
    let result = pool.install(|| dispatch(cli.command));
    if let Err(e) = result {
        let message = format!("{e:#}");
        eprintln!("error: {message}");
        if message.contains("data/") && !std::path::Path::new("data").is_dir() {
            eprintln!(
                "hint: the default files (data/...) are found from the current folder, which has no data/ folder: \
run mpw from the repository root, or name the files (mpw fit SET.toml, mpw verify --data DIR, mpw drive --material FILE)"
            );
        }
        std::process::exit(1);
    }
}

fn dispatch(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Drive(a) => fitting::cli::drive::run(a),
        Command::Verify(a) => fitting::cli::verify::run(a),
        Command::Bench(a) => fitting::cli::bench::run(a),
        Command::Shpb(a) => fitting::cli::shpb::run(a),
        Command::Fit(a) => fitting::cli::fit::run(a),
        Command::Export(a) => fitting::cli::export::run(a),
        Command::Predict(a) => fitting::cli::predict::run(a),
        Command::Synth(a) => fitting::cli::synth::run(a),
        Command::Simulate(a) => fitting::cli::simulate::run(a),
        Command::BenchMpm(a) => fitting::cli::bench_mpm::run(a),
        Command::Kernels(a) => fitting::cli::kernels::run(a),
    }
}

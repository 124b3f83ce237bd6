//! `mpw bench-runs`: what an executor costs. A one-second run (the colliding disks on a
//! 0.016 m grid, ≈ 7 000 points, one thread) is run `--runs` times one at a time through
//! each executor; the overhead per run is the batch's wall time less the runs' own time
//! (from their manifests), per run: process start, reading the description, writing
//! outcome and manifest, and the executor's polling (Slurm: queueing and job start too).
//! Then a sweep of `--sweep` such runs in this process (each run on every CPU, one after
//! another) against the local pool (one single-thread run per CPU at once): the speed-up
//! of running whole runs side by side. `--load K` runs K spinning threads meanwhile, a
//! machine busy with something else.

use anyhow::Result;
use runs::{Batch, Executor, RunDescription};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Runs one at a time through each executor.
    #[arg(long, default_value_t = 8)]
    pub runs: usize,
    /// Runs of the in-process against pool sweep.
    #[arg(long, default_value_t = 16)]
    pub sweep: usize,
    /// Slurm config: also measure Slurm's overhead (its max_running is set to 1).
    #[arg(long)]
    pub slurm: Option<PathBuf>,
    /// Spinning threads that keep the machine busy during the measurements.
    #[arg(long, default_value_t = 0)]
    pub load: usize,
    /// The scene (default: the colliding disks).
    #[arg(long, default_value = "data/scenes/colliding_disks.toml")]
    pub scene: PathBuf,
    /// Its grid spacing [m] (0.016: about one second a run on one thread).
    #[arg(long, default_value_t = 0.016)]
    pub spacing: f64,
    /// Where the batches go.
    #[arg(long, default_value = "out/bench_runs")]
    pub out: PathBuf,
}

/// A batch's wall time and its runs' own time [s].
struct Timing {
    wall: f64,
    own: f64,
}

pub fn run(args: Args) -> Result<()> {
    let scene = args.scene.canonicalize()?;
    let stop = AtomicBool::new(false);
    let _load = Load::start(args.load);
    let execute = |d: &RunDescription, dir: &Path| crate::tasks::execute(d, dir, None);
    let description = |threads| {
        let mut d = RunDescription::new("scene", &scene);
        d.set
            .insert("grid.spacing".into(), toml::Value::Float(args.spacing));
        d.set
            .insert("output.snapshots".into(), toml::Value::Integer(0));
        d.threads = threads;
        d
    };
    let time =
        |executor: &dyn Executor, name: &str, runs: usize, threads: usize| -> Result<Timing> {
            let batch = Batch::create(&args.out.join(name), &vec![description(threads); runs])?;
            let start = Instant::now();
            let reports = executor.run(&batch, &stop, &|_| {})?;
            let wall = start.elapsed().as_secs_f64();
            let mut own = 0.0;
            for r in reports {
                own += r.result.map_err(|f| anyhow::anyhow!("{f}"))?.1.wall_seconds;
            }
            Ok(Timing { wall, own })
        };
    let in_process = runs::InProcess {
        program: super::run_one::program(),
        execute: &execute,
    };
    println!(
        "one-second runs, one at a time ({} runs each; load: {} spinning threads)",
        args.runs, args.load
    );
    println!(
        "{:<12} {:>10} {:>12} {:>16}",
        "executor", "wall [s]", "run own [s]", "overhead/run [s]"
    );
    let overhead = |name: &str, executor: &dyn Executor| -> Result<()> {
        let t = time(executor, name, args.runs, 1)?;
        let n = args.runs as f64;
        println!(
            "{name:<12} {:>10.3} {:>12.3} {:>16.4}",
            t.wall,
            t.own / n,
            (t.wall - t.own) / n
        );
        Ok(())
    };
    overhead("in-process", &in_process)?;
    let pool = runs::ProcessPool::new(std::env::current_exe()?, 1, 1, 0);
    overhead("pool", &pool)?;
    if let Some(path) = &args.slurm {
        let mut config = runs::SlurmConfig::read(path)?;
        config.max_running = 1;
        config.cpus_per_task = 1;
        let slurm = runs::Slurm::new(config, std::env::current_exe()?, "mpw-bench-runs");
        overhead("slurm", &slurm)?;
    }
    let cpus = mpm_core::parallel::cpus();
    println!("\na sweep of {} runs on {cpus} CPUs", args.sweep);
    let in_process = time(&in_process, "sweep-in-process", args.sweep, 0)?;
    let pool = runs::ProcessPool::new(std::env::current_exe()?, cpus, 1, 0);
    let pooled = time(&pool, "sweep-pool", args.sweep, 0)?;
    println!(
        "in-process, each run on {cpus} threads: {:.2} s",
        in_process.wall
    );
    println!(
        "pool, {cpus} single-thread runs at once: {:.2} s",
        pooled.wall
    );
    println!("speed-up of the pool: {:.2}", in_process.wall / pooled.wall);
    Ok(())
}

/// Threads that spin until dropped.
struct Load {
    stop: Arc<AtomicBool>,
    threads: Vec<std::thread::JoinHandle<()>>,
}

impl Load {
    fn start(n: usize) -> Load {
        let stop = Arc::new(AtomicBool::new(false));
        let threads = (0..n)
            .map(|_| {
                let stop = stop.clone();
                std::thread::spawn(move || {
                    let mut x = 0u64;
                    while !stop.load(Ordering::Relaxed) {
                        x = std::hint::black_box(
                            x.wrapping_mul(6364136223846793005).wrapping_add(1),
                        );
                    }
                })
            })
            .collect();
        Load { stop, threads }
    }
}

impl Drop for Load {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        for t in self.threads.drain(..) {
            let _ = t.join();
        }
    }
}

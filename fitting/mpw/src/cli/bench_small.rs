//! Small models in `mpw bench-mpm`: (c) the shipped axisymmetric OFHC Taylor
//! bar (2 940 particles, MUSL) stepped alone with 1 and 2 threads, and (n) as many copies
//! of it as threads run at once, one thread each, as a fit evaluates its experiments.
//! Each measurement gives particle-steps per second and the user and system CPU time of
//! the process over the measured steps (`getrusage`), so that time spent waking and
//! parking threads shows as system time; a model alone also gives its time per stage.
//! `median` picks the median of repeated measurements, as this VM's rates drift.

use anyhow::{bail, Result};
use mpm_core::scene::{self, Simulation};
use mpm_core::{Solver, StageTimes};
use std::path::Path;
use std::sync::Barrier;
use std::time::Instant;

/// The small model: the shipped axisymmetric Taylor bar.
pub const SCENE: &str = "data/scenes/taylor_bar_axisymmetric.toml";

/// Throughput and CPU time of one measurement.
#[derive(Debug, Clone)]
pub struct SmallRun {
    pub particles: usize,
    /// Particle-steps per second of wall time, over all models.
    pub rate: f64,
    pub wall_s: f64,
    pub user_s: f64,
    pub system_s: f64,
    /// Wall time per stage over the measured steps (one model alone; empty for `concurrent`).
    pub stages: StageTimes,
}

fn model() -> Result<Solver<2>> {
    match scene::load(Path::new(SCENE))?.simulation {
        Simulation::Planar(s) => Ok(s),
        Simulation::Solid(_) => bail!("{SCENE}: expected a planar (axisymmetric) scene"),
    }
}

/// User and system CPU time of the process so far [s].
fn cpu_times() -> (f64, f64) {
    // SAFETY: getrusage writes into the zeroed struct it is given.
    let usage = unsafe {
        let mut usage: libc::rusage = std::mem::zeroed();
        libc::getrusage(libc::RUSAGE_SELF, &mut usage);
        usage
    };
    let seconds = |t: libc::timeval| t.tv_sec as f64 + 1e-6 * t.tv_usec as f64;
    (seconds(usage.ru_utime), seconds(usage.ru_stime))
}

/// Time `f` (wall, user, system).
fn timed(f: impl FnOnce() -> Result<()>) -> Result<(f64, f64, f64)> {
    let (user, system) = cpu_times();
    let start = Instant::now();
    f()?;
    let wall = start.elapsed().as_secs_f64();
    let (user_after, system_after) = cpu_times();
    Ok((wall, user_after - user, system_after - system))
}

/// One model stepped `warm_up` steps untimed, then `steps` timed (each stage's time too),
/// on `threads` threads, in a warm pool as a run steps (`Solver::run_until`).
pub fn alone(threads: usize, steps: usize, warm_up: usize) -> Result<SmallRun> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let mut s = model()?;
    pool.install(|| {
        s.initialize();
        for _ in 0..warm_up {
            s.step()?;
        }
        let mut stages = StageTimes::default();
        let (wall_s, user_s, system_s) = timed(|| {
            mpm_core::parallel::with_warm_pool(|| {
                for _ in 0..steps {
                    s.step_timed(&mut stages)?;
                }
                Ok(())
            })
        })?;
        let particles = s.particles.len();
        Ok(SmallRun {
            particles,
            rate: (particles * steps) as f64 / wall_s,
            wall_s,
            user_s,
            system_s,
            stages,
        })
    })
}

/// `copies` models at once, each on its own one-thread pool; all warm up, then all run
/// `steps` timed steps from one start.
pub fn concurrent(copies: usize, steps: usize, warm_up: usize) -> Result<SmallRun> {
    let ready = Barrier::new(copies + 1);
    let done = Barrier::new(copies + 1);
    let mut models = (0..copies).map(|_| model()).collect::<Result<Vec<_>>>()?;
    let particles = models[0].particles.len();
    let pools = (0..copies)
        .map(|_| rayon::ThreadPoolBuilder::new().num_threads(1).build())
        .collect::<Result<Vec<_>, _>>()?;
    std::thread::scope(|scope| {
        let workers: Vec<_> = models
            .iter_mut()
            .zip(&pools)
            .map(|(s, pool)| {
                let (ready, done) = (&ready, &done);
                scope.spawn(move || -> Result<()> {
                    // every model meets both barriers, also one that failed
                    let warmed = pool.install(|| {
                        s.initialize();
                        (0..warm_up).try_for_each(|_| s.step().map(drop))
                    });
                    ready.wait();
                    let stepped = warmed.and_then(|()| {
                        pool.install(|| (0..steps).try_for_each(|_| s.step().map(drop)))
                    });
                    done.wait();
                    Ok(stepped?)
                })
            })
            .collect();
        ready.wait();
        let (wall_s, user_s, system_s) = timed(|| {
            done.wait();
            Ok(())
        })?;
        for w in workers {
            w.join().expect("a model thread panicked")?;
        }
        Ok(SmallRun {
            particles,
            rate: (copies * particles * steps) as f64 / wall_s,
            wall_s,
            user_s,
            system_s,
            stages: StageTimes::default(),
        })
    })
}

/// The measurement with the median rate of `repeats` runs of `measure`, and the lowest and
/// highest rate [particle-steps/s].
pub fn median(
    repeats: usize,
    mut measure: impl FnMut() -> Result<SmallRun>,
) -> Result<(SmallRun, f64, f64)> {
    let mut runs = (0..repeats.max(1))
        .map(|_| measure())
        .collect::<Result<Vec<_>>>()?;
    runs.sort_by(|a, b| a.rate.total_cmp(&b.rate));
    let (low, high) = (runs[0].rate, runs[runs.len() - 1].rate);
    Ok((runs.swap_remove(runs.len() / 2), low, high))
}

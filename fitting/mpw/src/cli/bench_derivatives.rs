//! `mpw bench-derivatives`: what exact parameter derivatives through an MPM run cost. The
//! coarse axisymmetric Taylor bar of the verification table (OFHC copper, dx = 0.635 mm,
//! 960 points, linear shape functions, MUSL, 80 µs) runs plain, then with the derivative
//! pass along p = 4 (A, B, N, C) and p = 5 (and M) Johnson-Cook parameters, alternated,
//! on 1 and 2 threads; the median wall time of each is reported against one plain run
//! and against a finite-difference Jacobian (p + 1 plain runs, forward differences).

use crate::verify::mpm::taylor::COARSE;
use crate::verify::mpm::taylor_derivatives::{plain, with_derivatives, END, FREE};
use anyhow::Result;
use materials::{load_material, AnyModel};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Measurements of each variant; the median is reported.
    #[arg(long, default_value_t = 3)]
    pub repeats: usize,
    /// Thread counts to measure.
    #[arg(long, value_delimiter = ',', default_value = "1,2")]
    pub threads: Vec<usize>,
    /// Material file of the bar (Johnson-Cook).
    #[arg(long, default_value = "data/materials/ofhc_copper.toml")]
    pub material: PathBuf,
}

/// The median of `values`.
fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// Median wall times [s] of a plain run and of the runs with 4 and 5 derivatives.
fn measure(model: &AnyModel, repeats: usize) -> Result<[f64; 3]> {
    let mut walls = [vec![], vec![], vec![]];
    for _ in 0..repeats.max(1) {
        walls[0].push(plain(model, COARSE, END)?.1);
        let four: [&str; 4] = std::array::from_fn(|k| FREE[k]);
        walls[1].push(with_derivatives(model, &four, COARSE, END)?.wall);
        walls[2].push(with_derivatives(model, &FREE, COARSE, END)?.wall);
    }
    Ok(walls.map(median))
}

pub fn run(args: Args) -> Result<()> {
    let model = load_material(&args.material)?.model;
    println!(
        "Taylor bar, dx {:.3} mm, 80 µs, linear, MUSL: median of {} alternated runs",
        COARSE * 1e3,
        args.repeats
    );
    println!(
        "{:>7} {:>10} {:>12} {:>12} {:>14} {:>14}",
        "threads",
        "plain [s]",
        "p = 4 [s]",
        "p = 5 [s]",
        "p=4: / plain, / FD",
        "p=5: / plain, / FD"
    );
    for &threads in &args.threads {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()?;
        let [plain, four, five] = pool.install(|| measure(&model, args.repeats))?;
        println!(
            "{threads:>7} {plain:>10.3} {four:>12.3} {five:>12.3} {:>7.2}, {:>5.2} {:>8.2}, {:>5.2}",
            four / plain,
            four / (5.0 * plain),
            five / plain,
            five / (6.0 * plain),
        );
    }
    Ok(())
}

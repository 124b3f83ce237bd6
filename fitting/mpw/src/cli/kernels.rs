//! `mpw kernels`: the chart a user reads to pick a shape function. Every kernel
//! at several resolutions on the truss (plane strain, 0.5 m cells, n points per edge) and
//! on the OFHC Taylor bar (axisymmetric, n cells across the radius, 2 points per cell and
//! direction), each run's error against wall time:
//!
//! - truss: the peak displacement of the top centre against CPDI at n = 40, the finest
//!   run (a run whose upper part separates is listed, and drawn off the chart);
//! - Taylor bar: the final length against the experiment (16.205 mm) and against CPDI at
//!   the finest n, the converged discretization.
//!
//! Writes `kernels.csv` and `truss_accuracy_vs_cost.png`, `taylor_accuracy_vs_cost.png`.

use crate::charts::{LineChart, Series};
use crate::verify::data::VerifyData;
use crate::verify::mpm::taylor::{self, Model, COPPER, EXPERIMENT_LENGTH, RADIUS};
use crate::verify::mpm::truss::truss;
use anyhow::{Context, Result};
use mpm_core::shape::ShapeFunction;
use std::fmt::Write;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Output folder.
    #[arg(long, default_value = "out/kernels")]
    pub out: PathBuf,
    /// Reference data folder (scenes/, materials/).
    #[arg(long, default_value = "data")]
    pub data: PathBuf,
    /// Add the Taylor bar at 18 cells across the radius (about 3 min more).
    #[arg(long)]
    pub full: bool,
}

/// Errors above this [%] are drawn off the chart.
const SHOWN: f64 = 50.0;

/// One run: kernel, resolution, wall time [s], error [%] against the reference.
struct Point {
    kernel: ShapeFunction,
    n: usize,
    wall: f64,
    error: f64,
}

pub fn run(args: Args) -> Result<()> {
    let data = VerifyData::new(&args.data);
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("{}: cannot create", args.out.display()))?;
    let mut csv =
        String::from("benchmark,kernel,n,particles,wall_s,value,reference,error_percent\n");
    let truss_points = truss_study(&data, &mut csv)?;
    chart(
        "Truss, plane strain, 0.5 m cells: peak top displacement against CPDI n = 40",
        "error of the peak displacement [%]",
        &truss_points,
    )
    .write_png(&args.out.join("truss_accuracy_vs_cost.png"))?;
    let taylor_points = taylor_study(&data, args.full, &mut csv)?;
    chart(
        "OFHC Taylor bar, axisymmetric: final length against the experiment (16.205 mm)",
        "error of the final length [%]",
        &taylor_points,
    )
    .write_png(&args.out.join("taylor_accuracy_vs_cost.png"))?;
    std::fs::write(args.out.join("kernels.csv"), csv)?;
    println!(
        "kernels.csv, truss_accuracy_vs_cost.png and taylor_accuracy_vs_cost.png in {}",
        args.out.display()
    );
    Ok(())
}

fn truss_study(data: &VerifyData, csv: &mut String) -> Result<Vec<Point>> {
    let plane = data.scenes().join("truss.toml");
    let reference = truss(&plane, ShapeFunction::Cpdi, 0.5, 40).a_peak();
    println!("truss: CPDI n = 40 peak displacement {reference:.4} m (the reference)");
    println!(
        "{:>16} {:>4} {:>9} {:>8} {:>10} {:>9}",
        "kernel", "n", "particles", "wall s", "peak m", "error %"
    );
    let mut points = Vec::new();
    for kernel in ShapeFunction::ALL {
        for n in [6, 10, 20] {
            let run = truss(&plane, kernel, 0.5, n);
            let error = 100.0 * (run.a_peak() / reference - 1.0);
            println!(
                "{:>16} {n:>4} {:>9} {:>8.2} {:>10.4} {:>9.2}{}",
                kernel.name(),
                run.particles,
                run.wall_time,
                run.a_peak(),
                error,
                if run.separation() > run.separation_limit(reference) {
                    "  separates"
                } else {
                    ""
                }
            );
            writeln!(
                csv,
                "truss,{},{n},{},{:e},{:e},{reference:e},{error:e}",
                kernel.name(),
                run.particles,
                run.wall_time,
                run.a_peak()
            )?;
            points.push(Point {
                kernel,
                n,
                wall: run.wall_time,
                error,
            });
        }
    }
    Ok(points)
}

fn taylor_study(data: &VerifyData, full: bool, csv: &mut String) -> Result<Vec<Point>> {
    let levels: &[usize] = if full { &[3, 6, 12, 18] } else { &[3, 6, 12] };
    let materials = data.materials();
    println!(
        "Taylor bar: final length against the experiment {:.3} mm",
        EXPERIMENT_LENGTH * 1e3
    );
    println!(
        "{:>16} {:>4} {:>9} {:>8} {:>10} {:>9}",
        "kernel", "n", "particles", "wall s", "L_f mm", "error %"
    );
    let mut points = Vec::new();
    for kernel in ShapeFunction::ALL {
        for &n in levels {
            let r = taylor::taylor_bar(
                &materials,
                (Model::Axisymmetric, kernel),
                COPPER,
                RADIUS / n as f64,
                2,
                80e-6,
            )?;
            let error = 100.0 * (r.length / EXPERIMENT_LENGTH - 1.0);
            println!(
                "{:>16} {n:>4} {:>9} {:>8.2} {:>10.3} {:>9.2}",
                kernel.name(),
                r.particles,
                r.wall_time,
                r.length * 1e3,
                error
            );
            writeln!(
                csv,
                "taylor,{},{n},{},{:e},{:e},{EXPERIMENT_LENGTH:e},{error:e}",
                kernel.name(),
                r.particles,
                r.wall_time,
                r.length
            )?;
            points.push(Point {
                kernel,
                n,
                wall: r.wall_time,
                error,
            });
        }
    }
    Ok(points)
}

/// |error| against wall time, one line per kernel through its resolutions.
fn chart(title: &str, y_label: &str, points: &[Point]) -> LineChart {
    let mut chart = LineChart::new(title, "wall time of one run, 2 threads [s]", y_label);
    for kernel in ShapeFunction::ALL {
        let mine: Vec<&Point> = points.iter().filter(|p| p.kernel == kernel).collect();
        let off = mine.iter().any(|p| p.error.abs() > SHOWN);
        let resolutions: Vec<String> = mine.iter().map(|p| p.n.to_string()).collect();
        chart = chart.with(Series {
            label: format!(
                "{} (n = {}){}",
                kernel.name(),
                resolutions.join(", "),
                if off {
                    ", beyond the chart where missing"
                } else {
                    ""
                }
            ),
            points: mine
                .iter()
                .map(|p| {
                    (
                        p.wall,
                        if p.error.abs() > SHOWN {
                            f64::NAN
                        } else {
                            p.error.abs()
                        },
                    )
                })
                .collect(),
        });
    }
    chart
}

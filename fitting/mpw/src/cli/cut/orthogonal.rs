//! `mpw cut orthogonal`: forces, shear angle, Merchant's estimate, chip.

use super::pictures::{field_picture, force_range, with_peak};
use super::sensitivity::force_sensitivity;
use super::{orthogonal_scene_text, same_scene, Common, CutRun};
use crate::charts::{LineChart, Series};
use anyhow::{Context, Result};
use cutting::orthogonal::{OrthogonalCut, Resolution};
use cutting::orthogonal_result::{AngleSample, OrthogonalResult, STEADY_FROM};
use cutting::record::ToolForce;
use cutting::workpiece::RunOptions;
use materials::plasticity::ElastoPlastic;
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct OrthogonalArgs {
    /// Grid spacing [m] (the thesis: 2e-4, 1e-4, 8e-5).
    #[arg(long, default_value_t = 2e-4)]
    pub spacing: f64,
    /// Points over the workpiece's height (the thesis: 80, 100, 150).
    #[arg(long, default_value_t = 80)]
    pub points: usize,
    /// Depth of cut [m] (the thesis: 0.1e-3, 0.3e-3, 0.4e-3).
    #[arg(long, default_value_t = 0.3e-3)]
    pub depth: f64,
    /// Coulomb friction between tool and chip.
    #[arg(long, default_value_t = 0.0)]
    pub friction: f64,
    /// Run time [s].
    #[arg(long, default_value_t = 80e-6)]
    pub end: f64,
    /// Material file.
    #[arg(long, default_value = "data/materials/42crmo4_qt660.toml")]
    pub material: PathBuf,
    /// Analyse the run already in the output folder (its scene must be this one) instead
    /// of running it again: forces, shear angles, Merchant, chip picture.
    #[arg(long)]
    pub analyse_only: bool,
    /// Also carry exact derivatives along these material parameters (e.g. A,B,N,C,M; at
    /// most 6): the tool forces' sensitivities p ∂f/∂p, filtered as the forces, to
    /// force_sensitivity.csv and force_sensitivity.png, with their steady means. About
    /// ten times the plain run's cost.
    #[arg(long, value_delimiter = ',')]
    pub derivatives: Vec<String>,
    #[command(flatten)]
    pub common: Common,
}

pub fn orthogonal(args: OrthogonalArgs) -> Result<()> {
    let cut = OrthogonalCut {
        feed: args.depth,
        friction: args.friction,
        end: args.end,
        ..OrthogonalCut::default()
    };
    let resolution = Resolution {
        spacing: args.spacing,
        points_y: args.points,
    };
    // every option that changes the run names it, so that the default folders of two
    // different runs never coincide
    let mut name = format!(
        "dx{}_ny{}_h{}mm",
        args.spacing,
        args.points,
        (args.depth * 1e6).round() / 1e3
    );
    if args.friction != 0.0 {
        name += &format!("_mu{}", args.friction);
    }
    let out = (args.common.out.clone())
        .unwrap_or_else(|| Path::new("out").join(format!("cut_orthogonal_{name}")));
    let options = RunOptions {
        derivatives: args.derivatives.clone(),
        ..args.common.options(&args.material)?
    };
    let text = orthogonal_scene_text(&cut, &resolution, &options)?;
    match args.analyse_only {
        false => {
            let run = CutRun::start(&text, &out)?;
            run.report(&format!(
                "orthogonal {name} ({})",
                args.common.shape_function
            ));
            if let Some(e) = &run.summary.failure {
                println!("stopped at t = {:.2} µs: {e}", e.time * 1e6);
            }
        }
        true => same_scene(&out, &text)?,
    }
    let result = crate::cut_forces::orthogonal_result(&out, &cut)?;
    let force = &result.force;
    let (fx, fy) = (&result.filtered_x, &result.filtered_y);
    write_orthogonal_forces(&out.join("force.csv"), force, fx, fy)?;
    let us: Vec<f64> = force.time_s.iter().map(|t| t * 1e6).collect();
    let ((lo, hi), off) = force_range(&[&force.force_x, &force.force_y]);
    LineChart::new(
        with_peak(format!("orthogonal cut {name}: tool forces"), off),
        "time [µs]",
        "force per unit width [MN/m]",
    )
    .y_range(lo * 1e-6, hi * 1e-6)
    .with(Series::scaled("f_x raw", &us, &force.force_x, 1.0, 1e-6))
    .with(Series::scaled("f_y raw", &us, &force.force_y, 1.0, 1e-6))
    .with(Series::scaled("f_x filtered", &us, fx, 1.0, 1e-6))
    .with(Series::scaled("f_y filtered", &us, fy, 1.0, 1e-6))
    .write_png(&out.join("force.png"))?;
    print_angles(&result.angles);
    let material = materials::load_elasto_plastic(&args.material)?;
    print_steady(&result, &cut, &material);
    if !args.derivatives.is_empty() {
        let title = format!("orthogonal cut {name}");
        force_sensitivity(&out, &args.derivatives, &result, &title)?;
    }
    field_picture(&out, "chip.png", &format!("orthogonal cut {name}"))?;
    println!(
        "force.csv, force.png, chip.png, history and snapshots in {}",
        out.display()
    );
    Ok(())
}

fn write_orthogonal_forces(path: &Path, force: &ToolForce, fx: &[f64], fy: &[f64]) -> Result<()> {
    let mut text = String::from(
        "time_s,tool_force_x_n_per_m,tool_force_y_n_per_m,tool_force_x_filtered_n_per_m,tool_force_y_filtered_n_per_m\n",
    );
    for k in 0..force.time_s.len() {
        text += &format!(
            "{:e},{:e},{:e},{:e},{:e}\n",
            force.time_s[k], force.force_x[k], force.force_y[k], fx[k], fy[k]
        );
    }
    std::fs::write(path, text).with_context(|| format!("{}: cannot write", path.display()))
}

/// The shear angle of every snapshot from `STEADY_FROM` on, from the chip's flow and from
/// the strain-rate band with its contrast.
fn print_angles(angles: &[AngleSample]) {
    for a in angles {
        let flow = a.chip_flow.map_or("no chip yet".into(), |(phi, r)| {
            format!("{phi:.1}° (chip thickness ratio {r:.3})")
        });
        let thickness = a.chip_thickness.map_or("-".into(), |(phi, _, t)| {
            format!("{phi:.1}° (chip {:.3} mm thick)", t * 1e3)
        });
        let band = a.band.map_or("-".into(), |b| {
            let clear = if b.contrast < 2.0 {
                ", no clear band"
            } else {
                ""
            };
            format!("{:.1}° (contrast {:.1}{clear})", b.degrees, b.contrast)
        });
        println!(
            "  t = {:5.1} µs: shear angle from the chip flow {flow}; from its thickness {thickness}; strain-rate band {band}",
            a.time * 1e6
        );
    }
}

/// The steady forces, their drift and noise, the mean shear angle and Merchant's force.
fn print_steady(result: &OrthogonalResult, cut: &OrthogonalCut, material: &ElastoPlastic<f64>) {
    let Some([fx, fy]) = result.steady_force() else {
        println!(
            "the run ended before {:.0} µs: no steady force",
            STEADY_FROM * 1e6
        );
        return;
    };
    println!(
        "steady forces (filtered, t >= {:.0} µs): f_x {:.3} MN/m, f_y {:.3} MN/m; drift of f_x {:+.1} %; raw - filtered RMS {:.3} MN/m",
        STEADY_FROM * 1e6,
        fx * 1e-6,
        fy * 1e-6,
        100.0 * result.drift().unwrap_or(f64::NAN),
        result.noise_rms().unwrap_or(f64::NAN) * 1e-6
    );
    let (Some((phi, spread)), Some(estimate)) =
        (result.shear_angle(), result.merchant(cut, material))
    else {
        println!("no chip flow: no shear angle");
        return;
    };
    println!(
        "shear angle from the chip flow: {phi:.1}° ± {spread:.1}° (mean ± sample std over {} snapshots)",
        result.angles.iter().filter(|a| a.chip_flow.is_some()).count()
    );
    if let Some((phi, spread)) = result.shear_angle_from_thickness() {
        println!("shear angle from the chip thickness: {phi:.1}° ± {spread:.1}°");
    }
    println!(
        "Merchant with φ_s = {phi:.1}°: {:.3} MN/m, f_x over it {:.2} (shear zone ε = {:.2}, ε̇ = {:.2e} 1/s, θ = {:.0} K, τ_s = {:.0} MPa)",
        estimate.force * 1e-6,
        fx / estimate.force,
        estimate.strain,
        estimate.strain_rate,
        estimate.temperature,
        estimate.shear_stress * 1e-6
    );
}

//! `mpw cut orthogonal`: forces, shear angle, Merchant's estimate, chip.

use super::pictures::{field_picture, force_range, mean, snapshots, with_peak};
use super::{orthogonal_scene_text, same_scene, Common, CutRun};
use crate::charts::{LineChart, Series};
use anyhow::{Context, Result};
use cutting::merchant::Merchant;
use cutting::orthogonal::{OrthogonalCut, Resolution};
use cutting::record::ToolForce;
use fitting::experiment::processing::SavitzkyGolay;
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
    #[command(flatten)]
    pub common: Common,
}

/// Filter of the cutting forces (thesis §12.3): 31 samples, first order.
pub(super) const FORCE_FILTER: SavitzkyGolay = SavitzkyGolay {
    window: 31,
    order: 1,
};

/// Forces count as steady from this time on (the thesis: after 15-20 µs) [s].
pub(super) const STEADY_FROM: f64 = 20e-6;

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
    let options = args.common.options(&args.material)?;
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
    let force = ToolForce::read(&out.join("history.csv"), "tool")?;
    let (fx, fy) = (
        FORCE_FILTER.apply(&force.force_x),
        FORCE_FILTER.apply(&force.force_y),
    );
    write_orthogonal_forces(&out.join("force.csv"), &force, &fx, &fy)?;
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
    .with(Series::scaled("f_x filtered", &us, &fx, 1.0, 1e-6))
    .with(Series::scaled("f_y filtered", &us, &fy, 1.0, 1e-6))
    .write_png(&out.join("force.png"))?;
    let steady: Vec<f64> = (0..force.time_s.len())
        .filter(|&k| force.time_s[k] >= STEADY_FROM)
        .map(|k| fx[k])
        .collect();
    let angles = shear_angles(&out, &cut)?;
    let material = materials::load_elasto_plastic(&args.material)?;
    if let (Some(mean_fx), Some(phi)) = (mean(&steady), mean(&angles)) {
        let estimate = Merchant {
            depth: cut.feed,
            speed: cut.speed,
            rake_deg: cut.rake_deg,
            shear_deg: phi,
            friction: cut.friction,
        }
        .estimate(&material);
        let spread = (angles.iter().map(|a| (a - phi).powi(2)).sum::<f64>()
            / (angles.len().max(2) - 1) as f64)
            .sqrt();
        println!(
            "shear angle from the chip flow: {phi:.1}° ± {spread:.1}° (mean ± sample std over {} snapshots)",
            angles.len()
        );
        println!(
            "steady f_x (filtered, t >= {:.0} µs): {:.3} MN/m; Merchant with φ_s = {phi:.1}°: {:.3} MN/m (shear zone ε = {:.2}, ε̇ = {:.2e} 1/s, θ = {:.0} K, τ_s = {:.0} MPa)",
            STEADY_FROM * 1e6,
            mean_fx * 1e-6,
            estimate.force * 1e-6,
            estimate.strain,
            estimate.strain_rate,
            estimate.temperature,
            estimate.shear_stress * 1e-6
        );
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

/// The shear angle of every snapshot from `STEADY_FROM` on [degrees] from the chip's flow
/// (Merchant's geometry), printed with the strain-rate band's angle and its contrast.
fn shear_angles(out: &Path, cut: &OrthogonalCut) -> Result<Vec<f64>> {
    use cutting::shear_angle::{from_chip_flow, from_snapshot, ChipGeometry};
    let mut angles = Vec::new();
    for file in snapshots(out)? {
        let snapshot = mpm_core::output::read_snapshot(&file)?;
        if snapshot.time < STEADY_FROM {
            continue;
        }
        let [x, y] = cut.tip_at(snapshot.time);
        let geometry = ChipGeometry {
            tip: (x, y),
            y_surface: cut.height,
            depth: cut.feed,
            rake_deg: cut.rake_deg,
            speed: cut.speed,
        };
        let velocity = snapshot
            .vector("velocity")
            .context("snapshot without velocity")?;
        let flow = from_chip_flow(&snapshot.position, velocity, &geometry);
        let band = from_snapshot(&snapshot, (x, y), cut.height, 0.25 * cut.feed);
        let flow_text = flow.map_or("no chip yet".into(), |(phi, r)| {
            format!("{phi:.1}° (chip thickness ratio {r:.3})")
        });
        let band_text = band.map_or("-".into(), |b| {
            let clear = if b.contrast < 2.0 {
                ", no clear band"
            } else {
                ""
            };
            format!("{:.1}° (contrast {:.1}{clear})", b.degrees, b.contrast)
        });
        println!(
            "  t = {:5.1} µs: shear angle from the chip flow {flow_text}; strain-rate band {band_text}",
            snapshot.time * 1e6
        );
        angles.extend(flow.map(|(phi, _)| phi));
    }
    Ok(angles)
}

//! `mpw cut vertical`: one set of table 12.2.

use super::pictures::{field_picture, force_range, with_peak};
use super::{same_scene, vertical_scene_text, Common, CutRun};
use crate::charts::{LineChart, Series};
use anyhow::{Context, Result};
use cutting::record::snapshot_files;
use cutting::record::ToolForce;
use cutting::vertical::{discretization, VerticalCut, SETS};
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct VerticalArgs {
    /// Set of table 12.2: S0, S1, S2 (no grid shift, grid conditions), G0, G1, G2, G0_100,
    /// G0_200, G1_60, G1_200 (grid shift dx/2, springs).
    #[arg(long, default_value = "G0")]
    pub set: String,
    /// Relative feed at which the run ends (1 = 100 %, the sheet's thickness).
    #[arg(long, default_value_t = 1.2)]
    pub feed: f64,
    /// Stiffness κ_BC of the spring conditions of the G sets [kg/s²] (the thesis: 1e7).
    #[arg(long, default_value_t = 1e7)]
    pub spring_stiffness: f64,
    /// Material file.
    #[arg(long, default_value = "data/materials/al7075_t6.toml")]
    pub material: PathBuf,
    /// Chart the run already in the output folder (its scene must be this one) instead of
    /// running it again.
    #[arg(long)]
    pub analyse_only: bool,
    #[command(flatten)]
    pub common: Common,
}

pub fn vertical(args: VerticalArgs) -> Result<()> {
    let set = discretization(&args.set).with_context(|| {
        let names: Vec<&str> = SETS.iter().map(|s| s.name).collect();
        format!("--set {}: expected one of {}", args.set, names.join(", "))
    })?;
    if !(args.feed > 0.0 && args.feed <= 3.0) {
        anyhow::bail!("--feed {}: expected a relative feed in (0, 3]", args.feed);
    }
    let out = (args.common.out.clone())
        .unwrap_or_else(|| Path::new("out").join(format!("cut_vertical_{}", set.name)));
    if !(args.spring_stiffness > 0.0 && args.spring_stiffness.is_finite()) {
        anyhow::bail!(
            "--spring-stiffness {}: expected a positive stiffness in kg/s²",
            args.spring_stiffness
        );
    }
    let cut = VerticalCut {
        spring_stiffness: args.spring_stiffness,
        ..VerticalCut::default()
    };
    let options = args.common.options(&args.material)?;
    let text = vertical_scene_text(&cut, &set, args.feed, &options)?;
    let run = match args.analyse_only {
        false => Some(CutRun::start(&text, &out)?),
        true => {
            same_scene(&out, &text)?;
            None
        }
    };
    let force = ToolForce::read(&out.join("history.csv"), "punch")?;
    force.write_csv(&out.join("force.csv"), |t| cut.feed_at(t))?;
    let feed: Vec<f64> = force
        .time_s
        .iter()
        .map(|&t| 100.0 * cut.feed_at(t))
        .collect();
    let ((lo, hi), off) = force_range(&[&force.force_y]);
    LineChart::new(
        with_peak(format!("vertical cut {}: punch force", set.name), off),
        "relative feed [%]",
        "punch force f_y per unit thickness [MN/m]",
    )
    .y_range(lo * 1e-6, hi * 1e-6)
    .with(Series::scaled("f_y", &feed, &force.force_y, 1.0, 1e-6))
    .write_png(&out.join("force.png"))?;
    field_picture(&out, "sheet.png", &format!("vertical cut {}", set.name))?;
    let Some(run) = run else {
        println!("force.csv, force.png and sheet.png in {}", out.display());
        return Ok(());
    };
    run.report(&format!(
        "{} (dx = {} m, {})",
        set.name, set.spacing, args.common.shape_function
    ));
    match &run.summary.failure {
        None => println!(
            "ran through to {:.0} % relative feed; force.csv, force.png, sheet.png, history and snapshots in {}",
            100.0 * args.feed,
            out.display()
        ),
        Some(e) => println!(
            "stopped at {:.1} % relative feed: {e}{}\nforce.csv, force.png, sheet.png, history and snapshots up to there in {}",
            100.0 * cut.feed_at(e.time),
            where_it_failed(&out, e.particle)?,
            out.display()
        ),
    }
    Ok(())
}

/// Where the point a run failed on was, from the snapshot written at the failure, with
/// its temperature and plastic strain: `" (at (x, y) mm, θ = …, α = …)"`, or nothing.
fn where_it_failed(out: &Path, particle: Option<usize>) -> Result<String> {
    let (Some(p), Some(last)) = (particle, snapshot_files(out)?.pop()) else {
        return Ok(String::new());
    };
    let s = mpm_core::output::read_snapshot(&last)?;
    let value = |name: &str| {
        s.scalar(name)
            .and_then(|v| v.get(p))
            .copied()
            .unwrap_or(f64::NAN)
    };
    Ok(match s.position.get(p) {
        Some(x) => format!(
            " (at ({:.3}, {:.3}) mm, θ = {:.0} K, α = {:.2})",
            x[0] * 1e3,
            x[1] * 1e3,
            value("theta"),
            value("alpha")
        ),
        None => String::new(),
    })
}

//! `mpw cut`: metal cutting (thesis chapter 12, library `cutting`).
//!
//! - `mpw cut vertical --set G0`: the vertical cut at a set of table 12.2: the punch force
//!   per unit thickness against relative feed (`force.csv`, `force.png`), a picture of the
//!   sheet at the end coloured by plastic strain (`sheet.png`) and the relative
//!   feed reached: "ran through" to the end feed, or where and why the run stopped.
//! - `mpw cut orthogonal`: the orthogonal cut: tool forces f_x, f_y raw and
//!   Savitzky-Golay filtered (31 history samples, first order; `force.csv`, `force.png`),
//!   the shear angle in each snapshot from 20 µs on (from the chip's flow, and the
//!   strain-rate band with its contrast), the steady cutting force against Merchant's
//!   estimate from the mean angle, and a picture of the chip (`chip.png`).
//! - `mpw cut map`: the stability map of the vertical cut: one run per grid spacing ×
//!   points over the thickness, for each variant (shape function, grid shift), the feed
//!   reached and the wall time in each cell (`map.csv`, `map_<variant>.png`).
//! - `mpw cut repeat --set G0 --seeds 1,2,3,4,5`: the vertical cut once per grid-shift
//!   seed; the punch force's mean ± sample standard deviation and CV(t) per history sample
//!   (`repeat.csv`, `repeat.png`).
//! - `mpw cut scenes`: every set's scene into `data/scenes/cutting/` (the shipped ones).
//!
//! Each run's folder holds its scene (`scene.toml`, runnable with `mpw simulate`), history,
//! snapshots and results as `simulate` writes them.

use crate::charts::{LineChart, Series};
use anyhow::{Context, Result};
use cutting::merchant::Merchant;
use cutting::orthogonal::{OrthogonalCut, Resolution};
use cutting::record::ToolForce;
use cutting::vertical::{discretization, Discretization, VerticalCut, SETS};
use cutting::workpiece::RunOptions;
use fitting::experiment::processing::SavitzkyGolay;
use mpm_core::run::RunSummary;
use std::path::{Path, PathBuf};

#[derive(clap::Subcommand, Debug)]
pub enum Cut {
    /// Run the vertical cut (Al 7075-T6) at one set of table 12.2.
    Vertical(VerticalArgs),
    /// Run the orthogonal cut (42CrMo4): forces, shear angle, Merchant's estimate, chip.
    Orthogonal(OrthogonalArgs),
    /// The vertical cut's stability map: feed reached over spacing × points per variant.
    Map(MapArgs),
    /// The vertical cut once per grid-shift seed: mean, spread and CV(t) of the punch force.
    Repeat(RepeatArgs),
    /// Write the scene of every set of table 12.2 into a folder.
    Scenes {
        #[arg(long, default_value = "data/scenes/cutting")]
        out: PathBuf,
    },
}

/// The relative feed a shipped vertical scene runs to.
const END_FEED: f64 = 1.2;

/// What every cut takes.
#[derive(clap::Args, Debug, Clone)]
pub struct Common {
    /// Shape functions: linear, ugimp, cpgimp, cpdi.
    #[arg(long, default_value = "linear")]
    pub shape_function: String,
    /// A fixed time step [s]; default the solver's stability limit (CFL, and the
    /// penalty and spring stiffness on the lightest point).
    #[arg(long)]
    pub dt: Option<f64>,
    /// Seed of the grid shift.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output folder.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

impl Common {
    /// The run options with `material` (made absolute: the scene is written elsewhere).
    fn options(&self, material: &Path) -> Result<RunOptions> {
        Ok(RunOptions {
            shape_function: self.shape_function.clone(),
            dt: self.dt,
            seed: self.seed,
            ..RunOptions::new(absolute(material)?)
        })
    }
}

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

#[derive(clap::Args, Debug)]
pub struct MapArgs {
    /// Grid spacings [m].
    #[arg(long, value_delimiter = ',', default_value = "1e-4,6.25e-5,5e-5")]
    pub spacings: Vec<f64>,
    /// Points over the sheet's thickness.
    #[arg(long, value_delimiter = ',', default_value = "60,100,200")]
    pub points: Vec<usize>,
    /// Variants: a shape function, `+shift` for the grid shift with springs
    /// (linear, linear+shift, cpdi, cpdi+shift, ...).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "linear,linear+shift,cpdi,cpdi+shift"
    )]
    pub variants: Vec<String>,
    /// Relative feed at which each run ends.
    #[arg(long, default_value_t = 1.2)]
    pub feed: f64,
    #[arg(long, default_value = "data/materials/al7075_t6.toml")]
    pub material: PathBuf,
    /// Output folder.
    #[arg(long, default_value = "out/cut_map")]
    pub out: PathBuf,
}

#[derive(clap::Args, Debug)]
pub struct RepeatArgs {
    #[arg(long, default_value = "G0")]
    pub set: String,
    /// Grid-shift seeds, one run each (at least two).
    #[arg(long, value_delimiter = ',', default_value = "1,2,3,4,5")]
    pub seeds: Vec<u64>,
    #[arg(long, default_value_t = 1.2)]
    pub feed: f64,
    #[arg(long, default_value = "data/materials/al7075_t6.toml")]
    pub material: PathBuf,
    #[arg(long, default_value = "out/cut_repeat")]
    pub out: PathBuf,
    /// Chart the runs already in the output folder (each seed's scene must be this one).
    #[arg(long)]
    pub analyse_only: bool,
}

pub fn run(cut: Cut) -> Result<()> {
    match cut {
        Cut::Vertical(args) => vertical(args),
        Cut::Repeat(args) => repeat(args),
        Cut::Orthogonal(args) => orthogonal(args),
        Cut::Map(args) => map(args),
        Cut::Scenes { out } => scenes(&out),
    }
}

fn scenes(out: &Path) -> Result<()> {
    std::fs::create_dir_all(out).with_context(|| format!("{}: cannot create", out.display()))?;
    let cut = VerticalCut::default();
    for set in &SETS {
        let path = out.join(format!("vertical_{}.toml", set.name));
        std::fs::write(
            &path,
            vertical_scene_text(
                &cut,
                set,
                END_FEED,
                &RunOptions::new(cutting::vertical::MATERIAL),
            )?,
        )
        .with_context(|| format!("{}: cannot write", path.display()))?;
        println!("{}", path.display());
    }
    Ok(())
}

/// The scene file of `set`: a comment naming it, then the TOML.
fn vertical_scene_text(
    cut: &VerticalCut,
    set: &Discretization,
    end_feed: f64,
    options: &RunOptions,
) -> Result<String> {
    let shift = match set.shift {
        true => "grid shift dx/2 and spring conditions (eq. 12.1)",
        false => "no grid shift, grid conditions",
    };
    Ok(format!(
        "# Vertical cut, thesis section 12.2, set {} of table 12.2: dx = {} m, {} x {} points, {shift}.\n\
         # Written by `mpw cut scenes` (cutting::vertical, where every value the thesis gives\n\
         # only in a figure is chosen and explained); `mpw cut vertical --set {}` runs it with the\n\
         # punch force against relative feed.\n{}",
        set.name,
        set.spacing,
        3 * set.points_y,
        set.points_y,
        set.name,
        toml::to_string(&cut.scene(set, end_feed, options))?
    ))
}

/// An existing material file as an absolute path, for a scene written elsewhere.
fn absolute(material: &Path) -> Result<String> {
    let path = material
        .canonicalize()
        .with_context(|| format!("{}: cannot find the material file", material.display()))?;
    Ok(path.display().to_string())
}

/// The run in `out` is of the scene `text` (for `--analyse-only`).
fn same_scene(out: &Path, text: &str) -> Result<()> {
    let written = std::fs::read_to_string(out.join("scene.toml"))
        .with_context(|| format!("{}: no run to analyse", out.display()))?;
    if written != text {
        anyhow::bail!(
            "{}: holds a run of another scene; give the options it was run with",
            out.join("scene.toml").display()
        );
    }
    Ok(())
}

/// A finished cutting run: its summary and wall time [s].
struct CutRun {
    summary: RunSummary,
    wall_s: f64,
}

impl CutRun {
    /// Write `scene_text` into `out/scene.toml` and run it there with a progress bar.
    fn start(scene_text: &str, out: &Path) -> Result<CutRun> {
        std::fs::create_dir_all(out)
            .with_context(|| format!("{}: cannot create", out.display()))?;
        let scene_file = out.join("scene.toml");
        std::fs::write(&scene_file, scene_text)?;
        let scene = mpm_core::scene::load(&scene_file)?;
        let start = std::time::Instant::now();
        let summary = super::simulate::run_with_progress(scene, out)?;
        for m in &summary.melting {
            eprintln!("warning: {m}");
        }
        Ok(CutRun {
            summary,
            wall_s: start.elapsed().as_secs_f64(),
        })
    }

    /// Particle-steps per second.
    fn throughput(&self) -> f64 {
        (self.summary.steps * self.summary.particles) as f64 / self.wall_s
    }

    fn report(&self, name: &str) {
        println!(
            "{name}: {} points, {} steps of {:.3e} s in {:.1} s, {:.2} M particle-steps/s",
            self.summary.particles,
            self.summary.steps,
            self.summary.time_step.dt,
            self.wall_s,
            self.throughput() / 1e6
        );
    }
}

fn vertical(args: VerticalArgs) -> Result<()> {
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
    let (Some(p), Some(last)) = (particle, snapshots(out)?.pop()) else {
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

/// Filter of the cutting forces (thesis §12.3): 31 samples, first order.
const FORCE_FILTER: SavitzkyGolay = SavitzkyGolay {
    window: 31,
    order: 1,
};

/// Forces count as steady from this time on (the thesis: after 15-20 µs) [s].
const STEADY_FROM: f64 = 20e-6;

fn orthogonal(args: OrthogonalArgs) -> Result<()> {
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
    let name = format!("dx{}_ny{}", args.spacing, args.points);
    let out = (args.common.out.clone())
        .unwrap_or_else(|| Path::new("out").join(format!("cut_orthogonal_{name}")));
    let options = args.common.options(&args.material)?;
    let text = format!(
        "# Orthogonal cut, thesis section 12.3: dx = {} m, {} x {} points, depth of cut {} m.\n\
         # Written by `mpw cut orthogonal` (cutting::orthogonal explains every chosen value).\n{}",
        args.spacing,
        3 * args.points,
        args.points,
        args.depth,
        toml::to_string(&cut.scene(&resolution, &options))?
    );
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

/// A y range [SI] for a force chart that shows the steady level: from the smallest value
/// to 1.5 times the 99th percentile of the values (the first contact's impact peaks last a
/// few samples and would flatten everything else), and the peak it leaves off, if any.
fn force_range(series: &[&[f64]]) -> ((f64, f64), Option<f64>) {
    let mut all: Vec<f64> = series
        .iter()
        .flat_map(|s| s.iter().copied())
        .filter(|v| v.is_finite())
        .collect();
    all.sort_by(f64::total_cmp);
    let (Some(&lo), Some(&peak)) = (all.first(), all.last()) else {
        return ((0.0, 1.0), None);
    };
    let p99 = all[(0.99 * (all.len() - 1) as f64) as usize];
    let hi = 1.5 * p99.max(0.0) + 1e-30;
    let lo = lo.min(0.0) - 0.05 * (hi - lo.min(0.0));
    ((lo, hi), (peak > hi).then_some(peak))
}

/// A force chart's title, with the peak left off its scale.
fn with_peak(title: String, off_scale: Option<f64>) -> String {
    match off_scale {
        Some(p) => format!("{title} (peaks to {:.1} MN/m off the scale)", p * 1e-6),
        None => title,
    }
}

fn mean(values: &[f64]) -> Option<f64> {
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
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

/// The snapshots of a run folder in order.
fn snapshots(out: &Path) -> Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(out)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "vtp"))
        .collect();
    files.sort();
    Ok(files)
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

/// The last snapshot's points coloured by equivalent plastic strain (a picture of the chip
/// or the cut sheet) into `out/<png>`.
fn field_picture(out: &Path, png: &str, title: &str) -> Result<()> {
    use plotters::prelude::*;
    let Some(last) = snapshots(out)?.pop() else {
        return Ok(());
    };
    let s = mpm_core::output::read_snapshot(&last)?;
    let alpha = s.scalar("alpha").context("snapshot without alpha")?;
    let (lo, hi) = s.position.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        },
    );
    let path = out.join(png);
    let root = BitMapBackend::new(&path, (1000, 700)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("{title}: α at t = {:.1} µs", s.time * 1e6),
            ("sans-serif", 24),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(lo[0] * 1e3..hi[0] * 1e3, lo[1] * 1e3..hi[1] * 1e3)?;
    chart
        .configure_mesh()
        .x_desc("x [mm]")
        .y_desc("y [mm]")
        .draw()?;
    // colour scale to the 95th percentile: a few molten points reach α of 7
    let mut sorted: Vec<f64> = alpha.to_vec();
    sorted.sort_by(f64::total_cmp);
    let top = sorted[(0.95 * (sorted.len() - 1) as f64) as usize].max(1e-12);
    chart.draw_series(s.position.iter().zip(alpha).map(|(p, &a)| {
        let t = (a / top).clamp(0.0, 1.0);
        let colour = RGBColor(
            (255.0 * t) as u8,
            (80.0 + 100.0 * (1.0 - t)) as u8,
            (255.0 * (1.0 - t)) as u8,
        );
        Circle::new((p[0] * 1e3, p[1] * 1e3), 1, colour.filled())
    }))?;
    root.present()?;
    Ok(())
}

/// One cell of the stability map.
struct Cell {
    variant: String,
    spacing: f64,
    points: usize,
    feed: f64,
    wall_s: f64,
    stop: String,
}

fn map(args: MapArgs) -> Result<()> {
    let material = absolute(&args.material)?;
    let cut = VerticalCut::default();
    let mut cells = Vec::new();
    'map: for variant in &args.variants {
        let (kernel, shift) = match variant.split_once('+') {
            Some((k, "shift")) => (k, true),
            None => (variant.as_str(), false),
            Some(_) => {
                anyhow::bail!("--variants {variant}: expected a shape function, optionally +shift")
            }
        };
        for &spacing in &args.spacings {
            for &points_y in &args.points {
                let set = Discretization {
                    name: "map",
                    spacing,
                    points_y,
                    shift,
                };
                let options = RunOptions {
                    shape_function: kernel.to_string(),
                    snapshots: 2,
                    ..RunOptions::new(&material)
                };
                let folder = args.out.join(format!("{variant}_dx{spacing}_ny{points_y}"));
                println!("{variant}, dx = {spacing} m, {points_y} points over the thickness:");
                let text = vertical_scene_text(&cut, &set, args.feed, &options)?;
                let (feed, stop, wall_s) = match CutRun::start(&text, &folder) {
                    Err(e) => {
                        println!("  not run: {e:#}");
                        (f64::NAN, format!("not run: {e:#}"), f64::NAN)
                    }
                    Ok(run) => {
                        run.report(&format!("  {variant}"));
                        match &run.summary.failure {
                            None => (args.feed, "ran through".to_string(), run.wall_s),
                            Some(e) if e.cause == mpm_core::Cause::Interrupted => {
                                eprintln!("interrupted: the map holds the cells run before");
                                break 'map;
                            }
                            Some(e) => (cut.feed_at(e.time), e.cause.to_string(), run.wall_s),
                        }
                    }
                };
                cells.push(Cell {
                    variant: variant.clone(),
                    spacing,
                    points: points_y,
                    feed,
                    wall_s,
                    stop,
                });
            }
        }
    }
    let mut csv = String::from("variant,spacing_m,points_y,relative_feed_reached,wall_s,stop\n");
    for c in &cells {
        csv += &format!(
            "{},{:e},{},{:e},{:e},\"{}\"\n",
            c.variant,
            c.spacing,
            c.points,
            c.feed,
            c.wall_s,
            c.stop.replace('"', "'")
        );
    }
    std::fs::create_dir_all(&args.out)?;
    std::fs::write(args.out.join("map.csv"), csv)?;
    for variant in &args.variants {
        let of: Vec<&Cell> = cells.iter().filter(|c| &c.variant == variant).collect();
        crate::charts::cell_map::CellMap {
            title: format!("vertical cut, {variant}: relative feed reached (wall time)"),
            x_label: "grid spacing [mm]".into(),
            y_label: "points over the thickness".into(),
            columns: args
                .spacings
                .iter()
                .map(|s| format!("{}", s * 1e3))
                .collect(),
            rows: args.points.iter().map(|n| n.to_string()).collect(),
            cells: of
                .iter()
                .map(|c| {
                    let column = args.spacings.iter().position(|&s| s == c.spacing).unwrap();
                    let row = args.points.iter().position(|&n| n == c.points).unwrap();
                    let text = match c.feed >= args.feed {
                        _ if c.feed.is_nan() => "not run".to_string(),
                        true => format!("ran through\n{:.0} s", c.wall_s),
                        false => format!("{:.0} %\n{:.0} s", 100.0 * c.feed, c.wall_s),
                    };
                    (column, row, c.feed.max(0.0) / args.feed, text)
                })
                .collect(),
        }
        .write_png(
            &args
                .out
                .join(format!("map_{}.png", variant.replace('+', "_"))),
        )?;
    }
    println!(
        "map.csv and one chart per variant in {}",
        args.out.display()
    );
    Ok(())
}

fn repeat(args: RepeatArgs) -> Result<()> {
    let set = discretization(&args.set)
        .with_context(|| format!("--set {}: not a set of table 12.2", args.set))?;
    if args.seeds.len() < 2 {
        anyhow::bail!("--seeds: at least two seeds, to have a spread");
    }
    let cut = VerticalCut::default();
    let material = absolute(&args.material)?;
    let mut forces = Vec::new();
    let mut time = Vec::new();
    for &seed in &args.seeds {
        let options = RunOptions {
            seed,
            snapshots: 2,
            ..RunOptions::new(&material)
        };
        let folder = args.out.join(format!("seed_{seed}"));
        let text = vertical_scene_text(&cut, &set, args.feed, &options)?;
        if args.analyse_only {
            same_scene(&folder, &text)?;
        } else {
            let run = CutRun::start(&text, &folder)?;
            run.report(&format!("{} seed {seed}", set.name));
            if let Some(e) = &run.summary.failure {
                println!(
                    "  stopped at {:.1} % relative feed: {e}",
                    100.0 * cut.feed_at(e.time)
                );
            }
        }
        let force = ToolForce::read(&folder.join("history.csv"), "punch")?;
        if force.time_s.len() > time.len() {
            time = force.time_s.clone();
        }
        forces.push(force.force_y);
    }
    let s = cutting::repeatability::spread(&forces).context("no spread")?;
    let n = s.mean.len();
    let feed: Vec<f64> = time[..n].iter().map(|&t| 100.0 * cut.feed_at(t)).collect();
    let mut csv =
        String::from("relative_feed,time_s,mean_force_y_n_per_m,std_force_y_n_per_m,cv\n");
    for k in 0..n {
        csv += &format!(
            "{:e},{:e},{:e},{:e},{:e}\n",
            feed[k] / 100.0,
            time[k],
            s.mean[k],
            s.std[k],
            s.cv[k]
        );
    }
    std::fs::write(args.out.join("repeat.csv"), csv)?;
    let band = |sign: f64| -> Vec<f64> { (0..n).map(|k| s.mean[k] + sign * s.std[k]).collect() };
    let ((lo, hi), off) = force_range(&[&band(1.0), &band(-1.0)]);
    LineChart::new(
        with_peak(
            format!(
                "vertical cut {}: punch force over {} seeds",
                set.name,
                args.seeds.len()
            ),
            off,
        ),
        "relative feed [%]",
        "punch force f_y [MN/m]",
    )
    .y_range(lo * 1e-6, hi * 1e-6)
    .with(Series::scaled("mean", &feed, &s.mean, 1.0, 1e-6))
    .with(Series::scaled("mean + std", &feed, &band(1.0), 1.0, 1e-6))
    .with(Series::scaled("mean − std", &feed, &band(-1.0), 1.0, 1e-6))
    .write_png(&args.out.join("repeat.png"))?;
    LineChart::new(
        format!(
            "vertical cut {}: CV(t) = std/mean over {} seeds",
            set.name,
            args.seeds.len()
        ),
        "relative feed [%]",
        "coefficient of variation [-]",
    )
    .y_range(0.0, 1.0)
    .with(Series::scaled("CV", &feed, &s.cv, 1.0, 1.0))
    .write_png(&args.out.join("cv.png"))?;
    let settled: Vec<f64> = (0..n)
        .filter(|&k| feed[k] >= 40.0)
        .map(|k| s.cv[k])
        .filter(|c| c.is_finite())
        .collect();
    if let Some(m) = mean(&settled) {
        let above = settled.iter().filter(|&&c| c > 0.3).count();
        println!(
            "CV of f_y from 40 % feed on: mean {m:.3}, above 0.3 in {above} of {} samples",
            settled.len()
        );
    }
    println!(
        "repeat.csv, repeat.png, cv.png and one folder per seed in {}",
        args.out.display()
    );
    Ok(())
}

//! `mpw simulate SCENE.toml --derivatives A,B,N,C` on an SHPB scene: one run of the
//! record's model carrying the exact derivatives of the face forces along the named
//! parameters (`ShpbModel::run_with_derivatives`), written as sensitivities s_p ∂F/∂p
//! [N] with s_p the parameter's standard error from the fit report given with `--params`
//! (how far the force moves when the parameter moves by its uncertainty: which part of
//! the record informs which parameter), or the parameter's value when the parameters come
//! from a material file (p ∂F/∂p, the force's change per unit relative change).
//! `derivatives.csv`: time_s, then F1_{p}_n and F2_{p}_n per parameter;
//! `derivatives.png`: the F2 sensitivities over the record, the plateau marked.

use crate::charts::{LineChart, Series};
use anyhow::{Context, Result};
use fitting::fit::reports::report::read_std_errors;
use materials::material::Model;
use std::fmt::Write as _;
use std::path::Path;

/// How each parameter's derivative is scaled: by its standard error or by its value.
struct Scale {
    values: Vec<f64>,
    /// Whether `values` are standard errors (else the parameters' values).
    std_errors: bool,
}

impl Scale {
    fn of(free: &[&str], material: &impl Model<f64>, params: Option<&Path>) -> Result<Scale> {
        let errors = match params {
            Some(file) => read_std_errors(file)?,
            None => Default::default(),
        };
        let value = |n: &str| {
            material
                .param(n)
                .with_context(|| format!("the material has no parameter `{n}`"))
        };
        if !errors.is_empty() {
            let values = free
                .iter()
                .map(|n| {
                    errors.get(*n).copied().with_context(|| {
                        format!(
                            "the fit report gives no standard error of `{n}` (it fitted {})",
                            {
                                let fitted: Vec<&str> = errors.keys().map(String::as_str).collect();
                                fitted.join(", ")
                            }
                        )
                    })
                })
                .collect::<Result<_>>()?;
            return Ok(Scale {
                values,
                std_errors: true,
            });
        }
        Ok(Scale {
            values: free.iter().map(|n| value(n)).collect::<Result<_>>()?,
            std_errors: false,
        })
    }

    /// The axis label of the scaled sensitivity of force `f`.
    fn label(&self, f: &str) -> String {
        match self.std_errors {
            true => format!("s_p ∂{f}/∂p [kN] (s_p: standard error)"),
            false => format!("p ∂{f}/∂p [kN]"),
        }
    }
}

/// Run the scene's model with the derivatives along `free` into `out`.
pub fn run(scene_file: &Path, params: Option<&Path>, free: &[String], out: &Path) -> Result<()> {
    let (scene, material) = super::simulate_shpb::load(scene_file, params)?;
    let names: Vec<&str> = free.iter().map(String::as_str).collect();
    let scale = Scale::of(&names, &material, params)?;
    let model = scene.model(&material)?;
    let theta = scene.experiment.temperature_k;
    let (run, d) = model
        .run_with_derivatives(&material, theta, &names, model.end_s())
        .with_context(|| format!("{}: exact derivatives", scene_file.display()))?;
    println!(
        "{} steps with derivatives along {} in {:.2} s",
        run.steps,
        names.join(", "),
        run.wall_s
    );
    std::fs::create_dir_all(out).with_context(|| format!("{}: cannot create", out.display()))?;
    let mut csv = String::from("time_s");
    for n in &names {
        let _ = write!(csv, ",F1_{n}_n,F2_{n}_n");
    }
    csv.push('\n');
    for (r, t) in run.history.time_s.iter().enumerate() {
        let _ = write!(csv, "{t:e}");
        for (k, s) in scale.values.iter().enumerate() {
            let _ = write!(
                csv,
                ",{:e},{:e}",
                d.incident[r][k] * s,
                d.transmitted[r][k] * s
            );
        }
        csv.push('\n');
    }
    std::fs::write(out.join("derivatives.csv"), csv)?;
    let plateau = scene.plateau_times();
    let mut chart = LineChart::new(
        format!(
            "{}: exact sensitivity of F2 (plateau {:.0}-{:.0} µs)",
            scene.experiment.name,
            plateau.first().copied().unwrap_or(0.0) * 1e6,
            plateau.last().copied().unwrap_or(0.0) * 1e6
        ),
        "t [µs]",
        scale.label("F2"),
    );
    for (k, n) in names.iter().enumerate() {
        let points = (run.history.time_s.iter().zip(&d.transmitted))
            .map(|(t, row)| (t * 1e6, row[k] * scale.values[k] * 1e-3))
            .collect();
        chart = chart.with(Series {
            label: n.to_string(),
            points,
        });
    }
    chart.write_png(&out.join("derivatives.png"))?;
    println!(
        "derivatives.csv and derivatives.png in {} (scaled by {})",
        out.display(),
        match scale.std_errors {
            true => "each parameter's standard error from the report",
            false => "each parameter's value",
        }
    );
    Ok(())
}

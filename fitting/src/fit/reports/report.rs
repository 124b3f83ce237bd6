//! The fit report: a terminal table and a TOML file with, per stage, the fitted
//! parameters, standard errors, correlation matrix (from JᵀJ), objective, model
//! evaluations, wall time and termination reason; per experiment the RMS error [SI unit
//! and % of the mean measured magnitude]; and, for synthetic sets, the error against the
//! truth. Also the CSV of measured against fitted values per experiment.

use crate::fit::levels::model::{with_values, Material};
use crate::fit::objective::Block;
use crate::fit::optimize::run::{FitResult, StageResult};
use crate::fit::optimize::trace::INTERRUPTED;
use crate::fit::sets::fit_set::FitSet;
use crate::fit::statistics::identifiability;
use crate::fit::statistics::scatter::scatter;
use anyhow::{bail, Context, Result};
use materials::material::Model;
use materials::AnyModel;
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

#[derive(Serialize)]
struct ParamRow {
    name: String,
    value: f64,
    std_error: f64,
    truth: Option<f64>,
    error_vs_truth_percent: Option<f64>,
}

#[derive(Serialize)]
struct StageRow {
    free: Vec<String>,
    experiments: Vec<String>,
    optimizer: String,
    parameters: Vec<ParamRow>,
    correlation: Vec<Vec<f64>>,
    /// MPM levels: the fit under the contact penalty κ and friction μ halved and doubled
    /// (`fit::statistics::assumptions`).
    contact_assumptions: Vec<ContactRow>,
    /// Parameter pairs the data do not identify separately (`fit::statistics::identifiability`).
    not_identified: Vec<String>,
    /// Free parameters that ended on a bound, e.g. `A at its upper bound 800 MPa`.
    at_bounds: Vec<String>,
    objective: f64,
    samples: usize,
    starts: usize,
    best_start: usize,
    model_evaluations: usize,
    ad_jacobian_evaluations: usize,
    iterations: usize,
    wall_time_s: f64,
    termination: String,
    /// The caller stopped the stage: its values are the best point so far, without
    /// standard errors or correlations.
    interrupted: bool,
    /// The optimizer converged, no parameter sits on a bound and every correlation is a
    /// number.
    converged: bool,
}

/// One change of the contact assumptions: ΔS/S at the fitted parameters, and per free
/// parameter the linearized refit shift [SI] and that shift over its standard error.
#[derive(Serialize)]
struct ContactRow {
    change: String,
    objective_change_percent: f64,
    shifts: Vec<f64>,
    shifts_in_std_errors: Vec<f64>,
}

#[derive(Serialize)]
struct ExperimentRow {
    name: String,
    level: String,
    rate_per_s: f64,
    temperature_k: f64,
    samples: usize,
    rms_si: f64,
    unit: String,
    rms_percent_of_mean: f64,
    /// SHPB: mean equilibrium ratio R over the window.
    equilibrium_ratio: Option<f64>,
    /// Specimen strain over the compared samples (`Block::strain_range`).
    strain_range: Option<[f64; 2]>,
    /// Tensile: where rate and temperature were read.
    metadata_source: Option<String>,
    /// What the model's run warned about at the final parameters (an MPM level: specimen
    /// points that reached the melting temperature).
    warnings: Vec<String>,
}

/// A group's specimen scatter and the fit against it (`fit::statistics::scatter`).
#[derive(Serialize)]
struct GroupRow {
    group: String,
    records: usize,
    /// Common strain range of the records [-].
    strain_range: Option<[f64; 2]>,
    /// [strain, CV %] at fixed strains.
    cv_percent_at_strain: Vec<[f64; 2]>,
    cv_mean_percent: Option<f64>,
    rms_vs_mean_curve_percent: f64,
    rms_vs_single_records_percent: f64,
    verdict: String,
}

#[derive(Serialize)]
struct ReportFile {
    set: String,
    /// The material the set was fitted with: its name and file.
    material_name: String,
    material_file: String,
    final_parameters: Vec<(String, f64)>,
    stages: Vec<StageRow>,
    groups: Vec<GroupRow>,
    experiments: Vec<ExperimentRow>,
    total_wall_time_s: f64,
    /// The fit was stopped before it ended (Ctrl-C): a partial report.
    interrupted: bool,
}

fn group_rows(set: &FitSet, result: &FitResult) -> Vec<GroupRow> {
    let blocks: Vec<&Block> = set.blocks.iter().collect();
    scatter(&blocks, &result.predictions)
        .iter()
        .map(|s| GroupRow {
            group: s.group.label.clone(),
            records: s.group.members.len(),
            strain_range: s
                .strain
                .first()
                .map(|&lo| [lo, s.strain[s.strain.len() - 1]]),
            cv_percent_at_strain: s.cv_at.iter().map(|&(e, cv)| [e, 100.0 * cv]).collect(),
            cv_mean_percent: Some(100.0 * s.cv_mean).filter(|c| c.is_finite()),
            rms_vs_mean_curve_percent: 100.0 * s.rms_vs_mean,
            rms_vs_single_records_percent: 100.0 * s.rms_vs_records,
            verdict: s.verdict(),
        })
        .collect()
}

fn experiment_rows(set: &FitSet, result: &FitResult) -> Vec<ExperimentRow> {
    set.blocks
        .iter()
        .zip(&result.predictions)
        .zip(&result.warnings)
        .map(|((b, p), warnings)| {
            let rms = b.rms(p);
            ExperimentRow {
                name: b.name.clone(),
                level: b.model.level().into(),
                rate_per_s: b.rate_per_s,
                temperature_k: b.temperature_k,
                samples: b.measured.len(),
                rms_si: rms,
                unit: if b.channels.len() > 1 || b.channels[0].starts_with('F') {
                    "N".into()
                } else {
                    "Pa".into()
                },
                rms_percent_of_mean: 100.0 * rms / b.scale,
                equilibrium_ratio: Some(b.equilibrium_ratio).filter(|r| r.is_finite()),
                strain_range: Some(b.strain_range).filter(|r| r.iter().all(|x| x.is_finite())),
                metadata_source: Some(b.metadata_source.clone()).filter(|s| !s.is_empty()),
                warnings: warnings.clone(),
            }
        })
        .collect()
}

/// The free parameters whose value lies within 1e-6 of their bound range from a bound: the
/// optimizer was stopped there, not by the data.
fn at_bounds(set: &FitSet, free: &[String], values: &[f64]) -> Vec<String> {
    free.iter()
        .zip(values)
        .filter_map(|(name, &v)| {
            let p = set.params.iter().find(|p| &p.name == name)?;
            let near = |bound: f64| (v - bound).abs() <= 1e-6 * (p.upper - p.lower);
            let side = match (near(p.lower), near(p.upper)) {
                (true, _) => ("lower", p.lower),
                (_, true) => ("upper", p.upper),
                _ => return None,
            };
            Some(format!(
                "{name} at its {} bound {}",
                side.0,
                show(name, side.1)
            ))
        })
        .collect()
}

fn build(set: &FitSet, result: &FitResult) -> ReportFile {
    let stages = result
        .stages
        .iter()
        .map(|s| {
            let best = &s.runs[s.best];
            let stopped_at = at_bounds(set, &s.free, &s.values);
            // a stage with an interrupted start is not an optimum even if its best start
            // converged: the stopped start might have gone lower
            let converged = best.converged
                && !s.interrupted()
                && stopped_at.is_empty()
                && s.correlation.iter().flatten().all(|r| r.is_finite());
            StageRow {
                free: s.free.clone(),
                experiments: s
                    .experiments
                    .iter()
                    .map(|&e| set.blocks[e].name.clone())
                    .collect(),
                optimizer: best.optimizer.clone(),
                parameters: s
                    .free
                    .iter()
                    .enumerate()
                    .map(|(k, name)| {
                        let truth = set.truth.get(name).copied();
                        ParamRow {
                            name: name.clone(),
                            value: s.values[k],
                            std_error: s.std_errors[k],
                            truth,
                            error_vs_truth_percent: truth.map(|t| 100.0 * (s.values[k] - t) / t),
                        }
                    })
                    .collect(),
                correlation: s.correlation.clone(),
                contact_assumptions: s
                    .contact
                    .iter()
                    .map(|c| ContactRow {
                        change: c.label.to_string(),
                        objective_change_percent: 100.0 * c.cost_change,
                        shifts: c.shifts.clone(),
                        shifts_in_std_errors: c
                            .shifts
                            .iter()
                            .zip(&s.std_errors)
                            .map(|(d, se)| d / se)
                            .collect(),
                    })
                    .collect(),
                not_identified: match s.interrupted() {
                    true => Vec::new(),
                    false => identifiability::warnings(&s.free, &s.correlation),
                },
                at_bounds: stopped_at,
                objective: s.cost,
                samples: s.samples,
                starts: s.runs.len(),
                best_start: s.best,
                model_evaluations: s.evaluations,
                ad_jacobian_evaluations: s.jacobians,
                iterations: s.runs.iter().map(|r| r.iterations).sum(),
                wall_time_s: s.wall_s,
                termination: termination(s),
                interrupted: s.interrupted(),
                converged,
            }
        })
        .collect();
    let final_parameters = result
        .material
        .param_names()
        .iter()
        .filter_map(|n| result.material.param(n).map(|v| (n.to_string(), v)))
        .collect();
    ReportFile {
        set: set.name.clone(),
        material_name: set.material_name.clone(),
        material_file: set
            .material_file
            .canonicalize()
            .unwrap_or_else(|_| set.material_file.clone())
            .display()
            .to_string(),
        final_parameters,
        stages,
        groups: group_rows(set, result),
        experiments: experiment_rows(set, result),
        total_wall_time_s: result.wall_s,
        interrupted: result.interrupted,
    }
}

/// Human units for a parameter value: MPa for stresses (`materials::parameters`), plain
/// otherwise.
pub fn show(name: &str, v: f64) -> String {
    let quantity = materials::parameters::parameter(name).map(|p| p.quantity);
    match quantity {
        Some(materials::parameters::Quantity::Stress) => format!("{:.2} MPa", v * 1e-6),
        _ => format!("{v:.5}"),
    }
}

/// Why a stage stopped: its best start's reason, or, if a start was interrupted, that
/// (naming the start whose point is reported).
fn termination(s: &StageResult) -> String {
    match s.runs.iter().position(|r| r.interrupted) {
        Some(k) => format!(
            "{INTERRUPTED} (in start {}; the values are start {}'s)",
            k + 1,
            s.best + 1
        ),
        None => s.runs[s.best].termination.clone(),
    }
}

/// How a stage ended: "interrupted ...", "converged", "stopped at the bounds of A at its
/// upper bound ..." (the bounds, not the data, decided), "NOT converged: correlations
/// undefined ..." or "NOT converged".
fn verdict(s: &StageRow) -> String {
    if s.interrupted {
        return "INTERRUPTED: the values are the best point so far, not an optimum; later stages did not run".into();
    }
    if !s.at_bounds.is_empty() {
        return format!(
            "stopped at the bounds: {}; widen them or fix the data (a unit?)",
            s.at_bounds.join(", ")
        );
    }
    if s.correlation.iter().flatten().any(|r| !r.is_finite()) {
        return "NOT converged: correlations undefined (the Jacobian is singular: a parameter does not change the prediction)".into();
    }
    match s.converged {
        true => "converged".into(),
        false => "NOT converged".into(),
    }
}

/// One line: convergence, the worst group against its mean curve, and what the data do not
/// identify.
fn summary(r: &ReportFile) -> String {
    let worst = r.groups.iter().max_by(|a, b| {
        a.rms_vs_mean_curve_percent
            .total_cmp(&b.rms_vs_mean_curve_percent)
    });
    let mut parts = Vec::new();
    if !r.stages.is_empty() {
        let verdicts: Vec<String> = r.stages.iter().map(verdict).collect();
        parts.push(match r.stages.iter().all(|s| s.converged) {
            true => "converged".to_string(),
            false => verdicts
                .into_iter()
                .filter(|v| v != "converged")
                .collect::<Vec<_>>()
                .join("; "),
        });
    }
    if let Some(g) = worst {
        parts.push(format!(
            "worst group {} at {:.2} % RMS against its mean curve",
            g.group, g.rms_vs_mean_curve_percent
        ));
    }
    let pairs: Vec<&String> = r.stages.iter().flat_map(|s| &s.not_identified).collect();
    match pairs.is_empty() {
        true if !r.stages.is_empty() => parts.push(format!(
            "every parameter pair identified (|r| < {})",
            identifiability::LIMIT
        )),
        true => {}
        false => parts.extend(pairs.iter().map(|p| format!("WARNING: {p}"))),
    }
    format!("Summary: {}", parts.join("; "))
}

/// The terminal table.
pub fn table(set: &FitSet, result: &FitResult) -> String {
    let r = build(set, result);
    let mut out = String::new();
    if r.stages.is_empty() {
        let values: Vec<String> = r
            .final_parameters
            .iter()
            .filter(|(n, _)| ["A", "B", "N", "C", "M"].contains(&n.as_str()))
            .map(|(n, v)| format!("{n} = {}", show(n, *v)))
            .collect();
        let _ = writeln!(
            out,
            "Prediction of \"{}\" (no optimizer) with {}",
            r.set,
            values.join(", ")
        );
    } else {
        let _ = writeln!(out, "Fit of \"{}\"", r.set);
    }
    for (i, s) in r.stages.iter().enumerate() {
        let _ = writeln!(
            out,
            "\nStage {}: free {:?} on {}\n  {}; {} start(s), best {}; {} model evaluations + {} AD Jacobians; {} iterations; {:.2} s\n  termination: {} ({})\n  objective S = {:.6e} on {} samples",
            i + 1,
            s.free,
            match s.experiments.len() {
                n if n > 6 => format!("{n} experiments"),
                _ => format!("{:?}", s.experiments),
            },
            s.optimizer,
            s.starts,
            s.best_start + 1,
            s.model_evaluations,
            s.ad_jacobian_evaluations,
            s.iterations,
            s.wall_time_s,
            s.termination,
            verdict(s),
            s.objective,
            s.samples
        );
        let _ = writeln!(
            out,
            "  {:<6} {:>16} {:>14} {:>16} {:>10}",
            "param", "value", "std error", "truth", "error %"
        );
        for p in &s.parameters {
            let _ = writeln!(
                out,
                "  {:<6} {:>16} {:>14} {:>16} {:>10}",
                p.name,
                show(&p.name, p.value),
                match p.std_error.is_nan() {
                    true => "-".into(),
                    false => show(&p.name, p.std_error),
                },
                p.truth.map_or("-".into(), |t| show(&p.name, t)),
                p.error_vs_truth_percent
                    .map_or("-".into(), |e| format!("{e:+.3}"))
            );
        }
        if s.free.len() > 1 && !s.correlation.is_empty() {
            let _ = writeln!(out, "  correlation:");
            let _ = write!(out, "  {:<6}", "");
            for n in &s.free {
                let _ = write!(out, " {n:>7}");
            }
            let _ = writeln!(out);
            for (k, row) in s.correlation.iter().enumerate() {
                let _ = write!(out, "  {:<6}", s.free[k]);
                for c in row {
                    let _ = write!(out, " {c:>7.3}");
                }
                let _ = writeln!(out);
            }
        }
        contact_table(&mut out, s);
    }
    let _ = writeln!(out, "\nExperiments (final parameters):");
    let w = r
        .experiments
        .iter()
        .map(|e| e.name.chars().count())
        .max()
        .unwrap_or(0)
        .max(28);
    let _ = writeln!(
        out,
        "  {:<w$} {:>10} {:>9} {:>8} {:>14} {:>8} {:>6}",
        "name", "rate 1/s", "T K", "samples", "RMS", "RMS %", "R"
    );
    for e in &r.experiments {
        let rms = if e.unit == "Pa" {
            format!("{:.2} MPa", e.rms_si * 1e-6)
        } else {
            format!("{:.3} kN", e.rms_si * 1e-3)
        };
        let ratio = e
            .equilibrium_ratio
            .map_or_else(|| "-".to_string(), |r| format!("{r:.3}"));
        let _ = writeln!(
            out,
            "  {:<w$} {:>10.3e} {:>9.2} {:>8} {:>14} {:>8.3} {:>6}",
            e.name, e.rate_per_s, e.temperature_k, e.samples, rms, e.rms_percent_of_mean, ratio
        );
    }
    for e in &r.experiments {
        for w in &e.warnings {
            let _ = writeln!(out, "  WARNING: {}: {w}", e.name);
        }
    }
    if r.experiments.iter().any(|e| e.equilibrium_ratio.is_some()) {
        let _ = writeln!(
            out,
            "  R: mean equilibrium ratio 2|F1 − F2|/|F1 + F2| of an SHPB record over its window (0: the specimen in force balance)"
        );
    }
    if r.groups.iter().any(|g| g.records > 1) {
        let _ = writeln!(
            out,
            "\nSpecimen scatter (fit against each group's mean curve):"
        );
        for g in &r.groups {
            let _ = writeln!(out, "  {}", g.verdict);
            if !g.cv_percent_at_strain.is_empty() {
                let cvs: Vec<String> = g
                    .cv_percent_at_strain
                    .iter()
                    .map(|[e, cv]| format!("{:.0} %: {cv:.2} %", 100.0 * e))
                    .collect();
                let _ = writeln!(out, "    CV at strain {}", cvs.join(", "));
            }
        }
    }
    let _ = writeln!(out, "\n{}", summary(&r));
    let _ = writeln!(out, "Total wall time {:.2} s", r.total_wall_time_s);
    out
}

/// The stage's shifts under changed contact assumptions, if it has any.
fn contact_table(out: &mut String, s: &StageRow) {
    if s.contact_assumptions.is_empty() {
        return;
    }
    let _ = writeln!(
        out,
        "  contact assumptions (κ, μ of every MPM experiment; refit linearized at the optimum):"
    );
    let _ = write!(out, "  {:<8} {:>8}", "change", "ΔS/S");
    for n in &s.free {
        let _ = write!(out, " {:>22}", format!("Δ{n}"));
    }
    let _ = writeln!(out);
    for c in &s.contact_assumptions {
        let _ = write!(
            out,
            "  {:<8} {:>7.1}%",
            c.change, c.objective_change_percent
        );
        for ((n, d), z) in s.free.iter().zip(&c.shifts).zip(&c.shifts_in_std_errors) {
            let _ = write!(out, " {:>22}", format!("{} ({z:+.2} SE)", show(n, *d)));
        }
        let _ = writeln!(out);
    }
}

/// The material of `file`: a fit report's `final_parameters` applied to `base`, or a
/// material file as it is.
pub fn read_parameters(base: &Material, file: &Path) -> Result<Material> {
    let text = std::fs::read_to_string(file)
        .with_context(|| format!("{}: cannot read", file.display()))?;
    let value: toml::Value = toml::from_str(&text)
        .map_err(|e| anyhow::anyhow!("{}", materials::toml_place::describe(file, &text, &e)))?;
    let Some(list) = value.get("final_parameters") else {
        return match materials::load_material(file)?.model {
            AnyModel::ElastoPlastic(m) => Ok(m),
            _ => bail!(
                "{}: the material must be elasto-plastic (Johnson-Cook)",
                file.display()
            ),
        };
    };
    let field = || {
        let offset = materials::toml_place::find_key(&text, None, "final_parameters").start;
        let at = materials::toml_place::Location::in_text(file, &text, offset);
        format!("{at}: `final_parameters`")
    };
    let pairs = list
        .as_array()
        .with_context(|| format!("{}: expected an array of [name, value]", field()))?;
    let mut names = Vec::new();
    let mut values = Vec::new();
    for pair in pairs {
        let (Some(name), Some(v)) = (
            pair.get(0).and_then(|n| n.as_str()),
            pair.get(1).and_then(|v| v.as_float()),
        ) else {
            bail!("{}: expected [name, value], found {pair}", field());
        };
        if base.param(name).is_none() {
            bail!(
                "{}: unknown parameter `{name}`; known: {:?}",
                field(),
                base.param_names()
            );
        }
        names.push(name);
        values.push(v);
    }
    Ok(with_values(base, &names, &values))
}

/// The standard errors a fit report gives its fitted parameters (the last stage that fits
/// each), by name; empty for a material file.
pub fn read_std_errors(file: &Path) -> Result<BTreeMap<String, f64>> {
    let text = std::fs::read_to_string(file)
        .with_context(|| format!("{}: cannot read", file.display()))?;
    let value: toml::Value = toml::from_str(&text)
        .map_err(|e| anyhow::anyhow!("{}", materials::toml_place::describe(file, &text, &e)))?;
    let stages = value.get("stages").and_then(|s| s.as_array());
    let parameters = stages
        .into_iter()
        .flatten()
        .filter_map(|s| s.get("parameters"));
    let mut errors = BTreeMap::new();
    for p in parameters.filter_map(|p| p.as_array()).flatten() {
        if let (Some(name), Some(e)) = (
            p.get("name").and_then(|n| n.as_str()),
            p.get("std_error").and_then(|e| e.as_float()),
        ) {
            errors.insert(name.to_string(), e);
        }
    }
    Ok(errors)
}

/// Write `report.toml` and one `<experiment>.csv` (measured and fitted) into `dir`.
pub fn write_files(dir: &Path, set: &FitSet, result: &FitResult) -> Result<()> {
    std::fs::create_dir_all(dir)?;
    std::fs::write(
        dir.join("report.toml"),
        toml::to_string(&build(set, result))?,
    )?;
    for (b, p) in set.blocks.iter().zip(&result.predictions) {
        let per = b.measured.len() / b.channels.len();
        let unit = if b.y_chart_scale == 1e-6 { "pa" } else { "n" };
        let mut csv = String::new();
        let _ = write!(
            csv,
            "time_s,{}",
            if unit == "pa" {
                "engineering_strain"
            } else {
                "face_time_us"
            }
        );
        for ch in &b.channels {
            let q = if unit == "pa" {
                "engineering_stress".to_string()
            } else {
                format!("force_{}", ch.to_lowercase())
            };
            let _ = write!(csv, ",{q}_measured_{unit},{q}_fitted_{unit}");
        }
        csv.push('\n');
        for k in 0..per {
            let _ = write!(csv, "{:e},{:e}", b.times[k], b.x[k]);
            for c in 0..b.channels.len() {
                let _ = write!(csv, ",{:e},{:e}", b.measured[c * per + k], p[c * per + k]);
            }
            csv.push('\n');
        }
        std::fs::write(dir.join(format!("{}.csv", sanitize(&b.name))), csv)?;
    }
    Ok(())
}

/// A file-name-safe version of an experiment name.
pub fn sanitize(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::optimize::trace::OptimResult;

    fn run(cost: f64, converged: bool, interrupted: bool) -> OptimResult {
        OptimResult {
            optimizer: "lm".into(),
            u: vec![0.0],
            cost,
            iterations: 3,
            termination: match interrupted {
                true => INTERRUPTED.into(),
                false => "converged".into(),
            },
            converged,
            interrupted,
            history: Vec::new(),
            wall_s: 0.0,
        }
    }

    #[test]
    fn a_stage_whose_later_start_was_stopped_reports_the_interrupt_not_its_best_start() {
        let stage = StageResult {
            free: vec!["A".into()],
            experiments: vec![0],
            values: vec![1.0],
            std_errors: vec![f64::NAN],
            correlation: Vec::new(),
            contact: Vec::new(),
            cost: 1.0,
            samples: 10,
            runs: vec![run(1.0, true, false), run(2.0, false, true)],
            best: 0,
            evaluations: 0,
            jacobians: 0,
            wall_s: 0.0,
        };
        let why = termination(&stage);
        assert!(why.starts_with(INTERRUPTED), "{why}");
        assert!(
            why.ends_with("(in start 2; the values are start 1's)"),
            "{why}"
        );
        let finished = StageResult {
            runs: vec![run(1.0, true, false)],
            ..stage
        };
        assert_eq!(termination(&finished), "converged");
    }
}

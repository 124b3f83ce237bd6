//! `mpw fit SET` on a set with `[[candidate]]` laws: fit the set's own law and each
//! candidate to every record, cross-validate each by leaving one group out, and print
//! which law predicts best (`fitting::fit::statistics::model_choice`). Each law's report,
//! CSVs and charts go to `OUT/<law>/`, the comparison to `OUT/model_choice.csv`.

use super::fit::{fit_with_progress, warn_about_models, Args};
use crate::charts::fit as fit_charts;
use anyhow::Result;
use fitting::fit::optimize::run::Optimizer;
use fitting::fit::reports::report::{table, write_files};
use fitting::fit::sets::fit_set::FitSet;
use fitting::fit::statistics::cross_validation::leave_one_group_out;
use fitting::fit::statistics::model_choice::{best, score, Score};
use std::fmt::Write;
use std::path::Path;

/// The laws of `sets` (each with its name, the set as written first), fitted and compared.
pub fn run(args: &Args, sets: Vec<(String, FitSet)>) -> Result<()> {
    let stop = crate::cli::interrupt::interrupt_flag()?;
    let mut scores = Vec::new();
    for (k, (name, mut set)) in sets.into_iter().enumerate() {
        eprintln!("law {}: {name} ({} free)", k + 1, set.params.len());
        if let Some(s) = args.starts {
            set.starts = s.max(1);
        }
        let optimizer = Optimizer::parse(args.optimizer.as_deref().unwrap_or(&set.optimizer))?;
        let fit = fit_with_progress(&set, optimizer, &stop)?;
        if fit.interrupted {
            anyhow::bail!("{}: interrupted while fitting {name}", args.set.display());
        }
        let out = args.out.join(folder_name(&name));
        print!("\n{name}:\n{}", table(&set, &fit));
        write_files(&out, &set, &fit)?;
        fit_charts::fit_charts(&out, &set, &fit)?;
        warn_about_models(&set, &fit);
        let folds = leave_one_group_out(&set, &fit.material, &|i, g| {
            eprintln!("  {name}, fold {}: without {g}", i + 1)
        })?;
        scores.push(score(&name, &set, &fit, &folds));
    }
    print!("{}", choice_table(&scores));
    std::fs::write(args.out.join("model_choice.csv"), choice_csv(&scores))?;
    println!(
        "reports per law and model_choice.csv in {}",
        args.out.display()
    );
    if args.validate {
        validate_choice(&args.set, &scores)?;
    }
    Ok(())
}

/// A folder name from a law's name: letters and digits, the rest as `_`.
fn folder_name(name: &str) -> String {
    let s: String = (name.chars())
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    s.trim_matches('_').to_string()
}

/// One row per law, then the held-out RMS of each group per law, the choice and the
/// warnings.
pub fn choice_table(scores: &[Score]) -> String {
    let mut out = String::new();
    let Some(first) = scores.first() else {
        return out;
    };
    let _ = writeln!(
        out,
        "\nWhich flow-stress law predicts (RMS against each group's mean curve, %; held out: the group predicted by the fit without it):"
    );
    let _ = writeln!(
        out,
        "  {:<28} {:<42} {:>2} {:>10} {:>9} {:>7} {:>9}",
        "law", "factors", "k", "in-sample", "held out", "worst", "AICc"
    );
    for s in scores {
        let _ = writeln!(
            out,
            "  {:<28} {:<42} {:>2} {:>10.2} {:>9.2} {:>7.2} {:>9.1}{}",
            truncate(&s.name, 28),
            truncate(&s.law, 42),
            s.free.len(),
            100.0 * s.in_sample(),
            100.0 * s.held_out(),
            100.0 * s.worst_held_out(),
            s.aicc,
            if s.converged {
                ""
            } else {
                "  (a fit or fold did NOT converge)"
            }
        );
    }
    let width = |s: &Score| s.name.chars().count().clamp(9, 24);
    let _ = write!(out, "  {:<28}", "held out, per group:");
    for s in scores {
        let _ = write!(out, " {:>w$}", truncate(&s.name, 24), w = width(s));
    }
    out.push('\n');
    for (g, group) in first.groups.iter().enumerate() {
        let _ = write!(out, "  {:<28}", truncate(&group.0, 28));
        for s in scores {
            let _ = write!(out, " {:>w$.2}", 100.0 * s.groups[g].2, w = width(s));
        }
        out.push('\n');
    }
    if let Some(b) = best(scores) {
        let _ = writeln!(
            out,
            "chosen: {} (lowest mean held-out RMS, {:.2} %, among the laws whose fits and folds converged); AICc over records (lower is better) is the in-sample view",
            scores[b].name,
            100.0 * scores[b].held_out()
        );
    }
    for s in scores {
        for w in &s.warnings {
            let _ = writeln!(out, "  {}: {w}", s.name);
        }
    }
    out
}

fn truncate(s: &str, n: usize) -> String {
    s.chars().take(n).collect()
}

fn choice_csv(scores: &[Score]) -> String {
    let mut out = String::from("law,factors,free,group,in_sample_rms,held_out_rms,aicc\n");
    for s in scores {
        for g in &s.groups {
            let _ = writeln!(
                out,
                "\"{}\",\"{}\",\"{}\",\"{}\",{:e},{:e},{:e}",
                s.name,
                s.law,
                s.free.join(" "),
                g.0,
                g.1,
                g.2,
                s.aicc
            );
        }
    }
    out
}

/// A validated choice: the chosen law predicts every held-out group within
/// `fit::VALIDATION_RMS` of its mean curve, and every fit and fold converged.
fn validate_choice(file: &Path, scores: &[Score]) -> Result<()> {
    let b = best(scores).ok_or_else(|| anyhow::anyhow!("no law was scored"))?;
    let s = &scores[b];
    let limit = super::fit::VALIDATION_RMS;
    let failures: Vec<String> = (s.groups.iter())
        .filter(|g| !(g.2 <= limit))
        .map(|g| format!("{} held out: {:.2} %", g.0, 100.0 * g.2))
        .chain((!s.converged).then(|| "a fit or fold did not converge".to_string()))
        .collect();
    if !failures.is_empty() {
        anyhow::bail!(
            "validation of {} failed: the chosen law {} predicts above {:.0} %: {}",
            file.display(),
            s.name,
            100.0 * limit,
            failures.join(", ")
        );
    }
    println!(
        "validation passed: {} predicts every held-out group within {:.0} %",
        s.name,
        100.0 * limit
    );
    Ok(())
}

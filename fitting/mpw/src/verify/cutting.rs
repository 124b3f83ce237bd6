//! Metal cutting (thesis chapter 12, library `cutting`): what the thesis states about the
//! vertical cut, each asserted or reported with the measured value.
//!
//! - The time step: with the punch penalty κ_pen = 1e13 kg/s² the solver's limit is the
//!   spring-mass stability of the lightest point, safety · 2 √(m/κ) (asserted against that
//!   formula), within a factor of two of the thesis's 5e-10 s and 1/20 of the CFL limit
//!   dx/c: the thesis's "1-5 % of CFL" is the penalty's limit (reported).
//! - The grid shift is seeded: the same seed twice gives the same punch force to the bit,
//!   another seed another force (a run of set G0 to 2 % feed).
//! - `--full`: sets S0, S1, G0 and G1 to 120 % feed (41 minutes on one thread shared
//!   with four other runs):
//!   G0 runs past 100 % feed (asserted); S0, which the thesis saw abort near 70 %, and S1
//!   (the thesis: less far without the shift on the finer grid) are reported with the feed
//!   they reached, and the distance between the force curves of sets 0 and 1 with the
//!   shift over that without it (the thesis: the G curves lie closer together).

use crate::verify::row::Row;
use crate::verify::Inputs;
use cutting::repeatability::{binned_by_feed, curve_distance};
use cutting::vertical::{discretization, VerticalCut};
use cutting::workpiece::RunOptions;
use mpm_core::scene::{from_description, Simulation};
use mpm_core::Solver;
use std::path::Path;

pub fn rows(inputs: &Inputs) -> anyhow::Result<Vec<Row>> {
    let scene_file = inputs.data.scenes().join("cutting/vertical_G0.toml");
    // absolute: the scene resolves a relative material path from its own folder
    let material = inputs.data.materials().join("al7075_t6.toml");
    let material = material
        .canonicalize()
        .map_err(|e| anyhow::anyhow!("{}: {e}", material.display()))?;
    let mut out = vec![time_step(&scene_file, &material)?];
    out.extend(seeds(&scene_file, &material)?);
    if inputs.full {
        out.extend(sets_rows(&scene_file, &material)?);
    }
    Ok(out)
}

/// The plane-strain solver of set `set` run with `options`; `scene_file` places the
/// material path.
fn solver(
    scene_file: &Path,
    set: &str,
    end_feed: f64,
    options: &RunOptions,
) -> anyhow::Result<Solver<2>> {
    let set = discretization(set).expect("a set of table 12.2");
    let spec = VerticalCut::default().scene(&set, end_feed, options);
    match from_description(&spec, scene_file)?.simulation {
        Simulation::Planar(s) => Ok(s),
        Simulation::Solid(_) => anyhow::bail!("the vertical cut is plane strain"),
    }
}

fn options(material: &Path, seed: u64) -> RunOptions {
    RunOptions {
        seed,
        ..RunOptions::new(material.display().to_string())
    }
}

fn time_step(scene_file: &Path, material: &Path) -> anyhow::Result<Row> {
    let mut s = solver(scene_file, "S0", 1.0, &options(material, 1))?;
    let dt = s.initialize().dt;
    let lightest = s
        .particles
        .mass
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    let cut = VerticalCut::default();
    let limit = 0.5 * 2.0 * (lightest / cut.penalty).sqrt();
    let cfl = 1e-4 / s.blocks[0].wave_speed();
    Ok(Row::relative("cutting/vertical-S0/time-step-is-the-penalty-limit", dt, limit, 1e-9)
        .with_note(format!(
            "Δt = {dt:.3e} s = 0.5 · 2√(m/κ_pen); the thesis's 5e-10 s is {:.2} of it, the CFL limit dx/c = {cfl:.3e} s is {:.0} times it",
            5e-10 / dt,
            cfl / dt
        )))
}

/// The punch's vertical force of one run.
struct PunchForce {
    /// Relative feed at each step and the punch's force there [N/m].
    feed: Vec<f64>,
    force: Vec<f64>,
    /// When the run stopped before its end [s].
    stopped: Option<f64>,
}

/// The punch's vertical force at every step of set `set` run to `end_feed` with `seed`.
fn punch_force(
    scene_file: &Path,
    material: &Path,
    set: &str,
    end_feed: f64,
    seed: u64,
) -> anyhow::Result<PunchForce> {
    let mut s = solver(scene_file, set, end_feed, &options(material, seed))?;
    s.initialize();
    let cut = VerticalCut::default();
    let (mut feed, mut force) = (Vec::new(), Vec::new());
    let mut record = |s: &Solver<2>| {
        feed.push(cut.feed_at(s.time));
        force.push(s.rigid[0].contact.force[1]);
        mpm_core::solver::observer::CONTINUE
    };
    let end = end_feed * cut.full_feed_time;
    let stopped = match s.run_until(end, &mut [&mut record]) {
        Ok(_) => None,
        Err(mpm_core::RunError::Simulation(e)) => Some(e.time),
        Err(e) => return Err(e.into()),
    };
    Ok(PunchForce {
        feed,
        force,
        stopped,
    })
}

fn seeds(scene_file: &Path, material: &Path) -> anyhow::Result<Vec<Row>> {
    let one = punch_force(scene_file, material, "G0", 0.02, 1)?.force;
    let again = punch_force(scene_file, material, "G0", 0.02, 1)?.force;
    let other = punch_force(scene_file, material, "G0", 0.02, 2)?.force;
    let largest = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    };
    let scale = one.iter().map(|f| f.abs()).fold(0.0, f64::max);
    Ok(vec![
        Row::at_most("cutting/vertical-G0/same-seed-same-force", largest(&one, &again), 0.0)
            .with_note(format!("{} steps to 2 % feed, peak |f_y| {:.3e} N/m", one.len(), scale)),
        Row::info("cutting/vertical-G0/other-seed-force-change", largest(&one, &other) / scale, f64::NAN)
            .with_note("largest |Δf_y| with seed 2 over the peak |f_y|: the shift is random, so the force moves"),
    ])
}

/// The sets S0, S1, G0 and G1 to 120 % feed: the feed each reached (G0 past 100 %
/// asserted; the others reported against the thesis: S0 near 70 %, less with refinement
/// without the shift), and how far apart the force curves of the two resolutions are with
/// and without the shift (`cutting::repeatability::curve_distance` of the mean force per
/// 2 % of feed from 10 % to 90 %; the thesis: closer with the shift).
fn sets_rows(scene_file: &Path, material: &Path) -> anyhow::Result<Vec<Row>> {
    let end_feed = 1.2;
    let mut out = Vec::new();
    let mut binned = Vec::new();
    for set in ["S0", "S1", "G0", "G1"] {
        let run = punch_force(scene_file, material, set, end_feed, 1)?;
        let cut = VerticalCut::default();
        let (feed, note) = match run.stopped {
            None => (
                end_feed,
                format!("ran through to {:.0} %", 100.0 * end_feed),
            ),
            Some(t) => (
                cut.feed_at(t),
                format!("stopped at {:.1} %", 100.0 * cut.feed_at(t)),
            ),
        };
        let name = format!("cutting/vertical-{set}/feed-reached");
        out.push(match set {
            "G0" => Row::at_least(name, feed, 1.0).with_note(note),
            "S0" => Row::info(name, feed, 0.7).with_note(note + "; the thesis: near 70 %"),
            "S1" => Row::info(name, feed, f64::NAN)
                .with_note(note + "; the thesis: less far than S0 (without the shift, denser sets stop earlier)"),
            _ => Row::info(name, feed, f64::NAN)
                .with_note(note + "; the thesis: denser sets stop earlier with the shift too"),
        });
        binned.push(binned_by_feed(&run.feed, &run.force, 0.1, 0.9, 40));
    }
    let distance = |a: &Option<Vec<f64>>, b: &Option<Vec<f64>>| match (a, b) {
        (Some(a), Some(b)) => curve_distance(a, b).unwrap_or(f64::NAN),
        _ => f64::NAN,
    };
    let (without, with) = (
        distance(&binned[0], &binned[1]),
        distance(&binned[2], &binned[3]),
    );
    out.push(
        Row::info("cutting/vertical/force-curves-closer-with-shift", with / without, f64::NAN)
            .with_note(format!(
                "distance of the force curves of sets 0 and 1 (RMS of the difference of the mean force per 2 % feed, 10-90 %, over the RMS of set 0's): {with:.3} with the shift (G), {without:.3} without (S); the thesis: below 1 (NaN: a run stopped before 90 %)"
            )),
    );
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::verify::data::VerifyData;

    /// The default rows hold: the time step is the penalty limit, the same seed gives the
    /// same force.
    #[test]
    fn the_default_cutting_rows_pass() {
        let data = VerifyData::repository();
        let rows = rows(&Inputs {
            data: &data,
            full: false,
        })
        .unwrap();
        assert_eq!(rows.len(), 3);
        for r in &rows {
            assert_ne!(r.verdict, crate::verify::row::Verdict::Fail, "{r}");
            eprintln!("{r}");
        }
    }
}

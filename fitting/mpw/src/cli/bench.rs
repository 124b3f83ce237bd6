//! `mpw bench`: nanoseconds per material update (median of repeated timed batches), for
//! Neo-Hooke, J2 and Johnson-Cook, elastic and plastic steps, reference and fast
//! returns, and the cost of the AD tangent. Build with `--release` for meaningful numbers.

use anyhow::Result;
use materials::{ad, load_material, AnyModel, Material, ReturnMap, State};
use nalgebra::Matrix3;
use std::hint::black_box;
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Timed batches per case (the median is reported).
    #[arg(long, default_value_t = 15)]
    pub repeats: usize,
    /// Material parameter folder.
    #[arg(long, default_value = "data/materials")]
    pub materials: PathBuf,
}

/// Median nanoseconds per call of `f`, over `repeats` batches of ≈ 20 ms.
pub fn ns_per_call(repeats: usize, mut f: impl FnMut()) -> f64 {
    let start = Instant::now();
    let mut calibration = 0u64;
    while start.elapsed().as_secs_f64() < 0.02 {
        f();
        calibration += 1;
    }
    let batch = calibration.max(1);
    let mut samples: Vec<f64> = (0..repeats)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..batch {
                f();
            }
            t.elapsed().as_secs_f64() * 1e9 / batch as f64
        })
        .collect();
    samples.sort_by(f64::total_cmp);
    samples[samples.len() / 2]
}

fn elasto_plastic(file: &PathBuf, return_map: ReturnMap) -> Result<AnyModel> {
    match load_material(file)?.model {
        AnyModel::ElastoPlastic(mut m) => {
            m.return_map = return_map;
            Ok(AnyModel::ElastoPlastic(m))
        }
        other => Ok(other),
    }
}

/// A state in plastic flow (α ≥ 1 %) reached by MPM-sized increments of uniaxial
/// compression with some shear, and the next increment: Δε = 6e-5 over Δt = 3e-8 s
/// (2000 1/s, the steps of `bench-mpm` case (b)). Returns (old state, F, Δt).
fn in_flow(m: &AnyModel) -> Result<(State, Matrix3<f64>, f64)> {
    let (dt, de) = (3e-8, 6e-5);
    let f_at = |e: f64| {
        Matrix3::new(
            1.0 - e,
            0.1 * e,
            0.0,
            0.05 * e,
            1.0 + 0.5 * e,
            0.0,
            0.0,
            0.0,
            1.0 + 0.5 * e,
        )
    };
    let mut state = Material::initial_state(m);
    let mut k = 0;
    while state.alpha < 0.01 {
        k += 1;
        anyhow::ensure!(k < 100_000, "no plastic flow after {k} increments");
        state = Material::update(m, &f_at(k as f64 * de), dt, &state)?.1;
    }
    Ok((state, f_at((k + 1) as f64 * de), dt))
}

/// One batch update (`Material::update_batch`), its results kept from the optimizer.
fn m_batch(m: &AnyModel, f: &[Matrix3<f64>], dt: f64, old: &[State]) {
    m.update_batch(black_box(f), dt, black_box(old), &mut |_, r| {
        black_box(r.ok());
    });
}

pub fn run(args: Args) -> Result<()> {
    let dir = &args.materials;
    let neo_hooke = load_material(dir.join("aisi_52100.toml"))?.model;
    let dt = 1e-6;
    // Elastic: 0.1 % strain. Plastic: 2 % shear-tension from a pre-strained state.
    let f_elastic = Matrix3::new(1.001, 0.0002, 0.0, 0.0, 0.9997, 0.0, 0.0, 0.0, 0.9997);
    let f_pre = Matrix3::new(1.02, 0.01, 0.0, 0.0, 0.99, 0.0, 0.0, 0.0, 0.99);
    let f_plastic = Matrix3::new(1.04, 0.015, 0.0, 0.002, 0.98, 0.0, 0.0, 0.0, 0.981);

    println!(
        "material update cost, median of {} batches (ns per call)",
        args.repeats
    );
    println!("{:<52} {:>12}", "case", "ns/update");
    // `plastic`: whether the step must grow α (checked, so each row measures what it says).
    let row = |name: &str,
               m: &AnyModel,
               f: &Matrix3<f64>,
               dt: f64,
               old: &State,
               plastic: bool|
     -> Result<()> {
        let (_, new) = Material::update(m, f, dt, old)?;
        anyhow::ensure!(
            (new.alpha > old.alpha) == plastic,
            "{name}: step is not {}",
            if plastic { "plastic" } else { "elastic" }
        );
        let ns = ns_per_call(args.repeats, || {
            black_box(Material::update(black_box(m), black_box(f), dt, black_box(old)).ok());
        });
        println!("{:<52} {:>12.0}", name, ns);
        let ns_t = ns_per_call(args.repeats, || {
            black_box(ad::tangent(black_box(m), black_box(f), dt, black_box(old)).ok());
        });
        println!("{:<52} {:>12.0}", format!("{name} + AD tangent"), ns_t);
        Ok(())
    };
    let pre_strained = |m: &AnyModel| -> Result<State> {
        Ok(Material::update(m, &f_pre, dt, &Material::initial_state(m))?.1)
    };
    let virgin = Material::initial_state(&neo_hooke);
    row("neo-hooke", &neo_hooke, &f_elastic, dt, &virgin, false)?;
    for (label, file) in [
        ("j2", "al6061_t6.toml"),
        ("johnson-cook", "42crmo4_qt660.toml"),
        ("cowper-symonds (composed)", "ss304l_cowper_symonds.toml"),
    ] {
        let fast = elasto_plastic(&dir.join(file), ReturnMap::Principal)?;
        let reference = elasto_plastic(&dir.join(file), ReturnMap::Reference)?;
        row(
            &format!("{label} elastic step"),
            &fast,
            &f_elastic,
            dt,
            &Material::initial_state(&fast),
            false,
        )?;
        row(
            &format!("{label} plastic step, fast (principal) return"),
            &fast,
            &f_plastic,
            dt,
            &pre_strained(&fast)?,
            true,
        )?;
        let (old, f_next, dt_flow) = in_flow(&fast)?;
        row(
            &format!("{label} plastic increment in flow, fast return"),
            &fast,
            &f_next,
            dt_flow,
            &old,
            true,
        )?;
        let batch = 16;
        let (fs, olds) = (vec![f_next; batch], vec![old; batch]);
        let ns = ns_per_call(args.repeats, || {
            m_batch(&fast, &fs, dt_flow, &olds);
        }) / batch as f64;
        println!(
            "{:<52} {:>12.0}",
            format!("{label} increment in flow, {batch} at once (per point)"),
            ns
        );
        row(
            &format!("{label} plastic step, reference return"),
            &reference,
            &f_plastic,
            dt,
            &pre_strained(&reference)?,
            true,
        )?;
    }
    Ok(())
}

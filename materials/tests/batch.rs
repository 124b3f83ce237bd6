//! `Material::update_batch` (four points in lockstep) gives each point's `update` to
//! round-off (the lanes take exp, ln and pow from one vectorized routine, within 2 ulp of
//! the library's: `materials::elementary`): elastic, yielding and failing points mixed,
//! groups that are not a multiple of four, every material file that ships, at first yield
//! and in flow.

use materials::{load_material, Material, MaterialError, State};
use nalgebra::Matrix3;

type Update = Result<(Matrix3<f64>, State), MaterialError>;

/// Relative agreement asked of σ, Fp⁻¹, α and θ: a few ulp in the flow stress become some
/// 100 ulp through the return's Newton solve (measured 2026-12-07: at most 4.2e-14 over
/// the 1 295 differing values of the shipped materials).
const ROUND_OFF: f64 = 1e-13;

/// Whether two updates agree to `ROUND_OFF` (the same error where they fail).
fn agree(one: &Update, many: &Update) -> bool {
    let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= ROUND_OFF * scale;
    match (one, many) {
        (Ok((s1, n1)), Ok((s2, n2))) => {
            let stress = s1.norm().max(1.0);
            s1.iter().zip(s2.iter()).all(|(a, b)| close(*a, *b, stress))
                && n1
                    .fp_inv
                    .iter()
                    .zip(n2.fp_inv.iter())
                    .all(|(a, b)| close(*a, *b, 1.0))
                && close(n1.alpha, n2.alpha, n1.alpha.abs().max(1e-3))
                && close(n1.dalpha, n2.dalpha, n1.alpha.abs().max(1e-3))
                && close(n1.theta, n2.theta, n1.theta)
        }
        (Err(a), Err(b)) => a == b,
        _ => false,
    }
}

/// Point k's deformation after `step` increments of 4e-4 (a different mix of
/// compression, shear and out-of-plane stretch per point; plane points for even k).
fn f_of(k: usize, step: usize) -> Matrix3<f64> {
    let e = 4e-4 * step as f64 * (0.5 + 0.13 * k as f64);
    let s = 0.3 * e * ((k % 5) as f64 - 2.0);
    let z = if k.is_multiple_of(2) { 0.0 } else { 0.2 * s };
    Matrix3::new(
        1.0 - e,
        s,
        z,
        0.4 * s,
        1.0 + 0.45 * e,
        0.0,
        z,
        0.0,
        1.0 + 0.5 * e,
    )
}

#[test]
fn batch_updates_equal_single_updates_to_round_off() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/materials");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 4, "material files in {}", dir.display());
    let (points, dt) = (11, 2e-8);
    let mut plastic_seen = 0;
    for file in &files {
        let m = load_material(file).unwrap().model;
        let mut states = vec![Material::initial_state(&m); points];
        for step in 1..=60 {
            let mut f: Vec<_> = (0..points).map(|k| f_of(k, step)).collect();
            if step == 40 {
                f[7] = -Matrix3::identity(); // inverted: an error, in the middle of a group
            }
            let single: Vec<Update> = (0..points)
                .map(|k| Material::update(&m, &f[k], dt, &states[k]))
                .collect();
            let mut batch: Vec<Option<Update>> = vec![None; points];
            m.update_batch(&f, dt, &states, &mut |i, r| batch[i] = Some(r));
            for (k, (one, many)) in single.iter().zip(&batch).enumerate() {
                let many = many.as_ref().expect("every point delivered");
                assert!(
                    agree(one, many),
                    "{} step {step} point {k}: {one:?} alone, {many:?} in a batch",
                    file.display()
                );
                if let Ok((_, new)) = one {
                    plastic_seen += usize::from(new.alpha > states[k].alpha);
                    states[k] = *new;
                }
            }
        }
    }
    assert!(
        plastic_seen > 500,
        "only {plastic_seen} plastic updates compared"
    );
}

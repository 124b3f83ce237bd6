//! Single-point driver: mixed control against analytic Neo-Hooke uniaxial stress,
//! stress control as the inverse of strain control, and non-convergence as an error.

use materials::driver::{self, Control, LoadPath, Ramp, Temperature};
use materials::{load_material, AnyModel, NeoHooke};
use std::path::Path;

/// Lateral stretch of Neo-Hooke uniaxial stress at axial stretch `l`:
/// σ_yy = 0 ⇔ Λ ln(l t²) + G (t² − 1) = 0, solved by bisection (independent of the
/// driver's AD Newton).
fn lateral_stretch(m: &NeoHooke, l: f64) -> f64 {
    let (lam, g) = (m.elastic.lambda(), m.elastic.shear_modulus());
    let h = |t: f64| lam * (l * t * t).ln() + g * (t * t - 1.0);
    let (mut lo, mut hi) = (0.2, 5.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if h(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn neo_hooke_uniaxial_stress_matches_the_analytic_solution() {
    let m = NeoHooke::new(1e6, 0.45, 1000.0);
    let times: Vec<f64> = (0..=20).map(|k| k as f64 * 0.05).collect();
    let stretch: Vec<f64> = times.iter().map(|t| 1.0 + 0.8 * t).collect();
    let path = LoadPath::uniaxial_stretch(times, stretch.clone(), Temperature::Adiabatic).unwrap();
    let records = driver::run(&m, &path).unwrap();
    for (r, &l) in records.iter().zip(&stretch) {
        let t = lateral_stretch(&m, l);
        let j = l * t * t;
        let sigma_xx = m.elastic.shear_modulus() * (l * l - t * t) / j;
        assert!(
            (r.f[(1, 1)] / t - 1.0).abs() < 1e-9,
            "lateral stretch {} vs {t}",
            r.f[(1, 1)]
        );
        assert!(
            (r.sigma[(0, 0)] - sigma_xx).abs() < 1e-8 * sigma_xx.abs().max(1e3),
            "σ_xx {} vs {sigma_xx}",
            r.sigma[(0, 0)]
        );
        assert!(r.sigma[(1, 1)].abs() < 1e-3 && r.sigma[(2, 2)].abs() < 1e-3);
    }
}

#[test]
fn stress_control_inverts_strain_control() {
    let m = NeoHooke::new(1e6, 0.45, 1000.0);
    let times: Vec<f64> = (0..=20).map(|k| k as f64 * 0.05).collect();
    let stretch: Vec<f64> = times.iter().map(|t| 1.0 + 0.8 * t).collect();
    let strain_run = driver::run(
        &m,
        &LoadPath::uniaxial_stretch(times.clone(), stretch.clone(), Temperature::Adiabatic)
            .unwrap(),
    )
    .unwrap();
    let sigma_xx: Vec<f64> = strain_run.iter().map(|r| r.sigma[(0, 0)]).collect();
    let mut path =
        LoadPath::uniaxial_stretch(times.clone(), stretch.clone(), Temperature::Adiabatic).unwrap();
    path.controls[0][0] = Control::Stress(Ramp::new(times, sigma_xx).unwrap());
    let stress_run = driver::run(&m, &path).unwrap();
    for (r, &l) in stress_run.iter().zip(&stretch) {
        assert!(
            (r.f[(0, 0)] / l - 1.0).abs() < 1e-8,
            "F_xx {} vs {l}",
            r.f[(0, 0)]
        );
    }
}

#[test]
fn unreachable_stress_is_an_error_with_step_and_time() {
    // Perfectly plastic 6061-T6: the Kirchhoff stress cannot exceed τ0 = 300 MPa, so
    // σ_xx = τ/J < 300 MPa in tension and the ramp to 600 MPa fails at step 5 (300 MPa).
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/materials/al6061_t6.toml");
    let m = match load_material(path).unwrap().model {
        AnyModel::ElastoPlastic(m) => m,
        AnyModel::NeoHooke(_) => unreachable!(),
    };
    let times: Vec<f64> = (0..=10).map(|k| k as f64 * 0.1).collect();
    let target: Vec<f64> = times.iter().map(|t| 600e6 * t).collect();
    let mut path = LoadPath::uniaxial_stretch(
        times.clone(),
        vec![1.0; times.len()],
        Temperature::Adiabatic,
    )
    .unwrap();
    path.controls[0][0] = Control::Stress(Ramp::new(times, target).unwrap());
    let err = driver::run(&m, &path).unwrap_err().to_string();
    assert!(err.starts_with("step 5 (t = 5e-1 s)"), "got: {err}");
}

#[test]
fn a_held_temperature_stays_held_under_plastic_work() {
    // 42CrMo4 has γ_TQ = 0.9: shear to γ = 1 turns about 1 GJ/m³ of plastic work into
    // heat, which raised the recorded θ by about 1 K per step before the driver reset it
    // only at the start of the next step.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/materials/42crmo4_qt660.toml");
    let m = match load_material(&path).unwrap().model {
        AnyModel::ElastoPlastic(m) => m,
        _ => unreachable!(),
    };
    assert!(m.thermal.gamma_tq > 0.0);
    let held = 293.15;
    let path = LoadPath::simple_shear(1.0, 1e3, 300, Temperature::Prescribed(Ramp::constant(held)))
        .unwrap();
    let records = driver::run(&m, &path).unwrap();
    assert!(records.last().unwrap().state.alpha > 0.5, "plastic");
    for r in &records {
        assert_eq!(r.state.theta, held, "t = {}", r.time);
    }
}

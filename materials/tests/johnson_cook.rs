//! Johnson-Cook first yield with N < 1 (infinite slope of α^N at α = 0): the local solve
//! converges for increments from 3e-4 to 0.1 in random directions, never NaN.

mod common;
use common::aisi_4340;
use materials::{Model, ReturnMap};
use nalgebra::Matrix3;
use rand::{Rng, SeedableRng};

#[test]
fn first_yield_with_n_below_one_converges_for_all_increments() {
    // AISI 4340 has N = 0.26: α^N has an infinite slope at α = 0.
    for rm in [ReturnMap::Principal, ReturnMap::Reference] {
        let mut m = aisi_4340();
        m.return_map = rm;
        let mut rng = rand_pcg::Pcg64::seed_from_u64(13);
        for k in 0..60 {
            let size = 10f64.powf(-3.5 + 2.5 * (k as f64 / 59.0)); // 3e-4 .. 0.1
            let dir = Matrix3::from_fn(|_, _| rng.gen_range(-1.0..1.0));
            let f = Matrix3::identity() + dir * (size / dir.norm());
            for dt in [1e-6, 1.0] {
                let (sigma, state) = m
                    .update(&f, dt, &m.initial_state())
                    .unwrap_or_else(|e| panic!("increment {size:e}, dt {dt}: {e}"));
                assert!(sigma.iter().all(|s| s.is_finite()) && state.alpha.is_finite());
            }
        }
    }
}

#[test]
fn barely_plastic_step_at_large_strain_converges() {
    // A state met in the axisymmetric Taylor bar (OFHC copper, α ≈ 0.97, Δt = 24 ns):
    // the trial state is just outside the yield surface, Δα ≈ 2.6e-8, so the residual
    // hardly depends on ln Δα and an unlimited Newton step in ln Δα overflowed.
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/materials/ofhc_copper.toml");
    let f = Matrix3::from_column_slice(&[
        1.1016632851609656,
        0.2770363353264894,
        0.0,
        -0.45946529166025113,
        0.36037010849759865,
        0.0,
        0.0,
        0.0,
        1.9129442139041035,
    ]);
    let fp_inv = Matrix3::from_column_slice(&[
        0.9934044425378938,
        0.406096989503819,
        0.0,
        0.5040672786908376,
        2.1255890010624485,
        0.0,
        0.0,
        0.0,
        0.5244197767422152,
    ]);
    let old = materials::State {
        fp_inv,
        alpha: 0.9712945828856001,
        theta: 389.28882346222497,
        dalpha: 0.0,
    };
    let dt = 2.3786158111633972e-8;
    let mut results = Vec::new();
    for rm in [ReturnMap::Principal, ReturnMap::Reference] {
        let mut m = match materials::load_material(&path).unwrap().model {
            materials::AnyModel::ElastoPlastic(m) => m,
            materials::AnyModel::NeoHooke(_) => unreachable!(),
        };
        m.return_map = rm;
        let (sigma, state) = m
            .update(&f, dt, &old)
            .unwrap_or_else(|e| panic!("{rm:?}: {e}"));
        results.push((sigma, state.alpha - old.alpha));
    }
    let (dalpha_fast, dalpha_ref) = (results[0].1, results[1].1);
    assert!(
        dalpha_ref > 0.0 && (dalpha_fast / dalpha_ref - 1.0).abs() < 1e-8,
        "Δα {dalpha_fast:e} vs {dalpha_ref:e}"
    );
    assert!((results[0].0 - results[1].0).norm() / results[1].0.norm() < 1e-10);
}

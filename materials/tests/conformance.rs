//! Conformance checks applied to every material model (DESIGN 4.4), one macro for all,
//! in the style of fenris: each check asserts a number with a stated tolerance.

mod common;
use common::*;
use materials::driver::{self, LoadPath, Temperature};
use materials::tensor::{det, M3};
use materials::{ad, Model, ReturnMap, State};

/// Time step of the single updates [s] (plastic rate ≈ 1e3 1/s for the JC model).
const DT: f64 = 1e-5;

/// A loaded state: one plastic step from the virgin state, so F^p⁻¹ ≠ I.
fn preloaded<M: Model<f64>>(m: &M, rng: &mut Rng) -> State {
    let f = rng.deformation(0.02);
    m.update(&f, DT, &m.initial_state()).unwrap().1
}

fn rel(a: &M3<f64>, b: &M3<f64>) -> f64 {
    (a - b).norm() / b.norm().max(1e-300)
}

fn fd_stress<M: Model<f64>>(m: &M, f: &M3<f64>, old: &State) -> M3<f64> {
    m.update(f, DT, old).unwrap().0
}

macro_rules! conformance {
    ($name:ident, $model:expr) => {
        mod $name {
            use super::*;

            #[test]
            fn zero_stress_at_identity() {
                let m = $model;
                let (sigma, _) = m.update(&M3::identity(), DT, &m.initial_state()).unwrap();
                assert!(sigma.norm() < 1e-6, "|σ(I)| = {:e} Pa", sigma.norm());
            }

            #[test]
            fn symmetric_and_objective() {
                let m = $model;
                let mut rng = Rng(11);
                for _ in 0..20 {
                    let old = preloaded(&m, &mut rng);
                    let f = rng.deformation(0.03);
                    let q = rng.rotation();
                    let (sigma, _) = m.update(&f, DT, &old).unwrap();
                    let (sigma_q, _) = m.update(&(q * f), DT, &old).unwrap();
                    let asym = (sigma - sigma.transpose()).norm() / sigma.norm();
                    assert!(asym < 1e-12, "asymmetry {asym:e}");
                    let e = rel(&sigma_q, &(q * sigma * q.transpose()));
                    assert!(e < 1e-9, "objectivity error {e:e}");
                }
            }

            #[test]
            fn tangent_matches_central_differences() {
                let m = $model;
                let mut rng = Rng(5);
                let h = 1e-6;
                for _ in 0..5 {
                    let old = preloaded(&m, &mut rng);
                    let f = rng.deformation(0.03);
                    let (_, tangent, _) = ad::tangent(&m, &f, DT, &old).unwrap();
                    let mut fd = nalgebra::SMatrix::<f64, 9, 9>::zeros();
                    for k in 0..9 {
                        let (mut fp, mut fm) = (f, f);
                        fp[(k / 3, k % 3)] += h;
                        fm[(k / 3, k % 3)] -= h;
                        let col = (fd_stress(&m, &fp, &old) - fd_stress(&m, &fm, &old)) / (2.0 * h);
                        for r in 0..9 {
                            fd[(r, k)] = col[(r / 3, r % 3)];
                        }
                    }
                    let e = (tangent - fd).norm() / tangent.norm();
                    assert!(e < 1e-6, "tangent vs FD relative error {e:e}");
                }
            }

            #[test]
            fn parameter_sensitivities_match_central_differences() {
                let m = $model;
                let mut rng = Rng(7);
                let old = preloaded(&m, &mut rng);
                let f = rng.deformation(0.03);
                let sigma = fd_stress(&m, &f, &old);
                for name in m.param_names() {
                    let p = m.param(name).unwrap();
                    let (_, [ds]) = ad::sensitivities(&m, &[name], &f, DT, &old).unwrap();
                    // Fourth-order central differences; the best of a range of steps,
                    // since each parameter has its own scale (θ0 acts through θ − θ0).
                    let scale = if p != 0.0 { p.abs() } else { 1.0 };
                    let at = |d: f64| {
                        fd_stress(
                            &m.map_params(|n, v| if n == name { v + d } else { v }),
                            &f,
                            &old,
                        )
                    };
                    let e = [1e-2, 1e-3, 1e-4, 1e-5]
                        .iter()
                        .map(|rh| {
                            let h = rh * scale;
                            let fd = ((at(h) - at(-h)) * 8.0 - (at(2.0 * h) - at(-2.0 * h)))
                                / (12.0 * h);
                            // Compare dσ/d ln p (Pa), ignoring sensitivities below 1e-6 of |σ|.
                            (ds - fd).norm() * scale / (ds.norm() * scale).max(1e-6 * sigma.norm())
                        })
                        .fold(f64::INFINITY, f64::min);
                    assert!(e < 1e-6, "dσ/d{name}: relative error {e:e}");
                }
            }
        }
    };
}

conformance!(neo_hooke_model, neo_hooke());
conformance!(j2_reference, j2(ReturnMap::Reference));
conformance!(j2_principal, j2(ReturnMap::Principal));
conformance!(johnson_cook_reference, johnson_cook(ReturnMap::Reference));
conformance!(johnson_cook_principal, johnson_cook(ReturnMap::Principal));

#[test]
fn neo_hooke_stress_is_the_derivative_of_the_energy() {
    use num_dual::gradient;
    let m = neo_hooke();
    let mut rng = Rng(3);
    for _ in 0..10 {
        let f = rng.deformation(0.2);
        let x = nalgebra::SVector::<f64, 9>::from_fn(|k, _| f[(k / 3, k % 3)]);
        let elastic = m.elastic;
        let (_, p1) = gradient(
            |xd| {
                let fd = M3::from_fn(|i, j| xd[3 * i + j]);
                elastic
                    .map(|_, v| num_dual::DualSVec64::<9>::from(v))
                    .energy(&fd)
            },
            &x,
        );
        let p1 = M3::from_fn(|i, j| p1[3 * i + j]);
        let sigma_energy = p1 * f.transpose() / det(&f);
        let (sigma, _) = m.update(&f, DT, &m.initial_state()).unwrap();
        let e = rel(&sigma, &sigma_energy);
        assert!(e < 1e-12, "σ vs ∂ψ/∂F Fᵀ/J: relative error {e:e}");
    }
}

#[test]
fn reference_and_principal_returns_agree() {
    for (a, b) in [
        (j2(ReturnMap::Reference), j2(ReturnMap::Principal)),
        (
            johnson_cook(ReturnMap::Reference),
            johnson_cook(ReturnMap::Principal),
        ),
    ] {
        let mut rng = Rng(21);
        for _ in 0..50 {
            let old = preloaded(&a, &mut rng);
            let f = rng.deformation(0.05);
            let (sa, na) = a.update(&f, DT, &old).unwrap();
            let (sb, nb) = b.update(&f, DT, &old).unwrap();
            assert!(rel(&sb, &sa) < 1e-10, "σ differs by {:e}", rel(&sb, &sa));
            assert!(rel(&nb.fp_inv, &na.fp_inv) < 1e-10);
            assert!(((nb.alpha - na.alpha) / na.alpha).abs() < 1e-10);
        }
    }
}

#[test]
fn plastic_flow_is_isochoric() {
    for m in [
        j2(ReturnMap::Reference),
        j2(ReturnMap::Principal),
        johnson_cook(ReturnMap::Principal),
    ] {
        let mut rng = Rng(9);
        let mut state = m.initial_state();
        let mut f = M3::identity();
        for _ in 0..40 {
            f = rng.deformation(0.01) * f;
            state = m.update(&f, DT, &state).unwrap().1;
        }
        assert!(
            state.alpha > 0.05,
            "path should be plastic, α = {}",
            state.alpha
        );
        let e = (det(&state.fp_inv) - 1.0).abs();
        assert!(e < 1e-12, "|det Fp⁻¹ − 1| = {e:e}");
    }
}

#[test]
fn elastic_unloading_follows_the_elastic_slope() {
    for m in [j2(ReturnMap::Principal), johnson_cook(ReturnMap::Principal)] {
        // Load to 5 % true strain, then unload by 0.1 %; compare with the first 0.1 %.
        let times = vec![0.0, 1e-3, 1.0, 1.0 + 1e-3];
        let stretch = [1.0, 1e-3f64.exp(), 0.05f64.exp(), (0.05f64 - 1e-3).exp()].to_vec();
        let path = LoadPath::uniaxial_stretch(
            times,
            stretch,
            Temperature::Prescribed(driver::Ramp::constant(293.15)),
        )
        .unwrap();
        let r = driver::run(&m, &path).unwrap();
        let loading = r[1].sigma[(0, 0)] / 1e-3;
        let unloading = (r[2].sigma[(0, 0)] - r[3].sigma[(0, 0)]) / 1e-3;
        let e = (unloading / loading - 1.0).abs();
        assert!(r[2].state.alpha > 0.04);
        assert!(
            e < 0.01,
            "unloading slope {unloading:e} vs loading slope {loading:e}"
        );
    }
}

//! Conformance checks applied to every material model (DESIGN 4.4), as rows of the
//! `mpw verify` table; the tests in `tests/conformance.rs` assert that all pass.
//!
//! Each check measures one number against its reference with a stated tolerance:
//! zero stress at F = I, symmetry, objectivity σ(QF) = Q σ(F) Qᵀ, AD tangent against
//! central differences, parameter sensitivities against fourth-order differences,
//! plastic incompressibility det Fp = 1, elastic unloading slope, and (Neo-Hooke)
//! σ = ∂ψ/∂F Fᵀ/J.

use crate::case_result::CaseResult;
use materials::ad;
use materials::driver::{self, LoadPath, Ramp, Temperature};
use materials::material::{Model, State};
use materials::neo_hooke::NeoHooke;
use materials::plasticity::ElastoPlastic;
use materials::tensor::{det, M3};
use nalgebra::{Rotation3, SMatrix, SVector, Vector3};
use num_dual::{gradient, DualSVec64};

/// Time step of the single updates [s] (plastic rate ≈ 1e3 1/s for steels).
pub const DT: f64 = 1e-5;

/// A small deterministic generator (SplitMix64) for random deformations and rotations.
pub struct Rng(pub u64);

impl Rng {
    /// Uniform in [−1, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    /// I + amplitude · (random matrix with entries in [−1, 1)).
    pub fn deformation(&mut self, amplitude: f64) -> M3<f64> {
        M3::identity() + M3::from_fn(|_, _| amplitude * self.uniform())
    }

    pub fn rotation(&mut self) -> M3<f64> {
        let axis = Vector3::new(self.uniform(), self.uniform(), self.uniform());
        Rotation3::new(axis * 3.0).into_inner()
    }
}

/// A loaded state: one 2 % step from the virgin state, so F^p⁻¹ ≠ I for plastic models.
pub fn preloaded<M: Model<f64>>(m: &M, rng: &mut Rng) -> State {
    let f = rng.deformation(0.02);
    m.update(&f, DT, &m.initial_state())
        .expect("preload step")
        .1
}

fn rel(a: &M3<f64>, b: &M3<f64>) -> f64 {
    (a - b).norm() / b.norm().max(1e-300)
}

fn stress<M: Model<f64>>(m: &M, f: &M3<f64>, old: &State) -> M3<f64> {
    m.update(f, DT, old).expect("material update").0
}

/// Worst relative error of the AD tangent against central differences (h = 1e-6).
fn tangent_error<M: Model<f64>>(m: &M, rng: &mut Rng) -> f64 {
    let h = 1e-6;
    let mut worst = 0.0f64;
    for _ in 0..5 {
        let old = preloaded(m, rng);
        let f = rng.deformation(0.03);
        let (_, tangent, _) = ad::tangent(m, &f, DT, &old).expect("tangent");
        let mut fd = SMatrix::<f64, 9, 9>::zeros();
        for k in 0..9 {
            let (mut fp, mut fm) = (f, f);
            fp[(k / 3, k % 3)] += h;
            fm[(k / 3, k % 3)] -= h;
            let col = (stress(m, &fp, &old) - stress(m, &fm, &old)) / (2.0 * h);
            for r in 0..9 {
                fd[(r, k)] = col[(r / 3, r % 3)];
            }
        }
        worst = worst.max((tangent - fd).norm() / tangent.norm());
    }
    worst
}

/// Worst relative error of dσ/dp over all parameters, comparing p·dσ/dp [Pa] and
/// ignoring sensitivities below 1e-6 |σ|. Fourth-order differences, the best of a
/// range of steps (each parameter has its own scale: θ0 acts through θ − θ0).
fn sensitivity_error<M: Model<f64>>(m: &M, rng: &mut Rng) -> (f64, &'static str) {
    let old = preloaded(m, rng);
    let f = rng.deformation(0.03);
    let sigma = stress(m, &f, &old);
    let mut worst = (0.0, "");
    for name in m.param_names() {
        let p = m.param(name).expect("named parameter");
        let (_, [ds]) = ad::sensitivities(m, &[name], &f, DT, &old).expect("sensitivities");
        let scale = if p != 0.0 { p.abs() } else { 1.0 };
        let at = |d: f64| {
            stress(
                &m.map_params(|n, v| if n == name { v + d } else { v }),
                &f,
                &old,
            )
        };
        let e = [1e-2, 1e-3, 1e-4, 1e-5]
            .iter()
            .map(|rh| {
                let h = rh * scale;
                let fd = ((at(h) - at(-h)) * 8.0 - (at(2.0 * h) - at(-2.0 * h))) / (12.0 * h);
                (ds - fd).norm() * scale / (ds.norm() * scale).max(1e-6 * sigma.norm())
            })
            .fold(f64::INFINITY, f64::min);
        if e > worst.0 {
            worst = (e, name);
        }
    }
    worst
}

/// The checks every model passes.
pub fn check_model<M: Model<f64>>(name: &str, m: &M) -> Vec<CaseResult> {
    let mut rng = Rng(11);
    let (sigma0, _) = m
        .update(&M3::identity(), DT, &m.initial_state())
        .expect("update at F = I");
    let mut asym = 0.0f64;
    let mut objectivity = 0.0f64;
    for _ in 0..20 {
        let old = preloaded(m, &mut rng);
        let f = rng.deformation(0.03);
        let q = rng.rotation();
        let sigma = stress(m, &f, &old);
        asym = asym.max((sigma - sigma.transpose()).norm() / sigma.norm());
        objectivity = objectivity.max(rel(
            &stress(m, &(q * f), &old),
            &(q * sigma * q.transpose()),
        ));
    }
    let (sens, worst_param) = sensitivity_error(m, &mut rng);
    vec![
        CaseResult::at_most(format!("{name}: |σ(F=I)| [Pa]"), sigma0.norm(), 1e-6),
        CaseResult::at_most(format!("{name}: asymmetry of σ"), asym, 1e-12),
        CaseResult::at_most(format!("{name}: objectivity error"), objectivity, 1e-9),
        CaseResult::at_most(
            format!("{name}: AD tangent vs FD"),
            tangent_error(m, &mut rng),
            1e-6,
        ),
        CaseResult::at_most(
            format!("{name}: dσ/dp vs FD (worst: {worst_param})"),
            sens,
            1e-6,
        ),
    ]
}

/// Neo-Hooke: σ = ∂ψ/∂F Fᵀ / J with the gradient of ψ by AD.
pub fn check_energy(m: &NeoHooke) -> CaseResult {
    let mut rng = Rng(3);
    let mut worst = 0.0f64;
    for _ in 0..10 {
        let f = rng.deformation(0.2);
        let x = SVector::<f64, 9>::from_fn(|k, _| f[(k / 3, k % 3)]);
        let elastic = m.elastic.map(|_, v| DualSVec64::<9>::from(v));
        let (_, p1) = gradient(|xd| elastic.energy(&M3::from_fn(|i, j| xd[3 * i + j])), &x);
        let p1 = M3::from_fn(|i, j| p1[3 * i + j]);
        worst = worst.max(rel(
            &stress(m, &f, &m.initial_state()),
            &(p1 * f.transpose() / det(&f)),
        ));
    }
    CaseResult::at_most("neo-hooke: σ vs ∂ψ/∂F Fᵀ/J", worst, 1e-12)
}

/// Plastic models: det Fp = 1 along a random plastic path, and the elastic unloading
/// slope after 5 % uniaxial strain equals the initial loading slope (within 1 %).
pub fn check_plastic(name: &str, m: &ElastoPlastic) -> Vec<CaseResult> {
    let mut rng = Rng(9);
    let mut state = m.initial_state();
    let mut f = M3::identity();
    for _ in 0..40 {
        f = rng.deformation(0.01) * f;
        state = m.update(&f, DT, &state).expect("plastic path").1;
    }
    let times = vec![0.0, 1e-3, 1.0, 1.0 + 1e-3];
    let stretch = vec![1.0, 1e-3f64.exp(), 0.05f64.exp(), (0.05f64 - 1e-3).exp()];
    let path = LoadPath::uniaxial_stretch(
        times,
        stretch,
        Temperature::Prescribed(Ramp::constant(m.thermal.theta0)),
    )
    .expect("path");
    let r = driver::run(m, &path).expect("unloading path");
    let loading = r[1].sigma[(0, 0)] / 1e-3;
    let unloading = (r[2].sigma[(0, 0)] - r[3].sigma[(0, 0)]) / 1e-3;
    vec![
        CaseResult::at_most(
            format!("{name}: |det Fp - 1| after α = {:.2}", state.alpha),
            (det(&state.fp_inv) - 1.0).abs(),
            1e-12,
        ),
        CaseResult::relative(
            format!("{name}: unloading slope [Pa]"),
            unloading,
            loading,
            0.01,
        ),
    ]
}

/// Reference (algorithm 3) and fast (principal) returns agree on σ, Fp⁻¹ and α.
pub fn check_returns_agree(
    name: &str,
    reference: &ElastoPlastic,
    fast: &ElastoPlastic,
) -> CaseResult {
    let mut rng = Rng(21);
    let mut worst = 0.0f64;
    for _ in 0..50 {
        let old = preloaded(reference, &mut rng);
        let f = rng.deformation(0.05);
        let (sa, na) = reference.update(&f, DT, &old).expect("reference return");
        let (sb, nb) = fast.update(&f, DT, &old).expect("fast return");
        worst = worst
            .max(rel(&sb, &sa))
            .max(rel(&nb.fp_inv, &na.fp_inv))
            .max(((nb.alpha - na.alpha) / na.alpha).abs());
    }
    CaseResult::at_most(format!("{name}: reference vs fast return"), worst, 1e-10)
}

/// Johnson-Cook in uniaxial tension at constant true rate and fixed temperature: the
/// Kirchhoff stress follows eq. 4.52 at α̇ = ε̇ once α > 0.02 (within 0.5 %).
pub fn check_jc_uniaxial(name: &str, m: &ElastoPlastic) -> Vec<CaseResult> {
    let theta0 = m.thermal.theta0;
    [(1e-2, theta0), (1e3, theta0), (1e3, theta0 + 480.0)]
        .iter()
        .map(|&(rate, theta)| {
            let path = LoadPath::uniaxial(
                driver::RateKind::True,
                0.5,
                rate,
                0.0,
                500,
                Temperature::Prescribed(Ramp::constant(theta)),
            )
            .expect("path");
            let records = driver::run(m, &path).expect("uniaxial JC path");
            let worst = records
                .iter()
                .filter(|r| r.state.alpha > 0.02)
                .map(|r| {
                    let tau_xx = r.sigma[(0, 0)] * r.f.determinant();
                    (tau_xx / m.flow.tau_y(r.state.alpha, rate, theta, theta0) - 1.0).abs()
                })
                .fold(0.0, f64::max);
            CaseResult::at_most(
                format!("{name}: uniaxial vs eq. 4.52, rate {rate:e}, θ {theta}"),
                worst,
                5e-3,
            )
        })
        .collect()
}

/// dσ_xx(t)/dp over a whole adiabatic uniaxial compression path (history derivatives
/// through Fp⁻¹, α and θ) against fourth-order differences of the driver.
pub fn check_path_sensitivities(
    name: &str,
    m: &ElastoPlastic,
    params: &[&'static str],
) -> CaseResult {
    use num_dual::Dual64;
    let path = LoadPath::uniaxial(
        driver::RateKind::True,
        -0.2,
        2000.0,
        0.0,
        40,
        Temperature::Adiabatic,
    )
    .expect("path");
    let mut worst = (0.0, "");
    for &p_name in params {
        let p = m.param(p_name).expect("named parameter");
        let seeded = m.map_params(|n, v| {
            if n == p_name {
                Dual64::new(v, 1.0)
            } else {
                Dual64::from(v)
            }
        });
        let dual = driver::run(&seeded, &path).expect("dual path");
        let h = 1e-3 * p;
        let at = |d: f64| {
            driver::run(
                &m.map_params(|n, v| if n == p_name { v + d } else { v }),
                &path,
            )
            .expect("shifted path")
        };
        let (p1, m1, p2, m2) = (at(h), at(-h), at(2.0 * h), at(-2.0 * h));
        let (mut err, mut scale) = (0.0f64, 0.0f64);
        for k in 0..dual.len() {
            let fd = ((p1[k].sigma[(0, 0)] - m1[k].sigma[(0, 0)]) * 8.0
                - (p2[k].sigma[(0, 0)] - m2[k].sigma[(0, 0)]))
                / (12.0 * h);
            err = err.max((dual[k].sigma[(0, 0)].eps - fd).abs() * p);
            scale = scale.max(dual[k].sigma[(0, 0)].eps.abs() * p);
        }
        if err / scale > worst.0 {
            worst = (err / scale, p_name);
        }
    }
    CaseResult::at_most(
        format!("{name}: path dσ/dp vs FD (worst: {})", worst.1),
        worst.0,
        1e-6,
    )
}

//! Conformance checks that every material model must pass (DESIGN 4.4), each measuring
//! one number that a caller compares with its bound (`BOUND_*`): zero stress at F = I,
//! symmetry of σ, objectivity σ(QF) = Q σ(F) Qᵀ, the AD tangent dσ/dF against central
//! differences, the parameter sensitivities dσ/dp against fourth-order differences,
//! plastic incompressibility det Fᵖ = 1, the elastic unloading slope, the reference
//! (algorithm 3) against the fast (principal) return, uniaxial flow against the law's
//! τ_y (eq. 4.52 for Johnson-Cook), whole-path sensitivities, and (Neo-Hooke)
//! σ = ∂ψ/∂F Fᵀ/J (eq. 4.12-4.13).
//!
//! `cargo test -p materials` runs them on every shipped model (`tests/conformance.rs`);
//! the `mpw verify` table shows the same numbers. Random deformations come from a fixed
//! seed, so each measure is one reproducible number.

use crate::ad;
use crate::driver::{self, LoadPath, Ramp, RateKind, Temperature};
use crate::flow_stress::softening::ExponentialSoftening;
use crate::flow_stress::{Composed, FlowStress, ThermalSoftening};
use crate::material::{Model, State};
use crate::neo_hooke::NeoHooke;
use crate::plasticity::ElastoPlastic;
use crate::tensor::{det, M3};
use nalgebra::{Rotation3, SMatrix, SVector, Vector3};
use num_dual::{gradient, Dual64, DualSVec64};

/// Time step of the single updates [s] (plastic rate ≈ 1e3 1/s for steels).
pub const DT: f64 = 1e-5;

/// |σ(F = I)| [Pa].
pub const BOUND_STRESS_AT_IDENTITY: f64 = 1e-6;
/// |σ − σᵀ| / |σ|.
pub const BOUND_ASYMMETRY: f64 = 1e-12;
/// |σ(QF) − Q σ(F) Qᵀ| / |σ|.
pub const BOUND_OBJECTIVITY: f64 = 1e-9;
/// Relative error of the AD tangent and of dσ/dp against differences.
pub const BOUND_DERIVATIVE: f64 = 1e-6;
/// |σ − ∂ψ/∂F Fᵀ/J| / |σ| (Neo-Hooke).
pub const BOUND_ENERGY: f64 = 1e-12;
/// |det Fᵖ − 1| along a plastic path.
pub const BOUND_INCOMPRESSIBILITY: f64 = 1e-12;
/// Unloading slope against loading slope, relative.
pub const BOUND_UNLOADING: f64 = 0.01;
/// Reference against fast return, relative, on σ, Fᵖ⁻¹ and α.
pub const BOUND_RETURNS: f64 = 1e-10;
/// Uniaxial Kirchhoff stress against the law's τ_y at the step's plastic rate once
/// α > 0.02, relative: the consistency condition the return solves, in the driver's
/// uniaxial stress state, whose lateral stresses vanish only to the driver's tolerance
/// (1e-10 of the P-wave modulus, about 1e-7 of a steel's flow stress).
pub const BOUND_UNIAXIAL: f64 = 1e-6;

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

/// A loaded state: one 2 % step from the virgin state, so Fᵖ⁻¹ ≠ I for plastic models.
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

/// The measures every model is held to.
#[derive(Debug, Clone, Copy)]
pub struct ModelMeasures {
    /// |σ(F = I)| [Pa]
    pub stress_at_identity: f64,
    /// worst |σ − σᵀ| / |σ| of 20 random states
    pub asymmetry: f64,
    /// worst objectivity error of the same states
    pub objectivity: f64,
    /// worst relative error of the AD tangent against central differences (h = 1e-6)
    pub tangent: f64,
    /// worst relative error of p·dσ/dp, and the parameter where it is
    pub sensitivity: f64,
    pub sensitivity_worst: &'static str,
}

/// `ModelMeasures` of `m` (seed 11).
pub fn model_measures<M: Model<f64>>(m: &M) -> ModelMeasures {
    let mut rng = Rng(11);
    let (sigma0, _) = (m.update(&M3::identity(), DT, &m.initial_state())).expect("update at F = I");
    let (mut asymmetry, mut objectivity) = (0.0f64, 0.0f64);
    for _ in 0..20 {
        let old = preloaded(m, &mut rng);
        let f = rng.deformation(0.03);
        let q = rng.rotation();
        let sigma = stress(m, &f, &old);
        asymmetry = asymmetry.max((sigma - sigma.transpose()).norm() / sigma.norm());
        let rotated = stress(m, &(q * f), &old);
        objectivity = objectivity.max(rel(&rotated, &(q * sigma * q.transpose())));
    }
    let (sensitivity, sensitivity_worst) = sensitivity_error(m, &mut rng);
    ModelMeasures {
        stress_at_identity: sigma0.norm(),
        asymmetry,
        objectivity,
        tangent: tangent_error(m, &mut rng),
        sensitivity,
        sensitivity_worst,
    }
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
            let shifted = m.map_params(|n, v| if n == name { v + d } else { v });
            stress(&shifted, &f, &old)
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

/// Neo-Hooke: worst |σ − ∂ψ/∂F Fᵀ/J| / |σ| with the gradient of ψ by AD (seed 3).
pub fn energy_consistency(m: &NeoHooke) -> f64 {
    let mut rng = Rng(3);
    let mut worst = 0.0f64;
    for _ in 0..10 {
        let f = rng.deformation(0.2);
        let x = SVector::<f64, 9>::from_fn(|k, _| f[(k / 3, k % 3)]);
        let elastic = m.elastic.map(|_, v| DualSVec64::<9>::from(v));
        let (_, p1) = gradient(|xd| elastic.energy(&M3::from_fn(|i, j| xd[3 * i + j])), &x);
        let p1 = M3::from_fn(|i, j| p1[3 * i + j]);
        let from_energy = p1 * f.transpose() / det(&f);
        worst = worst.max(rel(&stress(m, &f, &m.initial_state()), &from_energy));
    }
    worst
}

/// What a plastic model is held to beyond `ModelMeasures`.
#[derive(Debug, Clone, Copy)]
pub struct PlasticMeasures {
    /// α at the end of a random plastic path of 40 steps (seed 9)
    pub alpha: f64,
    /// |det Fᵖ − 1| there
    pub incompressibility: f64,
    /// uniaxial slopes [Pa]: the first elastic step of loading (1e-3, or half the yield
    /// strain where that is smaller), and unloading by 1e-3 after 5 %
    pub loading_slope: f64,
    pub unloading_slope: f64,
}

/// `PlasticMeasures` of `m`.
pub fn plastic_measures(m: &ElastoPlastic) -> PlasticMeasures {
    let mut rng = Rng(9);
    let mut state = m.initial_state();
    let mut f = M3::identity();
    for _ in 0..40 {
        f = rng.deformation(0.01) * f;
        state = m.update(&f, DT, &state).expect("plastic path").1;
    }
    // the loading slope over an elastic first step: 1e-3, or half the yield strain where
    // that is smaller (a soft metal such as annealed copper yields below 1e-3)
    let yield_strain = m.flow.tau_y(0.0, 0.0, m.thermal.theta0, m.thermal.theta0) / m.elastic.e;
    let first = (0.5 * yield_strain).min(1e-3);
    let times = vec![0.0, 1e-3, 1.0, 1.0 + 1e-3];
    let stretch = vec![1.0, first.exp(), 0.05f64.exp(), (0.05f64 - 1e-3).exp()];
    let theta = Temperature::Prescribed(Ramp::constant(m.thermal.theta0));
    let path = LoadPath::uniaxial_stretch(times, stretch, theta).expect("path");
    let r = driver::run(m, &path).expect("unloading path");
    PlasticMeasures {
        alpha: state.alpha,
        incompressibility: (det(&state.fp_inv) - 1.0).abs(),
        loading_slope: r[1].sigma[(0, 0)] / first,
        unloading_slope: (r[2].sigma[(0, 0)] - r[3].sigma[(0, 0)]) / 1e-3,
    }
}

/// Worst relative difference of the reference and fast returns on σ, Fᵖ⁻¹ and α over 50
/// random steps from loaded states (seed 21).
pub fn returns_disagreement(reference: &ElastoPlastic, fast: &ElastoPlastic) -> f64 {
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
    worst
}

/// The (true strain rate [1/s], temperature [K]) of the uniaxial checks: quasi-static
/// and dynamic at θ0, dynamic 480 K above it.
pub fn uniaxial_conditions(m: &ElastoPlastic) -> [(f64, f64); 3] {
    let theta0 = m.thermal.theta0;
    [(1e-2, theta0), (1e3, theta0), (1e3, theta0 + 480.0)]
}

/// Uniaxial tension to 0.5 at constant true rate and fixed temperature (one of
/// `uniaxial_conditions`): the worst relative difference of the Kirchhoff stress from the
/// model's τ_y at the plastic rate of each record interval, α̇ = Δα/Δt, once α > 0.02.
/// (The plastic rate falls short of the imposed rate by the elastic strain rate σ̇/E,
/// 2-4 % early in hardening: a law as rate-sensitive as Cowper-Symonds with p = 5 shows
/// that as 5e-3 against τ_y at the imposed rate.)
pub fn uniaxial_flow_error(m: &ElastoPlastic, rate: f64, theta: f64) -> f64 {
    let fixed = Temperature::Prescribed(Ramp::constant(theta));
    let path = LoadPath::uniaxial(RateKind::True, 0.5, rate, 0.0, 500, fixed).expect("path");
    let records = driver::run(m, &path).expect("uniaxial path");
    (records.windows(2))
        .filter(|w| w[1].state.alpha > 0.02)
        .map(|w| {
            let (r, previous) = (&w[1], &w[0]);
            let plastic_rate = (r.state.alpha - previous.state.alpha) / (r.time - previous.time);
            let tau_xx = r.sigma[(0, 0)] * r.f.determinant();
            let theta0 = m.thermal.theta0;
            (tau_xx / m.flow.tau_y(r.state.alpha, plastic_rate, theta, theta0) - 1.0).abs()
        })
        .fold(0.0, f64::max)
}

/// The parameters whose path sensitivities are checked: every flow-stress parameter but
/// the reference rate α̇0 and θm (kinks of the clamped rate and thermal terms) and those
/// that are zero (no relative difference step), and γ_TQ.
pub fn path_parameters(m: &ElastoPlastic) -> Vec<&'static str> {
    (m.flow.names().into_iter())
        .filter(|n| !["alpha_dot0", "theta_m"].contains(n))
        .filter(|n| m.param(n) != Some(0.0))
        .chain(["gamma_tq"])
        .collect()
}

/// `m` with the exponential thermal softening (`flow_stress::softening`) in place of its
/// own: the factor no shipped parameter file uses, for the checks of every factor.
pub fn with_exponential_softening(m: &ElastoPlastic) -> ElastoPlastic {
    let mut out = *m;
    let theta_m = m.param("theta_m").unwrap_or(1800.0);
    let composed = match m.flow {
        FlowStress::Composed(law) => law,
        _ => panic!("a composed law"),
    };
    out.flow = FlowStress::Composed(Composed {
        softening: ThermalSoftening::Exponential(ExponentialSoftening {
            lambda: 1.1e-3,
            theta_m,
        }),
        ..composed
    });
    out
}

/// dσ_xx(t)/dp over a whole adiabatic uniaxial compression path to −0.2 at 2000 1/s
/// (history derivatives through Fᵖ⁻¹, α and θ) against fourth-order differences of the
/// driver: the worst relative error over `params`, and the parameter where it is.
pub fn path_sensitivity_error(m: &ElastoPlastic, params: &[&'static str]) -> (f64, &'static str) {
    let path = LoadPath::uniaxial(
        RateKind::True,
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
        let seed = |n, v| {
            if n == p_name {
                Dual64::new(v, 1.0)
            } else {
                Dual64::from(v)
            }
        };
        let dual = driver::run(&m.map_params(seed), &path).expect("dual path");
        let h = 1e-3 * p;
        let at = |d: f64| {
            let shifted = m.map_params(|n, v| if n == p_name { v + d } else { v });
            driver::run(&shifted, &path).expect("shifted path")
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
    worst
}

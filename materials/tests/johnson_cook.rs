//! Johnson-Cook specific checks: the analytic uniaxial curve (eq. 4.52) at constant
//! plastic rate and fixed temperature, safeguarded first yield with N < 1, and the
//! parameter sensitivities of a whole driver path against finite differences.

mod common;
use common::*;
use materials::driver::{self, LoadPath, Ramp, RateKind, Temperature};
use materials::{Model, ReturnMap};
use nalgebra::Matrix3;
use num_dual::Dual64;

#[test]
fn uniaxial_curve_matches_eq_4_52_at_constant_rate_and_temperature() {
    let m = aisi_4340();
    let law = jc_law(&m);
    for (rate, theta) in [(1e-2, 293.15), (1e3, 293.15), (1e3, 773.15)] {
        let path = LoadPath::uniaxial(
            RateKind::True,
            0.5,
            rate,
            0.0,
            500,
            Temperature::Prescribed(Ramp::constant(theta)),
        )
        .unwrap();
        let records = driver::run(&m, &path).unwrap();
        let mut worst = 0.0f64;
        for r in records.iter().filter(|r| r.state.alpha > 0.02) {
            // Kirchhoff axial stress equals τ_y at α̇ = ε̇ (plastic rate = total rate
            // once the elastic strain is constant to within σ̇/E).
            let tau_xx = r.sigma[(0, 0)] * r.f.determinant();
            let theta_star = (theta - 293.15) / (law.theta_m - 293.15);
            let expected = (law.a + law.b * r.state.alpha.powf(law.n))
                * (1.0 + law.c * (rate / law.alpha_dot0).max(1.0).ln())
                * (1.0 - theta_star.powf(law.m));
            worst = worst.max((tau_xx / expected - 1.0).abs());
        }
        assert!(
            worst < 0.005,
            "rate {rate}, θ {theta}: worst deviation {worst:e}"
        );
    }
}

#[test]
fn first_yield_with_n_below_one_converges_for_all_increments() {
    // AISI 4340 has N = 0.26: α^N has an infinite slope at α = 0.
    for rm in [ReturnMap::Principal, ReturnMap::Reference] {
        let mut m = aisi_4340();
        m.return_map = rm;
        let mut rng = Rng(13);
        for k in 0..60 {
            let size = 10f64.powf(-3.5 + 2.5 * (k as f64 / 59.0)); // 3e-4 .. 0.1
            let dir = rng.deformation(1.0) - Matrix3::identity();
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
fn path_sensitivities_match_finite_differences() {
    // dσ_xx(t)/dp over a whole adiabatic uniaxial compression path: history
    // derivatives flow through F^p⁻¹, α and θ of every step.
    let m = johnson_cook(ReturnMap::Principal);
    let path = LoadPath::uniaxial(
        RateKind::True,
        -0.2,
        2000.0,
        0.0,
        40,
        Temperature::Adiabatic,
    )
    .unwrap();
    for name in ["A", "B", "N", "C", "M", "gamma_tq"] {
        let p = m.param(name).unwrap();
        let seeded = m.map_params(|n, v| {
            if n == name {
                Dual64::new(v, 1.0)
            } else {
                Dual64::from(v)
            }
        });
        let dual = driver::run(&seeded, &path).unwrap();
        let h = 1e-3 * p;
        let at = |d: f64| {
            driver::run(
                &m.map_params(|n, v| if n == name { v + d } else { v }),
                &path,
            )
            .unwrap()
        };
        let (p1, m1, p2, m2) = (at(h), at(-h), at(2.0 * h), at(-2.0 * h));
        let mut worst = 0.0f64;
        let mut scale = 0.0f64;
        for k in 0..dual.len() {
            let fd = ((p1[k].sigma[(0, 0)] - m1[k].sigma[(0, 0)]) * 8.0
                - (p2[k].sigma[(0, 0)] - m2[k].sigma[(0, 0)]))
                / (12.0 * h);
            worst = worst.max((dual[k].sigma[(0, 0)].eps - fd).abs() * p);
            scale = scale.max(dual[k].sigma[(0, 0)].eps.abs() * p);
        }
        assert!(
            worst / scale < 1e-6,
            "dσ_xx/d{name}: max error {:e} of max |p dσ/dp| {scale:e}",
            worst / scale
        );
    }
}

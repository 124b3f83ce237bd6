//! Thesis figure 4.5: homogeneous tension of AISI 4340 (table 4.1, γ_TQ = 0) with the
//! engineering strain ε_xx ramped to 0.6 at a constant rate, then held, at two strain
//! rates and two fixed temperatures.
//!
//! The thesis does not state the rates and temperatures; this study uses
//! ε̇ = 1 and 1000 1/s and θ = 293.15 K and 773.15 K. Thermal expansion is switched
//! off (α_σ = 0), so every curve starts stress-free and ε_xx is the mechanical strain,
//! as in the thesis figure. Checks:
//! - at ε_xx = 0.6 the Kirchhoff stress equals eq. 4.52 at the imposed plastic rate
//!   α̇ = ε̇/(1 + ε_xx) (true rate of the engineering ramp), the temperature and the
//!   plastic strain α = ln(1 + ε_xx) − σ/E (within 0.5 %);
//! - the curves are ordered: colder above hotter, faster above slower;
//! - during the hold the rate term drops to 1: the end-of-hold stress equals the
//!   quasi-static JC value (within 0.5 %).

use crate::verify::row::Row;
use materials::driver::{self, LoadPath, Ramp, RateKind, Record, Temperature};
use materials::flow_stress::FlowStress;
use materials::plasticity::ElastoPlastic;

pub const RATES: [f64; 2] = [1.0, 1000.0];
pub const TEMPERATURES: [f64; 2] = [293.15, 773.15];
pub const STRAIN_END: f64 = 0.6;
/// Steps of the ramp; the hold lasts a quarter of the ramp with the same step size.
pub const STEPS: usize = 600;

pub struct Curve {
    pub rate: f64,
    pub theta: f64,
    pub records: Vec<Record>,
    /// Index of the record at the end of the ramp (ε_xx = 0.6).
    pub ramp_end: usize,
}

/// Run the four curves with the AISI 4340 model (γ_TQ must be 0).
pub fn run(model: &ElastoPlastic) -> Result<Vec<Curve>, driver::DriverError> {
    let mut model = *model;
    model.thermal.alpha_sigma = 0.0;
    let model = &model;
    let mut curves = Vec::new();
    for &theta in &TEMPERATURES {
        for &rate in &RATES {
            let hold = 0.25 * STRAIN_END / rate;
            let path = LoadPath::uniaxial(
                RateKind::Engineering,
                STRAIN_END,
                rate,
                hold,
                STEPS,
                Temperature::Prescribed(Ramp::constant(theta)),
            )
            .map_err(|e| driver::DriverError::Path(e.to_string()))?;
            let records = driver::run(model, &path)?;
            curves.push(Curve {
                rate,
                theta,
                records,
                ramp_end: STEPS,
            });
        }
    }
    Ok(curves)
}

/// Eq. 4.52 with the clamps of `FlowStress`.
fn jc(model: &ElastoPlastic, alpha: f64, alpha_dot: f64, theta: f64) -> f64 {
    model
        .flow
        .tau_y(alpha, alpha_dot, theta, model.thermal.theta0)
}

fn kirchhoff_xx(r: &Record) -> f64 {
    r.sigma[(0, 0)] * r.f.determinant()
}

pub fn cases(model: &ElastoPlastic, curves: &[Curve]) -> Vec<Row> {
    let mut out = Vec::new();
    assert!(matches!(model.flow, FlowStress::JohnsonCook(_)));
    let e = model.elastic.e;
    for c in curves {
        let r = &c.records[c.ramp_end];
        let tau = kirchhoff_xx(r);
        let alpha = (1.0 + STRAIN_END).ln() - tau / e;
        let expected = jc(model, alpha, c.rate / (1.0 + STRAIN_END), c.theta);
        out.push(Row::relative(
            format!("fig4.5/tau@0.6 rate {:e} T {}", c.rate, c.theta),
            tau,
            expected,
            5e-3,
        ));
        let end = c.records.last().unwrap();
        let quasi_static = jc(model, end.state.alpha, 0.0, c.theta);
        out.push(Row::relative(
            format!(
                "fig4.5/hold rate term -> 1, rate {:e} T {}",
                c.rate, c.theta
            ),
            kirchhoff_xx(end),
            quasi_static,
            5e-3,
        ));
    }
    // Ordering at ε_xx = 0.6: (cold, fast) > (cold, slow) > (hot, fast) > (hot, slow).
    let at_end: Vec<f64> = curves
        .iter()
        .map(|c| c.records[c.ramp_end].sigma[(0, 0)])
        .collect();
    let ordered = at_end[1] > at_end[0] && at_end[0] > at_end[3] && at_end[3] > at_end[2];
    out.push(Row::holds("fig4.5/curve ordering", ordered));
    out
}

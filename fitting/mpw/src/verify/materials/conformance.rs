//! The conformance checks of every material model (`materials::conformance`, DESIGN 4.4)
//! as rows of the `mpw verify` table, with the library's bounds.

use crate::verify::row::Row;
use materials::conformance::{self as c, BOUND_DERIVATIVE};
use materials::material::Model;
use materials::neo_hooke::NeoHooke;
use materials::plasticity::ElastoPlastic;

/// The checks every model passes.
pub fn check_model<M: Model<f64>>(name: &str, m: &M) -> Vec<Row> {
    let r = c::model_measures(m);
    vec![
        Row::at_most(
            format!("{name}: |σ(F=I)| [Pa]"),
            r.stress_at_identity,
            c::BOUND_STRESS_AT_IDENTITY,
        ),
        Row::at_most(
            format!("{name}: asymmetry of σ"),
            r.asymmetry,
            c::BOUND_ASYMMETRY,
        ),
        Row::at_most(
            format!("{name}: objectivity error"),
            r.objectivity,
            c::BOUND_OBJECTIVITY,
        ),
        Row::at_most(
            format!("{name}: AD tangent vs FD"),
            r.tangent,
            BOUND_DERIVATIVE,
        ),
        Row::at_most(
            format!("{name}: dσ/dp vs FD"),
            r.sensitivity,
            BOUND_DERIVATIVE,
        )
        .with_note(format!("worst: {}", r.sensitivity_worst)),
    ]
}

/// Neo-Hooke: σ = ∂ψ/∂F Fᵀ / J with the gradient of ψ by AD.
pub fn check_energy(m: &NeoHooke) -> Row {
    Row::at_most(
        "neo-hooke: σ vs ∂ψ/∂F Fᵀ/J",
        c::energy_consistency(m),
        c::BOUND_ENERGY,
    )
}

/// Plastic models: det Fp = 1 along a random plastic path, and the elastic unloading
/// slope after 5 % uniaxial strain equals the initial loading slope.
pub fn check_plastic(name: &str, m: &ElastoPlastic) -> Vec<Row> {
    let r = c::plastic_measures(m);
    vec![
        Row::at_most(
            format!("{name}: |det Fp - 1| on a plastic path"),
            r.incompressibility,
            c::BOUND_INCOMPRESSIBILITY,
        )
        .with_note(format!("α = {:.2}", r.alpha)),
        Row::relative(
            format!("{name}: unloading slope [Pa]"),
            r.unloading_slope,
            r.loading_slope,
            c::BOUND_UNLOADING,
        ),
    ]
}

/// Reference (algorithm 3) and fast (principal) returns agree on σ, Fp⁻¹ and α.
pub fn check_returns_agree(name: &str, reference: &ElastoPlastic, fast: &ElastoPlastic) -> Row {
    let worst = c::returns_disagreement(reference, fast);
    Row::at_most(
        format!("{name}: reference vs fast return"),
        worst,
        c::BOUND_RETURNS,
    )
}

/// Uniaxial tension against the model's flow stress: `law` names it (`eq. 4.52` for
/// Johnson-Cook).
pub fn check_uniaxial(name: &str, law: &str, m: &ElastoPlastic) -> Vec<Row> {
    (c::uniaxial_conditions(m).into_iter())
        .map(|(rate, theta)| {
            Row::at_most(
                format!("{name}: uniaxial vs {law}, rate {rate:e}, θ {theta}"),
                c::uniaxial_flow_error(m, rate, theta),
                c::BOUND_UNIAXIAL,
            )
        })
        .collect()
}

/// dσ_xx(t)/dp over a whole adiabatic uniaxial compression path, for every parameter of
/// `conformance::path_parameters`.
pub fn check_path_sensitivities(name: &str, m: &ElastoPlastic) -> Row {
    let (worst, param) = c::path_sensitivity_error(m, &c::path_parameters(m));
    Row::at_most(format!("{name}: path dσ/dp vs FD"), worst, BOUND_DERIVATIVE)
        .with_note(format!("worst: {param}"))
}

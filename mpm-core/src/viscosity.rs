//! Artificial bulk viscosity (von Neumann & Richtmyer 1950; the linear-quadratic form of
//! explicit impact codes, e.g. LS-DYNA's `*CONTROL_BULK_VISCOSITY`):
//!
//! q = ρ l (C₂ l ε̇_v² − C₁ c ε̇_v)  for ε̇_v = tr D < 0 (compression), q = 0 otherwise,
//!
//! with ρ the current density [kg/m³], l the cell size [m], c the dilatational wave speed
//! [m/s]; the pressure q [Pa] is added to the material stress, σ ← σ − q I. It damps the
//! grid-scale ringing behind a wave front, which the leapfrog carries undamped. In an
//! axisymmetric bar that ringing focuses on the axis (radial waves converge there, and
//! the first column of points moves closer to r = 0 as the grid is refined), where it
//! drove the column next to the axis past yield in a bar that stays elastic. q vanishes with l, so the converged solution is unchanged; its work is part of
//! the stress work, so the energy balance holds.

use materials::scalar::{c as constant, Scalar};

/// Coefficients C₁ (linear) and C₂ (quadratic) [-].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BulkViscosity {
    pub linear: f64,
    pub quadratic: f64,
}

impl BulkViscosity {
    /// LS-DYNA's defaults: C₁ = 0.06, C₂ = 1.5.
    pub const STANDARD: Self = BulkViscosity {
        linear: 0.06,
        quadratic: 1.5,
    };

    /// Viscous pressure q [Pa] at density `rho` [kg/m³], wave speed `c` [m/s], cell size
    /// `l` [m] and volumetric strain rate `trace_d` = tr D [1/s].
    /// In any scalar (dual in the derivative pass, `solver::tangent`).
    #[inline]
    pub fn pressure<T: Scalar>(&self, rho: T, c: f64, l: f64, trace_d: T) -> T {
        if trace_d.re() >= 0.0 {
            return T::zero();
        }
        rho * constant::<T>(l)
            * (constant::<T>(self.quadratic * l) * trace_d * trace_d
                - constant::<T>(self.linear * c) * trace_d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pressure_is_the_linear_quadratic_form_in_compression_and_zero_in_expansion() {
        let q = BulkViscosity::STANDARD;
        let (rho, c, l) = (7850.0, 5900.0, 1e-3);
        assert_eq!(q.pressure(rho, c, l, 1e4), 0.0);
        assert_eq!(q.pressure(rho, c, l, 0.0), 0.0);
        let rate = -1e4;
        let expected = rho * l * (1.5 * l * 1e8 + 0.06 * c * 1e4);
        assert!((q.pressure(rho, c, l, rate) - expected).abs() < 1e-9 * expected);
        // a velocity jump |ε̇| l = 10 m/s across a steel cell: the linear term is 6 % of the
        // elastic wave's stress ρ c Δv = 463 MPa, the quadratic one 1.2 MPa
        let linear = 0.06 * rho * c * 10.0;
        assert!((q.pressure(rho, c, l, rate) - linear - 1.5 * rho * 100.0).abs() < 1e-6 * linear);
    }
}

//! Neo-Hooke elasticity with thermal expansion coupling (eq. 4.12-4.13, 4.21-4.24).
//!
//! ψ = Λ/2 (ln J)² + G/2 (tr b − 3) − G ln J  [J/m³ of reference volume]
//! τ = Λ ln J I + G (b − I) − 3 α_σ κ (θ − θ0) I   (Kirchhoff, Pa)
//! with Λ = Eν/((1+ν)(1−2ν)), G = E/(2(1+ν)), κ = Λ + 2G/3.

use crate::parameter_set;
use crate::scalar::{c, Scalar};
use crate::tensor::{det, det_in, mul_transpose_self_in, symmetric_in, trace, M3};

parameter_set! {
    /// Elastic constants and reference density.
    Elastic {
        /// Young's modulus E [Pa]
        e => "E",
        /// Poisson's ratio ν [-]
        nu => "nu",
        /// reference density ρ0 [kg/m³]
        rho => "rho",
    }
}

impl<D: Scalar> Elastic<D> {
    /// Shear modulus G [Pa].
    pub fn shear_modulus(&self) -> D {
        self.e / (c::<D>(2.0) * (c::<D>(1.0) + self.nu))
    }

    /// Lamé constant Λ [Pa].
    pub fn lambda(&self) -> D {
        self.e * self.nu / ((c::<D>(1.0) + self.nu) * (c::<D>(1.0) - c::<D>(2.0) * self.nu))
    }

    /// Bulk modulus κ = Λ + 2G/3 [Pa].
    pub fn bulk_modulus(&self) -> D {
        self.lambda() + self.shear_modulus() * c::<D>(2.0 / 3.0)
    }

    /// P-wave modulus Λ + 2G [Pa], for the dilatational wave speed √((Λ+2G)/ρ).
    pub fn p_wave_modulus(&self) -> D {
        self.lambda() + self.shear_modulus() * c::<D>(2.0)
    }

    /// Kirchhoff stress of the elastic part `fe`, with the thermal coupling term of
    /// eq. 4.22 for a temperature rise `dtheta` = θ − θ0 and expansion coefficient
    /// `alpha_sigma`.
    #[inline]
    pub fn tau(&self, fe: &M3<D>, dtheta: D, alpha_sigma: D) -> M3<D> {
        self.tau_in::<false>(fe, dtheta, alpha_sigma)
    }

    /// `tau` of an `fe` with the structure `IN_PLANE` (`tensor::sum_coupled`).
    #[inline]
    pub fn tau_in<const IN_PLANE: bool>(&self, fe: &M3<D>, dtheta: D, alpha_sigma: D) -> M3<D> {
        let b = mul_transpose_self_in::<IN_PLANE, D>(fe);
        let ln_j = det_in::<IN_PLANE, D>(fe).ln();
        self.tau_of_stretch_in::<IN_PLANE>(&b, ln_j, dtheta, alpha_sigma)
    }

    /// τ = G (b − I) + (Λ ln J − 3 α_σ κ (θ − θ0)) I from the left stretch b = Fe Feᵀ
    /// (symmetric: its entries on and above the diagonal are read) and ln J = ln det Fe.
    #[inline]
    pub fn tau_of_stretch(&self, b: &M3<D>, ln_j: D, dtheta: D, alpha_sigma: D) -> M3<D> {
        self.tau_of_stretch_in::<false>(b, ln_j, dtheta, alpha_sigma)
    }

    /// `tau_of_stretch` of a `b` with the structure `IN_PLANE`.
    #[inline]
    pub fn tau_of_stretch_in<const IN_PLANE: bool>(
        &self,
        b: &M3<D>,
        ln_j: D,
        dtheta: D,
        alpha_sigma: D,
    ) -> M3<D> {
        let p = self.spherical(ln_j, dtheta, alpha_sigma);
        let g = self.shear_modulus();
        symmetric_in::<IN_PLANE, D>(|i, j| match i == j {
            true => (b[(i, i)] - c::<D>(1.0)) * g + p,
            false => b[(i, j)] * g,
        })
    }

    /// The spherical part Λ ln J − 3 α_σ κ (θ − θ0) of τ [Pa] (τ = G (b − I) + this · I).
    pub fn spherical(&self, ln_j: D, dtheta: D, alpha_sigma: D) -> D {
        self.lambda() * ln_j - c::<D>(3.0) * alpha_sigma * self.bulk_modulus() * dtheta
    }

    /// Strain energy density ψ(F) per reference volume (isothermal), eq. 4.12.
    pub fn energy(&self, f: &M3<D>) -> D {
        let ln_j = det(f).ln();
        let b = f * f.transpose();
        let g = self.shear_modulus();
        self.lambda() * c::<D>(0.5) * ln_j * ln_j + g * c::<D>(0.5) * (trace(&b) - c::<D>(3.0))
            - g * ln_j
    }
}

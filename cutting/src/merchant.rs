//! An independent estimate of the steady cutting force from the measured shear angle:
//! Merchant's thin-shear-plane model (Merchant 1945) with the Johnson-Cook flow stress in
//! the shear zone, per unit width of cut (plane strain):
//!
//!   F_c = τ_s h cos(β − α) / (sin φ cos(φ + β − α)),   β = atan μ,
//!
//! h the depth of cut, α the rake angle, φ the shear angle, μ the tool friction. The shear
//! plane imposes the shear strain γ = cos α / (sin φ cos(φ − α)) at the rate
//! γ̇ = v cos α / (cos(φ − α) Δ), Δ the shear zone's thickness; with ε = γ/√3,
//! ε̇ = γ̇/√3, the zone's shear flow stress is τ_s = σ_JC(ε, ε̇, θ)/√3, at the temperature
//! θ the plastic work heats the material to adiabatically on the way,
//! dθ/dε = γ_TQ σ_JC(ε, ε̇, θ)/(ρ c) from θ0 (integrated in 200 steps by the midpoint rule).
//! The shear zone thickness is taken as a tenth of the shear plane's length h/sin φ (the
//! flow stress depends on it only through ln ε̇).

use materials::plasticity::ElastoPlastic;

/// The inputs of the estimate. SI units, angles in degrees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Merchant {
    /// Depth of cut h [m], cutting speed v [m/s].
    pub depth: f64,
    pub speed: f64,
    pub rake_deg: f64,
    pub shear_deg: f64,
    pub friction: f64,
}

/// The estimate and the shear zone's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MerchantForce {
    /// Cutting force per unit width F_c [N/m].
    pub force: f64,
    /// Shear zone: equivalent strain [-], strain rate [1/s], temperature [K], shear flow
    /// stress [Pa].
    pub strain: f64,
    pub strain_rate: f64,
    pub temperature: f64,
    pub shear_stress: f64,
}

impl Merchant {
    pub fn estimate(&self, material: &ElastoPlastic<f64>) -> MerchantForce {
        let (a, phi) = (self.rake_deg.to_radians(), self.shear_deg.to_radians());
        let beta = self.friction.atan();
        let gamma = a.cos() / (phi.sin() * (phi - a).cos());
        let thickness = 0.1 * self.depth / phi.sin();
        let gamma_rate = self.speed * a.cos() / ((phi - a).cos() * thickness);
        let (strain, strain_rate) = (gamma / 3f64.sqrt(), gamma_rate / 3f64.sqrt());
        let t = &material.thermal;
        let sigma = |e: f64, theta: f64| material.flow.tau_y(e, strain_rate, theta, t.theta0);
        let steps = 200;
        let de = strain / steps as f64;
        let mut theta = t.theta0;
        for k in 0..steps {
            let e = (k as f64 + 0.5) * de;
            let half = theta
                + 0.5 * de * t.gamma_tq * sigma(e - 0.5 * de, theta)
                    / (material.elastic.rho * t.c_theta);
            theta += de * t.gamma_tq * sigma(e, half) / (material.elastic.rho * t.c_theta);
        }
        let shear_stress = sigma(strain, theta) / 3f64.sqrt();
        let force =
            shear_stress * self.depth * (beta - a).cos() / (phi.sin() * (phi + beta - a).cos());
        MerchantForce {
            force,
            strain,
            strain_rate,
            temperature: theta,
            shear_stress,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use materials::flow_stress::{FlowStress, JohnsonCookLaw};
    use materials::plasticity::{ReturnMap, Thermal};

    /// A steel with A = 500 MPa, hardening B ε^N, no rate term and θm = 1e15 K (no thermal
    /// softening).
    fn steel(b: f64, n: f64) -> ElastoPlastic<f64> {
        ElastoPlastic {
            elastic: materials::elastic::Elastic {
                e: 200e9,
                nu: 0.3,
                rho: 7800.0,
            },
            flow: FlowStress::JohnsonCook(JohnsonCookLaw {
                a: 500e6,
                b,
                n,
                c: 0.0,
                m: 1.0,
                alpha_dot0: 1.0,
                theta_m: 1e15,
            }),
            thermal: Thermal {
                theta0: 293.15,
                c_theta: 460.0,
                alpha_sigma: 1e-5,
                gamma_tq: 0.9,
            },
            return_map: ReturnMap::Principal,
        }
    }

    /// A perfectly plastic, rate- and temperature-free material (B = C = 0, θm = 1e15 K):
    /// F_c = (A/√3) h cos(β − α)/(sin φ cos(φ + β − α)) exactly; at α = 0, μ = 0 and
    /// φ = 45° that is 2 (A/√3) h; friction raises it.
    #[test]
    fn a_perfectly_plastic_material_gives_merchant_s_closed_form() {
        let m = steel(0.0, 0.5);
        let cut = Merchant {
            depth: 0.3e-3,
            speed: 40.0,
            rake_deg: 0.0,
            shear_deg: 45.0,
            friction: 0.0,
        };
        let f = cut.estimate(&m);
        let expected = 2.0 * 500e6 / 3f64.sqrt() * 0.3e-3;
        assert!(
            (f.force / expected - 1.0).abs() < 1e-12,
            "{} vs {expected}",
            f.force
        );
        assert!(
            (f.strain - 2.0 / 3f64.sqrt()).abs() < 1e-12,
            "γ = 2 at φ = 45°, α = 0"
        );
        let rubbing = Merchant {
            friction: 0.3,
            ..cut
        }
        .estimate(&m);
        let beta = 0.3f64.atan();
        let closed = 500e6 / 3f64.sqrt() * 0.3e-3 * beta.cos()
            / (45f64.to_radians().sin() * (45f64.to_radians() + beta).cos());
        assert!((rubbing.force / closed - 1.0).abs() < 1e-12);
        assert!(rubbing.force > f.force);
    }

    /// With hardening the adiabatic temperature follows the plastic work: for a linear
    /// hardening σ = A + B ε (N = 1, no thermal softening) θ − θ0 = γ_TQ (A ε + B ε²/2)/(ρ c).
    #[test]
    fn the_shear_zone_heats_by_its_plastic_work() {
        let m = steel(300e6, 1.0);
        let f = Merchant {
            depth: 0.3e-3,
            speed: 40.0,
            rake_deg: 5.0,
            shear_deg: 25.0,
            friction: 0.0,
        }
        .estimate(&m);
        let e = f.strain;
        let expected = 293.15 + 0.9 * (500e6 * e + 0.5 * 300e6 * e * e) / (7800.0 * 460.0);
        assert!(
            (f.temperature - expected).abs() < 1e-6 * expected,
            "{} vs {expected}",
            f.temperature
        );
    }
}

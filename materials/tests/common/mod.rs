//! Shared fixtures of the materials tests: models, random deformations, rotations.

#![allow(dead_code)]

use materials::flow_stress::{FlowStress, JohnsonCookLaw, Voce};
use materials::plasticity::Thermal;
use materials::{load_material, AnyModel, ElastoPlastic, NeoHooke, ReturnMap};
use nalgebra::{Matrix3, Rotation3, Vector3};

/// A small deterministic generator (SplitMix64) so tests need no RNG crate.
pub struct Rng(pub u64);

impl Rng {
    pub fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    /// I + amplitude · (random matrix with entries in [−1, 1)).
    pub fn deformation(&mut self, amplitude: f64) -> Matrix3<f64> {
        Matrix3::identity() + Matrix3::from_fn(|_, _| amplitude * self.uniform())
    }

    pub fn rotation(&mut self) -> Matrix3<f64> {
        let axis = Vector3::new(self.uniform(), self.uniform(), self.uniform());
        Rotation3::new(axis * 3.0).into_inner()
    }
}

pub fn data(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../data/materials")
        .join(name)
}

pub fn neo_hooke() -> NeoHooke {
    NeoHooke::new(200e9, 0.3, 7850.0)
}

/// J2 with Voce saturation and linear hardening (eq. 4.51), so every term is exercised.
pub fn j2(return_map: ReturnMap) -> ElastoPlastic {
    ElastoPlastic {
        elastic: materials::elastic::Elastic {
            e: 78.2e9,
            nu: 0.3,
            rho: 2700.0,
        },
        flow: FlowStress::Voce(Voce {
            tau0: 300e6,
            tau_inf: 450e6,
            eta: 12.0,
            h: 1e8,
        }),
        thermal: Thermal {
            theta0: 293.15,
            c_theta: 900.0,
            alpha_sigma: 0.0,
            gamma_tq: 0.0,
        },
        return_map,
    }
}

/// Johnson-Cook 42CrMo4 (table 11.1) with adiabatic heating and thermal expansion.
pub fn johnson_cook(return_map: ReturnMap) -> ElastoPlastic {
    match load_material(data("42crmo4_qt660.toml")).unwrap().model {
        AnyModel::ElastoPlastic(mut m) => {
            m.return_map = return_map;
            m
        }
        _ => unreachable!(),
    }
}

pub fn aisi_4340() -> ElastoPlastic {
    match load_material(data("aisi_4340.toml")).unwrap().model {
        AnyModel::ElastoPlastic(m) => m,
        _ => unreachable!(),
    }
}

pub fn jc_law(m: &ElastoPlastic) -> JohnsonCookLaw {
    match m.flow {
        FlowStress::JohnsonCook(p) => p,
        _ => panic!("not a Johnson-Cook model"),
    }
}

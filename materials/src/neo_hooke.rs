//! Compressible Neo-Hooke hyperelasticity (eq. 4.12-4.13):
//! σ = Λ/J ln J I + G/J (b − I).

use crate::elastic::Elastic;
use crate::error::MaterialError;
use crate::material::{Model, State};
use crate::scalar::{c, Scalar};
use crate::tensor::{det, M3};

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NeoHooke<D = f64> {
    pub elastic: Elastic<D>,
    /// Temperature carried in the state [K]; Neo-Hooke is isothermal.
    pub theta0: f64,
}

impl NeoHooke<f64> {
    pub fn new(e: f64, nu: f64, rho: f64) -> Self {
        NeoHooke {
            elastic: Elastic { e, nu, rho },
            theta0: 293.15,
        }
    }
}

impl<D: Scalar> Model<D> for NeoHooke<D> {
    type With<E: Scalar> = NeoHooke<E>;

    fn map_params<E: Scalar>(&self, f: impl FnMut(&'static str, D) -> E) -> NeoHooke<E> {
        NeoHooke {
            elastic: self.elastic.map(f),
            theta0: self.theta0,
        }
    }

    fn param_names(&self) -> Vec<&'static str> {
        Elastic::<D>::NAMES.to_vec()
    }

    fn param(&self, name: &str) -> Option<D> {
        self.elastic.get(name)
    }

    fn density(&self) -> D {
        self.elastic.rho
    }

    fn p_wave_modulus(&self) -> D {
        self.elastic.p_wave_modulus()
    }

    fn initial_state(&self) -> State<D> {
        State::virgin(c(self.theta0))
    }

    fn update(
        &self,
        f: &M3<D>,
        _dt: f64,
        old: &State<D>,
    ) -> Result<(M3<D>, State<D>), MaterialError> {
        let j = det(f);
        if j.re() <= 0.0 || !j.re().is_finite() {
            return Err(MaterialError::InvertedDeformation { det_f: j.re() });
        }
        let tau = self.elastic.tau(f, c(0.0), c(0.0));
        Ok((tau / j, *old))
    }
}

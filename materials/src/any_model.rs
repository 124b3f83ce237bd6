//! A model chosen at run time (from a parameter file), still generic over the scalar.

use crate::error::MaterialError;
use crate::material::{Deliver, Keep, Model, RealUpdate, State};
use crate::neo_hooke::NeoHooke;
use crate::plasticity::ElastoPlastic;
use crate::scalar::Scalar;
use crate::tensor::M3;

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AnyModel<D = f64> {
    NeoHooke(NeoHooke<D>),
    ElastoPlastic(ElastoPlastic<D>),
}

macro_rules! each {
    ($self:expr, $m:ident => $body:expr) => {
        match $self {
            AnyModel::NeoHooke($m) => $body,
            AnyModel::ElastoPlastic($m) => $body,
        }
    };
}

impl<D: Scalar> Model<D> for AnyModel<D> {
    type With<E: Scalar> = AnyModel<E>;

    fn map_params<E: Scalar>(&self, f: impl FnMut(&'static str, D) -> E) -> AnyModel<E> {
        match self {
            AnyModel::NeoHooke(m) => AnyModel::NeoHooke(m.map_params(f)),
            AnyModel::ElastoPlastic(m) => AnyModel::ElastoPlastic(m.map_params(f)),
        }
    }
    fn param_names(&self) -> Vec<&'static str> {
        each!(self, m => m.param_names())
    }
    fn param(&self, name: &str) -> Option<D> {
        each!(self, m => m.param(name))
    }
    fn density(&self) -> D {
        each!(self, m => m.density())
    }
    fn p_wave_modulus(&self) -> D {
        each!(self, m => m.p_wave_modulus())
    }
    fn initial_state(&self) -> State<D> {
        each!(self, m => m.initial_state())
    }
    fn update(
        &self,
        f: &M3<D>,
        dt: f64,
        old: &State<D>,
    ) -> Result<(M3<D>, State<D>), MaterialError> {
        each!(self, m => m.update(f, dt, old))
    }
    fn update_from_real(
        &self,
        f: &M3<D>,
        dt: f64,
        old: &State<D>,
        real: RealUpdate<'_>,
    ) -> Result<(M3<D>, State<D>), MaterialError> {
        each!(self, m => m.update_from_real(f, dt, old, real))
    }
    fn update_batch(&self, f: &[M3<D>], dt: f64, old: &[State<D>], deliver: &mut Deliver<D>) {
        each!(self, m => m.update_batch(f, dt, old, deliver))
    }
    fn update_batch_keeping(
        &self,
        f: &[M3<D>],
        dt: f64,
        old: &[State<D>],
        deliver: &mut Deliver<D>,
        keep: &mut Keep,
    ) {
        each!(self, m => m.update_batch_keeping(f, dt, old, deliver, keep))
    }
}

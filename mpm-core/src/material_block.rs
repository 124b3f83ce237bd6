//! A material block: one material model, the contiguous range of particles made of it and
//! their history variables `State { fp_inv, alpha, theta, dalpha }`, kept per block rather
//! than in a particle struct so that elastic and plastic bodies each store only what they
//! use (the history of every point of a block has the same layout).

use crate::shape::ShapeFunction;
use materials::{Material, State};
use std::ops::Range;
use std::sync::Arc;

#[derive(Clone)]
pub struct MaterialBlock {
    pub name: String,
    pub material: Arc<dyn Material>,
    /// Particles of this block (indices into `Particles`).
    pub range: Range<usize>,
    /// History of each particle of `range`, in the same order.
    pub state: Vec<State<f64>>,
    /// This body's shape functions; `None`: the scene's (`Settings::shape_function`).
    pub shape_function: Option<ShapeFunction>,
}

impl MaterialBlock {
    /// This body's shape functions, given the scene's.
    pub fn kernel(&self, scene: ShapeFunction) -> ShapeFunction {
        self.shape_function.unwrap_or(scene)
    }

    /// Dilatational wave speed c = √((Λ+2G)/ρ0) (eq. 7.23) [m/s].
    pub fn wave_speed(&self) -> f64 {
        wave_speed(&*self.material)
    }
}

/// Dilatational wave speed c = √((Λ+2G)/ρ0) of `material` (eq. 7.23) [m/s].
pub fn wave_speed(material: &dyn Material) -> f64 {
    (material.p_wave_modulus() / material.density()).sqrt()
}

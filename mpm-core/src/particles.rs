//! Material points as a structure of arrays (table 7.2): one `Vec` per property, so that
//! every loop touches only the data it needs. Material history (F^p⁻¹, α, θ) lives in the
//! `MaterialBlock` that owns a contiguous range of particles (which is also what says
//! which body a point belongs to: nothing here repeats it).
//!
//! Units: position x and reference position X [m], velocity v [m/s], mass m [kg], volume
//! V (current) and V0 (reference) [m³] (plane strain: per metre of thickness; axisymmetric:
//! the full ring 2π r A), Cauchy stress σ [Pa], external force [N].

use crate::shape::Hex;
use nalgebra::{Matrix3, SVector};

#[derive(Debug, Clone, Default)]
pub struct Particles<const D: usize> {
    pub position: Vec<SVector<f64, D>>,
    pub reference_position: Vec<SVector<f64, D>>,
    pub velocity: Vec<SVector<f64, D>>,
    pub mass: Vec<f64>,
    pub volume0: Vec<f64>,
    pub volume: Vec<f64>,
    /// Deformation gradient F (3×3 in every kinematics).
    pub deformation: Vec<Matrix3<f64>>,
    /// Cauchy stress σ.
    pub stress: Vec<Matrix3<f64>>,
    /// Constant applied force, e.g. the traction equivalent of eq. 7.31 / 8.3 [N].
    pub applied_force: Vec<SVector<f64, D>>,
    /// Half-widths a_i of the point's box-shaped domain in the reference configuration
    /// [m] (the domain vectors of CPDI, eq. 10.4, are F a_i e_i); zero for a point whose
    /// domain is not given. Contact uses it: a rigid surface touches the domain, not the
    /// centre (module `contact`).
    pub half_size: Vec<SVector<f64, D>>,
    /// Reference hexahedral domains of the `cpdi-hex` kernel (module `shape::hex`): empty
    /// unless a body gave them or that kernel runs, then one per point (`Hex::none()` for
    /// a point that `Solver::initialize` gives its box).
    pub hex: Vec<Hex<D>>,
}

impl<const D: usize> Particles<D> {
    pub fn len(&self) -> usize {
        self.position.len()
    }

    pub fn is_empty(&self) -> bool {
        self.position.is_empty()
    }

    /// Append one particle at rest in the reference configuration.
    pub fn push(&mut self, x: SVector<f64, D>, v: SVector<f64, D>, volume: f64, density: f64) {
        self.position.push(x);
        self.reference_position.push(x);
        self.velocity.push(v);
        self.mass.push(volume * density);
        self.volume0.push(volume);
        self.volume.push(volume);
        self.deformation.push(Matrix3::identity());
        self.stress.push(Matrix3::zeros());
        self.applied_force.push(SVector::zeros());
        self.half_size.push(SVector::zeros());
        if !self.hex.is_empty() {
            self.hex.push(Hex::none());
        }
    }

    /// Bytes of particle storage per particle (excluding material history and solver
    /// scratch).
    pub const BYTES_PER_PARTICLE: usize = 5 * std::mem::size_of::<SVector<f64, D>>()
        + 3 * std::mem::size_of::<f64>()
        + 2 * std::mem::size_of::<Matrix3<f64>>();
}

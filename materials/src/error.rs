//! Errors of a material update.

use thiserror::Error;

#[derive(Debug, Clone, Error, PartialEq)]
pub enum MaterialError {
    #[error("det F = {det_f:e} <= 0: the deformation gradient is inverted")]
    InvertedDeformation { det_f: f64 },
    #[error("local return mapping did not converge after {iterations} iterations (residual {residual:e})")]
    ReturnMapNotConverged { iterations: usize, residual: f64 },
    #[error("non-finite value in {what}")]
    NonFinite { what: &'static str },
    #[error("singular local Jacobian in {what}")]
    Singular { what: &'static str },
}

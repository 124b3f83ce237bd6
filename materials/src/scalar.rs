//! The scalar type every model is written in: `f64` for plain evaluation, a dual number
//! for derivatives (`dual::Dual`, or a `num-dual` type; DESIGN section 11).

use nalgebra::{ClosedAddAssign, ClosedDivAssign, ClosedMulAssign, ClosedSubAssign};
use num_dual::DualNum;

/// A real or dual scalar with `f64` as its primitive part, usable inside `nalgebra`
/// fixed-size matrices.
pub trait Scalar:
    DualNum<Primitive = f64>
    + nalgebra::Scalar
    + ClosedAddAssign
    + ClosedSubAssign
    + ClosedMulAssign
    + ClosedDivAssign
    + Copy
    + Send
    + Sync
{
}

impl<T> Scalar for T where
    T: DualNum<Primitive = f64>
        + nalgebra::Scalar
        + ClosedAddAssign
        + ClosedSubAssign
        + ClosedMulAssign
        + ClosedDivAssign
        + Copy
        + Send
        + Sync
{
}

/// The constant `x` as a scalar with zero derivative part.
#[inline]
pub fn c<D: Scalar>(x: f64) -> D {
    D::from(x)
}

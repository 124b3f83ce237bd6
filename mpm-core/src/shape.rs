//! Grid shape functions behind one interface, `Kernel`, and the one used today, linear
//! (bi-/trilinear, appendix E, eq. E.4-E.7).
//!
//! A kernel states its support as part of its type: a point reaches `SUPPORT` nodes per
//! axis, starting `PAD` nodes below the lower corner of its cell. The grid padding and the
//! slab width of the lock-free parallel scatter are derived from these, so a wider kernel
//! (GIMP, CPDI) changes neither. Weights and gradients are evaluated once per particle and
//! step into a `WeightCache` and read by every transfer of that step.
//!
//! Linear: for a point at local cell coordinates ξ_i = (x_i − x_i^min)/h_i ∈ [0, 1) the
//! factors are a_0 = 1 − ξ, a_1 = ξ (eq. E.5) and their derivatives ∓1/h_i (eq. E.7).
//! Corner `k` of the cell takes factor a_{bit_i(k)} in direction i, so
//! N_k = Π_i a_{bit_i(k)} and ∂N_k/∂x_j = da_{bit_j(k)} Π_{i≠j} a_{bit_i(k)}. The corner
//! order is binary (x fastest), which differs from the right-hand order of figure E.3 only
//! in labelling.

use nalgebra::SVector;

/// Number of cell corners in `D` dimensions, 2^D.
pub const fn corners(d: usize) -> usize {
    1 << d
}

/// Shape function values and gradients [1/m] at one point for the 2^D corners of its cell
/// (arrays sized for D ≤ 3; entries beyond 2^D are unused).
#[derive(Debug, Clone, Copy)]
pub struct CellWeights<const D: usize> {
    pub n: [f64; 8],
    pub grad: [SVector<f64, D>; 8],
}

/// Values and gradients for local coordinates `xi` ∈ [0, 1)^D in a cell of inverse
/// spacing `inv_h` [1/m].
#[inline]
pub fn linear<const D: usize>(xi: &SVector<f64, D>, inv_h: &SVector<f64, D>) -> CellWeights<D> {
    let mut w = CellWeights {
        n: [0.0; 8],
        grad: [SVector::zeros(); 8],
    };
    for k in 0..corners(D) {
        let mut n = 1.0;
        let mut g = SVector::<f64, D>::repeat(1.0);
        for i in 0..D {
            let upper = (k >> i) & 1 == 1;
            let a = if upper { xi[i] } else { 1.0 - xi[i] };
            let da = if upper { inv_h[i] } else { -inv_h[i] };
            n *= a;
            for j in 0..D {
                g[j] *= if i == j { da } else { a };
            }
        }
        w.n[k] = n;
        w.grad[k] = g;
    }
    w
}

/// A shape function: which nodes a point reaches and with what weights.
pub trait Kernel<const D: usize> {
    /// Nodes a point reaches along each axis.
    const SUPPORT: usize;
    /// Nodes of the stencil below the lower corner of the point's cell, per axis, before
    /// the point's own shift.
    const PAD: usize;
    /// Largest shift of a point's stencil per axis (0: the stencil is fixed by the cell).
    const SHIFT: usize;
    /// Nodes of the stencil, SUPPORTᴰ.
    const NODES: usize;
    /// Weights N and gradients ∇N [1/m] of the stencil nodes (x fastest) for a point at
    /// local cell coordinates `xi` ∈ [0, 1)ᴰ with domain half-widths `half` [m] in cells
    /// of inverse size `inv_h` [1/m]; returns the stencil's shift per axis (its first node
    /// is PAD − shift nodes below the cell's lower corner).
    fn evaluate(
        xi: &SVector<f64, D>,
        half: &SVector<f64, D>,
        inv_h: &SVector<f64, D>,
        n: &mut [f64],
        grad: &mut [SVector<f64, D>],
    ) -> [usize; D];
}

/// The shape functions a model can choose.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ShapeFunction {
    /// Bi-/trilinear (classic MPM).
    #[default]
    Linear,
    /// Uniform GIMP with each point's reference domain (`Particles::half_size`).
    UGimp,
}

impl std::str::FromStr for ShapeFunction {
    type Err = String;

    /// The names of input files: `linear`, `ugimp`.
    fn from_str(name: &str) -> Result<Self, String> {
        match name {
            "linear" => Ok(ShapeFunction::Linear),
            "ugimp" => Ok(ShapeFunction::UGimp),
            other => Err(format!("\"{other}\", expected \"linear\" or \"ugimp\"")),
        }
    }
}

/// Bi-/trilinear shape functions (appendix E): the 2ᴰ corners of the point's cell.
pub struct Linear;

impl<const D: usize> Kernel<D> for Linear {
    const SUPPORT: usize = 2;
    const PAD: usize = 0;
    const SHIFT: usize = 0;
    const NODES: usize = corners(D);
    #[inline]
    fn evaluate(
        xi: &SVector<f64, D>,
        _half: &SVector<f64, D>,
        inv_h: &SVector<f64, D>,
        n: &mut [f64],
        grad: &mut [SVector<f64, D>],
    ) -> [usize; D] {
        let w = linear(xi, inv_h);
        n.copy_from_slice(&w.n[..corners(D)]);
        grad.copy_from_slice(&w.grad[..corners(D)]);
        [0; D]
    }
}

/// Uniform GIMP (Bardenhagen & Kober 2004, thesis eq. 10.1-10.3 with a fixed domain):
/// each point's weight is the hat function averaged over its box-shaped domain of
/// reference half-widths l_k (in cells, at most 1/2, kept through the run). Per axis,
/// with r the distance from the node in cells:
///
///   S = 1 − (r² + l²)/(2l)   for |r| < l,
///   S = 1 − |r|             for l ≤ |r| ≤ 1 − l,
///   S = (1 + l − |r|)²/(4l)  for 1 − l < |r| < 1 + l,
///
/// zero beyond; a point without a domain (l = 0) gets the hat itself, so classic MPM is
/// the point-GIMP case. The domain reaches the three nodes nearest to the point: from
/// the node below its cell's lower corner when ξ < 1/2, from the corner itself otherwise.
pub struct UGimp;

/// Weights and derivatives [per cell] of the three nodes from `shift − 1` (in cells from
/// the cell's lower corner) for a point at ξ with half-width `l` (cells).
#[inline]
fn gimp_1d(xi: f64, l: f64) -> (usize, [f64; 3], [f64; 3]) {
    let shift = usize::from(xi >= 0.5);
    let mut s = [0.0; 3];
    let mut ds = [0.0; 3];
    for m in 0..3 {
        let r = xi - (shift + m) as f64 + 1.0;
        let (a, sign) = (r.abs(), r.signum());
        (s[m], ds[m]) = if l <= 0.0 {
            if a < 1.0 {
                (1.0 - a, -sign)
            } else {
                (0.0, 0.0)
            }
        } else if a < l {
            (1.0 - (r * r + l * l) / (2.0 * l), -r / l)
        } else if a <= 1.0 - l {
            (1.0 - a, -sign)
        } else if a < 1.0 + l {
            let b = 1.0 + l - a;
            (b * b / (4.0 * l), -sign * b / (2.0 * l))
        } else {
            (0.0, 0.0)
        };
    }
    (shift, s, ds)
}

impl<const D: usize> Kernel<D> for UGimp {
    const SUPPORT: usize = 3;
    const PAD: usize = 1;
    const SHIFT: usize = 1;
    const NODES: usize = 3usize.pow(D as u32);
    #[inline]
    fn evaluate(
        xi: &SVector<f64, D>,
        half: &SVector<f64, D>,
        inv_h: &SVector<f64, D>,
        n: &mut [f64],
        grad: &mut [SVector<f64, D>],
    ) -> [usize; D] {
        let axes: [(usize, [f64; 3], [f64; 3]); D] =
            std::array::from_fn(|k| gimp_1d(xi[k], half[k] * inv_h[k]));
        for (node, (n, g)) in n.iter_mut().zip(grad.iter_mut()).enumerate() {
            let index: [usize; D] = std::array::from_fn(|k| node / 3usize.pow(k as u32) % 3);
            *n = (0..D).map(|k| axes[k].1[index[k]]).product();
            for j in 0..D {
                g[j] = inv_h[j]
                    * (0..D)
                        .map(|k| match k == j {
                            true => axes[k].2[index[k]],
                            false => axes[k].1[index[k]],
                        })
                        .product::<f64>();
            }
        }
        std::array::from_fn(|k| axes[k].0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn partition_of_unity_and_linear_completeness_in_3d() {
        let xi = Vector3::new(0.3, 0.7, 0.11);
        let inv_h = Vector3::new(2.0, 4.0, 0.5);
        let w = linear(&xi, &inv_h);
        let sum: f64 = w.n[..8].iter().sum();
        let grad_sum: Vector3<f64> = w.grad[..8].iter().sum();
        assert!((sum - 1.0).abs() < 1e-15);
        assert!(grad_sum.norm() < 1e-14);
        // reproduces the linear field x (in cell units): Σ N_k x_k = x and Σ ∇N_k x_k = e_i
        for i in 0..3 {
            let x: f64 = (0..8).map(|k| w.n[k] * ((k >> i) & 1) as f64).sum();
            assert!((x - xi[i]).abs() < 1e-15);
            let g: Vector3<f64> = (0..8)
                .map(|k| w.grad[k] * ((k >> i) & 1) as f64 / inv_h[i])
                .sum();
            assert!((g - Vector3::ith(i, 1.0)).norm() < 1e-14);
        }
    }

    /// uGIMP at random points and half-widths (2D and 3D): partition of unity, zero
    /// gradient sum, linear completeness, gradients against central differences of the
    /// weights, and the hat (linear) weights for a point without a domain.
    #[test]
    fn ugimp_weights_are_a_partition_of_unity_with_consistent_gradients() {
        fn check<const D: usize>(seed: u64) {
            let mut state = seed;
            let mut uniform = || {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (state >> 11) as f64 / (1u64 << 53) as f64
            };
            let inv_h = SVector::<f64, D>::from_fn(|k, _| 2.0 + k as f64);
            let nodes = <UGimp as Kernel<D>>::NODES;
            for _ in 0..200 {
                let xi = SVector::<f64, D>::from_fn(|_, _| uniform());
                let half = SVector::<f64, D>::from_fn(|k, _| 0.5 * uniform() / inv_h[k]);
                let (mut n, mut g) = (vec![0.0; nodes], vec![SVector::zeros(); nodes]);
                let shift = UGimp::evaluate(&xi, &half, &inv_h, &mut n, &mut g);
                let sum: f64 = n.iter().sum();
                let grad_sum: SVector<f64, D> = g.iter().sum();
                assert!((sum - 1.0).abs() < 1e-14, "{sum}");
                assert!(grad_sum.norm() < 1e-12 * inv_h.norm(), "{grad_sum}");
                // node coordinates in cells from the cell's lower corner
                let node =
                    |m: usize, k: usize| (m / 3usize.pow(k as u32) % 3 + shift[k]) as f64 - 1.0;
                for k in 0..D {
                    let x: f64 = (0..nodes).map(|m| n[m] * node(m, k)).sum();
                    assert!((x - xi[k]).abs() < 1e-14);
                }
                for j in 0..D {
                    let d = 1e-6;
                    let (mut up, mut down) = (xi, xi);
                    up[j] += d;
                    down[j] -= d;
                    let (mut nu, mut nd) = (vec![0.0; nodes], vec![0.0; nodes]);
                    let mut scratch = vec![SVector::zeros(); nodes];
                    let su = UGimp::evaluate(&up, &half, &inv_h, &mut nu, &mut scratch);
                    let sd = UGimp::evaluate(&down, &half, &inv_h, &mut nd, &mut scratch);
                    if su != shift || sd != shift {
                        continue; // the stencil moved: compare only within one stencil
                    }
                    for m in 0..nodes {
                        let fd = (nu[m] - nd[m]) / (2.0 * d) * inv_h[j];
                        assert!(
                            (fd - g[m][j]).abs() < 1e-6 * inv_h[j],
                            "{fd} vs {}",
                            g[m][j]
                        );
                    }
                }
                // no domain: the hat weights of the point's cell
                let mut n0 = vec![0.0; nodes];
                let mut g0 = vec![SVector::zeros(); nodes];
                let s0 = UGimp::evaluate(&xi, &SVector::zeros(), &inv_h, &mut n0, &mut g0);
                for (m, weight) in n0.iter().enumerate() {
                    let hat: f64 = (0..D)
                        .map(|k| {
                            let r = xi[k] - ((m / 3usize.pow(k as u32) % 3 + s0[k]) as f64 - 1.0);
                            (1.0 - r.abs()).max(0.0)
                        })
                        .product();
                    assert!((weight - hat).abs() < 1e-15);
                }
            }
        }
        check::<2>(3);
        check::<3>(5);
    }
}

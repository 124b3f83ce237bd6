//! CPDI1 on hexahedral (2D: quadrilateral) domains of any shape, the form the thesis runs
//! for hexahedral particle meshes (§10.1, reading §1.3): eq. 10.4 integrated numerically
//! over the isoparametric map x(ξ) = x_p + Σ_j Q̂^j(ξ) d^j of the domain's 2ᴰ vertex
//! offsets d^j, with the 2ᴰ-point Gauss rule (exact for both integrals on a trilinear map):
//!
//!   w_j = Σ_g Q̂^j(ξ_g) det J_g,   g_j = Σ_g J_g⁻ᵀ ∇_ξ Q̂^j(ξ_g) det J_g,   v = Σ_g det J_g,
//!   N^I = Σ_j (w_j / v) N^I(x^j),   ∇N^I = Σ_j (g_j / v) N^I(x^j).
//!
//! CPDI1 moves the vertices with the point's F, d^j = F d^j_0, so J = F J_0 at every ξ:
//! w_j / v is constant and g_j / v = F⁻ᵀ (g_j / v)_0. The quadrature is therefore done once,
//! on the reference domain (`Hex::new`), and a step costs what the closed form costs. For a
//! box it gives w_j / v = 2⁻ᴰ and g_j / v = 2⁻ᴰ diag(a)⁻¹ ξ^j, the closed form of module
//! `cpdi` (tested).
//!
//! Vertex j sits at ξ^j with ξ_k = +1 where bit k of j is set (x fastest; a mesh reader
//! reorders its elements' counter-clockwise corners to this).

use super::cpdi::{vertex_extent, vertex_nodes, vertex_weights, Vertex};
use super::{corners, Kernel, Point, Weights};
use nalgebra::{Matrix3, SMatrix, SVector};

/// A point's reference domain: vertex offsets from the point and the eq. 10.4 integrals
/// over the domain's volume (arrays sized for D ≤ 3; entries beyond 2ᴰ are unused).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hex<const D: usize> {
    /// d^j_0 = X^j − X_p [m].
    pub offset: [SVector<f64, D>; 8],
    /// w_j / v [-], summing to 1.
    pub weight: [f64; 8],
    /// g_j / v [1/m], summing to 0.
    pub grad: [SVector<f64, D>; 8],
    /// v [m^D].
    pub volume: f64,
}

/// A domain whose map is not one-to-one: det J ≤ 0 at a Gauss point (vertices in the wrong
/// order, or a face folded over).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("the domain's map folds over: det J = {det_j:.3e} at Gauss point {gauss} (vertices in the wrong order, or a concave element)")]
pub struct FoldedDomain {
    pub det_j: f64,
    pub gauss: usize,
}

impl<const D: usize> Hex<D> {
    /// No domain: the point gets the linear weights.
    pub fn none() -> Self {
        Hex {
            offset: [SVector::zeros(); 8],
            weight: [0.0; 8],
            grad: [SVector::zeros(); 8],
            volume: 0.0,
        }
    }

    /// The domain with vertices `vertices` [m] (2ᴰ, order of the module docs) and its
    /// centroid, where the point must sit: the weights reproduce linear fields about the
    /// centroid, Σ_I N^I x_I = Σ_j (w_j / v) x^j = ∫ x dv / v.
    pub fn new(vertices: &[SVector<f64, D>]) -> Result<(SVector<f64, D>, Self), FoldedDomain> {
        assert_eq!(
            vertices.len(),
            corners(D),
            "a {D}-D domain has 2^{D} vertices"
        );
        let mean = vertices.iter().sum::<SVector<f64, D>>() / corners(D) as f64;
        let mut hex = Hex::none();
        for (j, x) in vertices.iter().enumerate() {
            hex.offset[j] = x - mean;
        }
        let gauss = 1.0 / 3f64.sqrt();
        for g in 0..corners(D) {
            let xi = SVector::<f64, D>::from_fn(|k, _| sign(g, k) * gauss);
            let jac = SMatrix::<f64, D, D>::from_fn(|a, k| {
                (0..corners(D))
                    .map(|j| hex.offset[j][a] * q_hat_grad(j, &xi)[k])
                    .sum()
            });
            let det_j = determinant(&jac);
            let inv_t = match jac.try_inverse() {
                Some(inv) if det_j > 0.0 => inv.transpose(),
                _ => return Err(FoldedDomain { det_j, gauss: g }),
            };
            hex.volume += det_j;
            for j in 0..corners(D) {
                hex.weight[j] += q_hat(j, &xi) * det_j;
                hex.grad[j] += inv_t * q_hat_grad(j, &xi) * det_j;
            }
        }
        let mut shift = SVector::zeros();
        for j in 0..corners(D) {
            hex.weight[j] /= hex.volume;
            hex.grad[j] /= hex.volume;
            shift += hex.offset[j] * hex.weight[j];
        }
        for d in &mut hex.offset[..corners(D)] {
            *d -= shift;
        }
        Ok((mean + shift, hex))
    }

    /// The box of half-widths `half` [m] around the point (`none` for a zero width).
    pub fn boxed(half: &SVector<f64, D>) -> Self {
        if half.min() <= 0.0 {
            return Hex::none();
        }
        let vertices: Vec<_> = (0..corners(D))
            .map(|j| SVector::<f64, D>::from_fn(|k, _| sign(j, k) * half[k]))
            .collect();
        Hex::new(&vertices).expect("a box does not fold").1
    }

    /// The half-extents of the vertices about the point [m] (the box that holds them).
    pub fn half_extent(&self) -> SVector<f64, D> {
        vertex_extent(&self.offset[..corners(D)], &SVector::repeat(1.0))
    }

    /// Whether the point has a domain.
    pub fn is_none(&self) -> bool {
        self.volume == 0.0
    }
}

/// det of a D×D matrix, D ≤ 3 (as the 3×3 with the identity below it).
fn determinant<const D: usize>(m: &SMatrix<f64, D, D>) -> f64 {
    let mut embedded = Matrix3::identity();
    embedded.view_mut((0, 0), (D, D)).copy_from(m);
    embedded.determinant()
}

/// ξ_k of vertex (or Gauss point) j: ±1.
fn sign(j: usize, k: usize) -> f64 {
    if (j >> k) & 1 == 1 {
        1.0
    } else {
        -1.0
    }
}

/// Q̂^j(ξ) = Π_k (1 + ξ_k^j ξ_k) / 2.
fn q_hat<const D: usize>(j: usize, xi: &SVector<f64, D>) -> f64 {
    (0..D).map(|k| 0.5 * (1.0 + sign(j, k) * xi[k])).product()
}

/// ∇_ξ Q̂^j(ξ).
fn q_hat_grad<const D: usize>(j: usize, xi: &SVector<f64, D>) -> SVector<f64, D> {
    SVector::from_fn(|k, _| {
        (0..D)
            .map(|m| match m == k {
                true => 0.5 * sign(j, k),
                false => 0.5 * (1.0 + sign(j, m) * xi[m]),
            })
            .product()
    })
}

/// CPDI1 on the points' hexahedral domains (`Particles::hex`).
pub struct CpdiHex;

/// The in-plane block of F.
fn in_plane<const D: usize>(f: &Matrix3<f64>) -> SMatrix<f64, D, D> {
    SMatrix::from_fn(|i, k| f[(i, k)])
}

/// The current vertex offsets F d^j_0 [m].
fn current_offsets<const D: usize>(hex: &Hex<D>, f: &Matrix3<f64>) -> [SVector<f64, D>; 8] {
    let f = in_plane::<D>(f);
    hex.offset.map(|d| f * d)
}

impl<const D: usize> Kernel<D> for CpdiHex {
    const DOMAIN: bool = true;

    fn extent(p: &Point<'_, D>) -> SVector<f64, D> {
        match p.hex {
            Some(hex) => vertex_extent(&current_offsets(hex, p.f)[..corners(D)], p.inv_h),
            None => SVector::zeros(),
        }
    }

    fn nodes(e: &SVector<f64, D>) -> usize {
        vertex_nodes(e)
    }

    fn evaluate(p: &Point<'_, D>, out: &mut impl Weights<D>) {
        let f = in_plane::<D>(p.f);
        let (Some(hex), Some(f_inv)) = (p.hex.filter(|h| !h.is_none()), f.try_inverse()) else {
            return vertex_weights(p, &[], out);
        };
        let f_inv_t = f_inv.transpose();
        let vertices: [Vertex<D>; 8] =
            std::array::from_fn(|j| (f * hex.offset[j], hex.weight[j], f_inv_t * hex.grad[j]));
        vertex_weights(p, &vertices[..corners(D)], out)
    }
}

//! Eigen decomposition of a symmetric 3×3 matrix in closed form, exact at repeated
//! eigenvalues (the trial be of `plasticity::return_principal`, where two stretches often coincide):
//!
//! 1. B = (A − qI)/p with q = tr A/3 and p = √(tr (A − qI)²/6); the eigenvalues β of B solve
//!    β³ − 3β − 2r = 0 with r = det B/2 ∈ [−1, 1] (Smith 1961), so β ∈ [−2, 2].
//! 2. The root farthest from the other two has |β| ∈ [√3, 2] and the sign of r, with a gap
//!    of at least √3 to the others. Newton from ±2 finds it (monotone: the cubic is convex
//!    there), and its eigenvector is the longest cross product of two rows of B − βI.
//! 3. The other two eigenpairs are those of the 2×2 restriction of B to the plane normal to
//!    that eigenvector, diagonalized by one Jacobi rotation, which stays exact when the two
//!    coincide.
//!
//! The steps are those of D. Eberly, "A robust eigensolver for 3 × 3 symmetric matrices"
//! (Geometric Tools, 2014); about a quarter of the instructions of nalgebra's iterative
//! `SymmetricEigen` on the matrices of a plastic MPM step.
//!
//! A matrix whose out-of-plane entries are exactly zero (plane strain and axisymmetric
//! models, where F and Fp⁻¹ keep the z axis) has e_z as an eigenvector: only step 3 is
//! needed, on its x-y block, in a tenth of the instructions.

use nalgebra::{Matrix3, Vector3};

/// Eigenvalues and orthonormal eigenvectors (columns, in the same order), unsorted.
#[derive(Debug, Clone, Copy, Default)]
pub struct SymEigen {
    pub values: Vector3<f64>,
    pub vectors: Matrix3<f64>,
}

/// Newton steps on the cubic before giving up on a smaller step (it needs ≤ 7).
const MAX_CUBIC_STEPS: usize = 32;

impl SymEigen {
    /// The symmetric matrix Σ_a d_a v_a v_aᵀ with these eigenvectors and the values `d`
    /// (6 distinct entries; a third of the work of V diag(d) Vᵀ).
    pub fn with_values(&self, d: &Vector3<f64>) -> Matrix3<f64> {
        let v = &self.vectors;
        let entry = |i: usize, j: usize| {
            d[0] * v[(i, 0)] * v[(j, 0)]
                + d[1] * v[(i, 1)] * v[(j, 1)]
                + d[2] * v[(i, 2)] * v[(j, 2)]
        };
        let (xy, xz, yz) = (entry(0, 1), entry(0, 2), entry(1, 2));
        Matrix3::new(
            entry(0, 0),
            xy,
            xz,
            xy,
            entry(1, 1),
            yz,
            xz,
            yz,
            entry(2, 2),
        )
    }
}

/// Decompose the symmetric matrix `a` (only its symmetric part is used).
pub fn decompose(a: &Matrix3<f64>) -> SymEigen {
    if a[(0, 2)] == 0.0 && a[(1, 2)] == 0.0 && a[(2, 0)] == 0.0 && a[(2, 1)] == 0.0 {
        return decompose_plane(a);
    }
    let q = a.trace() / 3.0;
    let d = (a + a.transpose()) * 0.5 - Matrix3::identity() * q;
    let p = (d.norm_squared() / 6.0).sqrt();
    if p == 0.0 || !p.is_finite() {
        // A multiple of I (any basis), or a non-finite entry (NaN values pass it on).
        return SymEigen {
            values: Vector3::repeat(q + p),
            vectors: Matrix3::identity(),
        };
    }
    let b = d / p;
    let r = (0.5 * b.determinant()).clamp(-1.0, 1.0);
    let sign = if r >= 0.0 { 1.0 } else { -1.0 };
    let mut beta = 2.0f64;
    for _ in 0..MAX_CUBIC_STEPS {
        let step = (beta * (beta * beta - 3.0) - 2.0 * r.abs()) / (3.0 * (beta * beta - 1.0));
        beta -= step;
        if step <= 4.0 * f64::EPSILON {
            break;
        }
    }
    let beta = sign * beta;
    let v1 = null_vector(&(b - Matrix3::identity() * beta));
    // An orthonormal basis (u, w) of the plane normal to v1, and B restricted to it.
    let u = if v1.x.abs() > v1.y.abs() {
        Vector3::new(-v1.z, 0.0, v1.x) / v1.x.hypot(v1.z)
    } else {
        Vector3::new(0.0, v1.z, -v1.y) / v1.y.hypot(v1.z)
    };
    let w = v1.cross(&u);
    let (bu, bw) = (b * u, b * w);
    let rotation = Jacobi::new(u.dot(&bu), u.dot(&bw), w.dot(&bw));
    let (value_u, value_w) = rotation.values;
    let values = Vector3::new(beta, value_u, value_w) * p + Vector3::repeat(q);
    let (cos, sin) = (rotation.cos, rotation.sin);
    let vectors = Matrix3::from_columns(&[v1, u * cos - w * sin, u * sin + w * cos]);
    SymEigen { values, vectors }
}

/// The eigenpairs of a matrix with zero out-of-plane entries: (0, 0, 1) with a_zz, and
/// the rotated x and y axes with the eigenvalues of the x-y block.
fn decompose_plane(a: &Matrix3<f64>) -> SymEigen {
    let rotation = Jacobi::new(a[(0, 0)], 0.5 * (a[(0, 1)] + a[(1, 0)]), a[(1, 1)]);
    let (value_x, value_y) = rotation.values;
    let (cos, sin) = (rotation.cos, rotation.sin);
    SymEigen {
        values: Vector3::new(value_x, value_y, a[(2, 2)]),
        vectors: Matrix3::new(cos, sin, 0.0, -sin, cos, 0.0, 0.0, 0.0, 1.0),
    }
}

/// The Jacobi rotation by θ that diagonalizes the symmetric 2×2 matrix [[m_uu, m_uw],
/// [m_uw, m_ww]] in the basis (u, w): tan θ = t (t = 0 when already diagonal), rotated
/// axes u cos θ − w sin θ and u sin θ + w cos θ with eigenvalues m_uu − t m_uw and
/// m_ww + t m_uw, exact when the two coincide.
struct Jacobi {
    cos: f64,
    sin: f64,
    values: (f64, f64),
}

impl Jacobi {
    fn new(m_uu: f64, m_uw: f64, m_ww: f64) -> Self {
        let t = if m_uw == 0.0 {
            0.0
        } else {
            let cot_2theta = (m_ww - m_uu) / (2.0 * m_uw);
            cot_2theta.signum() / (cot_2theta.abs() + (1.0 + cot_2theta * cot_2theta).sqrt())
        };
        let cos = 1.0 / (1.0 + t * t).sqrt();
        Jacobi {
            cos,
            sin: t * cos,
            values: (m_uu - t * m_uw, m_ww + t * m_uw),
        }
    }
}

/// Unit vector spanning the null space of a rank-2 symmetric matrix `c`: the longest
/// cross product of two of its rows.
fn null_vector(c: &Matrix3<f64>) -> Vector3<f64> {
    let rows = [
        c.row(0).transpose(),
        c.row(1).transpose(),
        c.row(2).transpose(),
    ];
    let candidates = [
        rows[0].cross(&rows[1]),
        rows[0].cross(&rows[2]),
        rows[1].cross(&rows[2]),
    ];
    let longest = candidates
        .iter()
        .max_by(|x, y| x.norm_squared().total_cmp(&y.norm_squared()))
        .expect("three candidates");
    longest / longest.norm()
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Rotation3, SymmetricEigen};

    /// ‖A V − V Λ‖ and ‖VᵀV − I‖ relative to ‖A‖, and the sorted eigenvalues against
    /// nalgebra's iterative solver.
    fn check(a: &Matrix3<f64>, tol: f64) {
        let e = decompose(a);
        let scale = a.norm();
        let residual = (a * e.vectors - e.vectors * Matrix3::from_diagonal(&e.values)).norm();
        assert!(residual <= tol * scale, "residual {residual:e} for {a}");
        let orthogonality = (e.vectors.transpose() * e.vectors - Matrix3::identity()).norm();
        assert!(
            orthogonality <= tol,
            "orthogonality {orthogonality:e} for {a}"
        );
        let mut ours: Vec<f64> = e.values.iter().copied().collect();
        let mut theirs: Vec<f64> = SymmetricEigen::new(*a)
            .eigenvalues
            .iter()
            .copied()
            .collect();
        ours.sort_by(f64::total_cmp);
        theirs.sort_by(f64::total_cmp);
        for (x, y) in ours.iter().zip(&theirs) {
            assert!(
                (x - y).abs() <= tol * scale,
                "eigenvalues {ours:?} vs {theirs:?}"
            );
        }
    }

    /// `with_values` equals V diag(d) Vᵀ and gives back the decomposed matrix.
    #[test]
    fn with_values_recomposes() {
        let a = rotated([3.0, -1.0, 0.5], [0.3, -1.1, 0.7]);
        let e = decompose(&a);
        assert!((e.with_values(&e.values) - a).norm() < 1e-14 * a.norm());
        let d = Vector3::new(0.2, 7.0, -3.0);
        let full = e.vectors * Matrix3::from_diagonal(&d) * e.vectors.transpose();
        assert!((e.with_values(&d) - full).norm() < 1e-14 * full.norm());
    }

    fn rotated(diagonal: [f64; 3], axis_angle: [f64; 3]) -> Matrix3<f64> {
        let rot = Rotation3::new(Vector3::from(axis_angle)).into_inner();
        rot * Matrix3::from_diagonal(&Vector3::from(diagonal)) * rot.transpose()
    }

    #[test]
    fn distinct_repeated_and_nearly_repeated_eigenvalues() {
        let rotations = [
            [0.0, 0.0, 0.0],
            [0.3, -1.1, 0.7],
            [2.0, 0.1, -0.4],
            [1e-9, 0.0, 0.0],
        ];
        let spectra = [
            [1.0, 2.0, 3.0],
            [1.0, 1.0, 2.0],
            [2.0, 1.0, 1.0],
            [1.0, 1.0, 1.0],
            [1.0, 1.0 + 1e-12, 1.3],
            [1.0 - 2e-3, 1.0 + 1e-3, 1.0 + 1e-3 + 1e-14],
            [0.7, 1.0, 1.9],
            [-5.0, 0.0, 5.0],
            [1e-8, 1.0, 1e8],
        ];
        for rotation in rotations {
            for spectrum in spectra {
                check(&rotated(spectrum, rotation), 1e-14);
            }
        }
    }

    /// Plane matrices (zero out-of-plane entries) take the block path: e_z is an
    /// eigenvector with a_zz, and the block's pairs are exact, also repeated ones.
    #[test]
    fn plane_matrices() {
        for (spectrum, angle) in [
            ([1.0, 2.0, 3.0], 0.3),
            ([1.0, 1.0, 2.0], 1.1),
            ([2.0, 1.0, 2.0], -0.7),
            ([1.0, 1.0 + 1e-12, 1.3], 0.2),
            ([0.99, 1.01, 1.0], 0.0),
            ([1e-8, 1e8, 1.0], 2.0),
        ] {
            let a = rotated(spectrum, [0.0, 0.0, angle]);
            let a = Matrix3::from_fn(|i, j| if (i == 2) != (j == 2) { 0.0 } else { a[(i, j)] });
            check(&a, 1e-15);
            let e = decompose(&a);
            assert_eq!(e.vectors.column(2).into_owned(), Vector3::z(), "{a}");
            assert_eq!(e.values[2], spectrum[2]);
        }
    }

    #[test]
    fn pseudo_random_symmetric_matrices() {
        // A fixed linear congruential sequence: the same matrices on every run.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for _ in 0..2000 {
            let m = Matrix3::from_fn(|_, _| next());
            check(&(m + m.transpose()), 1e-14);
        }
    }
}

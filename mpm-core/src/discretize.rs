//! Bodies from primitives: material points on a regular sub-lattice of the grid, one at
//! the centre of each sub-cell whose centre lies inside the shape (the sub-grid strategy
//! of section 8.4). A sub-cell of size s carries the volume Π s_i (plane strain: per metre
//! of thickness) or, axisymmetric, the ring 2π r s_r s_z.

use crate::kinematics::Kinematics;
use nalgebra::SVector;

/// A solid primitive. `Ball` is a disk in 2D and a sphere in 3D; `Cylinder` (3D) runs
/// from `start` to `end`; `Polygon` (2D) is any simple polygon.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape<const D: usize> {
    Box {
        min: SVector<f64, D>,
        max: SVector<f64, D>,
    },
    Ball {
        center: SVector<f64, D>,
        radius: f64,
    },
    Cylinder {
        start: SVector<f64, D>,
        end: SVector<f64, D>,
        radius: f64,
    },
    Polygon {
        vertices: Vec<SVector<f64, D>>,
    },
}

impl<const D: usize> Shape<D> {
    pub fn contains(&self, x: &SVector<f64, D>) -> bool {
        match self {
            Shape::Box { min, max } => (0..D).all(|i| x[i] >= min[i] && x[i] <= max[i]),
            Shape::Ball { center, radius } => (x - center).norm() <= *radius,
            Shape::Cylinder { start, end, radius } => {
                let axis = end - start;
                let s = (x - start).dot(&axis) / axis.norm_squared();
                (0.0..=1.0).contains(&s) && (x - start - axis * s).norm() <= *radius
            }
            Shape::Polygon { vertices } => {
                // even-odd ray casting in the first two coordinates
                let mut inside = false;
                let n = vertices.len();
                for k in 0..n {
                    let (a, b) = (vertices[k], vertices[(k + n - 1) % n]);
                    if (a[1] > x[1]) != (b[1] > x[1])
                        && x[0] < (b[0] - a[0]) * (x[1] - a[1]) / (b[1] - a[1]) + a[0]
                    {
                        inside = !inside;
                    }
                }
                inside
            }
        }
    }

    /// Axis-aligned bounding box.
    pub fn bounds(&self) -> (SVector<f64, D>, SVector<f64, D>) {
        match self {
            Shape::Box { min, max } => (*min, *max),
            Shape::Ball { center, radius } => {
                (center.add_scalar(-radius), center.add_scalar(*radius))
            }
            Shape::Cylinder { start, end, radius } => (
                start.inf(end).add_scalar(-radius),
                start.sup(end).add_scalar(*radius),
            ),
            Shape::Polygon { vertices } => vertices.iter().fold(
                (
                    SVector::repeat(f64::INFINITY),
                    SVector::repeat(f64::NEG_INFINITY),
                ),
                |(lo, hi), v| (lo.inf(v), hi.sup(v)),
            ),
        }
    }
}

/// Material points (position, volume) filling `shape` on the lattice of sub-cells of size
/// `spacing` anchored at `origin`.
pub fn fill<const D: usize>(
    shape: &Shape<D>,
    spacing: SVector<f64, D>,
    origin: SVector<f64, D>,
    kinematics: Kinematics,
) -> Vec<(SVector<f64, D>, f64)> {
    let (lo, hi) = shape.bounds();
    let first: [i64; D] =
        std::array::from_fn(|i| ((lo[i] - origin[i]) / spacing[i] - 0.5).floor() as i64);
    let count: [i64; D] = std::array::from_fn(|i| {
        ((hi[i] - origin[i]) / spacing[i] - 0.5).ceil() as i64 - first[i] + 1
    });
    let cell = spacing.product();
    let mut out = Vec::new();
    let total: i64 = count.iter().product();
    for flat in 0..total {
        let mut rem = flat;
        let x = SVector::<f64, D>::from_fn(|i, _| {
            let k = first[i] + rem % count[i];
            rem /= count[i];
            origin[i] + (k as f64 + 0.5) * spacing[i]
        });
        if shape.contains(&x) {
            let volume = match kinematics {
                Kinematics::Axisymmetric => 2.0 * std::f64::consts::PI * x[0] * cell,
                _ => cell,
            };
            out.push((x, volume));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Vector2, Vector3};

    #[test]
    fn filled_volumes_approach_the_shape_volumes() {
        let s = 0.01;
        let ball = fill(
            &Shape::Ball {
                center: Vector3::new(0.3, 0.3, 0.3),
                radius: 0.2,
            },
            Vector3::repeat(s),
            Vector3::zeros(),
            Kinematics::Solid,
        );
        let v: f64 = ball.iter().map(|p| p.1).sum();
        let exact = 4.0 / 3.0 * std::f64::consts::PI * 0.2f64.powi(3);
        assert!((v / exact - 1.0).abs() < 0.01, "sphere {v} vs {exact}");
        // axisymmetric cylinder r ≤ 0.1, 0 ≤ z ≤ 0.3 as a box in (r, z)
        let cyl = fill(
            &Shape::Box {
                min: Vector2::new(0.0, 0.0),
                max: Vector2::new(0.1, 0.3),
            },
            Vector2::repeat(s),
            Vector2::zeros(),
            Kinematics::Axisymmetric,
        );
        let v: f64 = cyl.iter().map(|p| p.1).sum();
        let exact = std::f64::consts::PI * 0.01 * 0.3;
        assert!((v / exact - 1.0).abs() < 1e-12, "cylinder {v} vs {exact}");
        let tri = fill(
            &Shape::Polygon {
                vertices: vec![
                    Vector2::new(0.0, 0.0),
                    Vector2::new(1.0, 0.0),
                    Vector2::new(0.0, 1.0),
                ],
            },
            Vector2::repeat(s),
            Vector2::zeros(),
            Kinematics::PlaneStrain,
        );
        let v: f64 = tri.iter().map(|p| p.1).sum();
        assert!((v - 0.5).abs() < 0.01, "triangle {v}");
    }
}

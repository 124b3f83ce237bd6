//! Rigid bodies with prescribed motion (section 9.3): half-spaces and convex bodies given
//! by their bounding planes (a convex polygon in 2D, a convex triangulated surface in 3D,
//! one plane per edge or triangle).
//!
//! Geometry is stated in the reference (t = 0) frame. At time t a body point X is at
//! x = c + u(t) + R(t) (X − c), with u(t) a piecewise-linear translation signal, R(t) a
//! rotation by the piecewise-linear angle φ(t) about a fixed axis through c (in 2D the
//! axis is z); a face on an elastic bar adds its displacement along the bar axis, which
//! the contact force drives (module `bar`). A point is inside when every plane has n·(X − p) < 0 (outward normals n);
//! for an interior point the closest surface point is on the plane of largest signed
//! distance d: X_C = X − d n.

use crate::bar::BarEnd;
use materials::scalar::c;
use materials::signal::TimeSignal;
use materials::Scalar;
use nalgebra::{Rotation3, SMatrix, SVector, Unit, Vector3};

/// A bounding plane: a point on it and its outward unit normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane<const D: usize> {
    pub point: SVector<f64, D>,
    pub normal: SVector<f64, D>,
}

/// Rotation about a fixed axis through `center` by the angle table [rad].
#[derive(Debug, Clone, PartialEq)]
pub struct Rotation {
    pub center: Vector3<f64>,
    pub axis: Unit<Vector3<f64>>,
    pub angle: TimeSignal<f64>,
}

/// Rigid motion: prescribed translation and rotation, and the displacement of a face
/// driven by an elastic bar (module `bar`), which follows the contact force.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Motion<const D: usize> {
    pub translation: Option<TimeSignal<SVector<f64, D>>>,
    pub rotation: Option<Rotation>,
    pub bar: Option<BarEnd<D>>,
}

/// Placement of a body at one instant: x = c + u + R (X − c).
#[derive(Debug, Clone, Copy)]
pub struct Pose<const D: usize> {
    pub center: SVector<f64, D>,
    pub translation: SVector<f64, D>,
    pub rotation: SMatrix<f64, D, D>,
}

impl<const D: usize> Pose<D> {
    /// World position of the body point `x_body` (real, or with derivatives).
    pub fn to_world<T: Scalar>(&self, x_body: &SVector<T, D>) -> SVector<T, D> {
        let center = self.center.map(c::<T>);
        center.clone()
            + self.translation.map(c::<T>)
            + self.rotation.map(c::<T>) * (x_body - center)
    }
    /// Body-frame position of the world point `x` (real, or with derivatives).
    pub fn to_body<T: Scalar>(&self, x: &SVector<T, D>) -> SVector<T, D> {
        let center = self.center.map(c::<T>);
        center.clone()
            + self.rotation.transpose().map(c::<T>) * (x - center - self.translation.map(c::<T>))
    }
}

impl<const D: usize> Motion<D> {
    pub fn pose(&self, t: f64) -> Pose<D> {
        let translation = self
            .translation
            .as_ref()
            .map_or(SVector::zeros(), |u| u.at(t))
            + self
                .bar
                .as_ref()
                .map_or(SVector::zeros(), |b| b.axis * b.displacement);
        match &self.rotation {
            None => Pose {
                center: SVector::zeros(),
                translation,
                rotation: SMatrix::identity(),
            },
            Some(r) => {
                let r3 = Rotation3::from_axis_angle(&r.axis, r.angle.at(t));
                Pose {
                    center: SVector::from_fn(|i, _| r.center[i]),
                    translation,
                    rotation: SMatrix::from_fn(|i, j| r3[(i, j)]),
                }
            }
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct RigidBody<const D: usize> {
    pub name: String,
    pub planes: Vec<Plane<D>>,
    pub motion: Motion<D>,
    /// Penalty stiffness κ_pen [kg/s²] (eq. 9.4), or, with `penalty_per_mass`, the
    /// squared contact frequency ω_c² [1/s²] with κ = ω_c² m_p for a point of mass m_p.
    pub penalty: f64,
    /// κ proportional to the point's mass: every point in contact oscillates at the same
    /// ω_c, so light points (the rings near the axis of an axisymmetric model, cut rim
    /// points) neither set Δt nor carry a pressure out of proportion to their area.
    pub penalty_per_mass: bool,
    /// Coulomb friction coefficient μ [-] (eq. 9.3).
    pub friction: f64,
    /// Steps between coarse proximity searches.
    pub search_interval: usize,
    /// Bounding sphere (centre, radius) in the body frame for the coarse search; `None`
    /// for an unbounded body (half-space).
    pub bounds: Option<(SVector<f64, D>, f64)>,
}

impl<const D: usize> RigidBody<D> {
    /// Penalty stiffness κ [N/m] on a point of mass `mass` [kg].
    #[inline]
    pub fn penalty_of(&self, mass: f64) -> f64 {
        match self.penalty_per_mass {
            true => self.penalty * mass,
            false => self.penalty,
        }
    }

    /// The half-space below the plane through `point` with outward normal `normal`.
    pub fn half_space(
        name: &str,
        point: SVector<f64, D>,
        normal: SVector<f64, D>,
        penalty: f64,
        friction: f64,
    ) -> Self {
        RigidBody {
            name: name.into(),
            planes: vec![Plane {
                point,
                normal: normal.normalize(),
            }],
            motion: Motion::default(),
            penalty,
            penalty_per_mass: false,
            friction,
            search_interval: 10,
            bounds: None,
        }
    }

    /// An axis-aligned box [min, max] as a convex body.
    pub fn boxed(
        name: &str,
        min: SVector<f64, D>,
        max: SVector<f64, D>,
        penalty: f64,
        friction: f64,
    ) -> Self {
        let mut planes = Vec::new();
        for i in 0..D {
            let e = SVector::<f64, D>::from_fn(|k, _| if k == i { 1.0 } else { 0.0 });
            planes.push(Plane {
                point: min,
                normal: -e,
            });
            planes.push(Plane {
                point: max,
                normal: e,
            });
        }
        let bounds = Some(((min + max) / 2.0, (max - min).norm() / 2.0));
        RigidBody {
            name: name.into(),
            planes,
            motion: Motion::default(),
            penalty,
            penalty_per_mass: false,
            friction,
            search_interval: 10,
            bounds,
        }
    }

    /// Signed distance to the nearest bounding plane and that plane (body frame): the
    /// point is inside if the distance is negative.
    #[inline]
    pub fn nearest_plane<T: Scalar>(&self, x_body: &SVector<T, D>) -> (T, &Plane<D>) {
        let mut best = (c::<T>(f64::NEG_INFINITY), &self.planes[0]);
        for p in &self.planes {
            let d = p.normal.map(c::<T>).dot(&(x_body - p.point.map(c::<T>)));
            if d.re() > best.0.re() {
                best = (d, p);
            }
        }
        best
    }
}

/// Centre and radius of a sphere holding all `vertices`.
/// The face plane through `point` with normal ±`normal` pointing away from `centroid`.
fn outward<const D: usize>(
    point: SVector<f64, D>,
    normal: SVector<f64, D>,
    centroid: &SVector<f64, D>,
) -> Plane<D> {
    let n = normal.normalize();
    let normal = if n.dot(&(point - centroid)) < 0.0 {
        -n
    } else {
        n
    };
    Plane { point, normal }
}

/// A convex body from its face planes, bounded by the sphere around its vertices.
fn convex<const D: usize>(
    name: &str,
    planes: Vec<Plane<D>>,
    vertices: &[SVector<f64, D>],
    penalty: f64,
    friction: f64,
) -> RigidBody<D> {
    RigidBody {
        name: name.into(),
        planes,
        motion: Motion::default(),
        penalty,
        penalty_per_mass: false,
        friction,
        search_interval: 10,
        bounds: Some(sphere_around(vertices)),
    }
}

fn sphere_around<const D: usize>(vertices: &[SVector<f64, D>]) -> (SVector<f64, D>, f64) {
    let c = vertices.iter().sum::<SVector<f64, D>>() / vertices.len() as f64;
    let r = vertices.iter().map(|v| (v - c).norm()).fold(0.0, f64::max);
    (c, r)
}

/// A convex body from a closed triangulated surface (3D): one plane per triangle with the
/// outward normal pointing away from the vertex centroid.
pub fn convex_from_triangles(
    name: &str,
    vertices: &[Vector3<f64>],
    triangles: &[[usize; 3]],
    penalty: f64,
    friction: f64,
) -> RigidBody<3> {
    let centroid = vertices.iter().sum::<Vector3<f64>>() / vertices.len() as f64;
    let planes = triangles
        .iter()
        .map(|t| {
            let (a, b, c) = (vertices[t[0]], vertices[t[1]], vertices[t[2]]);
            outward(a, (b - a).cross(&(c - a)), &centroid)
        })
        .collect();
    convex(name, planes, vertices, penalty, friction)
}

/// A convex polygon (2D), vertices in either orientation: one plane per edge.
pub fn convex_from_polygon(
    name: &str,
    vertices: &[SVector<f64, 2>],
    penalty: f64,
    friction: f64,
) -> RigidBody<2> {
    let centroid = vertices.iter().sum::<SVector<f64, 2>>() / vertices.len() as f64;
    let planes = (0..vertices.len())
        .map(|i| {
            let (a, b) = (vertices[i], vertices[(i + 1) % vertices.len()]);
            outward(
                a,
                SVector::<f64, 2>::new(b[1] - a[1], a[0] - b[0]),
                &centroid,
            )
        })
        .collect();
    convex(name, planes, vertices, penalty, friction)
}

/// The same body typed for dimension `E` (a scene knows its dimension only at run time;
/// panics unless D = E).
pub fn recast<const D: usize, const E: usize>(body: RigidBody<D>) -> RigidBody<E> {
    assert_eq!(D, E, "rigid body of dimension {D} used in a {E}D scene");
    let v = |x: &SVector<f64, D>| SVector::<f64, E>::from_column_slice(x.as_slice());
    RigidBody {
        name: body.name,
        planes: body
            .planes
            .iter()
            .map(|p| Plane {
                point: v(&p.point),
                normal: v(&p.normal),
            })
            .collect(),
        motion: Motion::default(),
        penalty: body.penalty,
        penalty_per_mass: body.penalty_per_mass,
        friction: body.friction,
        search_interval: body.search_interval,
        bounds: body.bounds.map(|(c, r)| (v(&c), r)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    #[test]
    fn rotating_box_maps_points_between_frames() {
        let mut b = RigidBody::<2>::boxed(
            "b",
            Vector2::new(-1.0, -1.0),
            Vector2::new(1.0, 1.0),
            1.0,
            0.0,
        );
        b.motion.rotation = Some(Rotation {
            center: Vector3::zeros(),
            axis: Vector3::z_axis(),
            angle: TimeSignal::new(vec![0.0, 1.0], vec![0.0, std::f64::consts::FRAC_PI_2]).unwrap(),
        });
        let pose = b.motion.pose(1.0);
        let x = pose.to_world(&Vector2::<f64>::new(1.0, 0.0));
        assert!((x - Vector2::new(0.0, 1.0)).norm() < 1e-14);
        let (d, p) = b.nearest_plane(&pose.to_body(&Vector2::<f64>::new(0.0, 0.9)));
        assert!((d + 0.1).abs() < 1e-14);
        assert!((p.normal - Vector2::new(1.0, 0.0)).norm() < 1e-14);
    }
}

//! Penalty contact with Coulomb friction between material points and rigid bodies
//! (section 9.3, algorithm 13, eq. 9.3-9.7).
//!
//! A penetrating point is pulled towards its attachment point X_A by f = κ (X_A − X_MP)
//! (eq. 9.4). X_A starts at the closest point projection X_C and moves with the body. If
//! the trial force leaves the friction cone f·t ≤ μ f·n (eq. 9.3, n and t from eq. 9.5),
//! X_A slides towards X_C by ξ̂ (X_C − X_A) with
//! ξ̂ = −(X_A − X_MP)·(t − μn) / ((X_C − X_A)·(t − μn)) (eq. 9.6-9.7).
//!
//! Search is hierarchical: every `search_interval` steps a coarse proximity check picks
//! candidate particles (bounding sphere or plane distance within a margin that covers the
//! motion until the next search); every step the exact inside test runs on the candidates.

use crate::bar::ContactSprings;
use crate::rigid::{Pose, RigidBody};
use materials::scalar::c;
use materials::Scalar;
use nalgebra::{Matrix3, SVector};

/// Algorithm 13 (body frame): penalty force on a point at `x_mp` whose closest surface
/// point is `x_c`, updating the attachment point `x_a` [N]. Real, or with derivatives:
/// the branches (stick or slip) follow the real parts.
#[inline]
pub fn penalty_force<T: Scalar, const D: usize>(
    x_mp: &SVector<T, D>,
    x_c: &SVector<T, D>,
    x_a: &mut SVector<T, D>,
    kappa: f64,
    mu: f64,
) -> SVector<T, D> {
    let (kappa, mu_t) = (c::<T>(kappa), c::<T>(mu));
    if mu == 0.0 {
        // frictionless: the attachment is the projection itself, whatever the slip
        *x_a = x_c.clone();
        return (x_c - x_mp) * kappa;
    }
    let trial = (x_a.clone() - x_mp) * kappa.clone();
    let slip = x_a.clone() - x_c;
    let depth = x_c - x_mp;
    let (slip_norm, depth_norm) = (norm_re(&slip), norm_re(&depth));
    if slip_norm <= 1e-12 * depth_norm.max(f64::MIN_POSITIVE) || depth_norm == 0.0 {
        return trial;
    }
    let n = unit(depth);
    let t = unit(slip);
    if trial.dot(&t).re() > mu * trial.dot(&n).re() {
        let m = t - n * mu_t;
        let xi = -(x_a.clone() - x_mp).dot(&m) / (x_c - x_a.clone()).dot(&m);
        *x_a += (x_c - x_a.clone()) * xi;
        (x_a.clone() - x_mp) * kappa
    } else {
        trial
    }
}

/// Euclidean norm of the real parts of `v`.
#[inline]
fn norm_re<T: Scalar, const D: usize>(v: &SVector<T, D>) -> f64 {
    v.map(|x| x.re()).norm()
}

/// `v` / |v| (real, or with derivatives).
#[inline]
fn unit<T: Scalar, const D: usize>(v: SVector<T, D>) -> SVector<T, D> {
    let length = v.dot(&v).sqrt();
    v / length
}

/// Contact bookkeeping of one rigid body.
#[derive(Debug, Clone)]
pub struct ContactState<const D: usize> {
    /// Particles found by the last coarse search, ascending.
    pub candidates: Vec<usize>,
    /// Attachment point (body frame) of each candidate in contact.
    pub attachment: Vec<Option<SVector<f64, D>>>,
    /// Total contact force on the rigid body at the current step (world frame) [N].
    pub force: SVector<f64, D>,
    /// Number of particles in contact at the current step.
    pub active: usize,
    /// The penalty springs of the points in contact along a bar-driven face's axis
    /// (module `bar`); default for other bodies.
    pub springs: ContactSprings,
}

impl<const D: usize> Default for ContactState<D> {
    fn default() -> Self {
        ContactState {
            candidates: Vec::new(),
            attachment: Vec::new(),
            force: SVector::zeros(),
            active: 0,
            springs: ContactSprings::default(),
        }
    }
}

impl<const D: usize> ContactState<D> {
    /// Replace the candidate list, keeping the attachment of particles still listed.
    pub fn set_candidates(&mut self, candidates: Vec<usize>) {
        let mut attachment = vec![None; candidates.len()];
        let mut j = 0;
        for (k, &p) in candidates.iter().enumerate() {
            while j < self.candidates.len() && self.candidates[j] < p {
                j += 1;
            }
            if j < self.candidates.len() && self.candidates[j] == p {
                attachment[k] = self.attachment[j];
            }
        }
        self.candidates = candidates;
        self.attachment = attachment;
    }
}

/// A candidate point: its centre x [m], mass [kg], deformation gradient F and reference
/// domain half-widths a [m]; x and F real, or with derivatives.
#[derive(Clone, Copy)]
pub struct Candidate<'a, T: Scalar, const D: usize> {
    pub x: &'a SVector<T, D>,
    pub mass: f64,
    pub f: &'a Matrix3<T>,
    pub half_size: &'a SVector<f64, D>,
}

impl<T: Scalar, const D: usize> Candidate<'_, T, D> {
    /// How far the point's current domain F·box(a) reaches from its centre along the unit
    /// vector `n`: Σ_i a_i |(Fᵀ n)_i| (the support function of the parallelogram or
    /// parallelepiped; 0 for a point without a domain).
    #[inline]
    pub fn reach(&self, n: &SVector<f64, D>) -> T {
        let mut reach = c::<T>(0.0);
        for i in 0..D {
            let along = (0..D).fold(c::<T>(0.0), |s, j| s + self.f[(j, i)].clone() * n[j]);
            let along = if along.re() < 0.0 { -along } else { along };
            reach += along * self.half_size[i];
        }
        reach
    }
}

/// A contact force on a point [N] and where it acts, the nearest point of the point's
/// domain [m] (both world frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactForce<T: Scalar, const D: usize> {
    pub force: SVector<T, D>,
    pub at: SVector<T, D>,
}

/// Exact check and penalty force for one candidate: returns the force on the particle
/// and where it acts (world frame), updating or clearing its attachment. The surface acts
/// on the nearest point of the candidate's domain, x − reach(n) n (the centre when it has
/// no domain). Whether the point touches follows the real parts.
#[inline]
pub fn candidate_force<T: Scalar, const D: usize>(
    body: &RigidBody<D>,
    pose: &Pose<D>,
    point: Candidate<'_, T, D>,
    attachment: &mut Option<SVector<T, D>>,
) -> Option<ContactForce<T, D>> {
    let mut xb = pose.to_body(point.x);
    let (mut d, mut plane) = body.nearest_plane(&xb);
    let reach = point.reach(&(pose.rotation * plane.normal));
    if reach.re() > 0.0 {
        xb -= plane.normal.map(c::<T>) * reach;
        (d, plane) = body.nearest_plane(&xb);
    }
    if d.re() >= 0.0 {
        *attachment = None;
        return None;
    }
    let xc = xb.clone() - plane.normal.map(c::<T>) * d;
    let xa = attachment.get_or_insert_with(|| xc.clone());
    let f = penalty_force(&xb, &xc, xa, body.penalty_of(point.mass), body.friction);
    Some(ContactForce {
        force: pose.rotation.map(c::<T>) * f,
        at: pose.to_world(&xb),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    #[test]
    fn sliding_point_stays_on_the_friction_cone() {
        // Surface y = 0, body below; point 0.01 deep, attachment 0.1 to the right.
        let x = Vector2::<f64>::new(0.0, -0.01);
        let xc = Vector2::new(0.0, 0.0);
        let mut xa = Vector2::new(0.1, 0.0);
        let mu = 0.3;
        let f = penalty_force(&x, &xc, &mut xa, 100.0, mu);
        // normal force κ δ = 1, tangential exactly μ times it
        assert!((f[1] - 1.0).abs() < 1e-12);
        assert!((f[0] - mu).abs() < 1e-12, "{f}");
        // inside the cone: unchanged
        let mut xa2 = Vector2::new(0.001, 0.0);
        let f2 = penalty_force(&x, &xc, &mut xa2, 100.0, mu);
        assert!((f2 - Vector2::new(0.1, 1.0)).norm() < 1e-12);
        // frictionless: back to the projection
        let mut xa3 = Vector2::new(0.1, 0.0);
        let f3 = penalty_force(&x, &xc, &mut xa3, 100.0, 0.0);
        assert!((f3 - Vector2::new(0.0, 1.0)).norm() < 1e-12 && xa3.norm() < 1e-14);
    }
}

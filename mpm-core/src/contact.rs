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
use nalgebra::{Matrix3, SVector};

/// Algorithm 13 (body frame): penalty force on a point at `x_mp` whose closest surface
/// point is `x_c`, updating the attachment point `x_a` [N].
#[inline]
pub fn penalty_force<const D: usize>(
    x_mp: &SVector<f64, D>,
    x_c: &SVector<f64, D>,
    x_a: &mut SVector<f64, D>,
    kappa: f64,
    mu: f64,
) -> SVector<f64, D> {
    let trial = (*x_a - x_mp) * kappa;
    let slip = *x_a - x_c;
    let depth = x_c - x_mp;
    if slip.norm() <= 1e-12 * depth.norm().max(f64::MIN_POSITIVE) || depth.norm() == 0.0 {
        return trial;
    }
    let n = depth.normalize();
    let t = slip.normalize();
    if trial.dot(&t) > mu * trial.dot(&n) {
        let m = t - n * mu;
        let xi = -(*x_a - x_mp).dot(&m) / (x_c - *x_a).dot(&m);
        *x_a += (x_c - *x_a) * xi;
        (*x_a - x_mp) * kappa
    } else {
        trial
    }
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
/// domain half-widths a [m].
#[derive(Clone, Copy)]
pub struct Candidate<'a, const D: usize> {
    pub x: &'a SVector<f64, D>,
    pub mass: f64,
    pub f: &'a Matrix3<f64>,
    pub half_size: &'a SVector<f64, D>,
}

impl<const D: usize> Candidate<'_, D> {
    /// How far the point's current domain F·box(a) reaches from its centre along the unit
    /// vector `n`: Σ_i a_i |(Fᵀ n)_i| (the support function of the parallelogram or
    /// parallelepiped; 0 for a point without a domain).
    #[inline]
    pub fn reach(&self, n: &SVector<f64, D>) -> f64 {
        (0..D)
            .map(|i| self.half_size[i] * (0..D).map(|j| self.f[(j, i)] * n[j]).sum::<f64>().abs())
            .sum()
    }
}

/// A contact force on a point [N] and where it acts, the nearest point of the point's
/// domain [m] (both world frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactForce<const D: usize> {
    pub force: SVector<f64, D>,
    pub at: SVector<f64, D>,
}

/// Exact check and penalty force for one candidate: returns the force on the particle
/// and where it acts (world frame), updating or clearing its attachment. The surface acts
/// on the nearest point of the candidate's domain, x − reach(n) n (the centre when it has
/// no domain).
#[inline]
pub fn candidate_force<const D: usize>(
    body: &RigidBody<D>,
    pose: &Pose<D>,
    point: Candidate<'_, D>,
    attachment: &mut Option<SVector<f64, D>>,
) -> Option<ContactForce<D>> {
    let mut xb = pose.to_body(point.x);
    let (mut d, mut plane) = body.nearest_plane(&xb);
    let reach = point.reach(&(pose.rotation * plane.normal));
    if reach > 0.0 {
        xb -= plane.normal * reach;
        (d, plane) = body.nearest_plane(&xb);
    }
    if d >= 0.0 {
        *attachment = None;
        return None;
    }
    let xc = xb - plane.normal * d;
    let xa = attachment.get_or_insert(xc);
    let f = penalty_force(&xb, &xc, xa, body.penalty_of(point.mass), body.friction);
    Some(ContactForce {
        force: pose.rotation * f,
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
        let x = Vector2::new(0.0, -0.01);
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

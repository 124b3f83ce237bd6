//! Boundary conditions.
//!
//! - Grid velocity conditions on node sets (eq. 7.28): the chosen components of
//!   v_{n+1/2}^I are set to v̄ and those of a_n^I to zero (constant, or scaled by a time
//!   signal);
//!   fixed supports set every component, rolling supports and symmetry planes only the
//!   normal one. The points keep the velocity the condition took from the node.
//! - One-sided conditions (a frictionless rigid wall that the body may leave): on the
//!   nodes below (above) a plane, a component is set to v̄ only when the free velocity
//!   would move into the wall, v_i < v̄ (v_i > v̄); otherwise the node moves freely. The
//!   points feel the wall: the constrained acceleration is the one that takes p/m to v̄,
//!   (v̄ − p_I/m_I)/Δt, so the layer that hit the wall stops (with eq. 7.28 the bottom
//!   layer of a Taylor bar kept −200 m/s while it sat on the wall). Two-sided conditions
//!   keep eq. 7.28: at a symmetry plane p/m is a one-sided average of the points' field,
//!   and the reaction form biased a homogeneous compression by 1.3e-3.
//! - Spring conditions on particles near a boundary (eq. 12.1):
//!   f_MP = −κ_BC ((x_MP)_i − (X_MP)_i) in the chosen directions i [N], which keep working
//!   when the grid moves under a grid shift.
//! - Conditions on points in general (`PointCondition`, Karamelo's "fixes"): registered
//!   with the solver (`Solver::add_condition`), each adds its forces on the points in the
//!   step's `AppliedForces` stage, in the order registered; the springs are one.

use crate::particles::Particles;
use materials::signal::TimeSignal;
use nalgebra::{SMatrix, SVector};

/// A condition on material points that acts through forces on them at t_n [N]
/// (plane strain: per metre; axisymmetric: per radian of the ring, as the points' mass).
pub trait PointCondition<const D: usize>: Send + Sync {
    /// What the run log calls it (e.g. "springs on 40 points").
    fn describe(&self) -> String;
    /// Add its forces at time `t` [s] to `forces` (one per point, in point order).
    fn add_forces(&self, t: f64, points: &Particles<D>, forces: &mut [SVector<f64, D>]);
    /// The largest stiffness with which it ties a point [N/m] (0: none), for the time
    /// step's spring limit on the lightest point (module `solver::time_step`).
    fn stiffness(&self) -> f64;
    /// ∂f_i/∂x_i [N/m] for each point i it acts on, when its force on a point depends on
    /// that point's position alone, the same way at every t; `None` otherwise. The
    /// derivative pass (`solver::Tangent`) carries a condition through this matrix and
    /// refuses one without it.
    fn position_jacobian(&self) -> Option<Vec<(usize, SMatrix<f64, D, D>)>>;
}

/// A set of grid nodes chosen by their position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NodeSet<const D: usize> {
    /// Nodes on the plane x_axis = at (within 1e-6 of a cell).
    Plane { axis: usize, at: f64 },
    /// Nodes with x_axis ≤ at.
    Below { axis: usize, at: f64 },
    /// Nodes with x_axis ≥ at.
    Above { axis: usize, at: f64 },
    /// Nodes inside an axis-aligned box.
    Inside {
        min: SVector<f64, D>,
        max: SVector<f64, D>,
    },
}

impl<const D: usize> NodeSet<D> {
    pub fn contains(&self, x: &SVector<f64, D>, h: &SVector<f64, D>) -> bool {
        match *self {
            NodeSet::Plane { axis, at } => (x[axis] - at).abs() <= 1e-6 * h[axis],
            NodeSet::Below { axis, at } => x[axis] <= at + 1e-6 * h[axis],
            NodeSet::Above { axis, at } => x[axis] >= at - 1e-6 * h[axis],
            NodeSet::Inside { min, max } => {
                (0..D).all(|i| x[i] >= min[i] - 1e-6 * h[i] && x[i] <= max[i] + 1e-6 * h[i])
            }
        }
    }
}

const AXES: [&str; 3] = ["x", "y", "z"];

impl<const D: usize> std::fmt::Display for NodeSet<D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NodeSet::Plane { axis, at } => write!(f, "nodes on {} = {at} m", AXES[*axis]),
            NodeSet::Below { axis, at } => write!(f, "nodes at {} <= {at} m", AXES[*axis]),
            NodeSet::Above { axis, at } => write!(f, "nodes at {} >= {at} m", AXES[*axis]),
            NodeSet::Inside { min, max } => write!(
                f,
                "nodes in the box {:?} .. {:?} m",
                min.as_slice(),
                max.as_slice()
            ),
        }
    }
}

impl<const D: usize> std::fmt::Display for VelocityBc<D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let set: Vec<String> = (self.velocity.iter().enumerate())
            .filter_map(|(i, v)| v.map(|v| format!("v_{} = {v} m/s", AXES[i])))
            .collect();
        write!(f, "{} on {}", set.join(", "), self.nodes)?;
        if self.one_sided {
            write!(f, " (one-sided wall)")?;
        }
        if self.history.is_some() {
            write!(f, " (scaled by a time history)")?;
        }
        Ok(())
    }
}

/// Prescribed velocity components on a node set; `None` leaves a component free. With a
/// `history` the components are v̄_i s(t), the signal taken at the leapfrog's velocity time
/// t_{n+1/2}.
#[derive(Debug, Clone, PartialEq)]
pub struct VelocityBc<const D: usize> {
    pub nodes: NodeSet<D>,
    pub velocity: [Option<f64>; D],
    /// Only stop motion into the wall (needs `Below` or `Above` nodes).
    pub one_sided: bool,
    /// Time factor s(t) of the prescribed components [-]; `None` for constant.
    pub history: Option<TimeSignal<f64>>,
}

impl<const D: usize> VelocityBc<D> {
    /// Zero velocity component `axis` on the node set `nodes`.
    pub fn normal(nodes: NodeSet<D>, axis: usize) -> Self {
        let mut velocity = [None; D];
        velocity[axis] = Some(0.0);
        VelocityBc {
            nodes,
            velocity,
            one_sided: false,
            history: None,
        }
    }

    /// No radial velocity on and beyond the axis r = 0 of an axisymmetric model.
    pub fn axis() -> Self {
        Self::normal(NodeSet::Below { axis: 0, at: 0.0 }, 0)
    }

    /// The prescribed components at time `t` [m/s].
    pub fn velocity_at(&self, t: f64) -> [Option<f64>; D] {
        match &self.history {
            None => self.velocity,
            Some(s) => {
                let s = s.at(t);
                self.velocity.map(|v| v.map(|v| v * s))
            }
        }
    }

    /// Largest prescribed speed component over the run [m/s].
    pub fn peak_speed(&self) -> f64 {
        let scale = self.history.as_ref().map_or(1.0, |s| {
            s.values().iter().fold(0.0, |m: f64, v| m.max(v.abs()))
        });
        self.velocity
            .iter()
            .flatten()
            .fold(0.0, |m: f64, v| m.max(v.abs()))
            * scale
    }

    /// All components zero.
    pub fn fixed(nodes: NodeSet<D>) -> Self {
        VelocityBc {
            nodes,
            velocity: [Some(0.0); D],
            one_sided: false,
            history: None,
        }
    }

    /// Zero normal velocity on the plane x_axis = at (rolling support, symmetry plane).
    pub fn symmetry(axis: usize, at: f64) -> Self {
        Self::normal(NodeSet::Plane { axis, at }, axis)
    }

    /// A frictionless rigid wall at x_axis = at that the body (on the side `above` of it)
    /// may leave: one-sided zero normal velocity on the nodes beyond the plane.
    pub fn wall(axis: usize, at: f64, above: bool) -> Self {
        let mut velocity = [None; D];
        velocity[axis] = Some(0.0);
        VelocityBc {
            nodes: if above {
                NodeSet::Below { axis, at }
            } else {
                NodeSet::Above { axis, at }
            },
            velocity,
            one_sided: true,
            history: None,
        }
    }

    /// Whether component `v_free` of the free nodal velocity is to be set to `target`.
    #[inline]
    pub fn acts(&self, v_free: f64, target: f64) -> bool {
        match (self.one_sided, self.nodes) {
            (false, _) => true,
            (true, NodeSet::Below { .. }) => v_free < target,
            (true, NodeSet::Above { .. }) => v_free > target,
            // a plane or box has no side: it acts both ways (scenes reject this)
            (true, _) => true,
        }
    }
}

/// Springs (eq. 12.1) tying particles to their reference positions in some directions.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringBc<const D: usize> {
    pub particles: Vec<usize>,
    pub directions: [bool; D],
    /// κ_BC [N/m = kg/s²].
    pub stiffness: f64,
}

impl<const D: usize> PointCondition<D> for SpringBc<D> {
    fn describe(&self) -> String {
        let axes: Vec<&str> = (0..D)
            .filter(|&i| self.directions[i])
            .map(|i| ["x", "y", "z"][i])
            .collect();
        let (n, k, along) = (self.particles.len(), self.stiffness, axes.join(", "));
        format!("springs on {n} points along {along}, κ = {k:e} N/m")
    }

    fn add_forces(&self, _t: f64, points: &Particles<D>, forces: &mut [SVector<f64, D>]) {
        for &i in &self.particles {
            forces[i] += self.force(&points.position[i], &points.reference_position[i]);
        }
    }

    fn stiffness(&self) -> f64 {
        self.stiffness
    }

    fn position_jacobian(&self) -> Option<Vec<(usize, SMatrix<f64, D, D>)>> {
        let k = SMatrix::from_fn(|i, j| {
            if i == j && self.directions[i] {
                -self.stiffness
            } else {
                0.0
            }
        });
        Some(self.particles.iter().map(|&i| (i, k)).collect())
    }
}

impl<const D: usize> SpringBc<D> {
    /// Spring force on a particle at `x` that started at `x_ref` [N].
    #[inline]
    pub fn force(&self, x: &SVector<f64, D>, x_ref: &SVector<f64, D>) -> SVector<f64, D> {
        SVector::from_fn(|i, _| {
            if self.directions[i] {
                -self.stiffness * (x[i] - x_ref[i])
            } else {
                0.0
            }
        })
    }
}

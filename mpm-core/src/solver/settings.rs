//! Solver parameters that do not depend on the bodies: kinematics, scheme, grid, time-step
//! control, damping, failure limits and bulk viscosity. SI units.

use super::Scheme;
use crate::kinematics::Kinematics;
use crate::shape::ShapeFunction;
use crate::viscosity::BulkViscosity;
use nalgebra::SVector;

/// Solver parameters that do not depend on the bodies.
#[derive(Debug, Clone)]
pub struct Settings<const D: usize> {
    pub kinematics: Kinematics,
    pub scheme: Scheme,
    /// Shape functions (module `shape`).
    pub shape_function: ShapeFunction,
    /// Cell size h_i [m].
    pub spacing: SVector<f64, D>,
    /// Lattice origin ō [m].
    pub origin: SVector<f64, D>,
    /// Body force per unit mass b [m/s²] (gravity).
    pub body_force: SVector<f64, D>,
    /// Artificial damping α_d [1/s] (eq. 7.24).
    pub damping: f64,
    /// Safety factor on the CFL and spring limits.
    pub safety: f64,
    /// Fixed time step [s] instead of the estimate.
    pub dt: Option<f64>,
    /// Particles must stay inside this box [m].
    pub domain: Option<(SVector<f64, D>, SVector<f64, D>)>,
    /// Grid shift amplitudes d̃ [m] and seed (eq. E.8).
    pub grid_shift: Option<(SVector<f64, D>, u64)>,
    /// A run fails when K + W_int exceeds this factor times the energy supplied.
    pub blowup_factor: f64,
    /// Nodes lighter than this fraction of the heaviest point that reaches them are not
    /// accelerated: their f/m would be huge (the force of a point near the far side of a
    /// cell does not shrink with its shape function value), which makes the USL unstable
    /// when a point nears a cell face. `initialize` raises it to the stability limit
    /// (c Δt / 2h)² of `time_step::node_mass_cutoff` when that is larger. The fraction is
    /// of the node's own points, not of the lightest point of the model: axisymmetric
    /// points weigh 2π r A ρ, so near the rim they are heavier than on the axis by R/r,
    /// and a cutoff from the lightest point let rim nodes with 1/100 of their points'
    /// mass be accelerated (USL failed there under refinement).
    pub mass_cutoff: f64,
    /// A run fails when the energy error exceeds this fraction of the energy supplied
    /// (module `watchdog`).
    pub energy_error_fraction: f64,
    /// Artificial bulk viscosity added to the stress (module `viscosity`); `None` for
    /// none.
    pub bulk_viscosity: Option<BulkViscosity>,
    /// Fraction β of the grid velocity in the points' velocity update, 0 (FLIP, the
    /// thesis's algorithm 11) to 1 (PIC): module `pic_blend`.
    pub pic_fraction: f64,
}

impl<const D: usize> Settings<D> {
    pub fn new(kinematics: Kinematics, spacing: f64) -> Self {
        assert_eq!(
            kinematics.dimension(),
            D,
            "kinematics {kinematics:?} needs a {}D grid",
            kinematics.dimension()
        );
        Settings {
            kinematics,
            scheme: Scheme::Musl,
            shape_function: ShapeFunction::Linear,
            spacing: SVector::repeat(spacing),
            origin: SVector::zeros(),
            body_force: SVector::zeros(),
            damping: 0.0,
            safety: 0.3,
            dt: None,
            domain: None,
            grid_shift: None,
            blowup_factor: 10.0,
            mass_cutoff: 1e-3,
            energy_error_fraction: 0.25,
            bulk_viscosity: Some(BulkViscosity::STANDARD),
            pic_fraction: 0.0,
        }
    }

    /// The thesis's algorithm as its benchmarks run it: USL (algorithm 6) and no bulk
    /// viscosity. The defaults (MUSL with bulk viscosity) are for impact: USL fails when a
    /// free surface of a fast body crosses a node plane, and without viscosity the ringing
    /// after an impact drives an axisymmetric axis past yield.
    pub fn thesis_scheme(&mut self) {
        self.scheme = Scheme::Usl;
        self.bulk_viscosity = None;
    }
}

//! A run that goes bad stops with an error naming the step, the time, the particle and
//! the cause. Users study where methods fail, so this is a result, not a crash: all output
//! written before the failure stays on disk.

use materials::limits::TooLarge;
use materials::MaterialError;
use thiserror::Error;

#[derive(Debug, Clone, PartialEq, Error)]
pub enum Cause {
    #[error("non-finite {what}")]
    NonFinite { what: &'static str },
    #[error("det F = {det_f:e} <= 0 (inverted deformation)")]
    InvertedDeformation { det_f: f64 },
    #[error("material update failed: {0}")]
    Material(MaterialError),
    #[error("left the allowed region at {position:?} m")]
    LeftDomain { position: Vec<f64> },
    #[error("energy blow-up: total energy {energy:e} J exceeds {limit:e} J (blow-up factor times the energy supplied)")]
    EnergyBlowUp { energy: f64, limit: f64 },
    #[error("speed {speed:.4e} m/s exceeds {limit:.4e} m/s (twice the fastest prescribed or initial speed plus the wave speed): the run has gone unstable, most likely near a free surface or contact with too few points per cell or too large a time step")]
    SpeedLimit { speed: f64, limit: f64 },
    #[error("{distance:.4e} m outside the initial extent of the bodies (limit {limit:.4e} m, its diagonal): the point has been thrown off, an instability")]
    Escaped { distance: f64, limit: f64 },
    #[error("the run would be too long: {0}")]
    TooManySteps(TooLarge),
    #[error("the grid would be too large: {0}")]
    GridTooLarge(TooLarge),
    #[error("energy error {error:.4e} J exceeds {limit:.4e} J (the energy-error fraction of the energy supplied): the integration is gaining energy, an instability (reduce time.safety)")]
    EnergyError { error: f64, limit: f64 },
    #[error("the point's domain reaches {extent:.3} cells from its centre: a GIMP box of more than {} nodes, or of more than {} along one axis, beyond what a point may reach; a coarser grid, or a vertex kernel (cpdi, cpgimp: at most 4^D nodes however far the domain stretches)", crate::shape::MAX_STENCIL_NODES, crate::shape::MAX_SUPPORT)]
    DomainTooLarge { extent: f64 },
    #[error("interrupted (Ctrl-C or a termination signal); the output up to here is kept")]
    Interrupted,
}

#[derive(Debug, Clone, PartialEq, Error)]
#[error("simulation failed at step {step}, t = {time:e} s{}: {cause}", particle.map(|p| format!(", particle {p}")).unwrap_or_default())]
pub struct SimulationError {
    pub step: usize,
    pub time: f64,
    pub particle: Option<usize>,
    pub cause: Cause,
}

/// What kind of failure a run met: the prediction itself went bad (an optimizer rejects
/// the trial parameters and goes on), the model asked for more than the limits allow
/// (fix the input), or the run was stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FailureKind {
    /// Non-finite values, inverted or failed material updates, energy or speed beyond
    /// bounds, points thrown off or out of the allowed region.
    Divergence,
    /// The run or the grid would exceed `materials::limits`.
    Limit,
    /// The caller stopped the run.
    Stopped,
}

impl Cause {
    pub fn kind(&self) -> FailureKind {
        match self {
            Cause::TooManySteps(_) | Cause::GridTooLarge(_) => FailureKind::Limit,
            Cause::Interrupted => FailureKind::Stopped,
            Cause::NonFinite { .. }
            | Cause::InvertedDeformation { .. }
            | Cause::Material(_)
            | Cause::LeftDomain { .. }
            | Cause::EnergyBlowUp { .. }
            | Cause::SpeedLimit { .. }
            | Cause::Escaped { .. }
            | Cause::DomainTooLarge { .. }
            | Cause::EnergyError { .. } => FailureKind::Divergence,
        }
    }
}

impl SimulationError {
    /// The prediction diverged (rather than hitting a limit).
    pub fn is_divergence(&self) -> bool {
        self.cause.kind() == FailureKind::Divergence
    }
}

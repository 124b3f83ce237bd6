//! A step as a list of named stages (Karamelo's schemes as stage lists), in three variants
//! of when the stress is updated (Bardenhagen 2002, section 7.5, algorithms 6-12):
//!
//! - `Usl` (algorithm 6): map m, p = Σ N m v, f = −Σ ∇N·σ V + Σ N (m b + f_ext) (eq. 7.30-
//!   7.32, 9.2); solve a_I = (f_I − α_d p_I)/m_I (eq. 7.21, 7.24), v_I = p_I/m_I + a_I Δt
//!   (eq. 7.27); velocity conditions (eq. 7.28); map back a_MP = Σ N a_I,
//!   ṽ_MP = Σ N v_I, L = Σ v_I ⊗ ∇N_I; x ← x + ṽ Δt, v ← v + a_MP Δt (algorithm 12 with the
//!   typo fixed), F ← (I + L Δt) F, V = det F V0, then σ and history from the material.
//! - `Usf`: map m, p; v_I = p_I/m_I; update F and σ from that field; then map f with the
//!   new stress, solve and move the particles.
//! - `Musl`: as USL, but after the particle velocities are updated they are mapped to the
//!   grid again and L is taken from that smoothed velocity field.

use std::fmt;

/// When the stress is updated within a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scheme {
    Usl,
    Usf,
    Musl,
}

/// One stage of a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// Fit the grid to the points and evaluate every point's shape functions once.
    FitGrid,
    /// Applied, spring (eq. 12.1) and penalty contact (eq. 9.2-9.7) forces on the points.
    ExternalForces,
    /// Map mass, momentum and force to the grid (algorithm 9).
    MapMassMomentumForce,
    /// Map mass and momentum (USF, before the stress update).
    MapMassMomentum,
    /// Map force with the updated stress (USF).
    MapForce,
    /// Map the updated point momentum again (MUSL).
    MapMomentum,
    /// a = (f − α_d p)/m, v = p/m + a Δt, then velocity conditions (algorithm 10).
    SolveMomentum,
    /// v = p/m without acceleration, then velocity conditions.
    NodalVelocity,
    /// v_MP ← v_MP + Σ N a_I Δt and ṽ = Σ N v_I stored (algorithm 11).
    UpdateVelocity,
    /// L = Σ v_I ⊗ ∇N_I, F, V, σ and history (algorithm 12).
    UpdateStress,
    /// Both in one pass over the points (USL).
    UpdateVelocityAndStress,
    /// x ← x + ṽ Δt, work of external forces, domain and watchdog checks; t ← t + Δt.
    Advect,
    /// Energy balance and blow-up checks.
    CheckEnergy,
    /// The CFL estimate with the current velocities; Δt reduced below it (module
    /// `time_step`).
    CheckTimeStep,
}

impl Scheme {
    /// The stages of one step, in order.
    pub fn stages(self) -> &'static [Stage] {
        use Stage::*;
        match self {
            Scheme::Usl => &[
                FitGrid,
                ExternalForces,
                MapMassMomentumForce,
                SolveMomentum,
                UpdateVelocityAndStress,
                Advect,
                CheckEnergy,
                CheckTimeStep,
            ],
            Scheme::Usf => &[
                FitGrid,
                ExternalForces,
                MapMassMomentum,
                NodalVelocity,
                UpdateStress,
                MapForce,
                SolveMomentum,
                UpdateVelocity,
                Advect,
                CheckEnergy,
                CheckTimeStep,
            ],
            Scheme::Musl => &[
                FitGrid,
                ExternalForces,
                MapMassMomentumForce,
                SolveMomentum,
                UpdateVelocity,
                MapMomentum,
                NodalVelocity,
                UpdateStress,
                Advect,
                CheckEnergy,
                CheckTimeStep,
            ],
        }
    }
}

impl fmt::Display for Stage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Stage::FitGrid => "fit grid",
            Stage::ExternalForces => "external forces",
            Stage::MapMassMomentumForce => "map m, p, f",
            Stage::MapMassMomentum => "map m, p",
            Stage::MapForce => "map f",
            Stage::MapMomentum => "map p",
            Stage::SolveMomentum => "solve momentum",
            Stage::NodalVelocity => "nodal velocity",
            Stage::UpdateVelocity => "update v",
            Stage::UpdateStress => "update F, σ",
            Stage::UpdateVelocityAndStress => "update v, F, σ",
            Stage::Advect => "advect",
            Stage::CheckEnergy => "check energy",
            Stage::CheckTimeStep => "check time step",
        })
    }
}

impl fmt::Display for Scheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = match self {
            Scheme::Usl => "USL",
            Scheme::Usf => "USF",
            Scheme::Musl => "MUSL",
        };
        write!(f, "{name}:")?;
        for (k, stage) in self.stages().iter().enumerate() {
            write!(f, "{} {stage}", if k == 0 { "" } else { "," })?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every scheme maps mass before it solves, updates the velocity and the stress
    /// exactly once, and ends by moving the points and checking the energy.
    #[test]
    fn every_scheme_updates_velocity_and_stress_once() {
        for scheme in [Scheme::Usl, Scheme::Usf, Scheme::Musl] {
            let s = scheme.stages();
            let count = |a: Stage| s.iter().filter(|x| **x == a).count();
            let both = count(Stage::UpdateVelocityAndStress);
            assert_eq!(count(Stage::UpdateVelocity) + both, 1, "{scheme}");
            assert_eq!(count(Stage::UpdateStress) + both, 1, "{scheme}");
            assert_eq!(count(Stage::SolveMomentum), 1, "{scheme}");
            assert_eq!(s[..2], [Stage::FitGrid, Stage::ExternalForces], "{scheme}");
            assert_eq!(
                s[s.len() - 3..],
                [Stage::Advect, Stage::CheckEnergy, Stage::CheckTimeStep],
                "{scheme}"
            );
        }
        assert_eq!(
            Scheme::Usl.to_string(),
            "USL: fit grid, external forces, map m, p, f, solve momentum, update v, F, σ, advect, check energy, check time step"
        );
    }
}

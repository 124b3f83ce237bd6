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

/// What a stage reads or writes: the state a step carries to the next, and the data a
/// step makes for itself (`within_step`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Data {
    /// Point positions x_p, masses, volumes V0, applied forces, domains.
    Points,
    /// Point velocities v_p.
    PointVelocity,
    /// F, V = det F V0, σ and material history (α, θ, Fᵖ⁻¹) of every point.
    PointDeformation,
    /// t and the step count.
    Time,
    /// Δt.
    TimeStep,
    /// Rigid bodies: contact candidates, attachments and the contact force on each.
    RigidBodies,
    /// The elastic bars behind bar-driven faces (face displacement and velocity).
    BarFaces,
    /// The energy bookkeeping (`Energies`).
    Energies,
    /// The grid fitted to the points (shifted origin) and every point's shape functions.
    Weights,
    /// Applied (traction) and condition forces on the points at t_n.
    PointForces,
    /// Contact forces at the points' surface points (module `surface_loads`).
    ContactLoads,
    /// Nodal mass m_I.
    NodalMass,
    /// Nodal momentum p_I.
    NodalMomentum,
    /// Nodal force f_I.
    NodalForce,
    /// Nodal velocity v_I and acceleration a_I.
    NodalVelocity,
    /// The grid velocity at the points, ṽ = Σ N v_I.
    GridVelocityAtPoints,
}

impl Data {
    /// Made by a step for itself: a stage may read it only after an earlier stage of
    /// the same step wrote it.
    pub fn within_step(self) -> bool {
        use Data::*;
        matches!(
            self,
            Weights
                | PointForces
                | ContactLoads
                | NodalMass
                | NodalMomentum
                | NodalForce
                | NodalVelocity
                | GridVelocityAtPoints
        )
    }
}

/// One stage of a step; `reads` and `writes` state its contract.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// Fit the grid to the points and evaluate every point's shape functions once
    /// (module `grid_fit`).
    FitGrid,
    /// Applied forces times the load factor at t_n, and the forces of every registered
    /// point condition (boundary springs, eq. 12.1; module `conditions`).
    AppliedForces,
    /// Penalty contact with every rigid body (eq. 9.2-9.7): candidate search, forces at
    /// the surface points (module `contact_forces`).
    ContactForces,
    /// Faces on elastic bars move with their contact force (module `bar`).
    BarFaces,
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
    /// x ← x + ṽ Δt, work of external forces, domain and watchdog checks.
    Advect,
    /// t ← t + Δt, one more step.
    AdvanceTime,
    /// Energy balance and blow-up checks.
    CheckEnergy,
    /// The CFL estimate with the current velocities; Δt reduced below it (module
    /// `time_step`).
    CheckTimeStep,
}

impl Stage {
    /// What the stage reads.
    pub fn reads(self) -> &'static [Data] {
        use Data::*;
        match self {
            Stage::FitGrid => &[Points, PointDeformation],
            Stage::AppliedForces => &[Time, Points],
            Stage::ContactForces => &[
                Weights,
                Time,
                TimeStep,
                Points,
                PointVelocity,
                PointDeformation,
                RigidBodies,
                BarFaces,
            ],
            Stage::BarFaces => &[Time, TimeStep, RigidBodies, BarFaces],
            Stage::MapMassMomentumForce => &[
                Weights,
                Points,
                PointVelocity,
                PointDeformation,
                PointForces,
                ContactLoads,
            ],
            Stage::MapMassMomentum => &[Weights, Points, PointVelocity],
            Stage::MapForce => &[Weights, Points, PointDeformation, PointForces, ContactLoads],
            Stage::MapMomentum => &[Weights, Points, PointVelocity],
            Stage::SolveMomentum => &[Time, TimeStep, NodalMass, NodalMomentum, NodalForce],
            Stage::NodalVelocity => &[Time, TimeStep, NodalMass, NodalMomentum],
            Stage::UpdateVelocity => &[TimeStep, Weights, NodalVelocity, PointVelocity],
            Stage::UpdateStress | Stage::UpdateVelocityAndStress => &[
                TimeStep,
                Weights,
                NodalVelocity,
                PointVelocity,
                PointDeformation,
            ],
            Stage::Advect => &[
                Time,
                TimeStep,
                Points,
                GridVelocityAtPoints,
                PointForces,
                ContactLoads,
            ],
            Stage::AdvanceTime => &[Time, TimeStep],
            Stage::CheckEnergy => &[Points, PointVelocity, Energies],
            Stage::CheckTimeStep => &[TimeStep, PointVelocity, PointDeformation],
        }
    }

    /// What the stage writes.
    pub fn writes(self) -> &'static [Data] {
        use Data::*;
        match self {
            Stage::FitGrid => &[Weights],
            Stage::AppliedForces => &[PointForces],
            Stage::ContactForces => &[ContactLoads, RigidBodies],
            Stage::BarFaces => &[BarFaces],
            Stage::MapMassMomentumForce => &[NodalMass, NodalMomentum, NodalForce],
            Stage::MapMassMomentum => &[NodalMass, NodalMomentum],
            Stage::MapForce => &[NodalForce],
            Stage::MapMomentum => &[NodalMomentum],
            Stage::SolveMomentum => &[NodalVelocity, Energies],
            Stage::NodalVelocity => &[NodalVelocity, Energies],
            Stage::UpdateVelocity => &[PointVelocity, GridVelocityAtPoints],
            Stage::UpdateStress => &[PointDeformation, Energies],
            Stage::UpdateVelocityAndStress => &[
                PointVelocity,
                GridVelocityAtPoints,
                PointDeformation,
                Energies,
            ],
            Stage::Advect => &[Points, Energies],
            Stage::AdvanceTime => &[Time],
            Stage::CheckEnergy => &[Energies],
            Stage::CheckTimeStep => &[TimeStep],
        }
    }
}

impl Scheme {
    /// The stages of one step, in order.
    pub fn stages(self) -> &'static [Stage] {
        use Stage::*;
        match self {
            Scheme::Usl => &[
                FitGrid,
                AppliedForces,
                ContactForces,
                BarFaces,
                MapMassMomentumForce,
                SolveMomentum,
                UpdateVelocityAndStress,
                Advect,
                AdvanceTime,
                CheckEnergy,
                CheckTimeStep,
            ],
            Scheme::Usf => &[
                FitGrid,
                AppliedForces,
                ContactForces,
                BarFaces,
                MapMassMomentum,
                NodalVelocity,
                UpdateStress,
                MapForce,
                SolveMomentum,
                UpdateVelocity,
                Advect,
                AdvanceTime,
                CheckEnergy,
                CheckTimeStep,
            ],
            Scheme::Musl => &[
                FitGrid,
                AppliedForces,
                ContactForces,
                BarFaces,
                MapMassMomentumForce,
                SolveMomentum,
                UpdateVelocity,
                MapMomentum,
                NodalVelocity,
                UpdateStress,
                Advect,
                AdvanceTime,
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
            Stage::AppliedForces => "applied forces",
            Stage::ContactForces => "contact forces",
            Stage::BarFaces => "bar faces",
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
            Stage::AdvanceTime => "advance time",
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

    /// The reads of `stages` (one step) of data made within the step that no earlier stage
    /// of the step wrote: empty for a step that keeps the contract.
    fn unmet_reads(stages: &[Stage]) -> Vec<(Stage, Data)> {
        let mut written: Vec<Data> = vec![];
        let mut unmet = vec![];
        for &stage in stages {
            let made_here = stage.reads().iter().filter(|d| d.within_step());
            unmet.extend(
                made_here
                    .filter(|d| !written.contains(d))
                    .map(|&d| (stage, d)),
            );
            written.extend(stage.writes());
        }
        unmet
    }

    /// Every scheme maps mass before it solves, updates the velocity and the stress
    /// exactly once, and ends by moving the points, advancing time and checking.
    #[test]
    fn every_scheme_updates_velocity_and_stress_once() {
        for scheme in [Scheme::Usl, Scheme::Usf, Scheme::Musl] {
            let s = scheme.stages();
            let count = |a: Stage| s.iter().filter(|x| **x == a).count();
            let both = count(Stage::UpdateVelocityAndStress);
            assert_eq!(count(Stage::UpdateVelocity) + both, 1, "{scheme}");
            assert_eq!(count(Stage::UpdateStress) + both, 1, "{scheme}");
            assert_eq!(count(Stage::SolveMomentum), 1, "{scheme}");
            let forces = [
                Stage::FitGrid,
                Stage::AppliedForces,
                Stage::ContactForces,
                Stage::BarFaces,
            ];
            assert_eq!(s[..4], forces, "{scheme}");
            let last = [
                Stage::Advect,
                Stage::AdvanceTime,
                Stage::CheckEnergy,
                Stage::CheckTimeStep,
            ];
            assert_eq!(s[s.len() - 4..], last, "{scheme}");
        }
        assert_eq!(
            Scheme::Usl.to_string(),
            "USL: fit grid, applied forces, contact forces, bar faces, map m, p, f, solve momentum, update v, F, σ, advect, advance time, check energy, check time step"
        );
    }

    /// The contract holds in every scheme.
    #[test]
    fn every_stage_reads_what_an_earlier_stage_of_its_step_wrote() {
        for scheme in [Scheme::Usl, Scheme::Usf, Scheme::Musl] {
            assert_eq!(unmet_reads(scheme.stages()), [], "{scheme}");
        }
    }

    /// A misordered step is caught: the force mapped before the forces are made.
    #[test]
    fn a_stage_before_its_inputs_breaks_the_contract() {
        use Stage::*;
        let early = [FitGrid, MapMassMomentumForce, AppliedForces, ContactForces];
        let unmet = unmet_reads(&early);
        assert_eq!(
            unmet,
            [
                (MapMassMomentumForce, Data::PointForces),
                (MapMassMomentumForce, Data::ContactLoads)
            ]
        );
    }
}

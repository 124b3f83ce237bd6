//! The MPM model of the SHPB test (thesis chapter 11): the specimen as material
//! points between two rigid faces, s_i on the incident side and s_t on the transmitter
//! side, with penalty contact and Coulomb friction μ (algorithm 13). Levels (`geometry`):
//! axisymmetric (r, z), 3D quarter and full 3D (x, y, z), z along the bars in each, the
//! transmitter face below the specimen (s_t at the lowest points, axis +z into the
//! specimen), the incident face above (axis −z).
//!
//! Two drives (`Drive`):
//! - `MeasuredVelocity`, as in the thesis: s_i follows the measured relative face velocity
//!   v1 − v2 = c0 (ε_i − ε_r − ε_t), s_t is fixed; the model's face forces are compared
//!   with the processed F1 and F2.
//! - `IncidentPulse`: both faces sit on elastic bars (`mpm_core::BarEnd`, the bars as 1D
//!   waveguides coupled through their impedance Z = E_b A_b / c0); only the incident
//!   pulse at the face drives the model, which then predicts the reflected and
//!   transmitted pulses ε_r = f_i/(E_b A_b) − ε_i and ε_t = f_t/(E_b A_b), the gauge
//!   signals themselves.
//!
//! Contact: the faces sit at the specimen's ends and act on the points' domains (half a
//! spacing, stretched with F, `mpm_core::contact::Candidate::reach`), so they touch the
//! end layers at t = 0 and the specimen between them has its true length L(t). The
//! contact forces act on the grid at those surface points (mpm-core's surface loads),
//! so a face on a node plane loads only that plane and the end cells carry the same
//! stress as the interior. Contact at
//! the point centres would leave a gap of half a spacing (why the thesis's coarse B1 run
//! starts late), and faces placed at the centres shorten the specimen to L − s: the strain
//! for a face displacement then comes out L/(L − s) too large, an error of first order in
//! s (11 % at 10 points along the length).
//! The penalty is per mass (`RigidBody::penalty_per_mass`), κ = ω_c² m_p with the contact
//! frequency ω_c = `contact_factor` · c / s (c the specimen's P-wave speed, s the point
//! spacing): the same for every ring, so the light rings at the axis set neither Δt nor
//! the pressure distribution. With the default factor 1 the contact springs are as stiff
//! as one layer of points (a penetration of σ s / E, 1 µm at 1 GPa for s = 0.2 mm) and
//! their limit 2/ω_c = 2 s / c equals the CFL limit h / c of the cells (h = 2 s).
//!
//! Known artefact of linear shape functions: when the specimen drifts with the
//! transmitter face (incident-pulse drive), its face layer crosses node planes as a whole
//! and the face force dips for ≈ 0.5 µs (the cell-crossing error; GIMP/CPDI).
//! Units: SI.

mod derivatives;
pub mod geometry;
pub mod record;
mod run;
pub mod scene;
pub mod study;

pub use derivatives::ForceDerivatives;
pub use run::{AnyObserver, FaceHistory, ShpbRun};

pub use geometry::{Discretization, ModelLevel};

use materials::signal::TimeSignal;
use materials::Material;
use mpm_core::shape::ShapeFunction;
use mpm_core::{BarEnd, RigidBody, Settings, Solver, Template};
use nalgebra::SVector;
use std::sync::Arc;

/// How the faces move.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Drive {
    MeasuredVelocity,
    IncidentPulse,
}

impl std::str::FromStr for Drive {
    type Err = String;

    /// The drive's name in scene and set files.
    fn from_str(name: &str) -> Result<Drive, String> {
        match name {
            "measured-velocity" => Ok(Drive::MeasuredVelocity),
            "incident-pulse" => Ok(Drive::IncidentPulse),
            other => Err(format!(
                "\"{other}\", expected \"measured-velocity\" or \"incident-pulse\""
            )),
        }
    }
}

/// Bars: axial stiffness E_b A_b [N] and wave speed c0 [m/s] (both bars alike).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bars {
    pub axial_stiffness: f64,
    pub wave_speed: f64,
}

/// Steel bars of the synthetic studies: the thesis's bars' E = 210 GPa with ρ = 7850
/// kg/m³, 7 mm in diameter, half the thesis's 14 mm (the 1D bar theory holds the better
/// the smaller the radius against a pulse's rise length).
pub const STUDY_BAR_MODULUS: f64 = 210e9;
pub const STUDY_BAR_DENSITY: f64 = 7850.0;
pub const STUDY_BAR_DIAMETER: f64 = 7e-3;

impl Bars {
    /// The bars of the synthetic studies (`STUDY_BAR_*`).
    pub fn study() -> Bars {
        let area = std::f64::consts::PI * 0.25 * STUDY_BAR_DIAMETER * STUDY_BAR_DIAMETER;
        Bars {
            axial_stiffness: STUDY_BAR_MODULUS * area,
            wave_speed: (STUDY_BAR_MODULUS / STUDY_BAR_DENSITY).sqrt(),
        }
    }
}

/// Specimen cylinder: diameter and length [m].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cylinder {
    pub diameter: f64,
    pub length: f64,
}

impl Cylinder {
    /// Cross-section π d²/4 [m²].
    pub fn area(&self) -> f64 {
        std::f64::consts::PI * 0.25 * self.diameter * self.diameter
    }
}

/// The measured histories at the specimen faces on one time base [s] from t = 0:
/// incident strain ε_i (compression positive) and relative face velocity v1 − v2 [m/s].
#[derive(Debug, Clone, PartialEq)]
pub struct FaceSignals {
    pub time_s: Vec<f64>,
    pub incident: Vec<f64>,
    pub relative_velocity_m_per_s: Vec<f64>,
}

/// Discretization and contact of the model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModelSettings {
    /// Material points along the specimen length (thesis table 11.2: 20, 40, 60).
    pub layers: usize,
    /// Coulomb friction μ at both faces [-].
    pub friction: f64,
    /// Contact frequency ω_c over c / s [-].
    pub contact_factor: f64,
    /// Safety factor on the CFL estimate [-].
    pub safety: f64,
    pub drive: Drive,
    /// Axisymmetric, 3D quarter or full 3D (`geometry`).
    pub level: ModelLevel,
    /// Shape functions of the grid (`ShapeFunction::SCENE_DEFAULT` unless set; domain
    /// kernels use the points' lattice domains).
    pub shape_function: ShapeFunction,
}

impl ModelSettings {
    pub fn new(layers: usize, drive: Drive) -> Self {
        ModelSettings {
            layers,
            friction: 0.1,
            contact_factor: 1.0,
            safety: 0.3,
            drive,
            level: ModelLevel::Axisymmetric,
            shape_function: ShapeFunction::SCENE_DEFAULT,
        }
    }
}

/// A change of the contact assumptions of the model: the penalty stiffness κ and the
/// friction μ of both faces scaled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactChange {
    pub label: &'static str,
    /// Factor on κ (κ ∝ ω_c², so `contact_factor` moves by its square root) [-].
    pub penalty: f64,
    /// Factor on μ [-].
    pub friction: f64,
}

/// κ and μ each halved and doubled: how far a result moves under them is what the
/// choice of the defaults (contact factor 1, μ = 0.1) is worth.
pub const CONTACT_CHANGES: [ContactChange; 4] = [
    ContactChange {
        label: "κ / 2",
        penalty: 0.5,
        friction: 1.0,
    },
    ContactChange {
        label: "κ × 2",
        penalty: 2.0,
        friction: 1.0,
    },
    ContactChange {
        label: "μ / 2",
        penalty: 1.0,
        friction: 0.5,
    },
    ContactChange {
        label: "μ × 2",
        penalty: 1.0,
        friction: 2.0,
    },
];

impl ModelSettings {
    /// These settings with the contact assumptions changed by `change`.
    pub fn with_contact(&self, change: &ContactChange) -> ModelSettings {
        ModelSettings {
            contact_factor: self.contact_factor * change.penalty.sqrt(),
            friction: self.friction * change.friction,
            ..*self
        }
    }
}

/// One SHPB model, discretized once; `run` instantiates it with a material.
#[derive(Clone)]
pub struct ShpbModel {
    template: Discretized,
    settings: ModelSettings,
    signals: FaceSignals,
    bars: Bars,
    /// Copies of the model that make the specimen (`geometry::Specimen::copies`) [-].
    copies: f64,
}

/// The template of a 2D (axisymmetric) or 3D level.
#[derive(Clone)]
enum Discretized {
    Axisymmetric(Template<2>),
    Solid(Template<3>),
}

/// Name of the specimen body, for `Template::instantiate`.
pub const SPECIMEN: &str = "specimen";
/// Rigid bodies: the transmitter face first, then the incident face.
const TRANSMITTER: usize = 0;
const INCIDENT: usize = 1;

impl ShpbModel {
    /// Discretize `cylinder` at `settings.level` with `settings.layers` points along its
    /// length (two per cell) and place the faces; `material` only fixes the wave speed for
    /// the contact frequency.
    pub fn new(
        cylinder: Cylinder,
        bars: Bars,
        signals: FaceSignals,
        settings: ModelSettings,
        material: Arc<dyn Material>,
    ) -> anyhow::Result<Self> {
        anyhow::ensure!(
            settings.layers >= 2,
            "layers = {}: at least 2 points along the specimen",
            settings.layers
        );
        let (template, copies) = match settings.level {
            ModelLevel::Axisymmetric => {
                let (t, copies) = discretize::<2>(&cylinder, &bars, &signals, &settings, material)?;
                (Discretized::Axisymmetric(t), copies)
            }
            ModelLevel::Quarter3d | ModelLevel::Full3d => {
                let (t, copies) = discretize::<3>(&cylinder, &bars, &signals, &settings, material)?;
                (Discretized::Solid(t), copies)
            }
        };
        Ok(ShpbModel {
            template,
            settings,
            signals,
            bars,
            copies,
        })
    }

    /// The same discretized model with the faces' κ and μ changed by `change`.
    pub fn with_contact(&self, change: &ContactChange) -> anyhow::Result<ShpbModel> {
        fn changed<const D: usize>(
            t: &Template<D>,
            change: &ContactChange,
        ) -> anyhow::Result<Template<D>> {
            let mut solver = t.model().clone();
            for rc in &mut solver.rigid {
                rc.body.penalty *= change.penalty;
                rc.body.friction *= change.friction;
            }
            Ok(Template::new(solver)?)
        }
        let template = match &self.template {
            Discretized::Axisymmetric(t) => Discretized::Axisymmetric(changed(t, change)?),
            Discretized::Solid(t) => Discretized::Solid(changed(t, change)?),
        };
        Ok(ShpbModel {
            template,
            settings: self.settings.with_contact(change),
            ..self.clone()
        })
    }

    pub fn settings(&self) -> &ModelSettings {
        &self.settings
    }

    /// Number of material points (of the model, not of its copies).
    pub fn particles(&self) -> usize {
        match &self.template {
            Discretized::Axisymmetric(t) => t.model().particles.len(),
            Discretized::Solid(t) => t.model().particles.len(),
        }
    }

    /// End of the signals [s].
    pub fn end_s(&self) -> f64 {
        self.signals.time_s.last().copied().unwrap_or(0.0)
    }
}

/// The specimen at `settings.level` between its two faces, as a template, and the number
/// of copies of it that make the specimen.
fn discretize<const D: usize>(
    cylinder: &Cylinder,
    bars: &Bars,
    signals: &FaceSignals,
    settings: &ModelSettings,
    material: Arc<dyn Material>,
) -> anyhow::Result<(Template<D>, f64)> {
    let specimen = geometry::specimen::<D>(cylinder, settings.layers, settings.level);
    let mut solver = Solver::new(Settings::<D>::new(specimen.kinematics, specimen.cell));
    solver.settings.safety = settings.safety;
    solver.settings.shape_function = settings.shape_function;
    let c = (material.p_wave_modulus() / material.density()).sqrt();
    let body = solver.add_body(SPECIMEN, material, &specimen.points, SVector::zeros());
    solver.set_half_size(body, specimen.spacing * 0.5);
    solver.velocity_bcs.extend(specimen.conditions);
    let s = specimen.spacing[0];
    let omega = settings.contact_factor * c / s;
    let axis = geometry::bar_axis::<D>();
    let face = |name: &str, z: f64, normal: SVector<f64, D>| {
        let mut body =
            RigidBody::half_space(name, axis * z, normal, omega * omega, settings.friction);
        body.penalty_per_mass = true;
        body
    };
    let mut transmitter = face("transmitter", 0.0, axis);
    let mut incident = face("incident", cylinder.length, -axis);
    match settings.drive {
        Drive::MeasuredVelocity => {
            let v = signals
                .relative_velocity_m_per_s
                .iter()
                .map(|v| axis * -v)
                .collect();
            let velocity = TimeSignal::new(signals.time_s.clone(), v)?;
            incident.motion.translation = Some(velocity.integrated());
        }
        Drive::IncidentPulse => {
            // each copy of the model sits on its share of the bar
            let stiffness = bars.axial_stiffness / specimen.copies;
            let pulse = TimeSignal::new(signals.time_s.clone(), signals.incident.clone())?;
            let bar = |axis, incoming| BarEnd::new(axis, stiffness, bars.wave_speed, incoming);
            incident.motion.bar = Some(bar(-axis, Some(pulse)));
            transmitter.motion.bar = Some(bar(axis, None));
        }
    }
    solver.add_rigid_body(transmitter);
    solver.add_rigid_body(incident);
    Ok((Template::new(solver)?, specimen.copies))
}

//! Explicit Material Point Method (thesis chapters 5, 7-9, appendix E).
//!
//! Particles (structure of arrays) carry mass, velocity, F and σ; material history lives in
//! per-material blocks. Each step maps particles to a regular Cartesian grid with linear
//! shape functions, solves the lumped-mass momentum balance with the leapfrog, and maps
//! back (USL, USF or MUSL). Plane strain, axisymmetric (D = 2) and 3D share one
//! implementation through the const generic dimension `D`. Rigid bodies act through
//! penalty contact with Coulomb friction. SI units throughout.
//!
//! A step is a list of named stages (`solver::scheme`); its loops are cut into fixed pieces
//! and run on the calling thread, through rayon or by a warm team (`parallel`), with the
//! same bits either way; weights come from a `shape::Kernel`
//! once per step (`weights`); motions and conditions follow `TimeSignal`s; outputs and
//! fits read the run through `solver::observer::Observer`; `Template` runs one discretized model
//! with many material parameter sets. The verification catalogue lives with the
//! application (`mpw::verify::mpm`).

pub mod bar;
pub mod boundary;
pub mod contact;
pub mod derivative_history;
pub mod discretize;
pub mod failure;
pub mod grid;
pub mod kinematics;
pub mod limits;
pub mod material_block;
pub mod melting;
pub mod mesh;
pub mod parallel;
pub mod particles;
pub mod rigid;
pub mod shape;
pub mod shift;
pub mod solver;
pub mod template;
pub mod viscosity;
pub mod watchdog;
pub mod weights;

pub use bar::{BarEnd, ContactSprings};
pub use boundary::{NodeSet, PointCondition, SpringBc, VelocityBc};
pub use failure::{Cause, FailureKind, SimulationError};
pub use grid::Grid;
pub use kinematics::Kinematics;
pub use material_block::MaterialBlock;
pub use particles::Particles;
pub use rigid::RigidBody;
pub use solver::{Energies, RunError, Scheme, Settings, Solver, StageTimes, TimeStep};
pub use template::{Template, TemplateError};
pub use viscosity::BulkViscosity;
pub mod output;
pub mod results;
pub mod run;
pub mod scene;

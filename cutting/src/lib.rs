//! Metal cutting with the explicit MPM (Maassen 2023, chapter 12): plane-strain cuts of a
//! Johnson-Cook workpiece by a rigid tool, without damage, adiabatic, with Coulomb contact.
//!
//! - `workpiece`: what both cuts share: how a run goes, the workpiece on its grid;
//! - `vertical`: the vertical cut of §12.2 (Al 7075-T6, a punch moving down past a die
//!   edge), its discretization sets of table 12.2 (S: no grid shift, grid conditions; G:
//!   grid shift dx/2, spring conditions eq. 12.1), and the scene each set runs;
//! - `orthogonal`: the orthogonal cut of §12.3 (42CrMo4, a tool moving to −x lifting a
//!   chip of depth f_y) and its sensitivity matrix;
//! - `record`: what a cutting run leaves: the tool force per unit thickness against time
//!   and relative feed, its snapshots, and the run's record (points, steps, wall time,
//!   how far it got and, for a run that stopped, why);
//! - `orthogonal_result`: an orthogonal run read back: filtered forces, their steady
//!   values and drift, the filter's noise, the shear angle per snapshot;
//! - `shear_angle`: the shear angle φ_s measured from the chip's flow, from its thickness
//!   and from the plastic strain rate field;
//! - `merchant`: Merchant's cutting force from the measured shear angle with the JC flow
//!   stress of the shear zone, an independent check of the force level;
//! - `repeatability`: mean, sample standard deviation and CV(t) of a force over runs that
//!   differ in the grid shift's seed.
//!
//! Every value the thesis gives only in a figure is chosen here once, with its reason, and
//! kept the same across the sets compared.

pub mod merchant;
pub mod orthogonal;
pub mod orthogonal_result;
pub mod record;
pub mod repeatability;
pub mod shear_angle;
pub mod vertical;
pub mod workpiece;

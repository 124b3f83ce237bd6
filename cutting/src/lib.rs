//! Metal cutting with the explicit MPM (Maassen 2023, chapter 12): plane-strain cuts of a
//! Johnson-Cook workpiece by a rigid tool, without damage, adiabatic, with Coulomb contact.
//!
//! - `vertical`: the vertical cut of §12.2 (Al 7075-T6, a punch moving down past a die
//!   edge), its discretization sets of table 12.2 (S: no grid shift, grid conditions; G:
//!   grid shift dx/2, spring conditions eq. 12.1), and the scene each set runs;
//! - `record`: what a cutting run leaves: the tool force per unit thickness against time
//!   and relative feed, the feed reached and, for a run that stopped, why;
//! - `shear_angle`: the shear angle φ_s measured from the plastic strain rate field.
//!
//! Every value the thesis gives only in a figure is chosen here once, with its reason, and
//! kept the same across the sets compared.

pub mod record;
pub mod shear_angle;
pub mod vertical;

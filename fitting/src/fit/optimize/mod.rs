//! The optimizers on an `Objective`: Levenberg-Marquardt with the exact AD Jacobian or
//! differences (`lm`), Nelder-Mead from argmin (`nelder_mead`); a fit's stages and starts
//! (`run`), what each run leaves behind (`trace`) and how many iterations one still needs
//! (`estimate`).

pub mod estimate;
pub mod lm;
pub mod nelder_mead;
pub mod run;
pub mod trace;

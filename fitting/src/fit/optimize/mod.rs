//! The optimizers on an `Objective`: Levenberg-Marquardt with the exact AD Jacobian or
//! differences (`lm`), Nelder-Mead from argmin (`nelder_mead`); a fit's stages and starts
//! (`run`) and what each run leaves behind (`trace`).

pub mod lm;
pub mod nelder_mead;
pub mod run;
pub mod trace;

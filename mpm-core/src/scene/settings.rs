//! Solver settings from the scene's `[grid]`, `[time]` and `[solver]` tables.

use super::check::Check;
use super::spec::SceneFile;
use super::SceneError;
use crate::kinematics::Kinematics;
use crate::shape::ShapeFunction;
use crate::solver::{Scheme, Settings};
use crate::viscosity::BulkViscosity;
use nalgebra::SVector;

pub(super) fn settings<const D: usize>(
    spec: &SceneFile,
    kinematics: Kinematics,
    check: &Check,
) -> Result<Settings<D>, SceneError> {
    let mut settings = Settings::<D>::new(
        kinematics,
        check.positive("grid.spacing", spec.grid.spacing)?,
    );
    if let Some(o) = &spec.grid.origin {
        settings.origin = check.vector("grid.origin", o)?;
    }
    if let Some(a) = &spec.grid.shift {
        let a: SVector<f64, D> = check.vector("grid.shift", a)?;
        if a.iter().any(|x| *x < 0.0) {
            return Err(check.err("grid.shift", "amplitudes must be >= 0"));
        }
        if kinematics == Kinematics::Axisymmetric && a[0] != 0.0 {
            return Err(check.err(
                "grid.shift",
                "the radial amplitude must be 0 in an axisymmetric scene (the axis is a grid line)",
            ));
        }
        settings.grid_shift = Some((a, spec.grid.seed));
    }
    settings.dt = spec
        .time
        .dt
        .map(|dt| check.positive("time.dt", dt))
        .transpose()?;
    if let Some(s) = spec.time.safety {
        settings.safety = check.positive("time.safety", s)?;
    }
    settings.scheme = match spec.time.scheme.as_deref().unwrap_or("musl") {
        "usl" => Scheme::Usl,
        "usf" => Scheme::Usf,
        "musl" => Scheme::Musl,
        other => {
            return Err(check.err(
                "time.scheme",
                format!("`{other}` is not one of usl, usf, musl"),
            ))
        }
    };
    let sv = &spec.solver;
    if let Some(d) = sv.damping {
        settings.damping = check.non_negative("solver.damping", d)?;
    }
    if let Some(c) = sv.mass_cutoff {
        settings.mass_cutoff = check.non_negative("solver.mass_cutoff", c)?;
    }
    if let Some(b) = &sv.body_force {
        settings.body_force = check.vector("solver.body_force", b)?;
    }
    if let Some(d) = &sv.domain {
        settings.domain = Some(check.boxed("solver.domain", d)?);
    }
    if let Some(f) = sv.blowup_factor {
        settings.blowup_factor = check.positive("solver.blowup_factor", f)?;
    }
    if let Some([linear, quadratic]) = sv.bulk_viscosity {
        check.non_negative("solver.bulk_viscosity[0]", linear)?;
        check.non_negative("solver.bulk_viscosity[1]", quadratic)?;
        settings.bulk_viscosity =
            (linear > 0.0 || quadratic > 0.0).then_some(BulkViscosity { linear, quadratic });
    }
    if let Some(beta) = sv.pic_fraction {
        if !(0.0..=1.0).contains(&beta) {
            return Err(check.err(
                "solver.pic_fraction",
                format!("{beta} is not a fraction from 0 (FLIP) to 1 (PIC)"),
            ));
        }
        settings.pic_fraction = beta;
    }
    settings.shape_function = match &sv.shape_function {
        Some(name) => name
            .parse()
            .map_err(|e: String| check.err("solver.shape_function", e))?,
        None => ShapeFunction::SCENE_DEFAULT,
    };
    Ok(settings)
}

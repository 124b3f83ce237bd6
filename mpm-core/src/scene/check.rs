//! Field checks of a scene description: each error names the file and the field
//! (`bodies[1].shape.radius`) and what was expected; `scene::load` adds the line.

use super::spec::BoxSpec;
use super::SceneError;
use nalgebra::SVector;
use std::path::Path;

/// Field-checking context: names the file and builds errors.
pub(super) struct Check<'a> {
    pub file: &'a Path,
}

impl Check<'_> {
    pub fn err(&self, field: impl Into<String>, problem: impl Into<String>) -> SceneError {
        SceneError::Field {
            file: self.file.into(),
            at: None,
            field: field.into(),
            problem: problem.into(),
        }
    }
    pub fn positive(&self, field: &str, v: f64) -> Result<f64, SceneError> {
        if v > 0.0 && v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(field, format!("must be a positive number, got {v}")))
        }
    }
    pub fn non_negative(&self, field: &str, v: f64) -> Result<f64, SceneError> {
        if v >= 0.0 && v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(field, format!("must be >= 0, got {v}")))
        }
    }
    pub fn vector<const D: usize>(
        &self,
        field: &str,
        v: &[f64],
    ) -> Result<SVector<f64, D>, SceneError> {
        if v.len() != D {
            return Err(self.err(field, format!("needs {D} components, got {}", v.len())));
        }
        if v.iter().any(|x| !x.is_finite()) {
            return Err(self.err(field, "components must be finite"));
        }
        Ok(SVector::from_column_slice(v))
    }
    pub fn axis<const D: usize>(&self, field: &str, name: &str) -> Result<usize, SceneError> {
        match ["x", "y", "z"][..D].iter().position(|a| *a == name) {
            Some(i) => Ok(i),
            None => Err(self.err(
                field,
                format!(
                    "unknown axis `{name}` (use one of x, y{})",
                    if D == 3 { ", z" } else { "" }
                ),
            )),
        }
    }
    pub fn boxed<const D: usize>(
        &self,
        field: &str,
        b: &BoxSpec,
    ) -> Result<(SVector<f64, D>, SVector<f64, D>), SceneError> {
        self.corners(field, &b.min, &b.max)
    }

    /// The lower and upper corners `min`, `max` of a box.
    pub fn corners<const D: usize>(
        &self,
        field: &str,
        min: &[f64],
        max: &[f64],
    ) -> Result<(SVector<f64, D>, SVector<f64, D>), SceneError> {
        let (lo, hi) = (
            self.vector::<D>(&format!("{field}.min"), min)?,
            self.vector::<D>(&format!("{field}.max"), max)?,
        );
        if (0..D).any(|i| lo[i] >= hi[i]) {
            return Err(self.err(field, "min must be below max in every direction"));
        }
        Ok((lo, hi))
    }
}

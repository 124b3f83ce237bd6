//! A discretized model made once and run many times (the fitting loop's use): the
//! particles, conditions, rigid bodies and settings of a solver before its first step.
//! `instantiate` clones it and gives named bodies new materials (new parameters,
//! `Solver::set_material`: history reset, masses m = ρ V0), without re-reading or
//! re-discretizing anything. A template is `Sync`: many solvers can be instantiated from
//! one in parallel.

use crate::solver::Solver;
use materials::Material;
use std::sync::Arc;
use thiserror::Error;

#[derive(Debug, Error, PartialEq)]
pub enum TemplateError {
    #[error("the model has no body named `{name}` (its bodies: {bodies})")]
    UnknownBody { name: String, bodies: String },
    #[error("a template is made from a model before its first step; this one is at step {0}")]
    Started(usize),
}

#[derive(Clone)]
pub struct Template<const D: usize> {
    model: Solver<D>,
}

impl<const D: usize> Template<D> {
    /// Keep `model` (not yet stepped) as a template.
    pub fn new(model: Solver<D>) -> Result<Self, TemplateError> {
        if model.step > 0 {
            return Err(TemplateError::Started(model.step));
        }
        Ok(Template { model })
    }

    /// The model as discretized.
    pub fn model(&self) -> &Solver<D> {
        &self.model
    }

    /// A new solver with the given bodies made of new materials (by body name); the
    /// other bodies keep theirs. Call `initialize` on it before stepping.
    pub fn instantiate(
        &self,
        materials: &[(&str, Arc<dyn Material>)],
    ) -> Result<Solver<D>, TemplateError> {
        let mut s = self.model.clone();
        for (name, material) in materials {
            let Some(block) = s.blocks.iter().position(|b| b.name == *name) else {
                return Err(TemplateError::UnknownBody {
                    name: name.to_string(),
                    bodies: s
                        .blocks
                        .iter()
                        .map(|b| b.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", "),
                });
            };
            s.set_material(block, material.clone());
        }
        Ok(s)
    }
}

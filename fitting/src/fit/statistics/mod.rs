//! What a fit can be trusted for: specimen scatter within groups (`scatter`), the
//! bootstrap over records (`bootstrap`), leave-one-group-out prediction
//! (`cross_validation`), the parameter pairs the data do not identify (`identifiability`),
//! and what the fitted values owe to the model's fixed assumptions (`assumptions`).

pub mod assumptions;
pub mod bootstrap;
pub mod cross_validation;
pub mod identifiability;
pub mod scatter;

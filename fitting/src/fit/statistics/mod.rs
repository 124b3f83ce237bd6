//! What a fit can be trusted for: specimen scatter within groups (`scatter`), the
//! bootstrap over records (`bootstrap`), leave-one-group-out prediction
//! (`cross_validation`), the parameter pairs the data do not identify (`identifiability`),
//! what the fitted values owe to the model's fixed assumptions (`assumptions`), and which
//! flow-stress law predicts best (`model_choice`), and which test to run next (`design`).

pub mod assumptions;
pub mod bootstrap;
pub mod cross_validation;
pub mod design;
pub mod identifiability;
pub mod model_choice;
pub mod scatter;

//! Shared fixtures of the materials tests.

use materials::{load_material, AnyModel, ElastoPlastic};

pub fn aisi_4340() -> ElastoPlastic {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/materials/aisi_4340.toml");
    match load_material(path).unwrap().model {
        AnyModel::ElastoPlastic(m) => m,
        AnyModel::NeoHooke(_) => unreachable!(),
    }
}

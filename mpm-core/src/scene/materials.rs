//! Materials of a scene: a parameter file (relative to the scene), the same contents
//! inline as `parameters`, or a Neo-Hooke solid by its three constants.

use super::check::Check;
use super::spec::SceneFile;
use super::SceneError;
use materials::param_file::parse_material;
use materials::{load_material, AnyModel, NeoHooke};
use std::collections::HashMap;
use std::path::Path;

/// A material given inline: checked as a parameter file would be, named by the field.
fn inline(table: &toml::Table, check: &Check, field: &str) -> Result<AnyModel<f64>, SceneError> {
    let label = format!("{}: {field}.parameters", check.file.display());
    let text = toml::to_string(table)
        .map_err(|e| check.err(format!("{field}.parameters"), e.to_string()))?;
    parse_material(&text, Path::new(&label))
        .map(|m| m.model)
        .map_err(|e| check.err(format!("{field}.parameters"), e.to_string()))
}

/// Every material of the scene by name (the model itself: a derivative pass seeds its
/// parameters, `solver::Tangent`).
pub(super) fn materials<'s>(
    spec: &'s SceneFile,
    check: &Check,
    dir: &Path,
) -> Result<HashMap<&'s str, AnyModel>, SceneError> {
    let mut materials: HashMap<&str, AnyModel> = HashMap::new();
    for (k, m) in spec.materials.iter().enumerate() {
        let field = format!("materials[{k}]");
        let material = match (&m.file, &m.neo_hooke, &m.parameters) {
            (Some(f), None, None) => {
                load_material(dir.join(f))
                    .map_err(|e| check.err(format!("{field}.file"), e.to_string()))?
                    .model
            }
            (None, None, Some(table)) => inline(table, check, &field)?,
            (None, Some(n), None) => {
                check.positive(&format!("{field}.neo_hooke.E"), n.e)?;
                check.positive(&format!("{field}.neo_hooke.rho"), n.rho)?;
                if !(-1.0 < n.nu && n.nu < 0.5) {
                    return Err(check.err(
                        format!("{field}.neo_hooke.nu"),
                        format!("must be in (-1, 0.5), got {}", n.nu),
                    ));
                }
                AnyModel::NeoHooke(NeoHooke::new(n.e, n.nu, n.rho))
            }
            _ => {
                return Err(check.err(
                    field,
                    "give exactly one of `file`, `neo_hooke` or `parameters`",
                ))
            }
        };
        if materials.insert(m.name.as_str(), material).is_some() {
            return Err(check.err(
                format!("{field}.name"),
                format!("`{}` is defined twice", m.name),
            ));
        }
    }

    Ok(materials)
}

//! The materials rows of `mpw verify` (conformance of every model, figure 4.5, the
//! iso-error maps): the application's catalogue, not the materials library. Each study
//! gives both numbers (`Row` rows) and data for charts.

pub mod conformance;
pub mod figure_4_5;
pub mod iso_error;

use crate::verify::row::Row;
use crate::verify::Inputs;
use materials::flow_stress::{FlowStress, Voce};
use materials::param_file::{load_elasto_plastic, load_material, ParamFileError};
use materials::plasticity::{ElastoPlastic, ReturnMap};
use materials::AnyModel;
use std::path::Path;

/// The J2 model of the studies: Voce saturation and linear hardening on the 6061-T6
/// elastic constants, so every term of eq. 4.51 is exercised.
pub fn j2_voce(dir: &Path) -> Result<ElastoPlastic, ParamFileError> {
    let mut j2 = load_elasto_plastic(dir.join("al6061_t6.toml"))?;
    j2.flow = FlowStress::Voce(Voce {
        tau0: 300e6,
        tau_inf: 450e6,
        eta: 12.0,
        h: 1e8,
    });
    Ok(j2)
}

/// One law of each factor of `flow_stress::composed`: the shipped composed files, and the
/// exponential softening (no shipped file has it) on the Cowper-Symonds one.
fn composed_laws(dir: &Path) -> Result<Vec<ElastoPlastic>, ParamFileError> {
    let mut laws = Vec::new();
    for file in [
        "ss304l_huh_kang.toml",
        "ss304l_cowper_symonds.toml",
        "ss304l_power_voce.toml",
        "steel_945_voce.toml",
    ] {
        laws.push(load_elasto_plastic(dir.join(file))?);
    }
    laws.push(materials::conformance::with_exponential_softening(&laws[1]));
    Ok(laws)
}

/// Every materials row of `mpw verify` (`full`: the finer iso-error map).
pub fn rows(inputs: &Inputs) -> anyhow::Result<Vec<Row>> {
    Ok(cases(&inputs.data.materials(), inputs.full)?)
}

/// The rows on the parameter sets in `dir` (`data/materials`).
fn cases(dir: &Path, full: bool) -> Result<Vec<Row>, ParamFileError> {
    let neo_hooke = match load_material(dir.join("aisi_52100.toml"))?.model {
        AnyModel::NeoHooke(m) => m,
        AnyModel::ElastoPlastic(_) => {
            return Err(ParamFileError::Field {
                file: dir.join("aisi_52100.toml"),
                at: None,
                field: "model".into(),
                problem: "expected \"neo-hooke\" for the hyperelastic rows".into(),
            })
        }
    };
    let j2 = j2_voce(dir)?;
    let jc = load_elasto_plastic(dir.join("42crmo4_qt660.toml"))?;
    let with = |m: &ElastoPlastic, rm| ElastoPlastic {
        return_map: rm,
        ..*m
    };

    let mut out = conformance::check_model("neo-hooke", &neo_hooke);
    out.push(conformance::check_energy(&neo_hooke));
    for (name, m) in [("j2", &j2), ("johnson-cook", &jc)] {
        for (label, rm) in [
            ("reference", ReturnMap::Reference),
            ("fast", ReturnMap::Principal),
        ] {
            out.extend(conformance::check_model(
                &format!("{name} {label}"),
                &with(m, rm),
            ));
        }
        out.extend(conformance::check_plastic(name, m));
        out.push(conformance::check_returns_agree(
            name,
            &with(m, ReturnMap::Reference),
            &with(m, ReturnMap::Principal),
        ));
    }
    out.extend(conformance::check_uniaxial("johnson-cook", "eq. 4.52", &jc));
    out.push(conformance::check_path_sensitivities("johnson-cook", &jc));
    for m in composed_laws(dir)? {
        let name = m.flow.describe();
        out.extend(conformance::check_model(&name, &m));
        out.extend(conformance::check_plastic(&name, &m));
        out.push(conformance::check_returns_agree(
            &name,
            &with(&m, ReturnMap::Reference),
            &with(&m, ReturnMap::Principal),
        ));
        out.extend(conformance::check_uniaxial(&name, "its τ_y", &m));
        out.push(conformance::check_path_sensitivities(&name, &m));
    }

    let aisi_4340 = load_elasto_plastic(dir.join("aisi_4340.toml"))?;
    let curves = figure_4_5::run(&aisi_4340).expect("figure 4.5 paths");
    out.extend(figure_4_5::cases(&aisi_4340, &curves));

    let multiples: Vec<f64> = if full {
        (0..=20).map(|k| 5.0 * k as f64).collect()
    } else {
        vec![0.0, 1.0, 3.0, 10.0, 27.0, 100.0]
    };
    out.extend(iso_error::cases(
        "j2",
        &iso_error::run(&j2, &multiples),
        true,
    ));
    out.extend(iso_error::cases(
        "johnson-cook",
        &iso_error::run(&jc, &multiples),
        false,
    ));
    Ok(out)
}

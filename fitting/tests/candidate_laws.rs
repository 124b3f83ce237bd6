//! A set with `[[candidate]]` laws: each candidate is the set with its own material and
//! free parameters (bounds from its own entries first, then the set's), the same
//! experiments; what is missing or contradictory is named.

use fitting::fit::sets::fit_set::FitSet;
use materials::FlowStress;
use std::path::{Path, PathBuf};

/// The shipped synthetic set with `extra` appended, written into a temporary folder with
/// absolute paths.
fn set_with(extra: &str, name: &str) -> PathBuf {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data");
    let experiments = data.join("experiments").canonicalize().unwrap();
    let materials = data.join("materials").canonicalize().unwrap();
    let set = std::fs::read_to_string(experiments.join("default.toml")).unwrap();
    let set = set
        .replace("file = \"", &format!("file = \"{}/", experiments.display()))
        .replace(
            "material = \"../materials/",
            &format!("material = \"{}/", materials.display()),
        );
    let extra = extra.replace("MATERIALS", &materials.display().to_string());
    let dir = std::env::temp_dir().join(format!("mpw-candidates-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("set.toml");
    std::fs::write(&file, set + &extra).unwrap();
    file
}

const HUH_KANG: &str = r#"
[[candidate]]
name = "Huh-Kang rate"
material = "MATERIALS/ss304l_huh_kang.toml"
free = ["A", "B", "N", "C", "C2"]

[[candidate.parameter]]
name = "C"
lower = 0.0
upper = 0.1
start = 0.004

[[candidate.parameter]]
name = "C2"
lower = 0.0
upper = 0.05
start = 0.001
"#;

#[test]
fn each_candidate_is_the_set_with_its_own_law_and_free_parameters() {
    let file = set_with(HUH_KANG, "ok");
    let sets = FitSet::load_candidates(&file).unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!(sets.len(), 2);
    assert!(matches!(sets[0].base.flow, FlowStress::JohnsonCook(_)));
    let FlowStress::Composed(law) = sets[1].base.flow else {
        panic!("the candidate's law")
    };
    assert_eq!(law.describe(), "power × huh-kang × johnson-cook");
    let names: Vec<&str> = sets[1].params.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["A", "B", "N", "C", "C2"]);
    let c = &sets[1].params[3];
    assert_eq!(
        (c.lower, c.upper),
        (0.0, 0.1),
        "the candidate's own bounds first"
    );
    let a_set = sets[0].params.iter().find(|p| p.name == "A").unwrap();
    let a_candidate = &sets[1].params[0];
    assert_eq!(
        (a_set.lower, a_set.upper),
        (a_candidate.lower, a_candidate.upper)
    );
    assert_eq!(sets[0].blocks.len(), sets[1].blocks.len());
    assert!(
        sets[1].name.ends_with(": Huh-Kang rate"),
        "{}",
        sets[1].name
    );
}

fn error_of(file: &Path) -> String {
    match FitSet::load_candidates(file) {
        Ok(_) => panic!("{} accepted", file.display()),
        Err(e) => format!("{e:#}"),
    }
}

#[test]
fn a_candidate_without_bounds_or_with_stages_is_refused_by_name() {
    let no_bounds = HUH_KANG.replace("name = \"C2\"\n", "name = \"Q\"\n");
    let err = error_of(&set_with(&no_bounds, "bounds"));
    assert!(
        err.contains("[[candidate]] \"Huh-Kang rate\"") && err.contains("no bounds for `C2`"),
        "{err}"
    );
    let staged = format!("{HUH_KANG}\n[[stage]]\nfree = [\"A\"]\nexperiments = [\"qs_tension\"]\n");
    let err = error_of(&set_with(&staged, "stages"));
    assert!(err.contains("remove the [[stage]] entries"), "{err}");
}

//! Every materials row of `mpw verify` must pass: conformance of each model (zero
//! stress, symmetry, objectivity, AD tangent and parameter sensitivities against finite
//! differences, incompressibility, unloading slope, energy derivative), reference vs
//! fast return, the analytic JC curve, path sensitivities, figure 4.5 and the iso-error
//! bound.

use materials::studies::verify_cases;
use std::path::Path;

#[test]
fn all_materials_verification_cases_pass() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/materials");
    let cases = verify_cases(&dir, false).unwrap();
    assert!(cases.len() > 40, "only {} cases", cases.len());
    for c in &cases {
        println!("{c}");
    }
    let failed: Vec<String> = cases
        .iter()
        .filter(|c| !c.passed)
        .map(|c| c.to_string())
        .collect();
    assert!(failed.is_empty(), "failed:\n{}", failed.join("\n"));
}

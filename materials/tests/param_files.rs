//! Parameter files: every shipped set loads; bad fields are errors naming file, line,
//! field and allowed range.

use materials::param_file::parse_material;
use materials::{load_material, Model};
use std::path::Path;

fn data_dir() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/materials")
}

#[test]
fn every_shipped_set_loads_with_its_table_values() {
    let expect = [
        ("aisi_4340.toml", "A", 792e6),
        ("42crmo4_qt660.toml", "B", 1531e6),
        ("al7075_t6.toml", "N", 0.71),
        ("ofhc_copper.toml", "C", 0.025),
        ("aisi_52100.toml", "E", 200e9),
        ("al6061_t6.toml", "tau0", 300e6),
    ];
    for (file, name, value) in expect {
        let m = load_material(data_dir().join(file)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(m.model.param(name), Some(value), "{file}: {name}");
    }
}

const GOOD: &str = r#"
name = "test"
model = "johnson-cook"
[elastic]
E = 200e9
nu = 0.3
rho = 7800.0
[johnson_cook]
A = 800e6
B = 500e6
N = 0.3
C = 0.01
M = 1.0
alpha_dot0 = 1.0
theta_m = 1700.0
[thermal]
theta0 = 293.15
c_theta = 460.0
alpha_sigma = 1.2e-5
gamma_tq = 0.9
"#;

fn error_of(text: &str) -> String {
    error_of_named(text, "bad.toml")
}

fn error_of_named(text: &str, file: &str) -> String {
    match parse_material(text, Path::new(file)) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_fields_are_named_with_the_allowed_range() {
    assert!(parse_material(GOOD, Path::new("good.toml")).is_ok());
    let cases = [
        (
            GOOD.replace("E = 200e9", "E = -200e9"),
            "elastic.E",
            "[1000000000, 1000000000000]",
            5,
        ),
        // a Johnson-Cook material is a metal: values in the wrong unit are named with the
        // likely mistake (E = 224.2 ran and gave σ = 0)
        (
            GOOD.replace("E = 200e9", "E = 224.2"),
            "elastic.E",
            "GPa or MPa given?",
            5,
        ),
        (
            GOOD.replace("rho = 7800.0", "rho = 7.8"),
            "elastic.rho",
            "g/cm^3 given?",
            7,
        ),
        (
            GOOD.replace("A = 800e6", "A = 800"),
            "johnson_cook.A",
            "MPa given?",
            9,
        ),
        (
            GOOD.replace("B = 500e6", "B = 5e12"),
            "johnson_cook.B",
            "[0, 10000000000]",
            10,
        ),
        (
            GOOD.replace("nu = 0.3", "nu = 0.5"),
            "elastic.nu",
            "(-1, 0.5)",
            6,
        ),
        (
            GOOD.replace("theta_m = 1700.0", "theta_m = 200.0"),
            "johnson_cook.theta_m",
            "(293.15, inf)",
            15,
        ),
        (
            GOOD.replace("gamma_tq = 0.9", "gamma_tq = 1.5"),
            "thermal.gamma_tq",
            "[0, 1]",
            20,
        ),
        (
            GOOD.replace("C = 0.01", "C = 0.01\nD = 3.0"),
            "johnson_cook.D",
            "unknown key",
            13,
        ),
        (
            GOOD.replace("M = 1.0\n", ""),
            "johnson_cook.M",
            "missing",
            8,
        ),
        (
            GOOD.replace("rho = 7800.0", "rho = \"heavy\""),
            "elastic.rho",
            "expected a number",
            7,
        ),
        (
            GOOD.replace("johnson-cook", "drucker-prager"),
            "model",
            "unknown model",
            3,
        ),
    ];
    for (text, field, what, line) in cases {
        let e = error_of(&text);
        assert!(
            e.starts_with(&format!("bad.toml:{line}:"))
                && e.contains(&format!(": `{field}`: "))
                && e.contains(what),
            "got: {e}"
        );
    }
}

/// A missing file names the path and the OS reason once: the reason is in the message and
/// not also a `source()` that error reporters append again.
#[test]
fn unreadable_file_names_path_and_reason_once() {
    let err = load_material("no/such/material.toml").unwrap_err();
    let message = err.to_string();
    assert!(
        message.starts_with("no/such/material.toml: cannot read: "),
        "{message}"
    );
    assert!(std::error::Error::source(&err).is_none(), "{message}");
}

/// The parameter table says in which section of a file each parameter stands: a
/// Johnson-Cook file written from the table alone (every elastic, johnson_cook and
/// thermal entry in its section, with 42CrMo4's values) reads back the same material.
#[test]
fn a_file_written_from_the_parameter_table_reads_back() {
    use materials::parameters::TABLE;
    let m = load_material(data_dir().join("42crmo4_qt660.toml"))
        .unwrap()
        .model;
    let mut text = String::from("name = \"from the table\"\nmodel = \"johnson-cook\"\n");
    for section in ["elastic", "johnson_cook", "thermal"] {
        text += &format!("[{section}]\n");
        for p in TABLE.iter().filter(|p| p.section == section) {
            let value = m.param(p.name).unwrap_or_else(|| panic!("no {}", p.name));
            text += &format!("{} = {value:e}\n", p.name);
        }
    }
    let back = parse_material(&text, Path::new("table.toml")).unwrap_or_else(|e| panic!("{e}"));
    for p in (TABLE.iter()).filter(|p| ["elastic", "johnson_cook", "thermal"].contains(&p.section))
    {
        assert_eq!(back.model.param(p.name), m.param(p.name), "{}", p.name);
    }
}

const COMPOSED: &str = r#"
name = "composed"
model = "composed"
[elastic]
E = 200e9
nu = 0.3
rho = 7800.0
[hardening]
law = "power-voce"
A = 800e6
B = 500e6
N = 0.3
Q = 100e6
beta = 20.0
[rate]
law = "huh-kang"
C = 0.01
C2 = 0.001
alpha_dot0 = 1.0
[softening]
law = "exponential"
lambda_theta = 1e-3
theta_m = 1700.0
[thermal]
theta0 = 293.15
c_theta = 460.0
alpha_sigma = 1.2e-5
gamma_tq = 0.9
"#;

/// A composed law reads each factor's law and parameters; the JC-equivalent composition
/// gives the flow stress of the JC file to round-off.
#[test]
fn a_composed_law_reads_its_three_factors() {
    use materials::flow_stress::FlowStress;
    use materials::AnyModel;
    let m = parse_material(COMPOSED, Path::new("c.toml")).unwrap_or_else(|e| panic!("{e}"));
    let AnyModel::ElastoPlastic(m) = m.model else {
        panic!("elasto-plastic")
    };
    let FlowStress::Composed(law) = m.flow else {
        panic!("composed")
    };
    assert_eq!(
        law.describe(),
        "power-voce × huh-kang × exponential",
        "{law:?}"
    );
    assert_eq!(m.param("C2"), Some(0.001));
    assert_eq!(m.param("lambda_theta"), Some(1e-3));
    let jc_text = COMPOSED
        .replace("law = \"power-voce\"", "law = \"power\"")
        .replace("Q = 100e6\nbeta = 20.0\n", "")
        .replace("law = \"huh-kang\"", "law = \"johnson-cook\"")
        .replace("C2 = 0.001\n", "")
        .replace(
            "law = \"exponential\"\nlambda_theta = 1e-3",
            "law = \"johnson-cook\"\nM = 1.0",
        );
    let composed = parse_material(&jc_text, Path::new("jc.toml")).unwrap_or_else(|e| panic!("{e}"));
    let jc = parse_material(GOOD, Path::new("good.toml")).unwrap();
    let (AnyModel::ElastoPlastic(a), AnyModel::ElastoPlastic(b)) = (composed.model, jc.model)
    else {
        panic!("elasto-plastic")
    };
    for (alpha, rate, theta) in [(0.1, 1e3, 500.0), (0.0, 0.0, 293.15), (0.5, 10.0, 1200.0)] {
        let (x, y) = (
            a.flow.tau_y(alpha, rate, theta, 293.15),
            b.flow.tau_y(alpha, rate, theta, 293.15),
        );
        assert!((x - y).abs() <= 1e-15 * y, "{x} vs {y}");
    }
}

/// A factor's law and its parameters are checked like every other field: unknown or
/// missing law, a parameter of another law, a value out of range, each named at its key.
#[test]
fn a_composed_law_names_what_is_wrong() {
    let cases = [
        (
            COMPOSED.replace("law = \"huh-kang\"", "law = \"huh_kang\""),
            "c.toml:16:1: `rate.law`: unknown law \"huh_kang\"; expected one of \"none\", \"johnson-cook\", \"huh-kang\", \"cowper-symonds\"",
        ),
        (
            COMPOSED.replace("law = \"power-voce\"\n", ""),
            "c.toml:8:1: `hardening.law`: missing; expected one of \"power\", \"voce\", \"power-voce\"",
        ),
        (
            COMPOSED.replace("law = \"huh-kang\"", "law = \"johnson-cook\""),
            "`rate.C2`: unknown key; allowed: C, alpha_dot0",
        ),
        (
            COMPOSED.replace("lambda_theta = 1e-3", "lambda_theta = 1.5"),
            "`softening.lambda_theta`: value 1.5 outside the allowed range [0, 0.1]",
        ),
        (
            COMPOSED.replace("theta_m = 1700.0", "theta_m = 200.0"),
            "`softening.theta_m`: value 200 outside the allowed range (293.15, inf): the melting temperature in K, above theta0",
        ),
        (
            COMPOSED.replace("[softening]", "[johnson_cook]"),
            "`johnson_cook`: unknown key for model \"composed\"",
        ),
    ];
    for (text, expected) in cases {
        let message = error_of_named(&text, "c.toml");
        assert!(
            message.contains(expected),
            "{message}\nexpected: {expected}"
        );
    }
}

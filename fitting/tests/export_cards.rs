//! Exported Johnson-Cook cards read back: every field of the Abaqus block and of the JSON
//! card, converted back to SI, equals the material's value (to 1e-14 relative: one
//! multiplication and one division by the unit factor), in every unit system; the LS-DYNA
//! card's 10-character fields to the precision of 9 written characters.

use fitting::export::{abaqus, field10, json, lsdyna, Provenance, UNIT_SYSTEMS};
use fitting::fit::levels::model::Material;
use materials::material::Model;
use std::path::Path;

fn material(file: &str) -> Material {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/materials");
    materials::load_elasto_plastic(dir.join(file)).unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-14 * b.abs()
}

/// The numbers on the data line after the keyword line that starts with `keyword`.
fn data_line(card: &str, keyword: &str) -> Vec<f64> {
    let mut lines = card.lines();
    lines
        .find(|l| l.starts_with(keyword))
        .unwrap_or_else(|| panic!("no {keyword}"));
    lines
        .next()
        .unwrap()
        .split(',')
        .map(str::trim)
        .filter(|f| !f.is_empty())
        .map(|f| f.parse().unwrap_or_else(|_| panic!("{keyword}: {f}")))
        .collect()
}

#[test]
fn abaqus_block_reads_back_in_every_unit_system() {
    for file in ["ss304l.toml", "aisi_4340.toml", "ofhc_copper.toml"] {
        let m = material(file);
        let p = |n: &str| m.param(n).unwrap();
        for u in UNIT_SYSTEMS {
            let card = abaqus(&m, "X", &Provenance::named(file), &u).unwrap();
            assert!(
                card.contains(&format!("units: {}", u.description)),
                "{card}"
            );
            let check = |keyword: &str, expected: &[f64]| {
                let got = data_line(&card, keyword);
                assert_eq!(got.len(), expected.len(), "{file} {} {keyword}", u.name);
                for (g, e) in got.iter().zip(expected) {
                    assert!(close(*g, *e), "{file} {} {keyword}: {g} vs {e}", u.name);
                }
            };
            let s = u.stress;
            check("*DENSITY", &[p("rho") * u.density]);
            check("*ELASTIC", &[p("E") * s, p("nu")]);
            check("*EXPANSION", &[p("alpha_sigma")]);
            let plastic = [
                p("A") * s,
                p("B") * s,
                p("N"),
                p("M"),
                p("theta_m"),
                p("theta0"),
            ];
            check("*PLASTIC, HARDENING=JOHNSON COOK", &plastic);
            check(
                "*RATE DEPENDENT, TYPE=JOHNSON COOK",
                &[p("C"), p("alpha_dot0") * u.rate],
            );
            check("*SPECIFIC HEAT", &[p("c_theta") * u.specific_heat]);
            check("*INELASTIC HEAT FRACTION", &[p("gamma_tq")]);
            assert!(card.contains(&format!("*EXPANSION, ZERO={:?}", p("theta0"))));
        }
    }
}

/// `"name": {"value": X, "unit": "U"}` of a JSON card.
fn json_field(card: &str, name: &str) -> (f64, String) {
    let at = card
        .find(&format!("\"{name}\": {{"))
        .unwrap_or_else(|| panic!("no {name}"));
    let rest = &card[at..];
    let value = rest
        .split("\"value\": ")
        .nth(1)
        .unwrap()
        .split(',')
        .next()
        .unwrap();
    let unit = rest
        .split("\"unit\": \"")
        .nth(1)
        .unwrap()
        .split('"')
        .next()
        .unwrap();
    (value.trim().parse().unwrap(), unit.to_string())
}

#[test]
fn json_card_reads_back_with_units() {
    let m = material("ss304l.toml");
    for u in UNIT_SYSTEMS {
        let card = json(&m, "X", &Provenance::named("test"), &u).unwrap();
        for (name, factor, unit) in [
            ("E", u.stress, u.stress_unit),
            ("A", u.stress, u.stress_unit),
            ("B", u.stress, u.stress_unit),
            ("rho", u.density, u.density_unit),
            ("alpha_dot0", u.rate, u.rate_unit),
            ("c_theta", u.specific_heat, u.specific_heat_unit),
            ("theta_m", 1.0, "K"),
            ("N", 1.0, "1"),
            ("C", 1.0, "1"),
            ("M", 1.0, "1"),
            ("gamma_tq", 1.0, "1"),
            ("alpha_sigma", 1.0, "1/K"),
        ] {
            let (v, got_unit) = json_field(&card, name);
            let expected = m.param(name).unwrap() * factor;
            assert!(close(v, expected), "{} {name}: {v} vs {expected}", u.name);
            assert_eq!(got_unit, unit, "{} {name}", u.name);
        }
    }
}

/// A unit conversion's rounding residue does not reach the card: 7850 kg/m³ in t/mm³ is
/// written 7.85e-9, not 7.849999999999999e-9, in every shipped material and unit system.
#[test]
fn converted_values_are_written_without_rounding_residue() {
    for file in [
        "aisi_4340.toml",
        "ss304l.toml",
        "steel_945.toml",
        "ofhc_copper.toml",
    ] {
        let m = material(file);
        for u in UNIT_SYSTEMS {
            for card in [
                abaqus(&m, "X", &Provenance::named("test"), &u).unwrap(),
                json(&m, "X", &Provenance::named("test"), &u).unwrap(),
            ] {
                let residue = card
                    .split(|c: char| !(c.is_ascii_digit() || c == '.'))
                    .any(|word| word.contains("99999999") || word.contains("00000001"));
                assert!(!residue, "{file} in {}:\n{card}", u.name);
            }
        }
    }
    let card = abaqus(
        &material("42crmo4_qt660.toml"),
        "X",
        &Provenance::named("test"),
        &UNIT_SYSTEMS[1],
    )
    .unwrap();
    assert!(card.contains("*DENSITY\n 7.85e-9,"), "{card}");
}

#[test]
fn known_values_in_the_mm_unit_systems() {
    // Hand conversion of the 304L file: E 193 GPa = 193000 MPa, ρ 7900 kg/m³ =
    // 7.9e-9 t/mm³, c 500 J/(kg K) = 5e8 mJ/(t K).
    let m = material("ss304l.toml");
    let u = fitting::export::units("mm-s-tonne").unwrap();
    let card = abaqus(&m, "SS304L", &Provenance::named("test"), &u).unwrap();
    assert_eq!(data_line(&card, "*ELASTIC"), [193000.0, 0.29]);
    assert!(close(data_line(&card, "*DENSITY")[0], 7.9e-9));
    assert!(close(data_line(&card, "*SPECIFIC HEAT")[0], 5e8));
    // mm-ms-kg: E = 193 GPa, ρ = 7.9e-6 kg/mm³, α̇0 = 1e-4 1/s = 1e-7 1/ms, c unchanged.
    let u = fitting::export::units("mm-ms-kg").unwrap();
    let card = abaqus(&m, "SS304L", &Provenance::named("test"), &u).unwrap();
    assert!(close(data_line(&card, "*ELASTIC")[0], 193.0));
    assert!(close(data_line(&card, "*DENSITY")[0], 7.9e-6));
    assert!(close(
        data_line(&card, "*RATE DEPENDENT, TYPE=JOHNSON COOK")[1],
        1e-7
    ));
    assert!(close(data_line(&card, "*SPECIFIC HEAT")[0], 500.0));
    assert!(fitting::export::units("inch").is_err());
}

/// The fixed-format cards (10 characters per field) after the keyword line `keyword`, up
/// to the next keyword.
fn lsdyna_cards(card: &str, keyword: &str) -> Vec<Vec<f64>> {
    card.lines()
        .skip_while(|l| *l != keyword)
        .skip(1)
        .take_while(|l| !l.starts_with('*'))
        .filter(|l| !l.starts_with('$'))
        .map(|l| {
            (0..l.len())
                .step_by(10)
                .map(|i| l[i..(i + 10).min(l.len())].trim())
                .map(|f| f.parse().unwrap_or_else(|_| panic!("{keyword}: {f:?}")))
                .collect()
        })
        .collect()
}

#[test]
fn lsdyna_card_reads_back_in_every_unit_system() {
    for file in ["ss304l.toml", "aisi_4340.toml", "ofhc_copper.toml"] {
        let m = material(file);
        let p = |n: &str| m.param(n).unwrap();
        for u in UNIT_SYSTEMS {
            let card = lsdyna(&m, "X", &Provenance::named(file), &u, 7).unwrap();
            assert!(card.contains(&format!("units: {}", u.description)));
            let (e, nu, s) = (p("E") * u.stress, p("nu"), u.stress);
            let mat = [
                vec![
                    7.0,
                    p("rho") * u.density,
                    e / (2.0 * (1.0 + nu)),
                    e,
                    nu,
                    0.0,
                    1.0,
                    0.0,
                ],
                vec![
                    p("A") * s,
                    p("B") * s,
                    p("N"),
                    p("C"),
                    p("M"),
                    p("theta_m"),
                    p("theta0"),
                    p("alpha_dot0") * u.rate,
                ],
                vec![
                    p("c_theta") * u.specific_heat,
                    -1e20,
                    1.0,
                    0.0,
                    1e20,
                    0.0,
                    0.0,
                    0.0,
                ],
                vec![0.0; 5],
            ];
            let eos = [
                vec![
                    7.0,
                    0.0,
                    e / (3.0 * (1.0 - 2.0 * nu)),
                    0.0,
                    0.0,
                    0.0,
                    0.0,
                    0.0,
                ],
                vec![0.0, 1.0],
            ];
            for (keyword, expected) in [
                ("*MAT_JOHNSON_COOK", &mat[..]),
                ("*EOS_LINEAR_POLYNOMIAL", &eos[..]),
            ] {
                let got = lsdyna_cards(&card, keyword);
                assert_eq!(got.len(), expected.len(), "{file} {} {keyword}", u.name);
                for (g, x) in got.iter().flatten().zip(expected.iter().flatten()) {
                    // 4 significant digits are the least 9 characters hold (d.dddE-xx)
                    assert!(
                        (g - x).abs() <= 5e-4 * x.abs(),
                        "{file} {} {keyword}: {g} vs {x}",
                        u.name
                    );
                }
            }
        }
    }
}

#[test]
fn ten_character_fields_keep_the_digits_they_can() {
    for (x, written) in [
        (207e9, "2.07E11"),
        (7.83e-9, "7.83E-9"),
        (79615.384615, "79615.385"),
        (0.014, "0.014"),
        (-1e20, "-1E20"),
        (1573.15, "1573.15"),
        (1.23456789e-12, "1.235E-12"),
    ] {
        let f = field10(x);
        assert_eq!(f.len(), 10, "{f:?}");
        assert!(f.starts_with(' '), "fields stay apart: {f:?}");
        assert_eq!(f.trim(), written);
    }
}

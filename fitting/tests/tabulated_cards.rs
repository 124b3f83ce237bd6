//! Tabulated cards read back: the Abaqus `*PLASTIC, RATE=` blocks and the LS-DYNA
//! `*DEFINE_TABLE` with its curves, parsed from the written text and converted back to SI,
//! rebuild a table that stays within the stated tolerance of the law off its nodes (in
//! every unit system, for a law no Johnson-Cook card can carry).

use fitting::export::{Provenance, UNIT_SYSTEMS};
use fitting::fit::levels::model::Material;
use fitting::flow_table::{FlowTable, TableRange};
use fitting::tabulated_cards::{abaqus_table, lsdyna_table};
use materials::material::Model;
use std::collections::BTreeMap;
use std::path::Path;

fn material(file: &str) -> Material {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/materials");
    materials::load_elasto_plastic(dir.join(file)).unwrap()
}

const RANGE: TableRange = TableRange {
    strain_max: 1.5,
    rates: [1e-4, 1e5],
    temperatures: [297.04, 1400.0],
    tolerance: 5e-3,
};

/// The numbers of a comma- or space-separated data line.
fn numbers(line: &str) -> Vec<f64> {
    (line.split([',', ' ']))
        .filter(|s| !s.trim().is_empty())
        .map(|s| s.trim().parse().unwrap_or_else(|e| panic!("{line}: {e}")))
        .collect()
}

/// A table from its nodes and a `(temperature, rate, strain) → stress` map.
fn table(points: &BTreeMap<(u64, u64, u64), f64>) -> FlowTable {
    let axis = |pick: fn(&(u64, u64, u64)) -> u64| {
        let mut v: Vec<u64> = points.keys().map(pick).collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let (ts, rs, ss) = (axis(|k| k.0), axis(|k| k.1), axis(|k| k.2));
    let stress = (ts.iter())
        .map(|&t| {
            (rs.iter())
                .map(|&r| ss.iter().map(|&s| points[&(t, r, s)]).collect())
                .collect()
        })
        .collect();
    let back = |v: &[u64]| v.iter().map(|&b| f64::from_bits(b)).collect();
    FlowTable {
        strains: back(&ss),
        rates: back(&rs),
        temperatures: back(&ts),
        stress,
    }
}

#[test]
fn an_abaqus_table_card_reads_back_within_its_tolerance() {
    let m = material("ss304l_cowper_symonds.toml");
    let theta0 = m.param("theta0").unwrap();
    for units in UNIT_SYSTEMS {
        let card = abaqus_table(&m, "T", &Provenance::named("test"), &units, &RANGE).unwrap();
        let mut points = BTreeMap::new();
        let mut rate = None;
        for line in card.lines().filter(|l| !l.starts_with("**")) {
            if let Some(r) = line.strip_prefix("*PLASTIC, RATE=") {
                rate = Some(r.parse::<f64>().unwrap() / units.rate);
            } else if line.starts_with('*') {
                rate = None;
            } else if let Some(r) = rate {
                let v = numbers(line);
                let key = (v[2].to_bits(), r.to_bits(), v[1].to_bits());
                points.insert(key, v[0] / units.stress);
            }
        }
        let t = table(&points);
        assert!(t.rates.len() > 10 && t.temperatures.len() >= 2 && t.rates[0] == 0.0);
        let worst = t.worst_error(&m.flow, theta0);
        assert!(worst <= RANGE.tolerance, "{}: worst {worst:e}", units.name);
    }
}

#[test]
fn an_lsdyna_table_card_reads_back_within_its_tolerance() {
    let m = material("ss304l_cowper_symonds.toml");
    let theta0 = m.param("theta0").unwrap();
    let range = TableRange {
        temperatures: [theta0, theta0],
        ..RANGE
    };
    for units in UNIT_SYSTEMS {
        let card = lsdyna_table(&m, "T", &Provenance::named("test"), &units, 7, &range).unwrap();
        assert!(
            card.contains("WARNING: *MAT_024 has no thermal softening"),
            "{card}"
        );
        let lines: Vec<&str> = card.lines().filter(|l| !l.starts_with('$')).collect();
        let mut curves: BTreeMap<u64, f64> = BTreeMap::new(); // curve id → rate
        let mut points = BTreeMap::new();
        let mut k = 0;
        while k < lines.len() {
            match lines[k] {
                "*DEFINE_TABLE" => {
                    assert_eq!(numbers(lines[k + 1])[0], 7000.0);
                    k += 2;
                    while !lines[k].starts_with('*') {
                        let v = numbers(lines[k]);
                        curves.insert(v[1] as u64, v[0] / units.rate);
                        k += 1;
                    }
                }
                "*DEFINE_CURVE" => {
                    let id = numbers(lines[k + 1])[0] as u64;
                    let rate = curves[&id];
                    k += 2;
                    while k < lines.len() && !lines[k].starts_with('*') {
                        let v = numbers(lines[k]);
                        points.insert(
                            (theta0.to_bits(), rate.to_bits(), v[0].to_bits()),
                            v[1] / units.stress,
                        );
                        k += 1;
                    }
                }
                _ => k += 1,
            }
        }
        let t = table(&points);
        assert_eq!(t.rates.len(), curves.len());
        let worst = t.worst_error(&m.flow, theta0);
        assert!(worst <= range.tolerance, "{}: worst {worst:e}", units.name);
    }
}

//! The figure 4.5 reproduction and the iso-error bound, as tests (the same rows
//! `mpw verify` prints).

mod common;
use common::*;
use materials::studies::{figure_4_5, iso_error};
use materials::ReturnMap;

#[test]
fn figure_4_5_reproduction() {
    let m = aisi_4340();
    assert_eq!(m.thermal.gamma_tq, 0.0, "figure 4.5 runs without heating");
    let curves = figure_4_5::run(&m).unwrap();
    for c in figure_4_5::cases(&m, &curves) {
        println!("{c}");
        assert!(c.passed, "{c}");
    }
}

#[test]
fn iso_error_bound_up_to_ten_percent_strain() {
    for (name, m, rate_independent) in [
        ("j2", j2(ReturnMap::Principal), true),
        ("johnson-cook", johnson_cook(ReturnMap::Principal), false),
    ] {
        let map = iso_error::run(&m, &[0.0, 1.0, 3.0, 10.0, 20.0, 27.0, 50.0, 100.0]);
        println!("{name} (yield strain {:.2e})", map.yield_strain);
        for row in &map.error {
            println!(
                "{:?}",
                row.iter()
                    .map(|e| e.map(|x| format!("{x:.2e}")))
                    .collect::<Vec<_>>()
            );
        }
        for c in iso_error::cases(name, &map, rate_independent) {
            println!("{c}");
            assert!(c.passed, "{c}");
        }
    }
}

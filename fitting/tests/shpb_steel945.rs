//! The six 945-steel SHPB records of the shared data folder (skipped if it is absent):
//! strain rate, plateau stress and equilibrium ratio per record, and agreement of the
//! strain rate within 10 % for the tests run at similar impact levels (1-2, 3-4, 5-6).

mod common;

use fitting::experiment::ShpbExperiment;
use fitting::shpb::{analyze, ShpbAnalysis};
use fitting::verify_data::VerifyData;

#[test]
fn paired_tests_agree_on_strain_rate() {
    let Some(files) = VerifyData::repository().steel_945() else {
        common::skip("../shared/data/shpb/steel_945");
        return;
    };
    let analyses: Vec<ShpbAnalysis> = files
        .iter()
        .map(|f| analyze(&ShpbExperiment::load(f).unwrap()).unwrap())
        .collect();
    println!(
        "{:<20} {:>10} {:>10} {:>10} {:>8} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "record",
        "rate3 1/s",
        "rate1 1/s",
        "σ3 MPa",
        "R",
        "plat µs",
        "strain",
        "inc µε",
        "Δt_r µs",
        "Δt_t µs"
    );
    for a in &analyses {
        let p = &a.plateau;
        let dt = a.time_s[1] - a.time_s[0];
        println!(
            "{:<20} {:>10.1} {:>10.1} {:>10.1} {:>8.3} {:>9.1} {:>9.4} {:>9.1} {:>9.2} {:>9.2}",
            a.name,
            p.strain_rate_3wave_per_s,
            p.strain_rate_1wave_per_s,
            p.stress_3wave_pa / 1e6,
            p.equilibrium_ratio,
            p.range.len() as f64 * dt * 1e6,
            a.strain[p.range.end - 1],
            a.pulses.incident_amplitude * 1e6,
            a.pulses.reflected_arrival_offset_s * 1e6,
            a.pulses.transmitted_arrival_offset_s * 1e6,
        );
    }
    for (i, j) in [(0, 1), (2, 3), (4, 5)] {
        let (ri, rj) = (
            analyses[i].plateau.strain_rate_3wave_per_s,
            analyses[j].plateau.strain_rate_3wave_per_s,
        );
        let difference = (rj - ri).abs() / ri;
        println!(
            "tests {} and {}: strain rates differ by {:.1} %",
            i + 1,
            j + 1,
            100.0 * difference
        );
        assert!(
            difference <= 0.10,
            "tests {} and {}: {ri} vs {rj} 1/s",
            i + 1,
            j + 1
        );
    }
}

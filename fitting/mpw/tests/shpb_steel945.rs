//! The six 945-steel SHPB records of the shared data folder (skipped if it is absent):
//! strain rate, plateau stress and equilibrium ratio per record, and agreement of the
//! strain rate within 10 % for the tests run at similar impact levels (1-2, 3-4, 5-6).

mod common;

use fitting::experiment::ShpbExperiment;
use fitting::shpb::{analyze, ShpbAnalysis};
use mpw::verify::data::VerifyData;

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

/// `mpw shpb FOLDER` on the six records: one table row each, and test 05 against the
/// hand-processed workbook of the data's source tool (plateau rate 1876 1/s, final strain
/// 0.138; 2 % each, its plateau bounds picked by hand, ours by rule). A folder with a
/// record that cannot be processed lists its error and exits 1.
#[test]
fn a_folder_of_records_gives_one_table() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    if VerifyData::repository().steel_945().is_none() {
        common::skip("../shared/data/shpb/steel_945");
        return;
    }
    let out = std::env::temp_dir().join(format!("mpw_shpb_folder-{}", std::process::id()));
    let run = |folder: &std::path::Path| {
        std::process::Command::new(env!("CARGO_BIN_EXE_mpw"))
            .args([
                "shpb",
                folder.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ])
            .output()
            .unwrap()
    };
    let done = run(&root.join("data/experiments/shpb_steel_945"));
    assert!(
        done.status.success(),
        "{}",
        String::from_utf8_lossy(&done.stderr)
    );
    let table = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    let rows: Vec<Vec<&str>> = table
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows.len(), 6, "{table}");
    let test_05 = rows.iter().find(|r| r[0] == "test_05").unwrap();
    let number = |k: usize| test_05[k].parse::<f64>().unwrap();
    assert!(
        (number(1) / 1876.0 - 1.0).abs() < 0.02,
        "rate {}",
        number(1)
    );
    assert!(
        (number(2) / 0.138 - 1.0).abs() < 0.02,
        "final strain {}",
        number(2)
    );
    // one broken record in a copy of the folder
    let broken = out.join("broken");
    std::fs::create_dir_all(&broken).unwrap();
    let good = std::fs::read_to_string(root.join("data/experiments/shpb_steel_945/test_01.toml"))
        .unwrap()
        .replace(
            "../../../../shared",
            &root.join("../shared").display().to_string(),
        );
    std::fs::write(broken.join("a.toml"), &good).unwrap();
    std::fs::write(broken.join("b.toml"), good.replace("20 mm", "20 parsecs")).unwrap();
    let failed = run(&broken);
    assert_eq!(failed.status.code(), Some(1));
    let table = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    assert!(table.lines().nth(1).unwrap().starts_with("a,"), "{table}");
    assert!(table.lines().nth(2).unwrap().contains("parsecs"), "{table}");
}

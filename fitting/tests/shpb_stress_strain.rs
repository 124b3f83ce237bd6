//! The stress-strain view of an SHPB block (`objective::StressStrain`, drawn by `mpw fit`
//! per record): the mean face force (F1 + F2)/2 at each sample turned into true stress
//! (F1 + F2)/2 · exp(−ε)/A0 is the record's own true 3-wave stress at the same true strain,
//! which the SHPB analysis forms from the three pulses and the engineering strain.

use fitting::experiment::ShpbExperiment;
use fitting::fit::sets::fit_set::FitSet;
use fitting::shpb::analyze;
use std::path::Path;

#[test]
fn the_mean_face_force_as_true_stress_is_the_record_s_3_wave_stress() {
    let experiments = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/experiments");
    let set = FitSet::load(&experiments.join("default.toml")).unwrap();
    let block = set.blocks.iter().find(|b| b.name.contains("293")).unwrap();
    let ss = block
        .stress_strain
        .as_ref()
        .expect("an SHPB block has a stress-strain view");
    let analysis =
        analyze(&ShpbExperiment::load(&experiments.join("shpb_293K.toml")).unwrap()).unwrap();
    // The record's true stress against its true strain over the loading (strain rising).
    let peak = (0..analysis.true_strain.len())
        .max_by(|&a, &b| {
            analysis.true_strain[a]
                .abs()
                .total_cmp(&analysis.true_strain[b].abs())
        })
        .unwrap();
    let strain: Vec<f64> = analysis.true_strain[..=peak]
        .iter()
        .map(|e| e.abs())
        .collect();
    let stress: Vec<f64> = analysis.true_stress_pa[..=peak]
        .iter()
        .map(|s| s.abs())
        .collect();
    let record_at = |e: f64| {
        let k = strain
            .partition_point(|&x| x < e)
            .clamp(1, strain.len() - 1);
        let w = (e - strain[k - 1]) / (strain[k] - strain[k - 1]);
        stress[k - 1] + w * (stress[k] - stress[k - 1])
    };
    let per = ss.strain.len();
    assert_eq!(block.channels, ["F1", "F2"]);
    let (f1, f2) = block.measured.split_at(per);
    let mut worst: f64 = 0.0;
    for k in 0..per {
        let sigma = 0.5 * (f1[k] + f2[k]) * ss.stress_per_force[k];
        worst = worst.max((sigma / record_at(ss.strain[k]) - 1.0).abs());
    }
    // The samples are the record's own, so only rounding separates the two.
    assert!(worst < 1e-9, "largest relative difference {worst:.3e}");
}

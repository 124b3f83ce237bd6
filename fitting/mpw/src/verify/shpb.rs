//! Verification of the SHPB processing: the round trip through a synthetic record with a
//! known specimen curve, and the agreement of paired real tests (945 steel, pairs 1-2,
//! 3-4, 5-6 at similar impact levels) when the shared data folder is present.

use crate::verify::data::VerifyData;
use crate::verify::row::Row;
use crate::verify::Inputs;
use fitting::experiment::ShpbExperiment;
use fitting::shpb::round_trip::{
    record_with_late_gauges, synthetic_round_trip, synthetic_round_trip_with,
};
use fitting::shpb::synthetic::SyntheticSetup;
use fitting::shpb::synthetic::SyntheticShpb;
use fitting::shpb::{analyze, analyze_with, Alignment, Processing, ShpbError};

const FORCE_BALANCE: Processing = Processing {
    alignment: Alignment::ForceBalance,
    dispersion: false,
    filter: None,
};

/// Median R and F1 oscillation (`ShpbAnalysis::force_front_oscillation`) of a record.
#[derive(Debug, Clone, Copy)]
struct Quality {
    median_r: f64,
    f1_oscillation: f64,
}

/// `Quality` of every 945 record processed as `before` and as `after`; `None` if one
/// fails.
fn steel_945_before_after(
    files: &[std::path::PathBuf],
    before: Processing,
    after: Processing,
) -> Option<Vec<(Quality, Quality)>> {
    let quality = |exp: &ShpbExperiment, p: Processing| {
        analyze_with(exp, p).ok().map(|a| Quality {
            median_r: a.median_equilibrium_ratio(),
            f1_oscillation: a.force_front_oscillation(),
        })
    };
    files
        .iter()
        .map(|f| {
            let exp = ShpbExperiment::load(f).ok()?;
            Some((quality(&exp, before)?, quality(&exp, after)?))
        })
        .collect()
}

/// The six 945 records aligned by force balance against geometrically: the median R
/// must fall on every record; the largest force-balance median R is reported beside the
/// source tool's 0.09 (its own force-balance alignment, 0.05-0.09 on these records).
fn steel_945_alignment_cases(files: &[std::path::PathBuf]) -> Vec<Row> {
    let name = "shpb/steel945: force balance lowers the median R of every record";
    let Some(q) = steel_945_before_after(files, Processing::default(), FORCE_BALANCE) else {
        return vec![Row::holds(name, false)];
    };
    let worst = q.iter().map(|r| r.1.median_r).fold(0.0, f64::max);
    vec![
        Row::holds(name, q.iter().all(|(g, b)| b.median_r < g.median_r)),
        Row::info(
            "shpb/steel945: largest force-balance median R (source tool: 0.09)",
            worst,
            0.09,
        ),
    ]
}

/// The six 945 records with and without the dispersion correction (geometric
/// alignment, ν 0.29): the F1 oscillation and the median R must fall on every record;
/// the largest F1 oscillation before and after is reported (measured 31.7 % and 11.2 %).
fn steel_945_dispersion_cases(files: &[std::path::PathBuf]) -> Vec<Row> {
    let corrected = Processing {
        dispersion: true,
        ..Processing::default()
    };
    let name = "shpb/steel945: dispersion correction lowers the F1 oscillation of every record";
    let Some(q) = steel_945_before_after(files, Processing::default(), corrected) else {
        return vec![Row::holds(name, false)];
    };
    let largest = |f: &dyn Fn(&(Quality, Quality)) -> f64| q.iter().map(f).fold(0.0, f64::max);
    vec![
        Row::holds(
            name,
            q.iter().all(|(b, a)| a.f1_oscillation < b.f1_oscillation),
        ),
        Row::holds(
            "shpb/steel945: dispersion correction lowers the median R of every record",
            q.iter().all(|(b, a)| a.median_r < b.median_r),
        ),
        Row::reported(
            "shpb/steel945: largest F1 oscillation, uncorrected",
            largest(&|r| r.0.f1_oscillation),
        ),
        Row::reported(
            "shpb/steel945: largest F1 oscillation, dispersion corrected",
            largest(&|r| r.1.f1_oscillation),
        ),
    ]
}

/// Plateau strain rate of 945 test 05 in the hand-processed workbook of the data's
/// source tool (shpb-shtb-data-processor) [1/s].
pub const WORKBOOK_RATE_TEST_05: f64 = 1876.0;

/// An inverted synthetic record is refused (never processed with the reflected pulse
/// taken for the incident one), and a record whose gauges sit at calibrated delays 2 %
/// longer than distance / c0 comes back within 1 % when the delays are stated.
fn polarity_and_delay_cases() -> Vec<Row> {
    let synthetic = SyntheticShpb::generate(&SyntheticSetup::steel_945_like(5));
    let mut inverted = synthetic.experiment;
    for v in [&mut inverted.incident, &mut inverted.transmitted] {
        v.iter_mut().for_each(|x| *x = -*x);
    }
    let refused = matches!(
        analyze(&inverted),
        Err(ShpbError::TensileIncidentPulse { .. })
    );
    let mut setup = SyntheticSetup::steel_945_like(6);
    setup.bar.incident_delay_calibrated_s = Some(1.02 * setup.bar.incident_delay_s());
    setup.bar.transmitted_delay_calibrated_s = Some(1.02 * setup.bar.transmitted_delay_s());
    let delayed = match synthetic_round_trip(&setup) {
        Ok(r) => Row::at_most(
            "shpb/calibrated delays: stress 3-wave (max rel)",
            r.stress_error_3wave,
            0.01,
        ),
        Err(e) => {
            eprintln!("shpb/calibrated delays: {e}");
            Row::holds("shpb/calibrated delays: round trip runs", false)
        }
    };
    let mut rows = vec![
        Row::holds("shpb/polarity: inverted synthetic record refused", refused),
        delayed,
    ];
    rows.extend(alignment_cases());
    let (dispersed, recovered) = fitting::shpb::dispersion::round_trip();
    rows.push(Row::info(
        "shpb/dispersion: pulse after 0.75 m with dispersion, max change (rel)",
        dispersed,
        0.0,
    ));
    rows.push(Row::at_most(
        "shpb/dispersion: corrected back, max error (rel)",
        recovered,
        1e-3,
    ));
    rows.extend(dispersed_record_cases());
    rows
}

/// A synthetic record whose pulses disperse between gauges and faces
/// (`SyntheticSetup::dispersed`), processed with the correction: stresses within the
/// 1 % of the non-dispersed round trip; the uncorrected errors are reported.
fn dispersed_record_cases() -> Vec<Row> {
    let mut setup = SyntheticSetup::steel_945_like(3);
    setup.dispersed = true;
    let corrected = Processing {
        dispersion: true,
        ..Processing::default()
    };
    match (
        synthetic_round_trip_with(&setup, corrected),
        synthetic_round_trip(&setup),
    ) {
        (Ok(c), Ok(u)) => vec![
            Row::at_most(
                "shpb/dispersion: dispersed record, corrected, stress 3-wave (max rel)",
                c.stress_error_3wave,
                0.01,
            ),
            Row::at_most(
                "shpb/dispersion: dispersed record, corrected, stress 1-wave (max rel)",
                c.stress_error_1wave,
                0.01,
            ),
            Row::reported(
                "shpb/dispersion: dispersed record, corrected, stress 2-wave (max rel)",
                c.stress_error_2wave,
            ),
            Row::reported(
                "shpb/dispersion: dispersed record, uncorrected, stress 3-wave (max rel)",
                u.stress_error_3wave,
            ),
        ],
        (c, u) => {
            for e in [c.err(), u.err()].into_iter().flatten() {
                eprintln!("shpb/dispersion: {e}");
            }
            vec![Row::holds(
                "shpb/dispersion: dispersed record processed",
                false,
            )]
        }
    }
}

/// Force-balance alignment of `record_with_late_gauges`, asserted within 0.05 µs (1.6
/// samples of 32 ns).
fn alignment_cases() -> Vec<Row> {
    let (exp, needed) = record_with_late_gauges(10);
    match analyze_with(&exp, FORCE_BALANCE) {
        Ok(a) => vec![
            Row::absolute(
                "shpb/alignment: force balance, reflected shift [us]",
                a.shifts.reflected_s * 1e6,
                needed.reflected_s * 1e6,
                0.05,
            ),
            Row::absolute(
                "shpb/alignment: force balance, transmitted shift [us]",
                a.shifts.transmitted_s * 1e6,
                needed.transmitted_s * 1e6,
                0.05,
            ),
        ],
        Err(e) => {
            eprintln!("shpb/alignment: {e}");
            vec![Row::holds(
                "shpb/alignment: synthetic record processed",
                false,
            )]
        }
    }
}

/// Rows of `mpw verify` for the SHPB processing.
/// Every SHPB processing row of `mpw verify`.
pub fn rows(inputs: &Inputs) -> anyhow::Result<Vec<Row>> {
    Ok(cases(inputs.data))
}

fn cases(data: &VerifyData) -> Vec<Row> {
    let mut cases = Vec::new();
    match synthetic_round_trip(&SyntheticSetup::steel_945_like(1)) {
        Ok(r) => {
            cases.push(Row::at_most(
                "shpb/synthetic stress 3-wave (max rel)",
                r.stress_error_3wave,
                0.01,
            ));
            cases.push(Row::at_most(
                "shpb/synthetic stress 1-wave (max rel)",
                r.stress_error_1wave,
                0.01,
            ));
            cases.push(Row::at_most(
                "shpb/synthetic stress 2-wave (max rel)",
                r.stress_error_2wave,
                0.01,
            ));
            cases.push(Row::at_most(
                "shpb/synthetic strain (max rel)",
                r.strain_error,
                0.01,
            ));
            cases.push(Row::relative(
                "shpb/synthetic plateau strain rate [1/s]",
                r.analysis.plateau.strain_rate_3wave_per_s,
                r.exact_plateau_rate_per_s,
                0.01,
            ));
        }
        Err(e) => {
            eprintln!("shpb/synthetic: {e}");
            cases.push(Row::holds("shpb/synthetic round trip runs", false));
        }
    }
    cases.extend(polarity_and_delay_cases());
    let Some(files) = data.steel_945() else {
        eprintln!(
            "note: {} not found; SHPB pair agreement skipped",
            data.shared_root().join("shpb/steel_945").display()
        );
        return cases;
    };
    let rates: Vec<Option<f64>> = files
        .iter()
        .map(|f| {
            let exp = ShpbExperiment::load(f).map_err(|e| e.to_string())?;
            let a = analyze(&exp).map_err(|e| e.to_string())?;
            Ok::<f64, String>(a.plateau.strain_rate_3wave_per_s)
        })
        .map(|r| r.map_err(|e| eprintln!("shpb/steel945: {e}")).ok())
        .collect();
    // The data's source tool's hand-processed workbook for test 05 reads a plateau rate of
    // 1876 1/s; its plateau bounds are picked by hand, ours by rule: 2 %.
    cases.push(match rates[4] {
        Some(rate) => Row::relative(
            "shpb/steel945 test 05 plateau rate vs the source's workbook [1/s]",
            rate,
            WORKBOOK_RATE_TEST_05,
            0.02,
        ),
        None => Row::holds("shpb/steel945 test 05 processed", false),
    });
    cases.extend(steel_945_alignment_cases(&files));
    cases.extend(steel_945_dispersion_cases(&files));
    for pair in [(0, 1), (2, 3), (4, 5)] {
        let name = format!("shpb/steel945 rate test {} vs {}", pair.1 + 1, pair.0 + 1);
        cases.push(match (rates[pair.0], rates[pair.1]) {
            (Some(a), Some(b)) => Row::relative(name, b, a, 0.10),
            _ => Row::holds(name, false),
        });
    }
    cases
}

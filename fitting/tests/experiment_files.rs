//! Experiment files: unit conversion against hand-computed SI values, and one test per
//! error kind checking that the message names the file, line and column.

mod common;

use fitting::experiment::{
    load_experiment, Experiment, ExperimentError, ShpbExperiment, TensileExperiment,
};
use std::path::{Path, PathBuf};

/// Write `files` (name, text) into a fresh folder and return it.
fn folder(test: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mpw-experiment-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    dir
}

const TENSILE_CSV: &str =
    "# a comment\ntime_ms,strain_pct,force_kn\n0,0,0\n10,1,10\n20,2,12\n30,3,11\n";

fn tensile_toml(columns: &str, extra: &str) -> String {
    format!(
        "kind = \"tensile\"\ndata = \"t.csv\"\ntemperature = \"20 degC\"\nnominal_strain_rate = \"1 1/s\"\n\
         [columns]\n{columns}\n[geometry]\ndiameter = \"10 mm\"\n{extra}"
    )
}

const TENSILE_COLUMNS: &str = "time = { name = \"time_ms\", unit = \"ms\" }\n\
     strain = { name = \"strain_pct\", unit = \"%\" }\n\
     force = { name = \"force_kn\", unit = \"kN\" }";

fn load_tensile(test: &str, toml: &str) -> Result<TensileExperiment, ExperimentError> {
    let dir = folder(test, &[("t.csv", TENSILE_CSV), ("t.toml", toml)]);
    TensileExperiment::load(&dir.join("t.toml"))
}

#[test]
fn tensile_force_and_units_convert_to_si_and_cut_at_max_stress() {
    let e = load_tensile("si", &tensile_toml(TENSILE_COLUMNS, "")).unwrap();
    let area = std::f64::consts::PI * 0.01 * 0.01 / 4.0;
    assert_eq!(e.time_s, vec![0.0, 0.01, 0.02, 0.03]);
    assert_eq!(e.eng_strain, vec![0.0, 0.01, 0.02, 0.03]);
    let expected = 12e3 / area;
    assert!((e.eng_stress_pa[2] - expected).abs() <= 1e-12 * expected);
    assert!((e.temperature_k - 293.15).abs() < 1e-12);
    // Maximum engineering stress (necking) at sample 2: samples 0..=2 are used.
    assert_eq!(e.used_range(), 0..3);
}

/// The columns written as `[columns.time]` table headers, not inline tables, read the same
/// (they were refused with "invalid type: string \"time\", expected a borrowed string").
#[test]
fn columns_as_table_headers_read_like_inline_tables() {
    let headers = "kind = \"tensile\"\ndata = \"t.csv\"\ntemperature = \"20 degC\"\n\
        nominal_strain_rate = \"1 1/s\"\n[geometry]\ndiameter = \"10 mm\"\n\
        [columns.time]\nname = \"time_ms\"\nunit = \"ms\"\n\
        [columns.strain]\nname = \"strain_pct\"\nunit = \"%\"\n\
        [columns.force]\nname = \"force_kn\"\nunit = \"kN\"\n\
        [window]\nup_to_max_stress = false\n";
    let e = load_tensile("headers", headers).unwrap();
    let inline = load_tensile("inline", &tensile_toml(TENSILE_COLUMNS, "")).unwrap();
    assert_eq!(e.eng_stress_pa, inline.eng_stress_pa);
    assert_eq!(e.used_range(), 0..4);
}

#[test]
fn window_outside_data_names_the_key() {
    let toml = tensile_toml(TENSILE_COLUMNS, "[window]\nstrain_max = 0.5\n");
    let e = load_tensile("window", &toml).unwrap_err();
    let msg = e.to_string();
    assert!(
        matches!(&e, ExperimentError::WindowOutsideData { at, key, .. } if at.line == 12 && key == "window.strain_max"),
        "{msg}"
    );
    assert!(
        msg.contains("t.toml:12:14") && msg.contains("0 .. 0.03"),
        "{msg}"
    );
    // Inside the data it restricts the used samples.
    let toml = tensile_toml(
        TENSILE_COLUMNS,
        "[window]\ntime_min = \"10 ms\"\nup_to_max_stress = false\n",
    );
    assert_eq!(load_tensile("window-ok", &toml).unwrap().used_range(), 1..4);
}

#[test]
fn unknown_unit_names_key_line_and_accepted_units() {
    let columns = TENSILE_COLUMNS.replace("unit = \"kN\"", "unit = \"tonnes\"");
    let e = load_tensile("unit", &tensile_toml(&columns, "")).unwrap_err();
    let msg = e.to_string();
    assert!(
        matches!(&e, ExperimentError::UnknownUnit { at, key, unit, .. }
            if at.line == 8 && key == "columns.force.unit" && unit == "tonnes"),
        "{msg}"
    );
    assert!(msg.contains("\"kN\""), "{msg}");
    // A quantity string with an unknown unit.
    let toml = tensile_toml(TENSILE_COLUMNS, "").replace("\"10 mm\"", "\"10 furlong\"");
    let e = load_tensile("unit-q", &toml).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::UnknownUnit { at, .. } if at.line == 10),
        "{e}"
    );
}

#[test]
fn missing_and_unknown_toml_keys_are_located() {
    let toml = tensile_toml(TENSILE_COLUMNS, "").replace("data = \"t.csv\"\n", "");
    let e = load_tensile("missing-key", &toml).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::Toml { message, .. } if message.contains("data")),
        "{e}"
    );
    assert!(e.to_string().contains("t.toml:1:1"), "{e}");
    let toml = tensile_toml(TENSILE_COLUMNS, "colour = \"red\"\n");
    let e = load_tensile("unknown-key", &toml).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::Toml { at, message, .. } if at.line == 11 && message.contains("colour")),
        "{e}"
    );
}

#[test]
fn missing_csv_column_names_csv_header_and_toml_key() {
    let columns = TENSILE_COLUMNS.replace("force_kn", "load_kn");
    let e = load_tensile("column", &tensile_toml(&columns, "")).unwrap_err();
    let msg = e.to_string();
    assert!(
        matches!(e, ExperimentError::MissingColumn { line: 2, .. }),
        "{msg}"
    );
    assert!(
        msg.contains("t.csv:2") && msg.contains("t.toml:8:") && msg.contains("force_kn"),
        "{msg}"
    );
}

#[test]
fn non_monotonic_time_and_nan_name_the_csv_line() {
    let dir = folder(
        "time",
        &[
            (
                "t.csv",
                "time_ms,strain_pct,force_kn\n0,0,0\n10,1,10\n10,2,12\n",
            ),
            ("t.toml", &tensile_toml(TENSILE_COLUMNS, "")),
        ],
    );
    let e = TensileExperiment::load(&dir.join("t.toml")).unwrap_err();
    assert!(
        matches!(
            e,
            ExperimentError::NonMonotonicTime {
                line: 4,
                column: 1,
                ..
            }
        ),
        "{e}"
    );
    let dir = folder(
        "nan",
        &[
            ("t.csv", "time_ms,strain_pct,force_kn\n0,0,0\n10,nan,10\n"),
            ("t.toml", &tensile_toml(TENSILE_COLUMNS, "")),
        ],
    );
    let e = TensileExperiment::load(&dir.join("t.toml")).unwrap_err();
    assert!(
        e.to_string().contains("t.csv:3: column 2 \"strain_pct\""),
        "{e}"
    );
}

#[test]
fn wrong_kind_is_an_error() {
    let toml = tensile_toml(TENSILE_COLUMNS, "").replace("\"tensile\"", "\"torsion\"");
    let dir = folder("kind", &[("t.csv", TENSILE_CSV), ("t.toml", &toml)]);
    let e = load_experiment(&dir.join("t.toml")).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::WrongKind { at, .. } if at.line == 1 && at.column == 8),
        "{e}"
    );
}

const SHPB_TOML: &str = "kind = \"shpb\"\ndata = \"s.csv\"\ntemperature = \"293 K\"\n[columns]\n\
time = { name = \"t_us\", unit = \"us\" }\n\
incident = { name = \"inc_v\", unit = \"mV\", gauge_factor = 2.0, excitation = \"10 V\", gain = 100.0, active_arms = 2 }\n\
transmitted = { name = \"tr_ue\", unit = \"microstrain\" }\n\
[bar]\nelastic_modulus = \"200 GPa\"\nwave_speed = \"5000 m/s\"\ndiameter = \"20 mm\"\n\
incident_gauge_to_specimen = \"1 m\"\ntransmitted_gauge_to_specimen = \"0.5 m\"\n\
[specimen]\ndiameter = \"8 mm\"\nlength = \"4 mm\"\n";

#[test]
fn shpb_bridge_volts_and_wave_speed_convert_to_si() {
    let dir = folder(
        "shpb",
        &[
            ("s.csv", "t_us,inc_v,tr_ue\n0,-100,-50\n1,200,25\n"),
            ("s.toml", SHPB_TOML),
        ],
    );
    let Experiment::Shpb(e) = load_experiment(&dir.join("s.toml")).unwrap() else {
        panic!("not an SHPB experiment")
    };
    // ε = 4 U / (n k U_ex gain) = 4 · (−0.1 V) / (2 · 2 · 10 V · 100) = −1e-4.
    assert!((e.incident[0] + 1e-4).abs() < 1e-18, "{}", e.incident[0]);
    assert!((e.transmitted[1] - 25e-6).abs() < 1e-18);
    assert_eq!(e.time_s, vec![0.0, 1e-6]);
    // ρ = E / c0² = 200e9 / 5000² = 8000 kg/m³.
    assert!((e.bar.density_kg_m3 - 8000.0).abs() < 1e-9);
    assert!((e.bar.wave_speed_m_per_s() - 5000.0).abs() < 1e-9);
}

/// A specimen not narrower than the bar (a unit written wrong: "8 m" for "8 mm") is
/// refused at reading, at its key and line, instead of giving a plateau stress of 0 MPa.
#[test]
fn a_specimen_as_wide_as_the_bar_is_refused_at_its_key() {
    let csv = "t_us,inc_v,tr_ue\n0,-100,-50\n1,200,25\n";
    for (test, specimen) in [("wide_m", "\"8 m\""), ("wide_equal", "\"20 mm\"")] {
        let toml = SHPB_TOML.replace(
            "[specimen]\ndiameter = \"8 mm\"",
            &format!("[specimen]\ndiameter = {specimen}"),
        );
        let dir = folder(test, &[("s.csv", csv), ("s.toml", &toml)]);
        let e = ShpbExperiment::load(&dir.join("s.toml")).unwrap_err();
        assert!(
            matches!(&e, ExperimentError::InvalidValue { at, key, problem } if at.line == 15 && key == "specimen.diameter" && problem.contains("not smaller than the bar")),
            "{e}"
        );
    }
    let dir = folder("narrow", &[("s.csv", csv), ("s.toml", SHPB_TOML)]);
    assert!(ShpbExperiment::load(&dir.join("s.toml")).is_ok());
}

#[test]
fn shpb_volts_without_bridge_is_an_error() {
    let toml = SHPB_TOML.replace(", excitation = \"10 V\"", "");
    let dir = folder(
        "bridge",
        &[
            ("s.csv", "t_us,inc_v,tr_ue\n0,1,1\n1,1,1\n"),
            ("s.toml", &toml),
        ],
    );
    let e = ShpbExperiment::load(&dir.join("s.toml")).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::InvalidValue { at, problem, .. } if at.line == 6 && problem.contains("excitation")),
        "{e}"
    );
}

/// `polarity = "compression-positive"` flips both gauges on loading; an unknown polarity
/// is an error naming its line; calibrated delays replace distance / c0 for timing only.
#[test]
fn shpb_polarity_and_calibrated_delays() {
    let csv = "t_us,inc_v,tr_ue\n0,-100,-50\n1,200,25\n";
    let positive = SHPB_TOML.replace(
        "temperature = \"293 K\"\n",
        "temperature = \"293 K\"\npolarity = \"compression-positive\"\n",
    );
    let delays = SHPB_TOML.replace(
        "transmitted_gauge_to_specimen = \"0.5 m\"\n",
        "transmitted_gauge_to_specimen = \"0.5 m\"\nincident_gauge_delay = \"210 us\"\ntransmitted_gauge_delay = \"105 us\"\n",
    );
    let dir = folder(
        "polarity",
        &[
            ("s.csv", csv),
            ("s.toml", SHPB_TOML),
            ("p.toml", &positive),
            ("d.toml", &delays),
            (
                "bad.toml",
                &positive.replace("compression-positive", "tension"),
            ),
        ],
    );
    let plain = ShpbExperiment::load(&dir.join("s.toml")).unwrap();
    let flipped = ShpbExperiment::load(&dir.join("p.toml")).unwrap();
    for k in 0..2 {
        assert_eq!(flipped.incident[k], -plain.incident[k]);
        assert_eq!(flipped.transmitted[k], -plain.transmitted[k]);
    }
    let e = ShpbExperiment::load(&dir.join("bad.toml")).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::InvalidValue { at, problem, .. } if at.line == 4 && problem.contains("compression-positive")),
        "{e}"
    );
    // distance / c0 = 1 m / 5000 m/s = 200 µs unless calibrated
    assert!((plain.bar.incident_delay_s() - 200e-6).abs() < 1e-15);
    assert!((plain.bar.transmitted_delay_s() - 100e-6).abs() < 1e-15);
    let calibrated = ShpbExperiment::load(&dir.join("d.toml")).unwrap();
    assert!((calibrated.bar.incident_delay_s() - 210e-6).abs() < 1e-15);
    assert!((calibrated.bar.transmitted_delay_s() - 105e-6).abs() < 1e-15);
    assert_eq!(
        calibrated.bar.wave_speed_m_per_s(),
        plain.bar.wave_speed_m_per_s()
    );
    // the alignment of the processing: default geometric, named, or an error at its line
    assert_eq!(plain.processing, fitting::shpb::Processing::default());
    let aligned =
        |a: &str| SHPB_TOML.replace("[columns]", &format!("alignment = \"{a}\"\n[columns]"));
    let dir = folder(
        "alignment",
        &[
            ("s.csv", csv),
            ("a.toml", &aligned("force-balance")),
            ("b.toml", &aligned("sideways")),
        ],
    );
    let a = ShpbExperiment::load(&dir.join("a.toml")).unwrap();
    assert_eq!(
        a.processing.alignment,
        fitting::shpb::Alignment::ForceBalance
    );
    let e = ShpbExperiment::load(&dir.join("b.toml")).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::InvalidValue { at, problem, .. } if at.line == 4 && problem.contains("force-balance")),
        "{e}"
    );
}

/// The dispersion correction is off by default; on, it needs the bars' Poisson ratio,
/// which must lie in (0, 0.5): errors name the key and its line.
#[test]
fn shpb_dispersion_needs_a_poisson_ratio() {
    let csv = "t_us,inc_v,tr_ue\n0,-100,-50\n1,200,25\n";
    let with = |nu: Option<&str>| {
        let toml = SHPB_TOML.replace("[columns]", "dispersion = true\n[columns]");
        match nu {
            Some(nu) => toml.replace("[specimen]", &format!("poisson_ratio = {nu}\n[specimen]")),
            None => toml,
        }
    };
    let dir = folder(
        "dispersion",
        &[
            ("s.csv", csv),
            ("ok.toml", &with(Some("0.29"))),
            ("none.toml", &with(None)),
            ("bad.toml", &with(Some("29"))),
        ],
    );
    let ok = ShpbExperiment::load(&dir.join("ok.toml")).unwrap();
    assert!(ok.processing.dispersion);
    assert_eq!(ok.bar.poisson_ratio, Some(0.29));
    let e = ShpbExperiment::load(&dir.join("none.toml")).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::InvalidValue { at, problem, .. } if at.line == 4 && problem.contains("poisson_ratio")),
        "{e}"
    );
    let e = ShpbExperiment::load(&dir.join("bad.toml")).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::InvalidValue { at, problem, .. } if at.line == 15 && problem.contains("between 0 and 0.5")),
        "{e}"
    );
}

/// The real 304L tension files, read as they are, if the shared data folder exists.
#[test]
fn real_304l_file_reads_as_it_is() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/data/tension/304L");
    if !data.is_dir() {
        common::skip(&data.display().to_string());
        return;
    }
    let file = "rate_0.01__SML4188-Ring1-17_Pull_0.01.csv";
    let toml = format!(
        "kind = \"tensile\"\ndata = \"{}\"\ntemperature = \"297.04 K\"\nnominal_strain_rate = \"0.01 1/s\"\n\
         [columns]\ntime = {{ name = \"time_s\", unit = \"s\" }}\n\
         strain = {{ name = \"engineering_strain\", unit = \"1\" }}\n\
         stress = {{ name = \"engineering_stress_pa\", unit = \"Pa\" }}\n",
        data.join(file).display()
    );
    let dir = folder("304l", &[("e.toml", &toml)]);
    let e = TensileExperiment::load(&dir.join("e.toml")).unwrap();
    // Independent check: the file's maximum engineering stress, found by scanning the text.
    let text = std::fs::read_to_string(data.join(file)).unwrap();
    let (mut best, mut rows) = (f64::NEG_INFINITY, 0);
    for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        best = best.max(
            line.split(',')
                .nth(2)
                .unwrap()
                .trim()
                .parse::<f64>()
                .unwrap(),
        );
        rows += 1;
    }
    assert_eq!(e.time_s.len(), rows);
    let used = e.used_range();
    assert_eq!(e.eng_stress_pa[used.end - 1], best);
    assert_eq!(used.start, 0);
}

/// Every experiment TOML shipped in `data/experiments` loads; a tensile TOML states the
/// nominal rate and temperature of its CSV's `#` header (read here independently), an
/// SHPB record has 20 000 samples of 32 ns (as the data README states). The measured mean
/// engineering strain rate up to the maximum stress is printed against the nominal one.
#[test]
fn shipped_experiment_files_load() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    if !root.join("../shared/data").is_dir() {
        common::skip("../shared/data");
        return;
    }
    let header_value = |text: &str, key: &str| -> f64 {
        let line = text
            .lines()
            .find(|l| l.starts_with('#') && l.contains(key))
            .unwrap();
        line.rsplit(':').next().unwrap().trim().parse().unwrap()
    };
    let mut count = 0;
    for folder in [
        "data/experiments/tension_304l",
        "data/experiments/shpb_steel_945",
    ] {
        for entry in std::fs::read_dir(root.join(folder)).unwrap() {
            let path = entry.unwrap().path();
            match load_experiment(&path).unwrap_or_else(|e| panic!("{e}")) {
                Experiment::Tensile(e) => {
                    let text = std::fs::read_to_string(&e.data_file).unwrap();
                    let nominal = header_value(&text, "nominal_engineering_strain_rate_per_s");
                    assert_eq!(e.nominal_strain_rate_per_s, nominal, "{}", e.name);
                    assert_eq!(e.temperature_k, header_value(&text, "temperature_K"));
                    let r = e.used_range();
                    let (a, b) = (r.start, r.end - 1);
                    let rate = (e.eng_strain[b] - e.eng_strain[a]) / (e.time_s[b] - e.time_s[a]);
                    println!(
                        "{}: measured mean rate {rate:.3e} 1/s = {:.2} x nominal",
                        e.name,
                        rate / nominal
                    );
                }
                Experiment::Shpb(e) => {
                    assert_eq!(e.time_s.len(), 20_000);
                    let dt = (e.time_s[19_999] - e.time_s[0]) / 19_999.0;
                    assert!((dt / 32e-9 - 1.0).abs() < 1e-3, "{dt}");
                }
            }
            count += 1;
        }
    }
    assert_eq!(count, 10);
}

/// A stress column in MPa declared "Pa" never reaches 1 MPa: refused at reading, naming
/// the CSV, the row of its largest value and the column, instead of a fit that runs into
/// its bounds.
#[test]
fn a_stress_column_below_one_mpa_is_refused_as_a_unit_mistake() {
    let toml = |unit: &str| {
        format!(
            "kind = \"tensile\"\ndata = \"t.csv\"\ntemperature = \"20 degC\"\nnominal_strain_rate = \"1 1/s\"\n\
             [columns]\ntime = {{ name = \"time_s\", unit = \"s\" }}\nstrain = {{ name = \"strain\", unit = \"1\" }}\n\
             stress = {{ name = \"stress\", unit = \"{unit}\" }}\n"
        )
    };
    let csv = "time_s,strain,stress\n0,0,0\n1,0.01,420\n2,0.02,515\n3,0.03,498\n";
    let load = |test: &str, unit: &str| {
        let dir = folder(test, &[("t.csv", csv), ("t.toml", &toml(unit))]);
        TensileExperiment::load(&dir.join("t.toml"))
    };
    let e = load("mpa-as-pa", "Pa").unwrap_err();
    assert!(
        matches!(&e, ExperimentError::Implausible { line: 4, column: 3, name, .. } if name == "stress"),
        "{e}"
    );
    let msg = e.to_string();
    assert!(
        msg.contains("t.csv") && msg.contains("515 Pa") && msg.contains("MPa declared as"),
        "{msg}"
    );
    assert!(load("mpa", "MPa").is_ok());
}

/// A value beyond the plausible range of its dimension names the row, the value as
/// written and the likely mistake: a stress of 2e9 "MPa" (Pa declared as MPa),
/// a strain of 6 (600 %), and forces in kN declared as "MN" (10 MN over a 10 mm diameter
/// is a stress of 127 GPa). Just inside the bounds the file reads.
#[test]
fn implausible_values_name_the_row_and_the_likely_mistake() {
    let columns = TENSILE_COLUMNS.replace("unit = \"kN\"", "unit = \"MN\"");
    let e = load_tensile("implausible-force", &tensile_toml(&columns, "")).unwrap_err();
    assert!(
        matches!(
            &e,
            ExperimentError::Implausible {
                line: 4,
                column: 3,
                ..
            }
        ),
        "{e}"
    );
    let msg = e.to_string();
    assert!(
        msg.contains("10000000 N is implausible") && msg.contains("the force's unit"),
        "{msg}"
    );
    let toml = "kind = \"tensile\"\ndata = \"t.csv\"\ntemperature = \"20 degC\"\nnominal_strain_rate = \"1 1/s\"\n\
         [columns]\ntime = { name = \"time_s\", unit = \"s\" }\nstrain = { name = \"strain\", unit = \"1\" }\n\
         stress = { name = \"stress_mpa\", unit = \"MPa\" }\n";
    let load = |test: &str, csv: &str| {
        let dir = folder(test, &[("t.csv", csv), ("t.toml", toml)]);
        TensileExperiment::load(&dir.join("t.toml"))
    };
    let e = load(
        "implausible-stress",
        "time_s,strain,stress_mpa\n0,0,0\n1,0.01,2e9\n",
    )
    .unwrap_err();
    assert!(
        matches!(
            &e,
            ExperimentError::Implausible {
                line: 3,
                column: 3,
                ..
            }
        ),
        "{e}"
    );
    assert!(
        e.to_string().contains("t.csv:3") && e.to_string().contains("declared as \"MPa\""),
        "{e}"
    );
    let e = load(
        "implausible-strain",
        "time_s,strain,stress_mpa\n0,0,0\n1,6,200\n",
    )
    .unwrap_err();
    assert!(
        matches!(
            &e,
            ExperimentError::Implausible {
                line: 3,
                column: 2,
                ..
            }
        ),
        "{e}"
    );
    load(
        "plausible",
        "time_s,strain,stress_mpa\n0,0,0\n1,4.99,9999\n",
    )
    .unwrap();
}

/// Metadata quantities are held to the same table: 20 000 °C and a rate of 1e12 1/s name
/// their key and line; "200 GPa" as a bar modulus is fine (the other tests), "200000 GPa"
/// is not.
#[test]
fn implausible_metadata_names_the_key() {
    let toml = tensile_toml(TENSILE_COLUMNS, "").replace("\"20 degC\"", "\"20000 degC\"");
    let e = load_tensile("implausible-temperature", &toml).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::InvalidValue { key, at, .. } if key == "temperature" && at.line == 3),
        "{e}"
    );
    assert!(e.to_string().contains("beyond 10 000 K"), "{e}");
    let toml = tensile_toml(TENSILE_COLUMNS, "").replace("\"1 1/s\"", "\"1e12 1/s\"");
    let e = load_tensile("implausible-rate", &toml).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::InvalidValue { key, .. } if key == "nominal_strain_rate"),
        "{e}"
    );
    let dir = folder(
        "implausible-modulus",
        &[
            ("s.csv", "t_us,inc_v,tr_ue\n0,-100,-50\n1,200,25\n"),
            (
                "s.toml",
                &SHPB_TOML.replace("\"200 GPa\"", "\"200000 GPa\""),
            ),
        ],
    );
    let e = ShpbExperiment::load(&dir.join("s.toml")).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::InvalidValue { key, at, .. } if key == "bar.elastic_modulus" && at.line == 9),
        "{e}"
    );
    assert!(e.to_string().contains("beyond 1000 GPa"), "{e}");
}

/// A tensile record whose `#` header states rate and temperature (as the shared 304L
/// records do), with stress scaled by `k`.
fn headed_csv(rate: &str, temperature: &str, k: f64) -> String {
    let mut csv = format!(
        "# source: test\n# nominal_engineering_strain_rate_per_s: {rate}\n# {temperature}\ntime_s,engineering_strain,engineering_stress_pa\n"
    );
    for i in 0..5 {
        let e = 0.01 * i as f64;
        csv.push_str(&format!("{},{e},{}\n", i as f64, k * (300e6 + 1e9 * e)));
    }
    csv
}

const HEADED_TOML: &str = "kind = \"tensile\"\nname = \"g\"\ndata = \"rate_*.csv\"\n\
     [columns]\ntime = { name = \"time_s\", unit = \"s\" }\n\
     strain = { name = \"engineering_strain\", unit = \"1\" }\n\
     stress = { name = \"engineering_stress_pa\", unit = \"Pa\" }\n";

#[test]
fn a_pattern_makes_one_experiment_per_record_with_rate_and_temperature_from_the_header() {
    let dir = folder(
        "pattern",
        &[
            ("rate_b.csv", &headed_csv("1800", "temperature_C: 20", 1.0)),
            (
                "rate_a.csv",
                &headed_csv("0.01", "temperature_K: 297.04", 1.1),
            ),
            ("other.csv", &headed_csv("1", "temperature_K: 300", 1.0)),
            ("g.toml", HEADED_TOML),
        ],
    );
    let all = TensileExperiment::load_all(&dir.join("g.toml")).unwrap();
    let names: Vec<&str> = all.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(names, ["g/rate_a", "g/rate_b"], "sorted by file name");
    assert_eq!(all[0].nominal_strain_rate_per_s, 0.01);
    assert_eq!(all[0].temperature_k, 297.04);
    assert_eq!(all[1].nominal_strain_rate_per_s, 1800.0);
    assert!((all[1].temperature_k - 293.15).abs() < 1e-12);
    assert_eq!(
        all[0].rate_source.to_string(),
        "CSV header `nominal_engineering_strain_rate_per_s` (line 2)"
    );
    assert_eq!(
        all[1].temperature_source.to_string(),
        "CSV header `temperature_C` (line 3)"
    );
    // The TOML overrides the header, and says so.
    let toml = HEADED_TOML.replace("data =", "temperature = \"400 K\"\ndata =");
    std::fs::write(dir.join("g.toml"), toml).unwrap();
    let all = TensileExperiment::load_all(&dir.join("g.toml")).unwrap();
    assert!(all.iter().all(|e| e.temperature_k == 400.0));
    assert_eq!(all[0].temperature_source.to_string(), "TOML `temperature`");
    // One record expected, two found.
    let e = TensileExperiment::load(&dir.join("g.toml")).unwrap_err();
    assert!(
        e.to_string()
            .contains("names 2 records where one is expected"),
        "{e}"
    );
}

#[test]
fn missing_and_bad_header_metadata_name_the_file_line_and_keys() {
    let no_temperature = headed_csv("1800", "operator: someone", 1.0);
    let dir = folder(
        "header-missing",
        &[("rate_x.csv", &no_temperature), ("g.toml", HEADED_TOML)],
    );
    let e = TensileExperiment::load_all(&dir.join("g.toml")).unwrap_err();
    let msg = e.to_string();
    assert!(
        matches!(e, ExperimentError::MissingMetadata { .. }),
        "{msg}"
    );
    assert!(
        msg.contains("rate_x.csv: no `temperature`") && msg.contains("`temperature_K`"),
        "{msg}"
    );
    let header_error = |test: &str, csv: &str| -> String {
        let dir = folder(test, &[("rate_x.csv", csv), ("g.toml", HEADED_TOML)]);
        TensileExperiment::load_all(&dir.join("g.toml"))
            .unwrap_err()
            .to_string()
    };
    let msg = header_error("header-bad", &headed_csv("fast", "temperature_K: 297", 1.0));
    assert!(
        msg.contains("rate_x.csv:2: header `nominal_engineering_strain_rate_per_s`: \"fast\""),
        "{msg}"
    );
    let msg = header_error("header-cold", &headed_csv("1", "temperature_C: -300", 1.0));
    assert!(
        msg.contains("rate_x.csv:3: header `temperature_C`") && msg.contains("positive"),
        "{msg}"
    );
    let dir = folder("header-none", &[("g.toml", HEADED_TOML)]);
    let msg = TensileExperiment::load_all(&dir.join("g.toml"))
        .unwrap_err()
        .to_string();
    assert!(msg.contains("g.toml:3:8: `data`: no file matches"), "{msg}");
}

#[test]
fn a_file_of_the_other_kind_is_named_as_such() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/experiments");
    let e = ShpbExperiment::load(&root.join("qs_tension.toml")).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::WrongKind { found, .. } if found == "tensile"),
        "{e}"
    );
    let e = TensileExperiment::load(&root.join("shpb_293K.toml")).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::WrongKind { found, .. } if found == "shpb"),
        "{e}"
    );
}

/// A bar whose wave speed √(E/ρ) lies outside 1000-8000 m/s is refused at the key that
/// made it, with the likely cause (a density in g/cm³ under kg/m³, a modulus in MPa).
#[test]
fn shpb_bar_wave_speed_is_checked() {
    let csv = "t_us,inc_v,tr_ue\n0,-100,-50\n1,200,25\n";
    let bar = |line: &str| SHPB_TOML.replace("wave_speed = \"5000 m/s\"", line);
    let dir = folder(
        "wave_speed",
        &[
            ("s.csv", csv),
            ("slow.toml", &bar("wave_speed = \"500 m/s\"")),
            ("grams.toml", &bar("density = \"7.85 kg/m^3\"")),
            ("steel.toml", &bar("density = \"7850 kg/m^3\"")),
        ],
    );
    let e = ShpbExperiment::load(&dir.join("slow.toml")).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::InvalidValue { at, key, problem, .. } if at.line == 10 && key == "bar.wave_speed" && problem.contains("500 m/s")),
        "{e}"
    );
    let e = ShpbExperiment::load(&dir.join("grams.toml")).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::InvalidValue { at, key, problem, .. } if at.line == 10 && key == "bar.density" && problem.contains("g/cm³")),
        "{e}"
    );
    let steel = ShpbExperiment::load(&dir.join("steel.toml")).unwrap();
    assert!((steel.bar.wave_speed_m_per_s() - (200e9f64 / 7850.0).sqrt()).abs() < 1e-9);
}

/// A CSV whose `#` header holds the bar and specimen metadata needs a TOML of columns
/// only; the TOML overrides the header; a missing key names both places, a bad header
/// value its line, and the wave-speed check reaches header values too.
#[test]
fn shpb_metadata_from_the_csv_header() {
    let header =
        "# temperature: 293 K\n# bar_elastic_modulus: 200 GPa\n# bar_density: 8000 kg/m^3\n\
# bar_diameter: 20 mm\n# bar_incident_gauge_to_specimen: 1 m\n\
# bar_transmitted_gauge_to_specimen: 0.5 m\n# bar_poisson_ratio: 0.29\n\
# specimen_diameter: 8 mm\n# specimen_length: 4 mm\n";
    let csv = format!("{header}t_us,inc_ue,tr_ue\n0,-100,-50\n1,200,25\n");
    let toml = "kind = \"shpb\"\ndata = \"s.csv\"\n[columns]\n\
time = { name = \"t_us\", unit = \"us\" }\n\
incident = { name = \"inc_ue\", unit = \"microstrain\" }\n\
transmitted = { name = \"tr_ue\", unit = \"microstrain\" }\n";
    let overriding = toml.replace("[columns]", "[specimen]\nlength = \"5 mm\"\n[columns]");
    let dir = folder(
        "shpb_header",
        &[
            ("s.csv", &csv),
            ("a.toml", toml),
            ("b.toml", &overriding),
            ("m.csv", &csv.replace("# specimen_length: 4 mm\n", "")),
            ("m.toml", &toml.replace("s.csv", "m.csv")),
            ("g.csv", &csv.replace("8000 kg/m^3", "8 kg/m^3")),
            ("g.toml", &toml.replace("s.csv", "g.csv")),
        ],
    );
    let a = ShpbExperiment::load(&dir.join("a.toml")).unwrap();
    assert!((a.bar.wave_speed_m_per_s() - 5000.0).abs() < 1e-9);
    assert_eq!(a.bar.poisson_ratio, Some(0.29));
    assert!((a.bar.incident_gauge_to_specimen_m - 1.0).abs() < 1e-15);
    assert!((a.specimen.length_m - 4e-3).abs() < 1e-15);
    assert!((a.temperature_k - 293.0).abs() < 1e-12);
    let b = ShpbExperiment::load(&dir.join("b.toml")).unwrap();
    assert!((b.specimen.length_m - 5e-3).abs() < 1e-15);
    let e = ShpbExperiment::load(&dir.join("m.toml")).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::MissingMetadata { key, header_keys, .. } if key == "specimen.length" && header_keys.contains("specimen_length")),
        "{e}"
    );
    let e = ShpbExperiment::load(&dir.join("g.toml")).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::BadHeader { line: 3, key, problem, .. } if key == "bar_density" && problem.contains("g/cm³")),
        "{e}"
    );
}

/// A bare number where a quantity string is expected gets the unit it probably lacked.
#[test]
fn a_bare_number_for_a_quantity_suggests_its_unit() {
    let toml = tensile_toml(TENSILE_COLUMNS, "").replace("diameter = \"10 mm\"", "diameter = 10");
    let e = load_tensile("bare", &toml).unwrap_err().to_string();
    assert!(
        e.contains(
            "t.toml:10:12: `geometry.diameter`: invalid type: integer `10`, expected a string"
        ) && e.contains("e.g. `diameter = \"10 mm\"`"),
        "{e}"
    );
}

/// A `data` path that does not resolve is an error at the key, saying the path is
/// relative to the TOML (a TOML copied without its CSV).
#[test]
fn a_data_path_that_does_not_resolve_names_the_key_and_the_folder() {
    let dir = folder("moved", &[("t.toml", &tensile_toml(TENSILE_COLUMNS, ""))]);
    let e = TensileExperiment::load(&dir.join("t.toml")).unwrap_err();
    assert!(
        matches!(&e, ExperimentError::InvalidValue { at, key, .. } if at.line == 2 && key == "data"),
        "{e}"
    );
    let text = e.to_string();
    assert!(
        text.contains("the path is relative to the folder of this TOML")
            && text.contains(&dir.display().to_string()),
        "{text}"
    );
}

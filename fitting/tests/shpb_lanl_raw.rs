//! The LANL standard raw format: a synthetic record written in that layout
//! (tab-separated, CRLF, Latin-1 ° and µ in key names, waveforms in volts with t0 and dt
//! on lines 2-3, compression positive, a density in g/cm³ under a kg/m³ label, a bar
//! block's calibrated gain that differs from the test's) reads back to the strains it was
//! made from and processes to the same plateau as the record itself.

use fitting::experiment::ShpbExperiment;
use fitting::shpb::synthetic::{SyntheticSetup, SyntheticShpb};
use fitting::shpb::{analyze, ShpbError};
use std::path::{Path, PathBuf};

/// An empty folder of this test under the system's temporary folder.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mpw_{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

const GAUGE_FACTOR: f64 = 2.061;
const EXCITATION_V: f64 = 8.0;
const GAIN: f64 = 200.0;
const ARMS: f64 = 2.0;

/// The metadata lines of the record (key, value), Latin-1 text.
fn metadata(bar: &fitting::experiment::Bar, specimen_mm: (f64, f64)) -> Vec<(String, String)> {
    let c0 = bar.wave_speed_m_per_s();
    let mut rows: Vec<(String, String)> = vec![
        ("Test Date".into(), "12/1/2006".into()),
        ("Test Time".into(), "11:48:55 AM".into()),
        ("Test Loading".into(), "Compression".into()),
        (
            "Initial Sample Diameter(mm)".into(),
            format!("{}", specimen_mm.0),
        ),
        (
            "Initial Sample Length(mm)".into(),
            format!("{}", specimen_mm.1),
        ),
        ("Test Temperature(\u{b0}C)".into(), "20".into()),
        ("Incident/Reflected Bar Gain".into(), format!("{GAIN}")),
        ("Transmitted Bar Gain".into(), format!("{GAIN}")),
        (String::new(), String::new()),
    ];
    for (name, distance) in [
        ("Incident", bar.incident_gauge_to_specimen_m),
        ("Transmitted", bar.transmitted_gauge_to_specimen_m),
    ] {
        rows.push((format!("{name} Bar Properties"), String::new()));
        let key = |k: &str| format!("{name} Bar {k}");
        rows.push((key("Calibrated Gage Factor"), format!("{GAUGE_FACTOR}")));
        if name == "Incident" {
            let round_trip_us = 2e6 * distance / c0;
            rows.push((
                key("Calibrated Reflected Time(\u{b5}s)"),
                format!("{round_trip_us}"),
            ));
            rows.push((key("Reflected Time Sound Speed(m/s)"), format!("{c0}")));
        }
        rows.push((
            key("Young's Modulus(GPa)"),
            format!("{}", bar.elastic_modulus_pa / 1e9),
        ));
        rows.push((key("Poisson Ratio"), "0.29".into()));
        rows.push((key("Rod Sound Speed(m/s)"), format!("{c0}")));
        // g/cm³ under a kg/m³ label, as in a published national-lab record
        rows.push((
            key("Density(kg/m^3)"),
            format!("{}", bar.density_kg_m3 / 1e3),
        ));
        rows.push((key("Diameter(mm)"), format!("{}", bar.diameter_m * 1e3)));
        rows.push((
            key("Strain Gage Location(mm)"),
            format!("{}", distance * 1e3),
        ));
        rows.push((key("Excitation Voltage(V)"), format!("{EXCITATION_V}")));
        let calibrated = if name == "Transmitted" { 500.0 } else { GAIN };
        rows.push((key("Calibrated Gain"), format!("{calibrated}")));
    }
    rows
}

/// How the record's text is stored.
#[derive(Clone, Copy)]
enum Encoding {
    /// As published: one byte per character.
    Latin1,
    /// UTF-8 behind a byte-order mark.
    Utf8Bom,
    /// UTF-8 after a conversion that replaced ° and µ by U+FFFD.
    Replaced,
}

/// Write `exp` as a LANL raw record (compression positive, volts) and its TOML.
fn write_record(dir: &Path, exp: &ShpbExperiment, polarity: Option<&str>) -> PathBuf {
    write_encoded(dir, exp, polarity, Encoding::Latin1)
}

fn write_encoded(
    dir: &Path,
    exp: &ShpbExperiment,
    polarity: Option<&str>,
    encoding: Encoding,
) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    let volts_per_strain = -ARMS * GAUGE_FACTOR * EXCITATION_V * GAIN / 4.0;
    let rows = metadata(
        &exp.bar,
        (exp.specimen.diameter_m * 1e3, exp.specimen.length_m * 1e3),
    );
    let dt = exp.time_s[1] - exp.time_s[0];
    let mut waves = vec![
        (
            "Incident/Reflected Waveform".to_string(),
            "Transmitted Waveform".to_string(),
        ),
        (
            format!("{:e}", exp.time_s[0]),
            format!("{:e}", exp.time_s[0]),
        ),
        (format!("{dt:e}"), format!("{dt:e}")),
    ];
    for (i, t) in exp.incident.iter().zip(&exp.transmitted) {
        waves.push((
            format!("{:e}", i * volts_per_strain),
            format!("{:e}", t * volts_per_strain),
        ));
    }
    let mut text = String::new();
    for (k, (a, b)) in waves.iter().enumerate() {
        let (key, value) = rows.get(k).cloned().unwrap_or_default();
        text.push_str(&format!("{key}\t{value}\t{a}\t{b}\r\n"));
    }
    let bytes: Vec<u8> = match encoding {
        Encoding::Latin1 => text
            .chars()
            .map(|c| u8::try_from(u32::from(c)).unwrap())
            .collect(),
        Encoding::Utf8Bom => [b"\xEF\xBB\xBF".as_slice(), text.as_bytes()].concat(),
        Encoding::Replaced => text.replace(['\u{b0}', '\u{b5}'], "\u{FFFD}").into_bytes(),
    };
    std::fs::write(dir.join("record.raw"), bytes).unwrap();
    let polarity = polarity.map_or(String::new(), |p| format!("polarity = \"{p}\"\n"));
    let toml = format!(
        "kind = \"shpb\"\nformat = \"lanl-raw\"\ndata = \"record.raw\"\n{polarity}active_arms = 2\n"
    );
    let path = dir.join(format!("record_{}.toml", polarity.len()));
    std::fs::write(&path, toml).unwrap();
    path
}

#[test]
fn a_lanl_raw_record_reads_back_and_processes_as_its_source() {
    let synthetic = SyntheticShpb::generate(&SyntheticSetup::steel_945_like(8));
    let exp = &synthetic.experiment;
    let dir = temp_dir("lanl_raw");
    let toml = write_record(&dir, exp, Some("compression-positive"));
    let read = ShpbExperiment::load(&toml).unwrap_or_else(|e| panic!("{e}"));
    // strains to the digits written ({:e} round-trips), times to t0 + k dt
    let worst = exp
        .incident
        .iter()
        .zip(&read.incident)
        .chain(exp.transmitted.iter().zip(&read.transmitted))
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-15, "{worst}");
    assert!((read.time_s.last().unwrap() - exp.time_s.last().unwrap()).abs() < 1e-12);
    assert!((read.temperature_k - 293.15).abs() < 1e-9);
    assert!((read.bar.density_kg_m3 / exp.bar.density_kg_m3 - 1.0).abs() < 1e-12);
    assert!((read.bar.incident_delay_s() / exp.bar.incident_delay_s() - 1.0).abs() < 1e-12);
    assert!((read.bar.transmitted_delay_s() / exp.bar.transmitted_delay_s() - 1.0).abs() < 1e-12);
    // the reader says what it decided
    let notes = read.notes.join("\n");
    assert!(notes.contains("looks like g/cm^3"), "{notes}");
    assert!(
        notes.contains("Transmitted Bar Calibrated Gain = 500"),
        "{notes}"
    );
    let (a, b) = (analyze(exp).unwrap(), analyze(&read).unwrap());
    let rate = |x: &fitting::shpb::ShpbAnalysis| x.plateau.strain_rate_3wave_per_s;
    assert!(
        (rate(&b) / rate(&a) - 1.0).abs() < 1e-9,
        "{} vs {}",
        rate(&b),
        rate(&a)
    );
    // the same file without its polarity is refused, not processed upside down
    let unflipped = write_record(&dir, exp, None);
    let e = analyze(&ShpbExperiment::load(&unflipped).unwrap()).unwrap_err();
    assert!(matches!(e, ShpbError::TensileIncidentPulse { .. }), "{e}");
}

/// The same record in UTF-8 with a byte-order mark, and with ° and µ replaced by U+FFFD
/// (as a real published record arrives), reads as the Latin-1 original, with notes.
#[test]
fn a_lanl_raw_record_in_utf8_or_with_replaced_unit_characters_reads_the_same() {
    let synthetic = SyntheticShpb::generate(&SyntheticSetup::steel_945_like(8));
    let exp = &synthetic.experiment;
    let read = |name: &str, encoding: Encoding| {
        let toml = write_encoded(&temp_dir(name), exp, Some("compression-positive"), encoding);
        ShpbExperiment::load(&toml).unwrap_or_else(|e| panic!("{name}: {e}"))
    };
    let original = read("lanl_latin1", Encoding::Latin1);
    for (name, encoding, said) in [
        (
            "lanl_bom",
            Encoding::Utf8Bom,
            "read as UTF-8 with a byte-order mark",
        ),
        ("lanl_replaced", Encoding::Replaced, "read as \"µs\""),
    ] {
        let e = read(name, encoding);
        assert_eq!(e.incident, original.incident, "{name}");
        assert_eq!(e.temperature_k, original.temperature_k, "{name}");
        assert_eq!(e.bar, original.bar, "{name}");
        let notes = e.notes.join("\n");
        assert!(notes.contains(said), "{name}: {notes}");
    }
    let replaced = read("lanl_replaced2", Encoding::Replaced).notes.join("\n");
    assert!(replaced.contains("`Test Temperature(\u{FFFD}C)` has a replaced character (U+FFFD) in its unit, read as \"°C\""), "{replaced}");
}

#[test]
fn a_damaged_lanl_raw_record_is_named() {
    let synthetic = SyntheticShpb::generate(&SyntheticSetup::steel_945_like(9));
    let dir = temp_dir("lanl_raw_bad");
    let toml = write_record(&dir, &synthetic.experiment, Some("compression-positive"));
    let raw = dir.join("record.raw");
    let original = std::fs::read(&raw).unwrap();
    let text: String = original.iter().map(|&b| char::from(b)).collect();
    for (damaged, expect) in [
        (
            text.replace("Compression", "Tension"),
            "record.raw:3:2: `Test Loading`",
        ),
        (
            text.replace(
                "Transmitted Bar Diameter(mm)\t20",
                "Transmitted Bar Diameter(mm)\t25",
            ),
            "one material and diameter",
        ),
        (text.replacen("\t3.2e-8", "\tabc", 1), "record.raw:3:3"),
        (
            text.replace(
                "Incident Bar Excitation Voltage(V)",
                "Incident Bar Excitation Voltage(kV)",
            ),
            "unit \"kV\"",
        ),
    ] {
        let bytes: Vec<u8> = damaged
            .chars()
            .map(|c| u8::try_from(u32::from(c)).unwrap())
            .collect();
        std::fs::write(&raw, bytes).unwrap();
        let e = ShpbExperiment::load(&toml).unwrap_err().to_string();
        assert!(e.contains(expect), "expected {expect:?} in: {e}");
    }
    std::fs::write(&raw, original).unwrap();
    let no_arms = std::fs::read_to_string(&toml)
        .unwrap()
        .replace("active_arms = 2\n", "");
    std::fs::write(&toml, no_arms).unwrap();
    let e = ShpbExperiment::load(&toml).unwrap_err().to_string();
    assert!(e.contains("active_arms"), "{e}");
}

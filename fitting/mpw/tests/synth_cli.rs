//! `mpw synth` with no arguments writes to `out/synth`, leaves the shipped
//! `data/experiments/` untouched, and writes the shipped synthetic records again (to the
//! last printed digit: values agree within 1e-8 of each column's peak magnitude).

use std::path::Path;
use std::process::Command;

const RECORDS: [&str; 3] = ["qs_tension", "shpb_293K", "shpb_573K"];

fn numbers(text: &str) -> Vec<Vec<f64>> {
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| l.split(',').map(|f| f.trim().parse().unwrap()).collect())
        .collect()
}

#[test]
fn synth_defaults_write_to_out_and_reproduce_the_shipped_records() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let shipped = root.join("data/experiments");
    let read = |dir: &Path, name: &str| std::fs::read_to_string(dir.join(name)).unwrap();
    let before: Vec<String> = RECORDS
        .iter()
        .map(|r| read(&shipped, &format!("{r}.csv")))
        .collect();
    let out = Command::new(env!("CARGO_BIN_EXE_mpw"))
        .current_dir(&root)
        .arg("synth")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let written = root.join("out/synth");
    for (r, old) in RECORDS.iter().zip(&before) {
        let name = format!("{r}.csv");
        assert_eq!(
            &read(&shipped, &name),
            old,
            "{name} in data/experiments was rewritten"
        );
        let (new, old) = (numbers(&read(&written, &name)), numbers(old));
        assert_eq!(new.len(), old.len(), "{name}: rows");
        for c in 0..old[0].len() {
            let peak = old.iter().fold(0.0f64, |m, row| m.max(row[c].abs()));
            for (a, b) in new.iter().zip(&old) {
                assert!(
                    (a[c] - b[c]).abs() <= 1e-8 * peak,
                    "{name} column {c}: {} vs {}",
                    a[c],
                    b[c]
                );
            }
        }
    }
}

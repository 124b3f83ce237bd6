//! `docs/reference.md` lists every key the readers accept, and no other.
//!
//! Each file kind has a complete example in the reference (a ```` ```toml example=KIND ````
//! block) and one section per table (`### `path``, a variant as `(type = "name")`) whose
//! rows name its keys. For every table of the example the test inserts an unknown key and
//! reads the file with the project's own reader, which refuses it and lists the keys it
//! accepts there (serde's `expected one of`, the material reader's `allowed:`). That list
//! must be the documented one, and every documented table must be in the example, so a key
//! added to a reader and not to the reference fails here.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const PROBE: &str = "zz_probe_key";

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

/// The reader of each documented file kind: its error text for a file.
fn read(kind: &str, file: &Path) -> String {
    let err = match kind {
        "tensile" | "shpb" | "lanl-raw" => fitting::experiment::load_experiments(file)
            .err()
            .map(|e| e.to_string()),
        "fit-set" => fitting::fit::sets::fit_set::FitSet::load(file)
            .err()
            .map(|e| format!("{e:#}")),
        "scene" => mpm_core::scene::read(file).err().map(|e| e.to_string()),
        "shpb-scene" => fitting::shpb_model::scene::ShpbScene::load(file)
            .err()
            .map(|e| format!("{e:#}")),
        "material" => materials::load_material(file).err().map(|e| e.to_string()),
        other => panic!("no reader for the documented kind `{other}`"),
    };
    err.unwrap_or_default()
}

/// The keys a reader lists as accepted in its refusal of `PROBE`, or `None` when it did not
/// refuse it (a free-form table such as `[truth]`).
fn accepted(error: &str) -> Option<BTreeSet<String>> {
    if let Some(at) = error.find(&format!("unknown field `{PROBE}`")) {
        let rest = &error[at..];
        let rest = rest.lines().next().unwrap_or(rest);
        if rest.contains("there are no fields") {
            return Some(BTreeSet::new());
        }
        let list = rest.split_once("expected").map(|(_, l)| l).unwrap_or("");
        return Some(
            list.split('`')
                .skip(1)
                .step_by(2)
                .map(String::from)
                .collect(),
        );
    }
    if error.contains(PROBE) {
        let list = error.split_once("allowed:").map(|(_, l)| l)?;
        let list = list.lines().next().unwrap_or(list);
        return Some(
            list.split(',')
                .map(|k| k.trim().trim_matches('`').to_string())
                .collect(),
        );
    }
    None
}

/// Every table of `value` with its documented label: `columns.time`, `body.shape (type =
/// "disk")`; array elements share their array's path.
fn tables(value: &toml::Table, path: &str, out: &mut Vec<(String, Vec<String>)>, at: Vec<String>) {
    let label = match value.get("type").and_then(|t| t.as_str()) {
        Some(variant) if !path.is_empty() => format!("{path} (type = \"{variant}\")"),
        _ => path.to_string(),
    };
    out.push((label, at.clone()));
    for (key, child) in value {
        let sub = if path.is_empty() {
            key.clone()
        } else {
            format!("{path}.{key}")
        };
        let mut at = at.clone();
        at.push(key.clone());
        match child {
            toml::Value::Table(t) => tables(t, &sub, out, at),
            toml::Value::Array(items) => {
                for (k, item) in items.iter().enumerate() {
                    if let toml::Value::Table(t) = item {
                        let mut at = at.clone();
                        at.push(k.to_string());
                        tables(t, &sub, out, at);
                    }
                }
            }
            _ => {}
        }
    }
}

/// The table of `root` at the address `at` (keys and array indices).
fn table_at<'a>(root: &'a mut toml::Table, at: &[String]) -> &'a mut toml::Table {
    let mut value = root;
    let mut k = 0;
    while k < at.len() {
        let child = value.get_mut(&at[k]).unwrap();
        value = match child {
            toml::Value::Table(t) => t,
            toml::Value::Array(items) => {
                k += 1;
                items[at[k].parse::<usize>().unwrap()]
                    .as_table_mut()
                    .unwrap()
            }
            _ => unreachable!(),
        };
        k += 1;
    }
    value
}

/// The reference's documentation of one file kind: its example and its tables' keys.
struct Kind {
    example: String,
    tables: BTreeMap<String, BTreeSet<String>>,
}

fn documented(reference: &str) -> BTreeMap<String, Kind> {
    let mut kinds: BTreeMap<String, Kind> = BTreeMap::new();
    let mut current: Option<String> = None;
    let mut labels: Vec<String> = Vec::new();
    let mut lines = reference.lines();
    while let Some(line) = lines.next() {
        if let Some(kind) = line.strip_prefix("```toml example=") {
            let example: Vec<&str> = lines
                .by_ref()
                .take_while(|l| !l.starts_with("```"))
                .collect();
            kinds.insert(
                kind.trim().to_string(),
                Kind {
                    example: example.join("\n") + "\n",
                    tables: BTreeMap::new(),
                },
            );
            current = Some(kind.trim().to_string());
        } else if let Some(heading) = line.strip_prefix("### ") {
            labels = table_labels(heading);
        } else if line.starts_with("## ") {
            current = None;
            labels.clear();
        } else if let (Some(kind), Some(key)) = (&current, line.strip_prefix("| `")) {
            let key = key.split('`').next().unwrap().to_string();
            for label in &labels {
                let tables = &mut kinds.get_mut(kind).unwrap().tables;
                tables.entry(label.clone()).or_default().insert(key.clone());
            }
        }
    }
    kinds
}

/// `### `columns.time`, `columns.strain` (type = "x")` → ["columns.time (type = "x")", ...];
/// `### top level` → [""].
fn table_labels(heading: &str) -> Vec<String> {
    if heading.trim() == "top level" {
        return vec![String::new()];
    }
    let variant = heading
        .split_once(" (type = ")
        .map(|(_, v)| format!(" (type = {v}"));
    heading
        .split('`')
        .skip(1)
        .step_by(2)
        .map(|p| format!("{p}{}", variant.clone().unwrap_or_default()))
        .collect()
}

#[test]
fn the_reference_lists_every_key_the_readers_accept() {
    let reference = std::fs::read_to_string(repo().join("docs/reference.md")).unwrap();
    let kinds = documented(&reference);
    let expected = [
        "tensile",
        "shpb",
        "lanl-raw",
        "fit-set",
        "scene",
        "shpb-scene",
        "material",
    ];
    assert_eq!(
        kinds.keys().map(String::as_str).collect::<BTreeSet<_>>(),
        expected.into_iter().collect(),
        "documented kinds"
    );
    let dir = std::env::temp_dir().join(format!("mpw-reference-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut problems = Vec::new();
    for (kind, doc) in &kinds {
        let file = dir.join(format!("{kind}.toml"));
        std::fs::write(&file, &doc.example).unwrap();
        let plain = read(kind, &file);
        if plain.contains("unknown") {
            problems.push(format!("{kind}: the example itself is refused: {plain}"));
            continue;
        }
        let example: toml::Table = doc.example.parse().unwrap();
        let mut found = Vec::new();
        tables(&example, "", &mut found, Vec::new());
        let mut probed = BTreeSet::new();
        for (label, at) in found {
            let mut probe = example.clone();
            table_at(&mut probe, &at).insert(PROBE.into(), toml::Value::Integer(0));
            std::fs::write(&file, toml::to_string(&probe).unwrap()).unwrap();
            let error = read(kind, &file);
            let Some(mut keys) = accepted(&error) else {
                continue;
            };
            if label.contains("(type = ") {
                keys.insert("type".into());
            }
            probed.insert(label.clone());
            match doc.tables.get(&label) {
                None => problems.push(format!(
                    "{kind}: table `{label}` accepts {keys:?} and is not documented"
                )),
                Some(listed) if listed != &keys => problems.push(format!(
                    "{kind}: table `{label}`: the reader accepts {keys:?}, the reference lists {listed:?}"
                )),
                Some(_) => {}
            }
        }
        for label in doc.tables.keys().filter(|l| !probed.contains(*l)) {
            problems.push(format!(
                "{kind}: documented table `{label}` is not in the example"
            ));
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(
        problems.is_empty(),
        "docs/reference.md differs from the readers:\n{}",
        problems.join("\n")
    );
}

#[test]
fn a_key_the_reader_does_not_accept_is_found() {
    let listed = accepted(
        "x.toml:3:1: `zz_probe_key`: unknown field `zz_probe_key`, expected one of `a`, `b`",
    );
    assert_eq!(listed, Some(["a".to_string(), "b".to_string()].into()));
    let listed = accepted("m.toml:2:1: `elastic.zz_probe_key`: unknown key; allowed: E, nu, rho");
    assert_eq!(listed, Some(["E", "nu", "rho"].map(String::from).into()));
    assert_eq!(
        table_labels("`body.shape` (type = \"disk\")"),
        ["body.shape (type = \"disk\")"]
    );
}

//! Every kind of input file reports a mistake one way: `file:line:column: `key`: what was
//! expected`. One mistake per kind, each where it is written: an experiment TOML, a
//! material file, a fit set (a TOML type error, an unknown key, a semantic error in an
//! `[[experiment]]` entry), an MPM scene and an SHPB scene.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap()
}

/// The first line of `mpw`'s error, without `error: `.
fn error_of(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_mpw"))
        .current_dir(root())
        .args(args)
        .output()
        .unwrap();
    assert!(!out.status.success(), "{args:?} should fail");
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    let line = err
        .lines()
        .find(|l| l.starts_with("error: "))
        .unwrap_or_else(|| panic!("{err}"));
    line["error: ".len()..].to_string()
}

/// `message` starts with `file:line:column: `key`: ` for this file, line and key.
fn assert_placed(message: &str, file: &Path, line: usize, key: &str) {
    let prefix = format!("{}:{line}:", file.display());
    assert!(
        message.starts_with(&prefix),
        "expected {prefix}…: {message}"
    );
    let rest = &message[prefix.len()..];
    let (column, rest) = rest.split_once(": ").unwrap();
    assert!(
        column.parse::<usize>().is_ok_and(|c| c >= 1),
        "column `{column}`: {message}"
    );
    assert!(
        rest.starts_with(&format!("`{key}`: ")),
        "key `{key}`: {message}"
    );
}

#[test]
fn every_input_file_names_file_line_column_and_key() {
    let dir = std::env::temp_dir().join(format!("mpw-error-format-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let data = root().join("data");
    let write = |name: &str, text: String| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path
    };
    // an experiment TOML: a rate without a unit (line 6 of the shipped file)
    let experiment = std::fs::read_to_string(data.join("experiments/qs_tension.toml"))
        .unwrap()
        .replace(
            "data = \"",
            &format!("data = \"{}/", data.join("experiments").display()),
        );
    let line = experiment
        .lines()
        .position(|l| l.starts_with("nominal_strain_rate"))
        .unwrap()
        + 1;
    let bad = write(
        "tension.toml",
        experiment
            .lines()
            .map(|l| match l.starts_with("nominal_strain_rate") {
                true => "nominal_strain_rate = \"fast\"",
                false => l,
            })
            .collect::<Vec<_>>()
            .join("\n"),
    );
    let set = |body: &str| {
        format!(
            "name = \"s\"\nmaterial = \"{}\"\n{body}",
            data.join("materials/42crmo4_qt660.toml").display()
        )
    };
    let fit_set = write(
        "set.toml",
        set(&format!("[[experiment]]\nfile = \"{}\"\n", bad.display())),
    );
    let message = error_of(&["fit", fit_set.to_str().unwrap()]);
    // the entry that names the file, then the experiment file's own place
    assert_placed(&message, &fit_set, 4, "experiment.file");
    assert!(
        message.contains(&format!("{}:{line}:", bad.display())),
        "{message}"
    );
    assert!(
        message.contains("`nominal_strain_rate`: expected"),
        "{message}"
    );

    // a material file: a number written as a string
    let steel = std::fs::read_to_string(data.join("materials/42crmo4_qt660.toml")).unwrap();
    let line = steel.lines().position(|l| l.starts_with("N = ")).unwrap() + 1;
    let material = write("steel.toml", steel.replace("N = 0.81", "N = \"0.81\""));
    let message = error_of(&["drive", "--material", material.to_str().unwrap()]);
    assert_placed(&message, &material, line, "johnson_cook.N");

    // a fit set: a wrong type, an unknown key, an entry's semantic error
    let typed = write("typed.toml", set("starts = \"two\"\n"));
    assert_placed(
        &error_of(&["fit", typed.to_str().unwrap()]),
        &typed,
        3,
        "starts",
    );
    let unknown = write("unknown.toml", set("startz = 2\n"));
    assert_placed(
        &error_of(&["fit", unknown.to_str().unwrap()]),
        &unknown,
        3,
        "startz",
    );
    let entry = write(
        "entry.toml",
        set(&format!(
            "[[parameter]]\nname = \"A\"\nlower = 1e8\nupper = 2e9\nstart = 6e8\n\n[[experiment]]\nfile = \"{}\"\nwindow = [1.5e-5, 1.15e-4]\nlevel = \"mpm-axisymmetric\"\nlayers = 1\n",
            data.join("experiments/shpb_293K.toml").display()
        )),
    );
    assert_placed(
        &error_of(&["fit", entry.to_str().unwrap()]),
        &entry,
        13,
        "experiment.layers",
    );

    // an MPM scene: a value a check refuses, and a key the reader does not know
    let disks = std::fs::read_to_string(data.join("scenes/colliding_disks.toml")).unwrap();
    let spacing = disks
        .lines()
        .position(|l| l.starts_with("spacing"))
        .unwrap()
        + 1;
    let mpm = write("disks.toml", disks.replacen("spacing = ", "spacing = -", 1));
    assert_placed(
        &error_of(&["simulate", mpm.to_str().unwrap()]),
        &mpm,
        spacing,
        "grid.spacing",
    );
    let typo = write("typo.toml", disks.replacen("spacing = ", "spaceing = ", 1));
    assert_placed(
        &error_of(&["simulate", typo.to_str().unwrap()]),
        &typo,
        spacing,
        "grid.spaceing",
    );

    // an SHPB scene
    let scene = write(
        "scene.toml",
        format!(
            "kind = \"shpb\"\nexperiment = \"{}\"\nmaterial = \"{}\"\nlevel = \"mpm-axisymmetric\"\ndrive = \"push\"\nlayers = 4\n",
            data.join("experiments/shpb_293K.toml").display(),
            data.join("materials/42crmo4_qt660.toml").display()
        ),
    );
    assert_placed(
        &error_of(&["simulate", scene.to_str().unwrap()]),
        &scene,
        5,
        "drive",
    );
}

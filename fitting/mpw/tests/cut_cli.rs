//! `mpw cut`: the shipped scenes of both cuts are what `mpw cut scenes` writes, and a short
//! run of set G0 (grid shift, springs) brings the punch into contact: the force on it rises
//! from zero, the force table and chart are written and the feed is reported; a stability
//! map of two cells writes its table and one chart per variant, and drawn again runs
//! nothing; the orthogonal map gives a cell's steady cutting force.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn mpw(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_mpw"))
        .current_dir(root())
        .args(args)
        .output()
        .unwrap()
}

/// `mpw args`, which must succeed; its standard output.
fn mpw_ok(args: &[&str]) -> String {
    let out = mpw(args);
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success(),
        "{args:?}: {text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    text
}

/// The numeric rows of a CSV file after its header.
fn numbers(path: &Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

#[test]
fn the_shipped_cutting_scenes_are_the_generator_s() {
    let dir = std::env::temp_dir().join(format!("mpw-cut-scenes-{}", std::process::id()));
    mpw_ok(&["cut", "scenes", "--out", dir.to_str().unwrap()]);
    let shipped = root().join("data/scenes/cutting");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap();
        let expected = std::fs::read_to_string(shipped.join(name))
            .unwrap_or_else(|_| panic!("{name:?} is not shipped in data/scenes/cutting"));
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            expected,
            "{name:?}: run `mpw cut scenes`"
        );
        count += 1;
    }
    assert_eq!(
        count, 19,
        "one scene per set of table 12.2 and per cell of the orthogonal sensitivity matrix"
    );
    assert_eq!(std::fs::read_dir(&shipped).unwrap().count(), 19);
}

#[test]
fn a_short_vertical_cut_loads_the_punch() {
    let dir = std::env::temp_dir().join(format!("mpw-cut-g0-{}", std::process::id()));
    let out = dir.to_str().unwrap();
    let text = mpw_ok(&[
        "cut", "vertical", "--set", "G0", "--feed", "0.04", "--out", out,
    ]);
    assert!(
        text.contains("G0 (dx = 0.0001 m, linear): 10800 points"),
        "{text}"
    );
    assert!(text.contains("ran through to 4 % relative feed"), "{text}");
    let rows = numbers(&dir.join("force.csv"));
    // feed = t / 20 µs; no force before the punch touches, compression after
    for r in &rows {
        assert!((r[0] - r[1] / 20e-6).abs() < 1e-12, "{r:?}");
    }
    assert_eq!(rows[0][3], 0.0);
    let last = rows.last().unwrap();
    assert!(last[0] > 0.039, "{last:?}");
    // 2-4 % feed is the first contact's impact: the mean force over it lies between the
    // sheet's quasi-static shear resistance τ_y l_y = (546 MPa/√3)(3 mm) = 0.95 MN/m and the
    // elastic impact force ρ c v w = 2800 · 6172 · 150 · 2.85 mm = 7.4 MN/m on the punch
    // face (measured 4.48 MN/m)
    let half = &rows[rows.len() / 2..];
    let mean = half.iter().map(|r| r[3]).sum::<f64>() / half.len() as f64;
    assert!(mean > 0.95e6 && mean < 7.4e6, "mean f_y {mean:.3e} N/m");
    assert!(dir.join("force.png").is_file() && dir.join("scene.toml").is_file());
}

#[test]
fn a_small_stability_map_writes_its_cells() {
    let dir = std::env::temp_dir().join(format!("mpw-cut-map-{}", std::process::id()));
    let out = dir.to_str().unwrap();
    let variants = "linear,linear+shift";
    let map_with = |out: &str, option: &[&str]| {
        let mut args = vec![
            "cut",
            "map",
            "--spacings",
            "1e-4",
            "--points",
            "60",
            "--variants",
            variants,
            "--feed",
            "0.02",
            "--out",
            out,
        ];
        args.extend(option);
        mpw_ok(&args)
    };
    let map = |out: &str, executor: &str| map_with(out, &["--executor", executor]);
    map(out, "in-process");
    let table = std::fs::read_to_string(dir.join("map.csv")).unwrap();
    let rows: Vec<&str> = table.lines().skip(1).collect();
    assert_eq!(rows.len(), 2, "{table}");
    assert!(
        rows[0].starts_with("linear,1e-4,60,2e-2,") && rows[0].ends_with("\"ran through\""),
        "{table}"
    );
    assert!(rows[1].starts_with("linear+shift,1e-4,60,2e-2,"), "{table}");
    assert!(dir.join("map_linear.png").is_file() && dir.join("map_linear_shift.png").is_file());
    // the same cells from the process pool, but for the wall times
    let pooled = dir.join("pool");
    map(pooled.to_str().unwrap(), "pool");
    // wall time, threads and throughput are each run's own
    let without_wall = |t: &str| -> Vec<String> {
        t.lines()
            .map(|l| {
                let mut c: Vec<&str> = l.split(',').collect();
                c.drain(5..8);
                c.join(",")
            })
            .collect()
    };
    let pooled = std::fs::read_to_string(pooled.join("map.csv")).unwrap();
    assert_eq!(without_wall(&table), without_wall(&pooled));
    // a map drawn again over finished cells runs none of them and gives the same table
    let again = map(out, "in-process");
    assert!(again.contains("2 cells, 2 of them already run"), "{again}");
    assert_eq!(std::fs::read_to_string(dir.join("map.csv")).unwrap(), table);
    // drawn from an empty folder without running: every cell not run
    let empty = dir.join("empty");
    let drawn = map_with(empty.to_str().unwrap(), &["--analyse-only"]);
    assert!(drawn.contains("2 cells, 0 of them already run"), "{drawn}");
    assert_eq!(drawn.matches(": not run").count(), 2, "{drawn}");
    let bad = mpw(&[
        "cut",
        "map",
        "--variants",
        "linear+tilt",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(String::from_utf8_lossy(&bad.stderr).contains("linear+tilt: expected a shape function"));
}

/// The orthogonal cut's map on a coarse grid for 24 µs: the cell's run, its steady cutting
/// force and shear angle in `map.csv`, the force the one `mpw cut orthogonal` run of the
/// same scene gives.
#[test]
fn a_small_orthogonal_map_gives_the_steady_cutting_force() {
    let dir = std::env::temp_dir().join(format!("mpw-cut-map-orth-{}", std::process::id()));
    let out = dir.join("map");
    let (spacing, points, end) = ("4e-4", "20", "24e-6");
    mpw_ok(&[
        "cut",
        "map",
        "--cut",
        "orthogonal",
        "--spacings",
        spacing,
        "--points",
        points,
        "--end",
        end,
        "--executor",
        "in-process",
        "--out",
        out.to_str().unwrap(),
    ]);
    let rows = std::fs::read_to_string(out.join("map.csv")).unwrap();
    let cell: Vec<&str> = rows.lines().nth(1).unwrap().split(',').collect();
    assert_eq!(&cell[..3], ["linear", "4e-4", "20"], "{rows}");
    let (fx, phi): (f64, f64) = (cell[3].parse().unwrap(), cell[4].parse().unwrap());
    assert!(fx > 0.0 && phi > 0.0 && phi < 90.0, "{rows}");
    let single = mpw_ok(&[
        "cut",
        "orthogonal",
        "--spacing",
        spacing,
        "--points",
        points,
        "--end",
        end,
        "--out",
        dir.join("single").to_str().unwrap(),
    ]);
    let printed = format!("f_x {:.3} MN/m", fx * 1e-6);
    assert!(
        single.contains(&printed),
        "map {printed}, single run: {single}"
    );
    assert!(out.join("map_linear.png").is_file());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Two seeds to 2 % feed: the spread table has mean, std and CV per sample, CV = std/|mean|.
#[test]
fn repeated_runs_give_the_force_spread() {
    let dir = std::env::temp_dir().join(format!("mpw-cut-repeat-{}", std::process::id()));
    mpw_ok(&[
        "cut",
        "repeat",
        "--seeds",
        "1,2",
        "--feed",
        "0.02",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let rows = numbers(&dir.join("repeat.csv"));
    assert!(rows.len() > 40, "{}", rows.len());
    let loaded: Vec<&Vec<f64>> = rows.iter().filter(|r| r[2] != 0.0).collect();
    assert!(!loaded.is_empty());
    for r in loaded {
        assert!(
            (r[4] - r[3] / r[2].abs()).abs() <= 1e-12 * r[4].abs().max(1.0),
            "{r:?}"
        );
    }
    assert!(dir.join("repeat.png").is_file() && dir.join("cv.png").is_file());
}

/// A run that fails (a time step 24 times the punch penalty's limit) reports the feed it
/// reached, the cause, and where the point was with its temperature and plastic strain.
#[test]
fn a_failed_cut_says_where_and_at_what_feed() {
    let dir = std::env::temp_dir().join(format!("mpw-cut-fail-{}", std::process::id()));
    let text = mpw_ok(&[
        "cut",
        "vertical",
        "--set",
        "G0",
        "--feed",
        "0.2",
        "--dt",
        "2e-8",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let line = text
        .lines()
        .find(|l| l.starts_with("stopped at "))
        .unwrap_or_else(|| panic!("{text}"));
    assert!(
        line.contains("% relative feed: simulation failed at step"),
        "{line}"
    );
    assert!(
        line.contains(") mm, θ = ") && line.contains(", α = "),
        "{line}"
    );
}

/// Two orthogonal cuts that differ only in depth or friction get default folders of their
/// own, so that one does not overwrite the other.
#[test]
fn orthogonal_cuts_of_other_depth_or_friction_get_their_own_folders() {
    let dir = std::env::temp_dir().join(format!("mpw-cut-orthogonal-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let material = root().join("data/materials/42crmo4_qt660.toml");
    for (depth, friction) in [("0.1e-3", "0"), ("0.3e-3", "0"), ("0.1e-3", "0.2")] {
        let out = Command::new(env!("CARGO_BIN_EXE_mpw"))
            .current_dir(&dir)
            .args([
                "cut",
                "orthogonal",
                "--spacing",
                "2e-4",
                "--points",
                "30",
                "--end",
                "2e-6",
            ])
            .args(["--depth", depth, "--friction", friction, "--material"])
            .arg(&material)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    for folder in [
        "cut_orthogonal_dx0.0002_ny30_h0.1mm",
        "cut_orthogonal_dx0.0002_ny30_h0.3mm",
        "cut_orthogonal_dx0.0002_ny30_h0.1mm_mu0.2",
    ] {
        let scene = dir.join("out").join(folder).join("scene.toml");
        assert!(scene.is_file(), "{} missing", scene.display());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The orthogonal cut repeated over two seeds to 4 µs on a coarse grid: the spread table
/// has time, mean, std and CV of the filtered f_x per sample, CV = std/|mean|, and the
/// seeds differ once the tool cuts.
#[test]
fn repeated_orthogonal_runs_give_the_cutting_force_spread() {
    let dir = std::env::temp_dir().join(format!("mpw-cut-repeat-orth-{}", std::process::id()));
    mpw_ok(&[
        "cut",
        "repeat",
        "--cut",
        "orthogonal",
        "--seeds",
        "1,2",
        "--end",
        "4e-6",
        "--spacing",
        "4e-4",
        "--points",
        "20",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let header = std::fs::read_to_string(dir.join("repeat.csv")).unwrap();
    assert!(
        header
            .starts_with("time_s,mean_force_x_filtered_n_per_m,std_force_x_filtered_n_per_m,cv\n"),
        "{header}"
    );
    let rows = numbers(&dir.join("repeat.csv"));
    let cutting: Vec<&Vec<f64>> = rows.iter().filter(|r| r[1] != 0.0).collect();
    assert!(!cutting.is_empty());
    for r in &cutting {
        assert!(
            (r[3] - r[2] / r[1].abs()).abs() <= 1e-12 * r[3].abs().max(1.0),
            "{r:?}"
        );
    }
    assert!(cutting.iter().any(|r| r[2] > 0.0), "two seeds, one force");
    assert!(dir.join("repeat.png").is_file() && dir.join("cv.png").is_file());
}

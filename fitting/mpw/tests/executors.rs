//! The three executors on real runs: a sweep of eight short runs gives the same CSV, byte
//! for byte, in this process, in the local process pool and through Slurm; an MPM-level
//! fit gives the same report in this process and with its runs in the pool; a task made
//! to fail is reported with its log; a task killed from outside is started again; a
//! stopped sweep leaves no task running, in the pool or in the Slurm queue.
//!
//! The Slurm tests need a Slurm controller that answers (`SLURM_CONF` naming its config):
//! `.ci/test` installs and starts a single-node one. Without it they fail with the reason.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap()
}

fn scene() -> String {
    root()
        .join("data/scenes/colliding_disks.toml")
        .display()
        .to_string()
}

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mpw-executors-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The Slurm config of a test: its work folder under `dir`, one CPU per task.
fn slurm_config(dir: &Path) -> PathBuf {
    let answer = Command::new("sinfo").args(["-h", "-o", "%T"]).output();
    let reason = match &answer {
        Err(e) => format!("sinfo does not run ({e})"),
        Ok(o) if !o.status.success() => String::from_utf8_lossy(&o.stderr).trim().to_string(),
        Ok(o) if String::from_utf8_lossy(&o.stdout).trim().is_empty() => "no node".into(),
        Ok(_) => String::new(),
    };
    assert!(
        reason.is_empty(),
        "no Slurm controller answers (SLURM_CONF = {:?}): {reason}. `.ci/test` installs and starts a single-node Slurm (Debian packages slurm-wlm and munge; needs root)",
        std::env::var("SLURM_CONF").ok()
    );
    let path = dir.join("slurm.toml");
    std::fs::write(
        &path,
        "work_dir = \"slurm-work\"\ntime_limit = \"00:10:00\"\ncpus_per_task = 1\nmax_running = 2\npoll_seconds = 0.2\n",
    )
    .unwrap();
    path
}

fn sweep_command(out: &Path, executor: &str, config: Option<&Path>, extra: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_mpw"));
    c.args(["sweep", &scene(), "--executor", executor, "--out"])
        .arg(out)
        .args(extra);
    if let Some(config) = config {
        c.arg("--slurm").arg(config);
    }
    c
}

fn sweep(out: &Path, executor: &str, config: Option<&Path>, extra: &[&str]) -> Output {
    sweep_command(out, executor, config, extra)
        .output()
        .unwrap()
}

/// Eight runs: two time-step safeties on four grids.
const EIGHT: [&str; 8] = [
    "--vary",
    "grid.spacing=0.05,0.04,0.025,0.02",
    "--vary",
    "time.safety=0.2,0.4",
    "--returns",
    "lower.x_max,upper.kinetic_energy,A.x,B.y,run.steps,run.dt",
    "--chart",
    "A.x",
];

#[test]
fn every_executor_gives_the_same_results_bit_for_bit() {
    let dir = temp("same");
    let config = slurm_config(&dir);
    let mut tables = Vec::new();
    for executor in ["in-process", "pool", "slurm"] {
        let out = dir.join(executor);
        let config = (executor == "slurm").then_some(config.as_path());
        let o = sweep(&out, executor, config, &EIGHT);
        assert!(
            o.status.success(),
            "{executor}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        tables.push(std::fs::read_to_string(out.join("results.csv")).unwrap());
        assert!(out.join("A.x.png").is_file(), "{executor}: no chart");
    }
    assert_eq!(tables[0].lines().count(), 9, "{}", tables[0]);
    assert!(
        tables[0].lines().skip(1).all(|l| l.contains(",ok,")),
        "{}",
        tables[0]
    );
    assert_eq!(tables[0], tables[1], "in-process and pool differ");
    assert_eq!(tables[0], tables[2], "in-process and Slurm differ");
    // a Slurm task ran on the one CPU it was given, and names its description
    let batch = std::fs::read_dir(dir.join("slurm-work"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.to_string_lossy().contains("mpw-sweep-colliding_disks-"))
        .expect("the sweep's folder under work_dir, named with its process id");
    let task = batch.join("task-3");
    let manifest: toml::Table =
        toml::from_str(&std::fs::read_to_string(task.join("manifest.toml")).unwrap()).unwrap();
    assert_eq!(manifest["threads"].as_integer(), Some(1));
    assert_eq!(manifest["status"].as_str(), Some("ok"));
    let pool_manifest: toml::Table = toml::from_str(
        &std::fs::read_to_string(dir.join("pool/tasks/task-3/manifest.toml")).unwrap(),
    )
    .unwrap();
    assert_eq!(
        manifest["description_hash"],
        pool_manifest["description_hash"]
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A negative end time is refused by the run, not by the sweep: the task fails, its row
/// says so, the failure is printed with its log, and the sweep exits non-zero.
#[test]
fn a_failed_task_is_reported_with_its_log() {
    let dir = temp("fail");
    let config = slurm_config(&dir);
    for executor in ["pool", "slurm"] {
        let out = dir.join(executor);
        let config = (executor == "slurm").then_some(config.as_path());
        let o = sweep(
            &out,
            executor,
            config,
            &["--vary", "time.end=3.5,-1", "--returns", "A.x"],
        );
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success(),
            "{executor}: a failed task must fail the sweep"
        );
        assert!(
            stderr.contains("task 1 failed")
                && stderr.contains("`time.end`: must be a positive number, got -1"),
            "{executor}: {stderr}"
        );
        let log = stderr
            .split("(log: ")
            .nth(1)
            .and_then(|s| s.split(')').next())
            .unwrap_or_else(|| panic!("{executor}: no log named in {stderr}"));
        let text = std::fs::read_to_string(log).unwrap();
        assert!(
            text.contains("must be a positive number"),
            "{executor}: {log}: {text}"
        );
        let table = std::fs::read_to_string(out.join("results.csv")).unwrap();
        let rows: Vec<&str> = table.lines().collect();
        assert!(
            rows[1].starts_with("0,3.5,ok,") && rows[2].starts_with("1,-1,failed,"),
            "{table}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Processes whose command line holds `text`.
fn processes_with(text: &str) -> Vec<String> {
    std::fs::read_dir("/proc")
        .unwrap()
        .filter_map(|e| std::fs::read(e.ok()?.path().join("cmdline")).ok())
        .map(|c| String::from_utf8_lossy(&c).replace('\0', " "))
        .filter(|c| c.contains(text))
        .collect()
}

fn wait_for(what: &str, limit: Duration, mut condition: impl FnMut() -> bool) {
    let start = Instant::now();
    while !condition() {
        assert!(start.elapsed() < limit, "waited {limit:?} for {what}");
        std::thread::sleep(Duration::from_millis(100));
    }
}

fn interrupt(child: &Child) {
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
}

/// Four runs of tens of seconds each, stopped once two are under way.
const LONG: [&str; 4] = [
    "--vary",
    "grid.spacing=0.004",
    "--vary",
    "time.safety=0.2,0.21,0.22,0.23",
];

#[test]
fn a_stopped_sweep_leaves_no_task_running() {
    let dir = temp("cancel");
    let config = slurm_config(&dir);
    for executor in ["pool", "slurm"] {
        let out = dir.join(executor);
        let config = (executor == "slurm").then_some(config.as_path());
        let mut child = sweep_command(&out, executor, config, &LONG)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let batch = match executor {
            "slurm" => dir.join(format!(
                "slurm-work/mpw-sweep-colliding_disks-{}",
                child.id()
            )),
            _ => out.join("tasks"),
        };
        let batch = batch.display().to_string();
        wait_for("two tasks under way", Duration::from_secs(120), || {
            processes_with(&format!("run-one {batch}/task-")).len() >= 2
        });
        interrupt(&child);
        let status = child.wait().unwrap();
        let mut stderr = String::new();
        std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).unwrap();
        assert!(
            !status.success() && stderr.contains("cancelled"),
            "{executor}: {stderr}"
        );
        let left = processes_with(&format!("run-one {batch}/task-"));
        assert!(
            left.is_empty(),
            "{executor}: still running after the stop: {left:?}"
        );
        if executor == "slurm" {
            // the queue's jobs by their scripts, which are in the batch folder
            let queue = Command::new("squeue")
                .args(["-h", "-o", "%i %o"])
                .output()
                .unwrap();
            let queue = String::from_utf8_lossy(&queue.stdout);
            let ours: Vec<&str> = queue.lines().filter(|l| l.contains(&batch)).collect();
            assert!(ours.is_empty(), "still in the queue: {ours:?}");
        }
        assert!(!Path::new(&batch).join("task-0/manifest.toml").exists());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A run killed from outside (as by the out-of-memory killer) leaves no manifest; the pool
/// starts it again and the sweep ends with every result.
#[test]
fn a_task_killed_from_outside_is_started_again() {
    let dir = temp("retry");
    let out = dir.join("pool");
    let batch = out.join("tasks").display().to_string();
    let mut child = sweep_command(
        &out,
        "pool",
        None,
        &["--vary", "grid.spacing=0.01", "--returns", "A.x"],
    )
    .stdout(Stdio::null())
    .stderr(Stdio::piped())
    .spawn()
    .unwrap();
    let mut victim = Vec::new();
    wait_for("the task to start", Duration::from_secs(60), || {
        victim = processes_with(&format!("run-one {batch}/task-0"));
        !victim.is_empty()
    });
    let killed = Command::new("pkill")
        .args(["-KILL", "-f", &format!("run-one {batch}/task-0/")])
        .status()
        .unwrap();
    assert!(killed.success(), "pkill found nothing: {victim:?}");
    let status = child.wait().unwrap();
    let mut stderr = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).unwrap();
    assert!(status.success(), "{stderr}");
    let task = Path::new(&batch).join("task-0");
    assert!(task.join("log-1.txt").exists() && task.join("log-2.txt").exists());
    let table = std::fs::read_to_string(out.join("results.csv")).unwrap();
    assert!(
        table.lines().nth(1).unwrap().starts_with("0,0.01,ok,"),
        "{table}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A small MPM-level fit (A and B of 42CrMo4 on the two synthetic SHPB records, 4 layers):
/// every run of its passes and Jacobians in the pool gives the report of the fit in this
/// process, every digit of it but the wall times.
#[test]
fn an_mpm_level_fit_through_the_pool_gives_the_same_report() {
    let dir = temp("fit");
    let data = root().join("data");
    let experiment = |name: &str| {
        format!(
            "[[experiment]]\nfile = \"{}\"\nwindow = [1.5e-5, 1.15e-4]\nforces = \"f2\"\nlevel = \"mpm-axisymmetric\"\nlayers = 4\nmax_samples = 60\n",
            data.join("experiments").join(name).display()
        )
    };
    let set = format!(
        "name = \"mpm through an executor\"\nmaterial = \"{}\"\noptimizer = \"lm\"\nstarts = 1\nftol = 1e-3\n\
         [[parameter]]\nname = \"A\"\nlower = 100e6\nupper = 2000e6\nstart = 700e6\n\
         [[parameter]]\nname = \"B\"\nlower = 10e6\nupper = 4000e6\nstart = 500e6\n{}{}",
        data.join("materials/42crmo4_qt660.toml").display(),
        experiment("shpb_293K.toml"),
        experiment("shpb_573K.toml"),
    );
    std::fs::write(dir.join("set.toml"), set).unwrap();
    let mut reports = Vec::new();
    for executor in ["in-process", "pool"] {
        let out = dir.join(executor);
        let o = Command::new(env!("CARGO_BIN_EXE_mpw"))
            .args([
                "fit",
                dir.join("set.toml").to_str().unwrap(),
                "--executor",
                executor,
                "--out",
            ])
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{executor}: {stderr}");
        if executor == "pool" {
            assert!(stderr.contains("MPM-level runs: 2 processes"), "{stderr}");
        }
        let report = std::fs::read_to_string(out.join("report.toml")).unwrap();
        let without_times: Vec<String> = report
            .lines()
            .filter(|l| !l.contains("wall"))
            .map(str::to_string)
            .collect();
        reports.push(without_times);
    }
    assert!(
        reports[0]
            .iter()
            .any(|l| l.starts_with("final_parameters = [")),
        "{reports:?}"
    );
    assert_eq!(reports[0], reports[1]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A part of the verification catalogue run as a task (`mpw run-one`, kind `verify-part`)
/// gives the rows the part gives in this process, every number to the bit.
#[test]
fn a_verification_part_as_a_task_gives_the_rows_in_process() {
    let dir = temp("verify");
    let data = root().join("data");
    let mut d = runs::RunDescription::new("verify-part", &data);
    d.set
        .insert("part".into(), toml::Value::String("shpb".into()));
    d.write(&dir.join("description.toml")).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_mpw"))
        .arg("run-one")
        .arg(dir.join("description.toml"))
        .arg(dir.join("task"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(dir.join("task/run/rows.toml")).unwrap();
    let task: mpw::tasks::VerifyRows = toml::from_str(&text).unwrap();
    let verify_data = mpw::verify::data::VerifyData::new(&data);
    let inputs = mpw::verify::Inputs {
        data: &verify_data,
        full: false,
    };
    let here = mpw::verify::part(&inputs, "shpb").unwrap();
    assert!(here.len() >= 5, "{} rows", here.len());
    assert_eq!(task.rows.len(), here.len());
    for (a, b) in task.rows.iter().zip(&here) {
        assert_eq!(a.name, b.name);
        assert_eq!(a.measured.to_bits(), b.measured.to_bits(), "{}", a.name);
        assert_eq!(a.reference.to_bits(), b.reference.to_bits(), "{}", a.name);
        assert_eq!(
            (a.verdict, &a.tolerance),
            (b.verdict, &b.tolerance),
            "{}",
            a.name
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Seeds set the grid-shift sequence: two seeds move the results, the same seed repeats
/// them to the bit; a scene without a shift is refused, its seed would change nothing.
#[test]
fn seeds_move_a_shifted_grid_and_repeat_to_the_bit() {
    let dir = temp("seeds");
    let args = [
        "--vary",
        "grid.shift=[0.01,0.01]",
        "--seeds",
        "1,2,1",
        "--returns",
        "A.x",
    ];
    let o = sweep(&dir.join("shifted"), "pool", None, &args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let table = std::fs::read_to_string(dir.join("shifted/results.csv")).unwrap();
    let ax: Vec<&str> = table
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap())
        .collect();
    assert_eq!(ax.len(), 3, "{table}");
    assert_ne!(ax[0], ax[1], "seeds 1 and 2 gave the same run: {table}");
    assert_eq!(ax[0], ax[2], "seed 1 twice differs: {table}");
    let o = sweep(&dir.join("plain"), "in-process", None, &["--seeds", "1,2"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && stderr.contains("has no grid.shift"),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

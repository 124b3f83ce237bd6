//! Hostile input: damaged copies of the shipped inputs run through `mpw` under a
//! memory and a time limit, so that a regression fails this test instead of the machine.
//!
//! - The regression corpus `tests/corpus/hostile/cases.toml`: every input that ever
//!   crashed, hung or exhausted memory, each replacing one file of a shipped input; it must
//!   end in an error that names the file and the row, within the limits.
//! - The damage campaign: a fixed number of randomly damaged copies (fixed seed) of the
//!   default experiment set (its 3 TOMLs, 3 CSVs and the material file) through
//!   `mpw fit`, and of two small scenes through `mpw simulate`. Damage: a flipped byte, the
//!   file cut short, a line doubled or dropped, a number replaced by 0, −1, 1e30, 1e-30,
//!   nan or a 20-digit integer, or `nan`, `inf`, NUL or `[[` inserted. Each run must fit,
//!   or end with exit status 1 and an `error:` line that names a file or the step of a
//!   simulation failure; a panic, a signal (the memory limit makes allocation fail), or a
//!   run past the time limit fails the test.
//!
//! Limits per run: 100 MiB of address space (`ulimit -v`; the undamaged default fit needs
//! under 60 MiB) and `TIME_LIMIT`.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use serde::Deserialize;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const MEMORY_KIB: usize = 100 * 1024;
const TIME_LIMIT: Duration = Duration::from_secs(60);
/// Damaged copies per input in CI; `HOSTILE_CASES` and `HOSTILE_SEED` run a longer or
/// different campaign by hand.
const CASES_PER_INPUT: usize = 60;

fn env_or<T: std::str::FromStr>(key: &str, default: T) -> T {
    std::env::var(key)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data")
}

/// How one run ended.
#[derive(Debug)]
enum Outcome {
    Success,
    /// Exit status 1 with this `error:` message.
    Error(String),
    /// Anything else: a panic, a signal, another status, or the time limit.
    Failure(String),
}

/// Run `mpw args` under the memory and time limits.
fn run_limited(args: &[&str]) -> (Outcome, Duration) {
    let mut command = format!("ulimit -v {MEMORY_KIB} && exec \"$0\"");
    for k in 1..=args.len() {
        command += &format!(" \"${k}\"");
    }
    let started = Instant::now();
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(command)
        .arg(env!("CARGO_BIN_EXE_mpw"))
        .args(args)
        .env("RAYON_NUM_THREADS", "1")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn sh");
    let mut stderr = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut text = String::new();
        let _ = stderr.read_to_string(&mut text);
        text
    });
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break Some(status);
        }
        if started.elapsed() > TIME_LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let elapsed = started.elapsed();
    let text = reader.join().unwrap();
    let outcome = match status {
        None => Outcome::Failure(format!("still running after {TIME_LIMIT:?}")),
        Some(s) if s.success() => Outcome::Success,
        Some(s) if s.code() == Some(1) && !text.contains("panicked") => {
            match text.lines().find(|l| l.starts_with("error:")) {
                Some(line) if names_its_place(line) => Outcome::Error(line.to_string()),
                Some(line) => Outcome::Failure(format!("an error that names no file: {line}")),
                None => Outcome::Failure(format!("status 1 without an error line: {text}")),
            }
        }
        Some(s) => Outcome::Failure(format!("{s}: {}", text.trim())),
    };
    (outcome, elapsed)
}

/// An error names the file it is about, or it is a simulation failure with its step and
/// cause (a bare "No such file or directory" is not an answer).
fn names_its_place(line: &str) -> bool {
    [".toml", ".csv", "simulation failed at step"]
        .iter()
        .any(|p| line.contains(p))
}

/// A fresh copy of the files of `data/experiments`, `data/materials` and `data/scenes`
/// (their relative paths stay valid) under a per-test folder.
fn copy_inputs(name: &str) -> PathBuf {
    let root = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&root);
    for dir in ["experiments", "materials", "scenes"] {
        std::fs::create_dir_all(root.join(dir)).unwrap();
        for entry in std::fs::read_dir(data().join(dir)).unwrap() {
            let path = entry.unwrap().path();
            if path.is_file() {
                std::fs::copy(&path, root.join(dir).join(path.file_name().unwrap())).unwrap();
            }
        }
    }
    root
}

#[derive(Deserialize)]
struct Corpus {
    case: Vec<CorpusCase>,
}

#[derive(Deserialize)]
struct CorpusCase {
    /// The corpus file, beside `cases.toml`.
    file: String,
    /// The shipped file it replaces, relative to `data/`.
    replaces: String,
    /// `mpw` arguments; `{root}` is the copy of `data/`, `{out}` an output folder.
    args: Vec<String>,
    /// The error must contain this text.
    expect: String,
}

#[test]
fn every_corpus_input_ends_in_a_named_error_within_the_limits() {
    let corpus_dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/hostile");
    let text = std::fs::read_to_string(corpus_dir.join("cases.toml")).unwrap();
    let corpus: Corpus = toml::from_str(&text).unwrap();
    assert!(!corpus.case.is_empty());
    for (k, case) in corpus.case.iter().enumerate() {
        let root = copy_inputs(&format!("hostile-corpus-{k}"));
        std::fs::copy(corpus_dir.join(&case.file), root.join(&case.replaces)).unwrap();
        let args = expand(&case.args, &root);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (outcome, elapsed) = run_limited(&args);
        match outcome {
            Outcome::Error(e) => assert!(
                e.contains(&case.expect),
                "{}: expected an error containing {:?}, got {e}",
                case.file,
                case.expect
            ),
            other => panic!("{}: expected an error, got {other:?}", case.file),
        }
        eprintln!("{}: named error after {elapsed:?}", case.file);
    }
}

fn expand(args: &[String], root: &Path) -> Vec<String> {
    args.iter()
        .map(|a| {
            a.replace("{root}", &root.display().to_string())
                .replace("{out}", &root.join("out").display().to_string())
        })
        .collect()
}

/// One random damage of `bytes`, and what it was.
fn damage(bytes: &[u8], rng: &mut Pcg64) -> (Vec<u8>, String) {
    let mut b = bytes.to_vec();
    let lines: Vec<(usize, usize)> = line_spans(&b);
    match rng.gen_range(0..6) {
        0 => {
            let i = rng.gen_range(0..b.len());
            let bit = 1u8 << rng.gen_range(0..8);
            b[i] ^= bit;
            (b, format!("byte {i} xor {bit:#04x}"))
        }
        1 => {
            let n = rng.gen_range(0..b.len());
            b.truncate(n);
            (b, format!("cut after byte {n}"))
        }
        2 | 3 => {
            let (s, e) = lines[rng.gen_range(0..lines.len())];
            let line = b[s..e].to_vec();
            if rng.gen_bool(0.5) {
                b.splice(s..s, line);
                (b, format!("line at byte {s} doubled"))
            } else {
                b.drain(s..e);
                (b, format!("line at byte {s} dropped"))
            }
        }
        4 => {
            let numbers = number_spans(&b);
            if numbers.is_empty() {
                return (b, "no number to replace".into());
            }
            let (s, e) = numbers[rng.gen_range(0..numbers.len())];
            let by =
                ["0", "-1", "1e30", "1e-30", "nan", "99999999999999999999"][rng.gen_range(0..6)];
            let was = String::from_utf8_lossy(&b[s..e]).to_string();
            b.splice(s..e, by.bytes());
            (b, format!("number {was} at byte {s} replaced by {by}"))
        }
        _ => {
            let i = rng.gen_range(0..=b.len());
            let what = ["nan", "inf", "\0", "[["][rng.gen_range(0..4)];
            b.splice(i..i, what.bytes());
            (b, format!("{what:?} inserted at byte {i}"))
        }
    }
}

/// (start, end) of every line including its newline.
fn line_spans(b: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut start = 0;
    for (i, &c) in b.iter().enumerate() {
        if c == b'\n' {
            spans.push((start, i + 1));
            start = i + 1;
        }
    }
    if start < b.len() {
        spans.push((start, b.len()));
    }
    spans
}

/// (start, end) of every maximal run of number characters that parses as a number.
fn number_spans(b: &[u8]) -> Vec<(usize, usize)> {
    let is_num = |c: u8| c.is_ascii_digit() || b"+-.eE".contains(&c);
    let mut spans = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if is_num(b[i]) && (i == 0 || !b[i - 1].is_ascii_alphabetic()) {
            let s = i;
            while i < b.len() && is_num(b[i]) {
                i += 1;
            }
            let text = std::str::from_utf8(&b[s..i]).unwrap_or("");
            if text.parse::<f64>().is_ok() && text.bytes().any(|c| c.is_ascii_digit()) {
                spans.push((s, i));
            }
        } else {
            i += 1;
        }
    }
    spans
}

/// One input of the campaign: the files that may be damaged and the command that reads
/// them (relative to the copy of `data/`).
struct Input {
    name: &'static str,
    files: &'static [&'static str],
    args: &'static [&'static str],
}

const INPUTS: &[Input] = &[
    Input {
        name: "default experiment set",
        files: &[
            "experiments/default.toml",
            "experiments/qs_tension.toml",
            "experiments/qs_tension.csv",
            "experiments/shpb_293K.toml",
            "experiments/shpb_293K.csv",
            "experiments/shpb_573K.toml",
            "experiments/shpb_573K.csv",
            "materials/42crmo4_qt660.toml",
        ],
        args: &["fit", "{root}/experiments/default.toml", "--out", "{out}"],
    },
    Input {
        name: "colliding disks scene",
        files: &["scenes/colliding_disks.toml"],
        args: &[
            "simulate",
            "{root}/scenes/colliding_disks.toml",
            "--out",
            "{out}",
        ],
    },
    Input {
        name: "single particle scene",
        files: &["scenes/single_particle.toml"],
        args: &[
            "simulate",
            "{root}/scenes/single_particle.toml",
            "--out",
            "{out}",
        ],
    },
];

#[test]
fn randomly_damaged_inputs_never_panic_hang_or_exhaust_memory() {
    let mut rng = Pcg64::seed_from_u64(env_or("HOSTILE_SEED", 16));
    let cases = env_or("HOSTILE_CASES", CASES_PER_INPUT);
    let mut failures = Vec::new();
    for input in INPUTS {
        let (mut fitted, mut errors, mut slowest) = (0, 0, Duration::ZERO);
        for k in 0..cases {
            let root = copy_inputs("hostile-campaign");
            let file = input.files[rng.gen_range(0..input.files.len())];
            let original = std::fs::read(root.join(file)).unwrap();
            let (damaged, what) = damage(&original, &mut rng);
            std::fs::write(root.join(file), damaged).unwrap();
            let args: Vec<String> = input.args.iter().map(|a| a.to_string()).collect();
            let args = expand(&args, &root);
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            let (outcome, elapsed) = run_limited(&args);
            slowest = slowest.max(elapsed);
            match outcome {
                Outcome::Success => fitted += 1,
                Outcome::Error(_) => errors += 1,
                Outcome::Failure(why) => {
                    failures.push(format!("{} case {k}: {file}: {what}: {why}", input.name))
                }
            }
        }
        eprintln!(
            "{}: {cases} damaged copies: {fitted} ran to the end, {errors} named errors, slowest {slowest:?}",
            input.name
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

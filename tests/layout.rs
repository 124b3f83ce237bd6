//! The layout the README shows is the repository's, and dependencies point one way
//! (DESIGN 2): `materials` <- `mpm-core` <- `fitting`, `cutting` <- `mpw`, and `runs` (the
//! executors, which know no mechanics) <- `mpw`; no library depends on a
//! command-line, chart or terminal crate; within each crate, the top-level modules import
//! each other without circles.

use mpw_workspace_tests::repo_root;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The paths listed in the README's "Layout" block (first word of each line).
fn readme_layout() -> BTreeSet<String> {
    let readme = std::fs::read_to_string(repo_root().join("README.md")).unwrap();
    let section = readme
        .split("\n## Layout")
        .nth(1)
        .expect("a Layout section in the README");
    let block = section
        .split("```")
        .nth(1)
        .expect("a code block in the Layout section");
    (block.lines())
        .filter(|l| !l.starts_with(' '))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|w| w.ends_with('/') || w.contains('.'))
        .map(str::to_owned)
        .collect()
}

fn manifest(dir: &str) -> toml::Table {
    let path = repo_root().join(dir).join("Cargo.toml");
    std::fs::read_to_string(&path).unwrap().parse().unwrap()
}

fn dependencies(dir: &str) -> BTreeSet<String> {
    let m = manifest(dir);
    (m.get("dependencies").and_then(|d| d.as_table()))
        .map(|d| d.keys().cloned().collect())
        .unwrap_or_default()
}

#[test]
fn the_readme_layout_lists_every_folder_and_package() {
    let listed = readme_layout();
    for path in &listed {
        assert!(
            repo_root().join(path).exists(),
            "README layout lists {path}, which does not exist"
        );
    }
    let root = manifest(".");
    let members = root["workspace"]["members"].as_array().unwrap();
    for m in members.iter().map(|m| format!("{}/", m.as_str().unwrap())) {
        assert!(
            listed.contains(&m),
            "workspace member {m} is not in the README layout"
        );
    }
    for entry in std::fs::read_dir(repo_root()).unwrap().map(|e| e.unwrap()) {
        let name = entry.file_name().to_string_lossy().into_owned();
        let ignored = name.starts_with('.') || name == "target" || name == "out";
        if entry.file_type().unwrap().is_dir() && !ignored {
            assert!(
                listed.contains(&format!("{name}/")),
                "folder {name}/ is not in the README layout"
            );
        }
    }
}

#[test]
fn dependencies_point_from_the_program_to_the_libraries() {
    let program_only = ["clap", "plotters", "indicatif", "ctrlc"];
    let above = [
        ("materials", vec!["mpm-core", "fitting", "cutting", "mpw"]),
        ("mpm-core", vec!["fitting", "cutting", "mpw"]),
        ("fitting", vec!["cutting", "mpw"]),
        ("cutting", vec!["fitting", "mpw"]),
        (
            "runs",
            vec!["materials", "mpm-core", "fitting", "cutting", "mpw"],
        ),
    ];
    for (library, not_on) in above {
        let deps = dependencies(library);
        for d in program_only.iter().chain(&not_on) {
            assert!(!deps.contains(*d), "the {library} library depends on {d}");
        }
    }
    let program = dependencies("fitting/mpw");
    for library in [
        "materials",
        "mpm-core",
        "fitting",
        "cutting",
        "runs",
        "clap",
    ] {
        assert!(
            program.contains(library),
            "mpw does not depend on {library}"
        );
    }
}

/// Top-level module of a source file under `src` (`None` for lib.rs and main.rs).
fn top_module(src: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src).unwrap();
    let first = rel
        .components()
        .next()?
        .as_os_str()
        .to_string_lossy()
        .into_owned();
    let name = first.trim_end_matches(".rs").to_owned();
    (name != "lib" && name != "main").then_some(name)
}

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()) {
        if entry.is_dir() {
            rust_files(&entry, out);
        } else if entry.extension().is_some_and(|e| e == "rs") {
            out.push(entry);
        }
    }
}

/// Which top-level modules each top-level module of `src` names through `crate::`
/// (outside its unit tests).
fn module_graph(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut files = vec![];
    rust_files(src, &mut files);
    let tops: BTreeSet<String> = files.iter().filter_map(|f| top_module(src, f)).collect();
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for file in &files {
        let Some(top) = top_module(src, file) else {
            continue;
        };
        let text = std::fs::read_to_string(file).unwrap();
        let code = text.split("#[cfg(test)]\nmod tests").next().unwrap();
        let mut named = BTreeSet::new();
        for (k, _) in code.match_indices("crate::") {
            let rest = &code[k + 7..];
            if let Some(group) = rest.strip_prefix('{') {
                let inner = &group[..group.find('}').unwrap_or(0)];
                named.extend(
                    inner
                        .split(',')
                        .filter_map(|p| p.split("::").next())
                        .map(|p| p.trim().to_owned()),
                );
            } else {
                named.insert(
                    rest.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                        .next()
                        .unwrap()
                        .to_owned(),
                );
            }
        }
        let edges = graph.entry(top.clone()).or_default();
        edges.extend(named.into_iter().filter(|n| *n != top && tops.contains(n)));
    }
    graph
}

/// The modules that lie on a circle, grouped (strongly connected components of two or
/// more).
fn circles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<BTreeSet<String>> {
    let reach = |from: &String| {
        let (mut seen, mut todo) = (BTreeSet::new(), vec![from.clone()]);
        while let Some(m) = todo.pop() {
            for n in graph.get(&m).into_iter().flatten() {
                if seen.insert(n.clone()) {
                    todo.push(n.clone());
                }
            }
        }
        seen
    };
    let reaches: BTreeMap<_, _> = graph.keys().map(|m| (m.clone(), reach(m))).collect();
    let mut groups: Vec<BTreeSet<String>> = vec![];
    for m in graph.keys() {
        let group: BTreeSet<String> = (reaches[m].iter())
            .filter(|n| reaches.get(*n).is_some_and(|r| r.contains(m)))
            .cloned()
            .collect();
        if group.len() > 1 && !groups.contains(&group) {
            groups.push(group);
        }
    }
    groups
}

#[test]
fn the_modules_of_each_crate_import_each_other_without_circles() {
    for src in [
        "materials/src",
        "mpm-core/src",
        "fitting/src",
        "cutting/src",
        "runs/src",
        "fitting/mpw/src",
    ] {
        let graph = module_graph(&repo_root().join(src));
        assert!(graph.len() >= 3, "{src}: {} modules found", graph.len());
        let on_circles = circles(&graph);
        assert!(
            on_circles.is_empty(),
            "{src}: modules on a circle of imports: {on_circles:?}"
        );
    }
}

/// The circle finder finds a circle of three, and not a chain.
#[test]
fn a_circle_of_imports_is_found() {
    let edges = |pairs: &[(&str, &str)]| {
        let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (a, b) in pairs {
            g.entry(a.to_string()).or_default().insert(b.to_string());
            g.entry(b.to_string()).or_default();
        }
        g
    };
    let circle = edges(&[("a", "b"), ("b", "c"), ("c", "a"), ("c", "d")]);
    let found: Vec<BTreeSet<String>> = vec![["a", "b", "c"].map(String::from).into()];
    assert_eq!(circles(&circle), found);
    assert!(circles(&edges(&[("a", "b"), ("b", "c"), ("a", "c")])).is_empty());
}

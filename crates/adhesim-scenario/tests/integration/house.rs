//! The shape of the source tree (ARCHITECTURE.md): no crate's top-level modules import each
//! other in a circle, and no source file passes 600 lines. Read from the files, so that a
//! change that knots the house fails here rather than in a later review.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The longest a source file may be (tests included).
const MAX_FILE_LINES: usize = 600;

/// The workspace's crates folder.
fn crates_folder() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap().to_path_buf()
}

/// Every `.rs` file under `folder`, recursively.
fn rust_files(folder: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut pending = vec![folder.to_path_buf()];
    while let Some(dir) = pending.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                pending.push(path);
            } else if path.extension().is_some_and(|ext| ext == "rs") {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

/// The names `crate::NAME` refers to in `text`, outside comments and test modules.
fn crate_references(text: &str) -> BTreeSet<String> {
    let code = text.split("#[cfg(test)]").next().unwrap_or_default();
    let mut names = BTreeSet::new();
    for line in code.lines().filter(|line| !line.trim_start().starts_with("//")) {
        for (at, _) in line.match_indices("crate::") {
            let rest = &line[at + "crate::".len()..];
            let name: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            // `$crate::` and `adhesim_scenario::crate` are not this crate's paths.
            let before = line[..at].chars().last();
            if !name.is_empty() && !matches!(before, Some('$' | '_') | Some('a'..='z')) {
                names.insert(name);
            }
        }
    }
    names
}

/// The import graph of a crate's top-level modules (a module's files and submodules count
/// as the module; test files are left out).
fn module_graph(source: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for file in rust_files(source) {
        let relative = file.strip_prefix(source).unwrap();
        let parts: Vec<String> = relative.iter().map(|p| p.to_string_lossy().into_owned()).collect();
        let file_name = parts.last().unwrap();
        let is_test = file_name == "tests.rs"
            || file_name.ends_with("_tests.rs")
            || file_name.starts_with("tests_")
            || parts[..parts.len() - 1].iter().any(|dir| dir == "tests");
        let top = parts[0].trim_end_matches(".rs").to_string();
        if is_test || top == "lib" || top == "main" {
            continue;
        }
        let text = std::fs::read_to_string(&file).unwrap();
        let references = crate_references(&text);
        graph
            .entry(top.clone())
            .or_default()
            .extend(references.into_iter().filter(|name| *name != top));
    }
    let modules: BTreeSet<String> = graph.keys().cloned().collect();
    for targets in graph.values_mut() {
        targets.retain(|name| modules.contains(name));
    }
    graph
}

/// A circle of modules in `graph` (its modules in order, the first repeated at the end), if any.
fn find_circle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        node: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(start) = path.iter().position(|name| name == node) {
            let mut circle = path[start..].to_vec();
            circle.push(node.to_string());
            return Some(circle);
        }
        if done.contains(node) {
            return None;
        }
        path.push(node.to_string());
        for next in &graph[node] {
            if let Some(circle) = visit(next, graph, path, done) {
                return Some(circle);
            }
        }
        path.pop();
        done.insert(node.to_string());
        None
    }
    let mut done = BTreeSet::new();
    graph
        .keys()
        .find_map(|node| visit(node, graph, &mut Vec::new(), &mut done))
}

#[test]
fn the_finder_sees_a_circle_and_ignores_comments() {
    let graph = |edges: &[(&str, &str)]| {
        let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (from, to) in edges {
            graph.entry(from.to_string()).or_default().insert(to.to_string());
            graph.entry(to.to_string()).or_default();
        }
        graph
    };
    assert_eq!(
        find_circle(&graph(&[("a", "b"), ("b", "c"), ("c", "a")])),
        Some(vec!["a".into(), "b".into(), "c".into(), "a".into()])
    );
    assert_eq!(find_circle(&graph(&[("a", "b"), ("b", "c"), ("a", "c")])), None);
    let text = "use crate::grid::Grid;\n// crate::surface in a comment\nfn f() { $crate::x(); }\n#[cfg(test)]\nuse crate::tests;";
    assert_eq!(crate_references(text), BTreeSet::from(["grid".to_string()]));
}

#[test]
fn no_crate_imports_its_own_modules_in_a_circle() {
    let crates = crates_folder();
    for name in [
        "adhesim",
        "adhesim-scenario",
        "adhesim-cli",
        "adhesim-py",
        "adhesim-experiment",
        "adhesim-topography",
    ] {
        let graph = module_graph(&crates.join(name).join("src"));
        assert!(graph.len() > 3, "{name}: only {} modules read", graph.len());
        if let Some(circle) = find_circle(&graph) {
            panic!(
                "{name}'s modules import each other in a circle: {}",
                circle.join(" -> ")
            );
        }
    }
}

#[test]
fn no_source_file_passes_the_line_limit() {
    let crates = crates_folder();
    let mut long = Vec::new();
    let files = rust_files(&crates);
    assert!(
        files.len() > 100,
        "only {} source files found under {}",
        files.len(),
        crates.display()
    );
    for file in files {
        if file.components().any(|part| part.as_os_str() == "target") {
            continue;
        }
        let lines = std::fs::read_to_string(&file).unwrap().lines().count();
        if lines > MAX_FILE_LINES {
            long.push(format!("{} ({lines} lines)", file.display()));
        }
    }
    assert!(
        long.is_empty(),
        "files over {MAX_FILE_LINES} lines: {}",
        long.join(", ")
    );
}

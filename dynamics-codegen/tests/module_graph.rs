//! The compiler's modules import each other without cycles, and the expansion does not
//! depend on the passes, the scheduler or the printer.
//!
//! The module graph is read from the source text: each file of `src/` is a module
//! (`expand/rnea.rs` is `expand::rnea`, `expand/mod.rs` is `expand`), and it depends on every
//! module it names with `crate::a::b` or `super::a` (in `use` lines or paths; comments and
//! `#[cfg(test)]` test modules left out). An edge between two modules is lifted to the
//! children of their closest common ancestor (`expand::aba` → `passes::fusion` is
//! `expand` → `passes`; `expand::aba` → `expand::spatial` stays as it is); an edge to an
//! ancestor or a descendant is no edge (a module always declares its children).

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

type Module = Vec<String>;

/// Every module of `src/` with its source text, tests and comments removed.
fn modules() -> BTreeMap<Module, String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut out = BTreeMap::new();
    let mut stack = vec![root.clone()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("src/ is readable") {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            if path.extension().is_none_or(|e| e != "rs") {
                continue;
            }
            let relative = path.strip_prefix(&root).expect("under src/");
            let mut name: Module = relative
                .with_extension("")
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            if name
                .last()
                .is_some_and(|l| l == "mod" || l == "lib" || l == "main")
            {
                name.pop();
            }
            let text = std::fs::read_to_string(&path).expect("a readable source file");
            out.insert(name, without_tests_and_comments(&text));
        }
    }
    out
}

fn without_tests_and_comments(text: &str) -> String {
    let mut kept = String::new();
    for line in text.lines() {
        let trimmed = line.trim_start();
        if trimmed.starts_with("#[cfg(test)]") {
            // A test module or a test-only item ends the part that counts (the test
            // modules stand at the end of every file here).
            break;
        }
        let code = line.split("//").next().unwrap_or("");
        kept.push_str(code);
        kept.push('\n');
    }
    kept
}

/// The longest prefix of `path` that names a module.
fn resolve(path: &[String], names: &BTreeSet<Module>) -> Option<Module> {
    (1..=path.len())
        .rev()
        .map(|k| path[..k].to_vec())
        .find(|candidate| names.contains(candidate))
}

/// The identifiers in a path after `prefix` (`crate::a::b` → [a, b]); for `super::{a, b}`,
/// one path per element.
fn paths_after(text: &str, prefix: &str) -> Vec<Vec<String>> {
    let mut paths = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find(prefix) {
        let before = rest[..at].chars().last();
        rest = &rest[at + prefix.len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        if let Some(group) = rest.strip_prefix('{') {
            let end = group.find('}').unwrap_or(group.len());
            for part in group[..end].split(',') {
                let ident: String = part
                    .trim()
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if ident.starts_with(|c: char| c.is_ascii_lowercase()) {
                    paths.push(vec![ident]);
                }
            }
            continue;
        }
        let path: Vec<String> = rest
            .split("::")
            .map(|seg| {
                seg.chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect::<String>()
            })
            .take_while(|seg| seg.starts_with(|c: char| c.is_ascii_lowercase()))
            .collect();
        if !path.is_empty() {
            paths.push(path);
        }
    }
    paths
}

/// The module graph, edges lifted to siblings.
fn graph() -> BTreeMap<Module, BTreeSet<Module>> {
    let modules = modules();
    let names: BTreeSet<Module> = modules.keys().cloned().collect();
    let mut edges: BTreeMap<Module, BTreeSet<Module>> = BTreeMap::new();
    for (module, text) in &modules {
        let parent = &module[..module.len().saturating_sub(1)];
        let targets = paths_after(text, "crate::")
            .into_iter()
            .chain(paths_after(text, "super::").into_iter().map(|p| {
                let mut full = parent.to_vec();
                full.extend(p);
                full
            }))
            .filter_map(|p| resolve(&p, &names));
        for target in targets {
            let common = module
                .iter()
                .zip(&target)
                .take_while(|(a, b)| a == b)
                .count();
            if common == module.len() || common == target.len() {
                continue;
            }
            edges
                .entry(module[..=common].to_vec())
                .or_default()
                .insert(target[..=common].to_vec());
        }
    }
    edges
}

/// A cycle through `start`, if any.
fn cycle_from(edges: &BTreeMap<Module, BTreeSet<Module>>, start: &Module) -> Option<Vec<Module>> {
    let mut stack = vec![(start.clone(), vec![start.clone()])];
    let mut seen = BTreeSet::new();
    while let Some((node, path)) = stack.pop() {
        for next in edges.get(&node).into_iter().flatten() {
            if next == start {
                let mut cycle = path.clone();
                cycle.push(next.clone());
                return Some(cycle);
            }
            if seen.insert(next.clone()) {
                let mut longer = path.clone();
                longer.push(next.clone());
                stack.push((next.clone(), longer));
            }
        }
    }
    None
}

#[test]
fn module_imports_form_no_cycle() {
    let edges = graph();
    assert!(edges.len() > 5, "the module graph was not read: {edges:?}");
    let cycles: Vec<String> = edges
        .keys()
        .filter_map(|m| cycle_from(&edges, m))
        .map(|c| {
            c.iter()
                .map(|m| m.join("::"))
                .collect::<Vec<_>>()
                .join(" -> ")
        })
        .collect();
    assert!(cycles.is_empty(), "import cycles:\n{}", cycles.join("\n"));
}

#[test]
fn the_expansion_depends_on_no_later_stage() {
    let edges = graph();
    let expand = vec!["expand".to_owned()];
    let targets = edges.get(&expand).cloned().unwrap_or_default();
    for later in ["passes", "schedule", "print", "functions", "declare"] {
        assert!(
            !targets.contains(&vec![later.to_owned()]),
            "expand depends on {later}: {targets:?}"
        );
    }
    // The reading works: expand does depend on the model and the graph.
    assert!(targets.contains(&vec!["model".to_owned()]), "{targets:?}");
    assert!(targets.contains(&vec!["sym".to_owned()]), "{targets:?}");
}

//! The workspace's layers, as Cargo.lock records them: a crate's build
//! holds only the crates below it. The Python module (and the runner it
//! stands on) never pulls in the command line, the language server or the
//! Rerun SDK (issue 42); a lower crate never names a higher one (issue 40).

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Each package of Cargo.lock and the names of its dependencies (a
/// dependency written `name version` when two versions are locked).
fn lock() -> BTreeMap<String, Vec<String>> {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.lock"))
        .expect("Cargo.lock is readable");
    let mut packages = BTreeMap::new();
    for block in text.split("[[package]]").skip(1) {
        let mut name = None;
        let mut deps = Vec::new();
        let mut in_deps = false;
        for line in block.lines() {
            let line = line.trim();
            if let Some(n) = line.strip_prefix("name = ") {
                name = Some(n.trim_matches('"').to_string());
            } else if line == "dependencies = [" {
                in_deps = true;
            } else if in_deps && line == "]" {
                in_deps = false;
            } else if in_deps {
                let dep = line.trim_end_matches(',').trim_matches('"');
                let dep = dep.split(' ').next().expect("a name");
                deps.push(dep.to_string());
            }
        }
        packages.insert(name.expect("a package has a name"), deps);
    }
    packages
}

/// Every package `root` depends on, directly or not. Cargo.lock lists
/// dev-dependencies too: the closure is a superset of a build's, so a name
/// absent from it is absent from the build.
fn closure(packages: &BTreeMap<String, Vec<String>>, root: &str) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    let mut todo = vec![root.to_string()];
    while let Some(p) = todo.pop() {
        for d in packages.get(&p).into_iter().flatten() {
            if seen.insert(d.clone()) {
                todo.push(d.clone());
            }
        }
    }
    seen
}

#[test]
fn the_python_module_and_the_runner_stand_below_the_command_line() {
    let packages = lock();
    for root in ["scen-python", "scen-runner"] {
        assert!(packages.contains_key(root), "{root} is in the workspace");
        let below = closure(&packages, root);
        for higher in [
            "scen",
            "clap",
            "lsp-server",
            "lsp-types",
            "rerun",
            "indicatif",
        ] {
            assert!(
                !below.contains(higher),
                "{root} depends on `{higher}`, which belongs to the command line"
            );
        }
        assert!(below.contains("scen-language"), "{root} loads scenarios");
    }
}

#[test]
fn a_lower_crate_never_names_a_higher_one() {
    let packages = lock();
    let layers = [
        "scen-geometry",
        "scen-planners",
        "scen-language",
        "scen-runner",
        "scen",
    ];
    for (k, crate_name) in layers.iter().enumerate() {
        let below = closure(&packages, crate_name);
        for higher in &layers[k + 1..] {
            assert!(
                !below.contains(*higher),
                "`{crate_name}` depends on `{higher}`, a crate above it"
            );
        }
        for lower in &layers[..k] {
            assert!(
                below.contains(*lower),
                "`{crate_name}` does not stand on `{lower}`"
            );
        }
    }
}

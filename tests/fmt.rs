//! `scen fmt` on every scenario, every bad input that parses and random
//! scenarios with random layouts and comments: formatting twice changes
//! nothing, every comment is kept in order, the parse is the same, and the
//! formatted file runs exactly as before (`scen run --json`'s document,
//! timings, lines and the expressions' blanks and comments aside).

mod common;

use std::path::{Path, PathBuf};

use common::format_oracle;
use common::random::{Rng, scenario};
use common::{TempDir, Test, repo};
use scen::format::format_text;
use scen::rng::SplitMix64;
use serde_json::Value;

/// Formats `text` and checks the properties of the module docs that need no
/// run (`common::format_oracle`); returns the formatted text.
fn check_format(text: &str, what: &str) -> String {
    match format_oracle::check_format(text) {
        Ok(Some(formatted)) => formatted,
        Ok(None) => panic!("{what}: {:?}", format_text(text).err()),
        Err(broke) => panic!("{what}: {broke}"),
    }
}

/// `scen run --json`'s document without what may change: timings, check
/// lines, the file's path, blanks and comments inside expressions.
fn run_json(file: &Path) -> Option<Value> {
    let scenario = scen::load(file).ok()?;
    let mut doc = scen::report::json::to_json(&scen::run_scenario(scenario, &[]));
    fn strip(v: &mut Value) {
        match v {
            Value::Object(map) => {
                // Timings: `time_ms` and the other `*_ms` metrics.
                map.retain(|k, _| !k.ends_with("_ms"));
                map.remove("line");
                map.remove("file");
                if let Some(Value::String(expr)) = map.get_mut("expr") {
                    let without_comments: String = expr
                        .lines()
                        .map(|l| l.split('#').next().unwrap_or(""))
                        .collect();
                    *expr = without_comments.split_whitespace().collect();
                }
                map.values_mut().for_each(strip);
            }
            Value::Array(items) => items.iter_mut().for_each(strip),
            _ => {}
        }
    }
    strip(&mut doc);
    Some(doc)
}

/// The diagnostics' codes and messages of a file under `root` that does not
/// load (`root` written `<root>` in them).
fn diag_codes(root: &Path, file: &Path) -> Vec<(String, String)> {
    let root = root.display().to_string();
    match scen::load(&root_join(&root, file)) {
        Ok(_) => Vec::new(),
        Err(f) => f
            .diags
            .iter()
            .map(|d| (d.code.to_string(), d.message.replace(&root, "<root>")))
            .collect(),
    }
}

fn root_join(root: &str, file: &Path) -> PathBuf {
    Path::new(root).join(file)
}

fn scen_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for e in entries {
        if e.is_dir() {
            scen_files(&e, out);
        } else if e.extension().is_some_and(|x| x == "scen")
            && !scen::scenario::movingai::is_scen_file(&e)
        {
            out.push(e);
        }
    }
}

/// Copies `from` into `to`, every `.scen` file formatted (those that parse).
fn copy_formatted(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap().path();
        let target = to.join(e.file_name().unwrap());
        if e.is_dir() {
            copy_formatted(&e, &target);
            continue;
        }
        let bytes = std::fs::read(&e).unwrap();
        let text = String::from_utf8(bytes.clone()).ok();
        match text
            .as_deref()
            .filter(|_| e.extension().is_some_and(|x| x == "scen"))
        {
            Some(t) if format_text(t).is_ok() => {
                std::fs::write(&target, check_format(t, &e.display().to_string())).unwrap()
            }
            _ => std::fs::write(&target, bytes).unwrap(),
        }
    }
}

#[test]
fn every_scenario_formats_and_runs_as_before() {
    let dir = TempDir::new("fmt-scenarios");
    let formatted = dir.path().join("scenarios");
    copy_formatted(&repo().join("scenarios"), &formatted);
    let mut files = Vec::new();
    scen_files(&repo().join("scenarios"), &mut files);
    assert!(files.len() > 20);
    for file in files {
        let relative = file.strip_prefix(repo().join("scenarios")).unwrap();
        let name = relative.display().to_string();
        if name.starts_with('_') || name.contains("/_") {
            continue;
        }
        let before = run_json(&file);
        let after = run_json(&formatted.join(relative));
        assert!(before.is_some(), "{name} loads");
        assert_eq!(before, after, "{name} runs differently once formatted");
    }
}

#[test]
fn every_bad_input_that_parses_formats_and_reports_the_same() {
    let dir = TempDir::new("fmt-bad");
    let formatted = dir.path().join("bad_inputs");
    copy_formatted(&repo().join("tests/bad_inputs"), &formatted);
    let mut files = Vec::new();
    scen_files(&repo().join("tests/bad_inputs"), &mut files);
    let mut parsed = 0;
    for file in files {
        let Ok(text) = std::fs::read_to_string(&file) else {
            continue;
        };
        if format_text(&text).is_err() {
            continue;
        }
        parsed += 1;
        let relative = file.strip_prefix(repo().join("tests/bad_inputs")).unwrap();
        assert_eq!(
            diag_codes(&repo().join("tests/bad_inputs"), relative),
            diag_codes(&formatted, relative),
            "{}",
            relative.display()
        );
    }
    assert!(parsed > 50, "{parsed} bad inputs parse");
}

/// The text with its layout shuffled: extra blanks, blanks removed after
/// commas, comments at line ends and on lines of their own.
fn shuffle_layout(text: &str, seed: u64) -> String {
    let mut r = Rng(SplitMix64::new(seed ^ 0x5eed));
    let mut out = String::new();
    for (k, line) in text.lines().enumerate() {
        if r.below(4) == 0 {
            out.push_str(&format!("# comment {k} before\n"));
        }
        let mut l = line.replace(", ", if r.below(2) == 0 { "," } else { " ,  " });
        if r.below(3) == 0 {
            l = l.replacen(' ', "   ", 1);
        }
        out.push_str(&l);
        if r.below(3) == 0 {
            out.push_str(&format!("  # comment {k} after"));
        }
        out.push('\n');
        if r.below(5) == 0 {
            out.push('\n');
        }
    }
    out
}

#[test]
fn random_scenarios_with_random_layouts_format_and_run_as_before() {
    let dir = TempDir::new("fmt-random");
    for seed in 0..200u64 {
        let text = shuffle_layout(&scenario(seed), seed);
        let formatted = check_format(&text, &format!("seed {seed}:\n{text}"));
        // Running is slow: every tenth case.
        if seed % 10 == 0 {
            let (a, b) = (dir.path().join("a.scen"), dir.path().join("b.scen"));
            std::fs::write(&a, &text).unwrap();
            std::fs::write(&b, &formatted).unwrap();
            assert_eq!(run_json(&a), run_json(&b), "seed {seed}:\n{text}");
        }
    }
}

#[test]
fn fmt_rewrites_files_and_check_lists_those_that_would_change() {
    let messy = "robot r   point\nplan p astar r { start (0,0) goal (1,1) }\n";
    let tidy = "robot r point\nplan p astar r {\n  start (0, 0)\n  goal (1, 1)\n}\n";
    Test::new()
        .file("a.scen", messy)
        .file("sub/b.scen", tidy)
        .args(&["fmt", "--check", "."])
        .stdout("./a.scen\n")
        .status(1)
        .run();
    let t = Test::new()
        .file("a.scen", messy)
        .args(&["fmt", "a.scen"])
        .stdout("")
        .status(0);
    t.run();
    assert_eq!(
        std::fs::read_to_string(t.dir().join("a.scen")).unwrap(),
        tidy
    );
    Test::new()
        .file("bad.scen", "world {\n")
        .args(&["fmt", "bad.scen"])
        .stderr_contains("has syntax errors: not formatted")
        .status(2)
        .run();
}

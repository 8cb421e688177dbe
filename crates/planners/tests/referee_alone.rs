//! The validator judges; planners search with their own motion checkers
//! (SPEC 3.0, issue 40). No planner's code names the validator's checks:
//! what a planner may ask of it goes through the referee the runner lends
//! (`contract::referee`), and only tests (which judge) call it directly.
//! Their checkers come from the task (`Task::motion_checker`,
//! `Task::car_checker`), built from the robot's body, never by hand.

use std::fs;
use std::path::{Path, PathBuf};

/// What only the validator does.
const REFEREE_CALLS: [&str; 6] = [
    "Validator",
    "validate_path",
    "validate_car_path",
    "validate_and_measure",
    "config_collision",
    "check_wall_crossings",
];

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = fs::read_dir(dir)
        .expect("read the planners' sources")
        .map(|e| e.expect("a directory entry").path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// The code of a file before its first `#[cfg(test)]`, comments dropped;
/// none for a file of tests.
fn planner_code(path: &Path) -> String {
    if path.file_name().is_some_and(|n| n == "tests.rs") {
        return String::new();
    }
    let text = fs::read_to_string(path).expect("read a source file");
    text.lines()
        .take_while(|l| l.trim() != "#[cfg(test)]")
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn no_planner_calls_the_validator() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/planners");
    let mut files = Vec::new();
    rust_files(&root, &mut files);
    assert!(files.len() > 20, "found {} planner files", files.len());
    let mut found = Vec::new();
    for f in &files {
        let code = planner_code(f);
        for call in REFEREE_CALLS {
            if code.contains(call) {
                found.push(format!("{} names `{call}`", f.display()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "planners must use their motion checkers (geometry::motion, proximity, car::CarChecker) or the referee the task lends:\n{}",
        found.join("\n")
    );
}

/// How a planner would build a checker itself instead of taking the task's.
const OWN_CHECKERS: [&str; 2] = ["MotionChecker::new", "CarChecker::new"];

#[test]
fn planners_take_their_checkers_from_the_task() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/planners");
    let mut files = Vec::new();
    rust_files(&root, &mut files);
    let found: Vec<String> = files
        .iter()
        .flat_map(|f| {
            let code = planner_code(f);
            OWN_CHECKERS
                .iter()
                .filter(move |c| code.contains(*c))
                .map(move |c| format!("{} calls `{c}`", f.display()))
        })
        .collect();
    assert!(
        found.is_empty(),
        "planners take their checkers from the task (task.motion_checker(), task.car_checker()):\n{}",
        found.join("\n")
    );
}

/// The test can fail: the rule sees a call planted in planner code.
#[test]
fn the_rule_sees_a_planted_call() {
    let dir = std::env::temp_dir().join(format!("scen-referee-{}", std::process::id()));
    fs::create_dir_all(&dir).unwrap();
    let planted = dir.join("planted.rs");
    fs::write(
        &planted,
        "use x::Validator;\n// validate_path in a comment is fine\n#[cfg(test)]\nmod tests {}\n",
    )
    .unwrap();
    let code = planner_code(&planted);
    assert!(code.contains("Validator"));
    assert!(!code.contains("validate_path"));
    fs::remove_dir_all(&dir).unwrap();
}

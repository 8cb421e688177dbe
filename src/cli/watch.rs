//! `scen watch FILE [run's options]` (SPEC §4): run again on every save of
//! the file or of a file it reads (includes, maps), streaming to the same
//! viewer (`--spawn` starts it once; later runs connect to it) and printing
//! the report each time. A save that does not parse prints its diagnostics
//! and waits for the next.
//!
//! Changes are found by polling the files' modification times and sizes a
//! few times a second: no watcher library (one more dependency and its
//! platform back-ends) for what a handful of `stat` calls do, and it works
//! on every file system, network mounts and editors that save by renaming
//! included.

use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

use super::clobber::{Input, outputs_are_not_inputs};
use super::{EXIT_BAD_INPUT, RunArgs, run_file};
use crate::viz::ViewerTarget;

/// How often the files are looked at.
const POLL: Duration = Duration::from_millis(200);

/// Runs until interrupted; returns only on bad usage (exit 2).
pub(super) fn cmd_watch(args: &RunArgs) -> i32 {
    let [file] = args.files.as_slice() else {
        eprintln!("error: `scen watch` takes one scenario file");
        return EXIT_BAD_INPUT;
    };
    if !file.is_file() {
        eprintln!(
            "error: `{}` does not exist (or is not a file); `scen watch` needs a scenario to run",
            file.display()
        );
        return EXIT_BAD_INPUT;
    }
    // An output onto the watched file is refused at once; onto an include
    // or a map, each run refuses it (until a save removes the include).
    let watched_file = Input {
        path: file,
        role: "the scenario",
    };
    if !args.usable() || !outputs_are_not_inputs(&args.output_files(None), &[watched_file]) {
        return EXIT_BAD_INPUT;
    }
    let mut target = args.viewer_target();
    let mut viewer_warned = false;
    eprintln!(
        "watching `{}` and the files it reads; Ctrl-C to stop",
        file.display()
    );
    let mut run = 1u64;
    // The files the last run read, looked at before the next run starts:
    // a save made while a run is going on (after the file was read) is
    // then seen, whatever the file system's clock granularity.
    let mut watched: Vec<PathBuf> = vec![file.clone()];
    loop {
        let before_run = stamps(&watched);
        let (_, read) = run_file(file, args, target.as_ref(), &mut viewer_warned);
        // The viewer `--spawn` started keeps running: later runs go to it.
        if target == Some(ViewerTarget::Spawn) {
            target = Some(ViewerTarget::Connect(None));
        }
        watched = read;
        watched.push(file.clone());
        watched.sort();
        watched.dedup();
        wait_for_change(&watched, &before_run);
        run += 1;
        eprintln!("\n── `{}` changed: run {run} ──", file.display());
    }
}

/// What a file looks like to a poll: its modification time and size, or
/// nothing when it does not exist (a file being replaced by an editor).
type Stamp = Option<(SystemTime, u64)>;

fn stamp(path: &Path) -> Stamp {
    let meta = std::fs::metadata(path).ok()?;
    Some((meta.modified().ok()?, meta.len()))
}

fn stamps(files: &[PathBuf]) -> Vec<(PathBuf, Stamp)> {
    files.iter().map(|f| (f.clone(), stamp(f))).collect()
}

/// Returns once one of `files` changed and has stayed the same for one
/// more poll, so that a save in progress is not read half-written. A file
/// is compared with how it looked before the run that read it (from
/// `before_run`; a file the run read for the first time, with how it looks
/// now): written, replaced, removed or created.
fn wait_for_change(files: &[PathBuf], before_run: &[(PathBuf, Stamp)]) {
    let before: Vec<Stamp> = files
        .iter()
        .map(|f| match before_run.iter().find(|(g, _)| g == f) {
            Some((_, s)) => *s,
            None => stamp(f),
        })
        .collect();
    let mut now: Vec<Stamp> = files.iter().map(|f| stamp(f)).collect();
    while now == before {
        std::thread::sleep(POLL);
        now = files.iter().map(|f| stamp(f)).collect();
    }
    // Settle: wait until two polls agree.
    loop {
        std::thread::sleep(POLL);
        let again: Vec<Stamp> = files.iter().map(|f| stamp(f)).collect();
        if again == now {
            return;
        }
        now = again;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A save made after the run read the file but before the poll began
    /// (a fast run, a coarse file-system clock) is still a change: the file
    /// is compared with how it looked before the run.
    #[test]
    fn a_save_during_the_run_is_seen() {
        let dir = std::env::temp_dir().join(format!("scen-watch-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let file = dir.join("a.scen");
        std::fs::write(&file, "robot p point\n").expect("write");
        let before_run = stamps(std::slice::from_ref(&file));
        // The "run" reads the file; the user saves at once.
        std::fs::write(&file, "robot p point\nrobot q point\n").expect("save");
        let (tx, rx) = std::sync::mpsc::channel();
        let watched = vec![file.clone()];
        std::thread::spawn(move || {
            wait_for_change(&watched, &before_run);
            let _ = tx.send(());
        });
        let seen = rx.recv_timeout(Duration::from_secs(20));
        let _ = std::fs::remove_dir_all(&dir);
        assert!(seen.is_ok(), "the save was not seen");
    }
}

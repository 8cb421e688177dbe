//! A `Test` builder in the style of casey/just's integration tests: write
//! files into a temporary folder, run the real `scen` binary there, and
//! compare stdout, stderr and the exit code.

#![allow(dead_code)]

pub mod format_oracle;
pub mod lsp_client;
pub mod planner_cases;
pub mod random;

use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Output};
use std::time::{Duration, Instant};

pub fn scen_bin() -> &'static str {
    env!("CARGO_BIN_EXE_scen")
}

/// The repository's root folder.
pub fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The `rerun` binary of rerun-sdk==0.36.3 (`SCEN_RERUN`, else the one
/// scripts/test.sh installs, else PATH); `None` after saying so when there
/// is none, which on CI (`CI=true`) is a failure.
pub fn rerun_binary() -> Option<PathBuf> {
    let found = std::env::var_os("SCEN_RERUN")
        .map(PathBuf::from)
        .or_else(|| Some(repo().join("target/rerun-venv/bin/rerun")).filter(|p| p.exists()))
        .or_else(|| {
            std::env::var_os("PATH").and_then(|paths| {
                std::env::split_paths(&paths)
                    .map(|d| d.join("rerun"))
                    .find(|p| p.exists())
            })
        });
    if found.is_none() {
        assert_ne!(
            std::env::var("CI").as_deref(),
            Ok("true"),
            "CI must have the rerun binary (scripts/test.sh installs rerun-sdk==0.36.3)"
        );
        eprintln!(
            "skipped: no `rerun` binary (pip install rerun-sdk==0.36.3, or run scripts/test.sh)"
        );
    }
    found
}

/// What `rerun rrd print` lists for the recording of `scen run SCENARIO
/// --save` (SCENARIO relative to the repository); `None` without the
/// `rerun` binary (see [`rerun_binary`]).
pub fn recording_printout(scenario: &str) -> Option<String> {
    let rerun = rerun_binary()?;
    let dir = TempDir::new("recording");
    let rrd = dir.path().join("run.rrd");
    let run = Command::new(scen_bin())
        .args(["run", scenario, "--save"])
        .arg(&rrd)
        .current_dir(repo())
        .output()
        .expect("run scen");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let print = Command::new(&rerun)
        .args(["rrd", "print"])
        .arg(&rrd)
        .output()
        .expect("run rerun");
    assert!(print.status.success());
    Some(String::from_utf8_lossy(&print.stdout).into_owned())
}

/// The public test data folder `../shared/data/SUB` when it holds every
/// one of `files`; `None` after saying what is missing, which on CI
/// (`CI=true`) is a failure.
pub fn shared_data(sub: &str, files: &[&str]) -> Option<PathBuf> {
    let dir = repo().join("../shared/data").join(sub);
    let missing: Vec<&str> = files
        .iter()
        .copied()
        .filter(|f| !dir.join(f).is_file())
        .collect();
    if missing.is_empty() {
        return Some(dir);
    }
    let message = format!(
        "test data missing in `{}`: {}",
        dir.display(),
        missing.join(", ")
    );
    assert!(std::env::var("CI").as_deref() != Ok("true"), "{message}");
    eprintln!("skipped: {message}");
    None
}

/// A fresh temporary folder, removed on drop.
pub struct TempDir(PathBuf);

impl TempDir {
    pub fn new(tag: &str) -> Self {
        use std::sync::atomic::{AtomicUsize, Ordering};
        static N: AtomicUsize = AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!(
            "scen-test-{tag}-{}-{}",
            std::process::id(),
            N.fetch_add(1, Ordering::SeqCst)
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create temp dir");
        TempDir(dir)
    }

    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

pub struct Test {
    dir: TempDir,
    args: Vec<String>,
    env: Vec<(String, String)>,
    stdout: Option<String>,
    stdout_contains: Vec<String>,
    stderr: Option<String>,
    stderr_contains: Vec<String>,
    status: i32,
    timeout: Duration,
}

impl Test {
    pub fn new() -> Self {
        Test {
            dir: TempDir::new("cli"),
            args: Vec::new(),
            env: vec![("NO_COLOR".into(), "1".into())],
            stdout: None,
            stdout_contains: Vec::new(),
            stderr: None,
            stderr_contains: Vec::new(),
            status: 0,
            timeout: Duration::from_secs(60),
        }
    }

    /// Writes a file (relative to the test's folder).
    pub fn file(self, name: &str, text: &str) -> Self {
        let p = self.dir.path().join(name);
        if let Some(parent) = p.parent() {
            std::fs::create_dir_all(parent).expect("create folder");
        }
        std::fs::write(p, text).expect("write test file");
        self
    }

    pub fn args(mut self, args: &[&str]) -> Self {
        self.args.extend(args.iter().map(|s| s.to_string()));
        self
    }

    pub fn env(mut self, key: &str, value: &str) -> Self {
        self.env.push((key.into(), value.into()));
        self
    }

    pub fn stdout(mut self, s: &str) -> Self {
        self.stdout = Some(s.into());
        self
    }

    pub fn stdout_contains(mut self, s: &str) -> Self {
        self.stdout_contains.push(s.into());
        self
    }

    pub fn stderr(mut self, s: &str) -> Self {
        self.stderr = Some(s.into());
        self
    }

    pub fn stderr_contains(mut self, s: &str) -> Self {
        self.stderr_contains.push(s.into());
        self
    }

    pub fn status(mut self, code: i32) -> Self {
        self.status = code;
        self
    }

    pub fn dir(&self) -> &Path {
        self.dir.path()
    }

    /// Runs `scen` in the test's folder and checks every expectation.
    pub fn run(&self) -> Output {
        let out = run_with_timeout(
            Command::new(scen_bin())
                .args(&self.args)
                .current_dir(self.dir.path())
                .envs(self.env.iter().map(|(k, v)| (k.as_str(), v.as_str()))),
            self.timeout,
        );
        let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        let ctx = format!(
            "scen {}\n--- stdout\n{stdout}\n--- stderr\n{stderr}",
            self.args.join(" ")
        );
        assert_eq!(out.status.code(), Some(self.status), "exit code\n{ctx}");
        if let Some(s) = &self.stdout {
            assert_eq!(&stdout, s, "stdout\n{ctx}");
        }
        for s in &self.stdout_contains {
            assert!(stdout.contains(s.as_str()), "stdout lacks {s:?}\n{ctx}");
        }
        if let Some(s) = &self.stderr {
            assert_eq!(&stderr, s, "stderr\n{ctx}");
        }
        for s in &self.stderr_contains {
            assert!(stderr.contains(s.as_str()), "stderr lacks {s:?}\n{ctx}");
        }
        assert!(!stderr.contains("panicked"), "scen panicked\n{ctx}");
        out
    }
}

/// Runs a command, killing it after `timeout` (a hang is a test failure).
pub fn run_with_timeout(cmd: &mut Command, timeout: Duration) -> Output {
    let finished = run_or_kill(cmd, timeout);
    let Some(status) = finished.status else {
        panic!("scen did not finish within {timeout:?}");
    };
    Output {
        status,
        stdout: finished.stdout,
        stderr: finished.stderr,
    }
}

/// What a process did.
pub struct Finished {
    /// `None` when it was killed at the timeout.
    pub status: Option<ExitStatus>,
    pub stdout: Vec<u8>,
    pub stderr: Vec<u8>,
}

/// Runs a command with stdin closed and its output piped (drained while it
/// runs, so that a chatty child cannot block on a full pipe), killing it
/// after `timeout`.
pub fn run_or_kill(cmd: &mut Command, timeout: Duration) -> Finished {
    use std::process::Stdio;
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the command starts");
    let drain = |mut pipe: Box<dyn std::io::Read + Send>| {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            let _ = pipe.read_to_end(&mut bytes);
            bytes
        })
    };
    let stdout = drain(Box::new(child.stdout.take().expect("piped stdout")));
    let stderr = drain(Box::new(child.stderr.take().expect("piped stderr")));
    let began = Instant::now();
    let status = loop {
        match child.try_wait().expect("waiting for the command") {
            Some(status) => break Some(status),
            None if began.elapsed() > timeout => {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
            None => std::thread::sleep(Duration::from_millis(2)),
        }
    };
    Finished {
        status,
        stdout: stdout.join().expect("stdout reader"),
        stderr: stderr.join().expect("stderr reader"),
    }
}

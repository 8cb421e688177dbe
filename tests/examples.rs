//! The job files of `examples/` run their commands as their schedulers
//! would: every Slurm array task, every pod index of the Kubernetes Indexed
//! Job and every entry of the GitHub Actions matrix in turn, in a folder
//! that holds the repository's `scenarios/` (a symlink), with the `scen`
//! under test first on `PATH`. The merge steps then run on the parts the
//! shards wrote, their checks must all pass, and the merged table must be
//! the table one machine prints (timings aside).
//!
//! What the schedulers themselves do is not run: `#SBATCH` lines are
//! comments to bash, a Job's volume is a folder here (`/results` is
//! replaced by it), and the workflow's `uses:` steps (checkout, artifacts)
//! and its `cargo install` step (the binary under test is that build) are
//! skipped; the artifacts' layout (`parts/part-K.jsonl`) is the folder's.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Duration;

use common::{TempDir, repo, run_with_timeout, scen_bin};

const BENCH: &str = "scenarios/features/bench_seeds.scen";
/// The table's columns compared between the merge and one machine: no
/// timings.
const METRICS: &str = "length,expanded,steps,clearance";

/// A folder with the repository's scenarios, as a job's working directory.
fn workspace(tag: &str) -> TempDir {
    let dir = TempDir::new(tag);
    std::os::unix::fs::symlink(repo().join("scenarios"), dir.path().join("scenarios"))
        .expect("symlink scenarios/");
    dir
}

/// `PATH` with the directory of the `scen` under test first.
fn path_with_scen() -> String {
    let bin = Path::new(scen_bin()).parent().expect("the binary's folder");
    format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    )
}

/// Runs `script` with `shell -c` in `dir`; it must succeed.
fn run_script(shell: &str, dir: &Path, script: &str, env: &[(&str, String)]) -> String {
    let mut cmd = Command::new(shell);
    cmd.arg("-c")
        .arg(script)
        .current_dir(dir)
        .env("PATH", path_with_scen());
    for (k, v) in env {
        cmd.env(k, v);
    }
    let out = run_with_timeout(&mut cmd, Duration::from_secs(600));
    assert_success(&out, script);
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn assert_success(out: &Output, what: &str) {
    assert!(
        out.status.success(),
        "`{what}` failed ({}):\n{}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// What a merge printed is a whole bench whose checks all passed.
fn assert_merged(stdout: &str) {
    assert!(
        stdout.contains("bench seeds (40 runs)"),
        "the merged table:\n{stdout}"
    );
    assert!(stdout.contains(" passed, 0 failed"), "{stdout}");
}

/// The merged parts under `dir/parts` print the table one machine prints.
fn assert_same_table(dir: &Path, parts: &str) {
    let merged = run_script(
        "bash",
        dir,
        &format!("scen bench merge {parts} --metrics {METRICS}"),
        &[],
    );
    let whole = run_script(
        "bash",
        dir,
        &format!("scen bench {BENCH} --metrics {METRICS}"),
        &[],
    );
    assert_eq!(merged, whole);
}

fn example(path: &str) -> String {
    std::fs::read_to_string(repo().join("examples").join(path)).expect("the example file")
}

#[test]
fn the_slurm_array_and_its_merge() {
    let script = example("slurm/bench.sbatch");
    let tasks: usize = script
        .lines()
        .find_map(|l| l.strip_prefix("#SBATCH --array=1-"))
        .expect("an #SBATCH --array=1-N line")
        .trim()
        .parse()
        .expect("N");
    assert!(tasks > 1);
    let dir = workspace("slurm");
    let bench = repo().join("examples/slurm/bench.sbatch");
    for k in 1..=tasks {
        let out = Command::new("bash")
            .arg(&bench)
            .current_dir(dir.path())
            .env("PATH", path_with_scen())
            .env("SLURM_ARRAY_TASK_ID", k.to_string())
            .env("SLURM_ARRAY_TASK_COUNT", tasks.to_string())
            .output()
            .expect("bash runs");
        assert_success(&out, &format!("bench.sbatch as task {k}"));
        assert!(dir.path().join(format!("parts/part-{k}.jsonl")).is_file());
    }
    let merge = repo().join("examples/slurm/merge.sbatch");
    let out = Command::new("bash")
        .arg(&merge)
        .current_dir(dir.path())
        .env("PATH", path_with_scen())
        .output()
        .expect("bash runs");
    assert_success(&out, "merge.sbatch");
    assert_merged(&String::from_utf8_lossy(&out.stdout));
    let csv = std::fs::read_to_string(dir.path().join("parts/runs.csv")).expect("runs.csv");
    assert_eq!(csv.lines().count(), 1 + 40, "a header and every run");
    let svg = std::fs::read_to_string(dir.path().join("parts/plots.svg")).expect("plots.svg");
    assert!(svg.starts_with("<svg"));
    assert_same_table(dir.path(), "parts/part-*.jsonl");
}

/// The shell script of a container's `args: - |` block.
fn container_script(yaml: &str) -> String {
    let mut lines = yaml.lines();
    let indent = loop {
        let line = lines.next().expect("an `- |` block");
        if line.trim() == "- |" {
            break line.len() - line.trim_start().len();
        }
    };
    lines
        .take_while(|l| l.trim().is_empty() || l.len() - l.trim_start().len() > indent)
        .map(|l| l.trim())
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn the_kubernetes_indexed_job_and_its_merge() {
    let job = example("kubernetes/bench-job.yaml");
    assert!(job.contains("completionMode: Indexed"));
    let pods: usize = job
        .lines()
        .find_map(|l| l.trim().strip_prefix("completions: "))
        .expect("completions: N")
        .parse()
        .expect("N");
    let dir = workspace("k8s");
    let results = dir.path().join("results");
    std::fs::create_dir(&results).expect("the volume");
    let volume = results.display().to_string();
    let script = container_script(&job).replace("/results", &volume);
    for index in 0..pods {
        run_script(
            "sh",
            dir.path(),
            &script,
            &[("JOB_COMPLETION_INDEX", index.to_string())],
        );
    }
    let merge =
        container_script(&example("kubernetes/merge-job.yaml")).replace("/results", &volume);
    assert_merged(&run_script("sh", dir.path(), &merge, &[]));
    assert!(results.join("runs.csv").is_file());
    assert_same_table(dir.path(), &format!("{volume}/part-*.jsonl"));
}

/// One job of a workflow: its matrix's `shard` values (or none) and the
/// commands of its `run:` steps, in order.
#[derive(Debug, Default)]
struct Job {
    name: String,
    shards: Vec<String>,
    runs: Vec<String>,
}

/// The jobs of a workflow file, read line by line (the layout of
/// `examples/github-actions/scen.yml`: two-space indentation).
fn workflow_jobs(yaml: &str) -> Vec<Job> {
    let mut jobs: Vec<Job> = Vec::new();
    let lines: Vec<&str> = yaml.lines().collect();
    let indent = |l: &str| l.len() - l.trim_start().len();
    let mut in_jobs = false;
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        i += 1;
        if line == "jobs:" {
            in_jobs = true;
            continue;
        }
        if !in_jobs || line.trim().is_empty() || line.trim_start().starts_with('#') {
            continue;
        }
        if indent(line) == 2 && line.trim_end().ends_with(':') {
            jobs.push(Job {
                name: line.trim().trim_end_matches(':').to_string(),
                ..Job::default()
            });
            continue;
        }
        let job = jobs.last_mut().expect("a step inside a job");
        let trimmed = line.trim();
        if let Some(list) = trimmed.strip_prefix("shard: [") {
            job.shards = list
                .trim_end_matches(']')
                .split(',')
                .map(|s| s.trim().to_string())
                .collect();
        } else if let Some(run) = trimmed.strip_prefix("- run: ") {
            if run == "|" {
                let block_indent = indent(line);
                let mut block = Vec::new();
                while i < lines.len() && indent(lines[i]) > block_indent {
                    block.push(lines[i].trim());
                    i += 1;
                }
                job.runs.push(block.join("\n"));
            } else {
                job.runs.push(run.to_string());
            }
        }
    }
    jobs
}

#[test]
fn the_github_actions_matrix_and_its_merge() {
    let jobs = workflow_jobs(&example("github-actions/scen.yml"));
    let names: Vec<&str> = jobs.iter().map(|j| j.name.as_str()).collect();
    assert_eq!(names, ["test", "bench", "merge"]);
    let dir = workspace("gha");
    let mut merged = None;
    for job in &jobs {
        let shards = if job.shards.is_empty() {
            vec![String::new()]
        } else {
            job.shards.clone()
        };
        for shard in &shards {
            for run in &job.runs {
                if run.starts_with("cargo install") {
                    continue;
                }
                let script = run.replace("${{ matrix.shard }}", shard);
                let out = run_script("bash", dir.path(), &script, &[]);
                if job.name == "merge" {
                    merged = Some(out);
                }
            }
        }
    }
    // Every scenario ran in exactly one test shard, and each wrote a report.
    let mut cases = 0;
    for shard in &jobs[0].shards {
        let xml = std::fs::read_to_string(dir.path().join(format!("junit-{shard}.xml")))
            .expect("a JUnit report per shard");
        assert!(xml.starts_with("<?xml"), "{xml}");
        let suites = xml
            .lines()
            .find(|l| l.starts_with("<testsuites "))
            .expect("<testsuites>");
        assert!(suites.contains(" failures=\"0\""), "{suites}");
        cases += xml.matches("<testcase ").count();
    }
    assert!(cases > 100, "{cases} test cases over the shards");
    assert_merged(&merged.expect("the merge job ran"));
    assert!(dir.path().join("runs.csv").is_file() && dir.path().join("plots.svg").is_file());
    assert_same_table(dir.path(), "parts/part-*.jsonl");
}

#[test]
fn every_example_is_tested_here() {
    let mut files: Vec<PathBuf> = Vec::new();
    for sub in std::fs::read_dir(repo().join("examples")).expect("examples/") {
        let sub = sub.expect("an entry").path();
        if sub.is_dir() {
            for f in std::fs::read_dir(&sub).expect("a folder") {
                files.push(f.expect("an entry").path());
            }
        }
    }
    files.sort();
    let names: Vec<String> = files
        .iter()
        .map(|f| {
            f.strip_prefix(repo().join("examples"))
                .expect("under examples/")
                .display()
                .to_string()
        })
        .collect();
    assert_eq!(
        names,
        [
            // Run by tests/python/test_bench.py (it needs the wheel and
            // Dask's `distributed`, which scripts/wheel.sh --check installs).
            "dask/bench.py",
            "github-actions/scen.yml",
            "kubernetes/bench-job.yaml",
            "kubernetes/merge-job.yaml",
            "slurm/bench.sbatch",
            "slurm/merge.sbatch",
        ],
        "a new example gets its test above"
    );
}

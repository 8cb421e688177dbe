//! `scen._scen`: the Python module (SPEC §7), on the crates below the
//! command line (`scen-runner` and the language, planners and geometry
//! under it: no clap, no language server, no Rerun SDK), never through the
//! command line.
//!
//! - [`load`] / [`loads`]: a scenario from a file or from text; bad input
//!   raises `ScenError`, carrying the located diagnostics.
//! - [`Scenario::run`]: its plans run with the GIL released; a
//!   [`Report`] whose plans hold their metrics, and their path and
//!   trajectory as numpy float64 arrays, taken from the same document as
//!   `scen run --json` (so the two agree to the bit).
//! - [`Scenario::validate`]: the validator on a path made elsewhere (a
//!   numpy array), as `scen validate` does.
//! - [`plan`]: a planner straight on a numpy occupancy grid.
//! - [`Scenario::bench`], [`Scenario::bench_part`], [`bench_merge`]: `scen
//!   bench`, one shard of it as a part's text, and the merge of the parts.
//! - `_repr_svg_` on scenarios, reports and plans' results, for Jupyter.
//!
//! The Python package (`python/scen/__init__.py`) re-exports this module;
//! its type stubs are `python/scen/_scen.pyi`.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyReadonlyArray2};
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyKeyError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use pyo3::{IntoPyObjectExt, Py};
use serde_json::Value;

use scen_runner::diagnostics::{Diag, SourceMap, render_diags};
use scen_runner::geometry::Config;
use scen_runner::scenario::SampleChoice;
use scen_runner::scenario::loader::{LoadFailure, load_sample};

create_exception!(
    _scen,
    ScenError,
    PyException,
    "Bad input: a scenario that does not load, a plan that does not exist, a path of the wrong shape. `diagnostics` lists each problem as a dict (severity, code, message, label, help, and file, line, column when located); str(error) is the report `scen check` prints."
);

/// The error for diagnostics: its text the rendered report, its
/// `diagnostics` the list of dicts (`scen check --format json`'s).
fn scen_error(py: Python<'_>, diags: &[Diag], sources: &SourceMap) -> PyErr {
    let text = render_diags(diags, sources);
    let err = ScenError::new_err(text.trim_end().to_string());
    let list: Vec<Value> = diags.iter().map(|d| d.to_json(sources)).collect();
    match json_to_py(py, &Value::Array(list)) {
        Ok(value) => match err.value(py).setattr("diagnostics", value) {
            Ok(()) => err,
            Err(e) => e,
        },
        Err(e) => e,
    }
}

/// A `ScenError` with one message and no location.
fn plain_error(py: Python<'_>, code: &'static str, message: String, help: &str) -> PyErr {
    scen_error(
        py,
        &[Diag::error(code, message).help(help)],
        &SourceMap::default(),
    )
}

fn failure(py: Python<'_>, f: LoadFailure) -> PyErr {
    scen_error(py, &f.diags, &f.sources)
}

/// JSON as Python: objects as dicts (in order), arrays as lists, numbers
/// as int or float, null as None.
fn json_to_py<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => b.into_bound_py_any(py)?,
        Value::Number(n) => {
            if let Some(i) = n.as_i64() {
                i.into_bound_py_any(py)?
            } else if let Some(u) = n.as_u64() {
                u.into_bound_py_any(py)?
            } else {
                n.as_f64().unwrap_or(f64::NAN).into_bound_py_any(py)?
            }
        }
        Value::String(s) => s.into_bound_py_any(py)?,
        Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(json_to_py(py, item)?)?;
            }
            list.into_any()
        }
        Value::Object(map) => {
            let dict = PyDict::new(py);
            for (k, item) in map {
                dict.set_item(k, json_to_py(py, item)?)?;
            }
            dict.into_any()
        }
    })
}

/// A JSON array of equally long number arrays as an (N, K) float64 array
/// (null, JSON's NaN, as NaN); `None` when `v` is not such an array.
fn json_matrix<'py>(py: Python<'py>, v: &Value) -> Option<Bound<'py, PyAny>> {
    let rows = v.as_array()?;
    let width = rows.first().map_or(0, |r| r.as_array().map_or(0, Vec::len));
    let mut flat = Vec::with_capacity(rows.len() * width);
    for row in rows {
        let row = row.as_array()?;
        if row.len() != width {
            return None;
        }
        for x in row {
            flat.push(x.as_f64().unwrap_or(f64::NAN));
        }
    }
    let array = Array2::from_shape_vec((rows.len(), width), flat).ok()?;
    Some(array.into_pyarray(py).into_any())
}

/// Reads a scenario file (its includes and maps inside its folder, or
/// inside `root`). For a family (`param`, `scatter`): sample `sample`,
/// drawn from `family_seed` (as `scen run --sample K --family-seed S`).
#[pyfunction]
#[pyo3(signature = (path, *, root = None, sample = 0, family_seed = 0))]
fn load(
    py: Python<'_>,
    path: PathBuf,
    root: Option<PathBuf>,
    sample: u64,
    family_seed: u64,
) -> PyResult<Scenario> {
    let choice = SampleChoice {
        sample,
        family_seed,
    };
    let loaded = py.detach(|| load_sample(&path, root.as_deref(), &|_| None, choice));
    loaded.map(Scenario::new).map_err(|f| failure(py, f))
}

/// Reads a scenario from its text. `name` is the file it is reported as
/// (its includes and maps are read relative to the current folder, which
/// is its root unless `root` is given); `sample` and `family_seed` as for
/// [`load`].
#[pyfunction]
#[pyo3(signature = (text, *, name = "<string>.scen", root = None, sample = 0, family_seed = 0))]
fn loads(
    py: Python<'_>,
    text: &str,
    name: &str,
    root: Option<PathBuf>,
    sample: u64,
    family_seed: u64,
) -> PyResult<Scenario> {
    let path = PathBuf::from(name);
    let text: Arc<str> = Arc::from(text);
    let root = root.unwrap_or_else(|| PathBuf::from("."));
    let choice = SampleChoice {
        sample,
        family_seed,
    };
    let loaded = py.detach(|| {
        let overlay = in_memory(vec![(&path, text)]);
        load_sample(&path, Some(&root), &overlay, choice)
    });
    loaded.map(Scenario::new).map_err(|f| failure(py, f))
}

/// The loader's overlay for files made in memory: each text, by its
/// path's canonical form (as the loader asks).
fn in_memory(files: Vec<(&Path, Arc<str>)>) -> impl Fn(&Path) -> Option<Arc<str>> + use<> {
    let files: Vec<(PathBuf, Arc<str>)> = files
        .into_iter()
        .map(|(path, text)| (scen_runner::scenario::loader::canonical(path), text))
        .collect();
    move |p| files.iter().find(|(c, _)| c == p).map(|(_, t)| t.clone())
}

/// A numpy grid as the text of a MovingAI map: `@` where the array is
/// non-zero (True), `.` elsewhere; row 0 the top row. `None` when the
/// array's element type is not a number or a bool.
fn map_text(grid: &Bound<'_, PyAny>) -> Option<(usize, usize, String)> {
    fn write<T: numpy::Element + Copy>(
        grid: &Bound<'_, PyAny>,
        blocked: impl Fn(T) -> bool,
    ) -> Option<(usize, usize, String)> {
        let array = grid.extract::<PyReadonlyArray2<'_, T>>().ok()?;
        let view = array.as_array();
        let (height, width) = view.dim();
        let mut text = format!("type octile\nheight {height}\nwidth {width}\nmap\n");
        text.reserve(height * (width + 1));
        for row in view.rows() {
            text.extend(row.iter().map(|&x| if blocked(x) { '@' } else { '.' }));
            text.push('\n');
        }
        Some((width, height, text))
    }
    write::<bool>(grid, |x| x)
        .or_else(|| write::<u8>(grid, |x| x != 0))
        .or_else(|| write::<i8>(grid, |x| x != 0))
        .or_else(|| write::<i32>(grid, |x| x != 0))
        .or_else(|| write::<i64>(grid, |x| x != 0))
        .or_else(|| write::<u32>(grid, |x| x != 0))
        .or_else(|| write::<u64>(grid, |x| x != 0))
        .or_else(|| write::<f32>(grid, |x| x != 0.0))
        .or_else(|| write::<f64>(grid, |x| x != 0.0))
}

/// A pose as the language writes it: `(x, y)` or `(x, y, θrad)`.
fn pose_text(py: Python<'_>, what: &str, pose: &[f64]) -> PyResult<String> {
    if !(2..=3).contains(&pose.len()) || pose.iter().any(|x| !x.is_finite()) {
        return Err(plain_error(
            py,
            "scen::python::bad_plan",
            format!("the {what} is not a pose: {pose:?}"),
            "give (x, y), or (x, y, theta) with theta in radians, as finite numbers",
        ));
    }
    Ok(match pose {
        [x, y] => format!("({x}, {y})"),
        [x, y, t] => format!("({x}, {y}, {t}rad)"),
        _ => unreachable!("2 or 3 numbers"),
    })
}

/// A keyword argument of `plan` as a plan parameter's text.
fn param_text(py: Python<'_>, key: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    let bad = |why: &str| {
        plain_error(
            py,
            "scen::python::bad_plan",
            format!("the parameter `{key}` {why}"),
            "give a number, True or False, a word (`heuristic=\"zero\"`), or a tuple of numbers; the planner's parameters are in the manual's planners page",
        )
    };
    let simple = |s: &str| {
        !s.is_empty()
            && s.chars()
                .all(|c| c.is_alphanumeric() || " _.-+()[],".contains(c))
    };
    if !key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(bad("is not a parameter's name"));
    }
    let text = if let Ok(b) = value.extract::<bool>() {
        b.to_string()
    } else if let Ok(i) = value.extract::<i64>() {
        i.to_string()
    } else if let Ok(x) = value.extract::<f64>() {
        if !x.is_finite() {
            return Err(bad("is not a finite number"));
        }
        x.to_string()
    } else if let Ok(word) = value.extract::<String>() {
        if !simple(&word) {
            return Err(bad("holds characters a parameter's value cannot"));
        }
        word
    } else if let Ok(xs) = value.extract::<Vec<f64>>() {
        if xs.iter().any(|x| !x.is_finite()) {
            return Err(bad("holds a number that is not finite"));
        }
        let items: Vec<String> = xs.iter().map(f64::to_string).collect();
        format!("({})", items.join(", "))
    } else {
        return Err(bad("has a value of a type the language has no word for"));
    };
    Ok(format!("  {key} {text}\n"))
}

/// Plans on a numpy grid without writing a scenario: the grid is the
/// world's obstacles (a cell is blocked where the array is non-zero or
/// True; row 0 is the top row), `cell` its cells' side and `origin` its
/// bottom-left corner; `robot` is a robot as the language writes it after
/// its name (`"point"`, `"disk 0.3"`); the keyword arguments are the
/// planner's parameters (`connect=4`, `heuristic="zero"`). The plan is
/// named `p`; its path is validated like any other.
#[pyfunction]
#[pyo3(signature = (grid, start, goal = None, *, planner = "astar", robot = "point", cell = 1.0, origin = (0.0, 0.0), **params))]
#[allow(clippy::too_many_arguments)]
fn plan(
    py: Python<'_>,
    grid: &Bound<'_, PyAny>,
    start: Vec<f64>,
    goal: Option<Vec<f64>>,
    planner: &str,
    robot: &str,
    cell: f64,
    origin: (f64, f64),
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<PlanResult> {
    let Some((width, height, map)) = map_text(grid) else {
        return Err(plain_error(
            py,
            "scen::python::bad_grid",
            "the grid is not a 2-D numpy array of numbers or booleans".into(),
            "pass a 2-D array: True or non-zero where a cell is blocked, row 0 the top row",
        ));
    };
    let word =
        |s: &str| !s.is_empty() && s.chars().all(|c| c.is_alphanumeric() || " _.-".contains(c));
    if !word(planner) || !word(robot) {
        return Err(plain_error(
            py,
            "scen::python::bad_plan",
            format!(
                "`{planner}` / `{robot}` is not a planner and a robot as the language writes them"
            ),
            "e.g. planner=\"astar\", robot=\"disk 0.3\"",
        ));
    }
    let (ox, oy) = origin;
    if !(cell.is_finite() && cell > 0.0 && ox.is_finite() && oy.is_finite()) {
        return Err(plain_error(
            py,
            "scen::python::bad_plan",
            format!("a grid of cell {cell} at ({ox}, {oy})"),
            "the cell is a positive number and the origin finite",
        ));
    }
    let mut text = format!(
        "scenario \"a numpy grid\"\nworld {{\n  bounds ({ox}, {oy}) ({}, {})\n  grid cells \"grid.map\" cell {cell} origin ({ox}, {oy})\n}}\nrobot r {robot}\nplan p {planner} r {{\n  start {}\n",
        ox + width as f64 * cell,
        oy + height as f64 * cell,
        pose_text(py, "start", &start)?,
    );
    if let Some(goal) = &goal {
        text.push_str(&format!("  goal {}\n", pose_text(py, "goal", goal)?));
    }
    if let Some(params) = params {
        for (k, v) in params.iter() {
            text.push_str(&param_text(py, &k.extract::<String>()?, &v)?);
        }
    }
    text.push_str("}\n");
    // A folder that exists only in the overlay: the scenario and its map.
    let folder = std::env::current_dir()
        .unwrap_or_default()
        .join("<numpy grid>");
    let main = folder.join("plan.scen");
    let map_path = folder.join("grid.map");
    let outcome = py.detach(move || {
        let overlay = in_memory(vec![(&main, text.into()), (&map_path, map.into())]);
        let loaded = load_sample(&main, Some(&folder), &overlay, SampleChoice::default());
        drop(overlay);
        loaded.map(|mut scenario| {
            // The map's text served the loading (and its diagnostics) only:
            // dropped before planning, so that the world's cells are the
            // one copy of the grid that remains.
            for f in &mut scenario.sources.files {
                if f.path == map_path {
                    f.text = Arc::from("");
                }
            }
            scen_runner::run_scenario_drawing(scenario, &[], false)
        })
    });
    let report = Arc::new(outcome.map_err(|f| failure(py, f))?);
    let doc = scen_runner::report::json::to_json(&report);
    let plan = doc
        .get("plans")
        .and_then(|p| p.get("p"))
        .cloned()
        .unwrap_or(Value::Null);
    PlanResult::new(py, &report, "p", &plan)
}

/// `scen bench merge`: the whole bench's report from the parts of its
/// shards (files written from `Scenario.bench_part`'s text, or by `scen
/// bench --shard K/N --out`), refused as the command refuses them (a part
/// missing or given twice, parts of another split or of a changed
/// scenario, a run edited on the way). The scenario is read again from
/// the path the parts name (relative to the current folder), its root
/// `root` or its folder.
#[pyfunction]
#[pyo3(signature = (paths, *, root = None))]
fn bench_merge(py: Python<'_>, paths: Vec<PathBuf>, root: Option<PathBuf>) -> PyResult<Report> {
    let merged = py.detach(|| scen_runner::merge_bench_parts(&paths, root.as_deref()));
    match merged {
        Ok(report) => Report::new(py, report),
        Err(e) => Err(plain_error(
            py,
            "scen::python::bad_bench",
            e,
            "give every part of one split once, made from the scenario as it is now",
        )),
    }
}

/// The picture `scen run --svg` draws of `scenario` with the runs of
/// `plans` (none: the world, its robots' starts and goals).
fn picture(scenario: &scen_runner::Scenario, plans: Vec<scen_runner::run::PlanRun>) -> String {
    scen_runner::report::svg::to_svg(&scen_runner::RunReport {
        scenario: scenario.clone(),
        plans,
        bench_runs: Vec::new(),
        checks: Vec::new(),
        skipped: Vec::new(),
    })
}

/// A loaded scenario: its world, robots, plans and checks.
#[pyclass(frozen, module = "scen")]
struct Scenario {
    inner: scen_runner::Scenario,
}

impl Scenario {
    fn new(inner: scen_runner::Scenario) -> Self {
        Scenario { inner }
    }

    /// `scen bench`'s preparation, its refusals as `ScenError`s.
    fn prepare(
        &self,
        py: Python<'_>,
        only: &[String],
        runs: Option<u64>,
        worlds: Option<u64>,
        shard: Option<scen_runner::bench::Shard>,
    ) -> PyResult<scen_runner::bench::Prepared> {
        if self.inner.benches.is_empty() {
            return Err(plain_error(
                py,
                "scen::python::bad_bench",
                format!("`{}` has no `bench`", self.inner.file.display()),
                "write e.g. `bench b { vary cell [1, 0.5] runs 10 }`, or use `run`",
            ));
        }
        if runs == Some(0) || worlds == Some(0) {
            return Err(plain_error(
                py,
                "scen::python::bad_bench",
                "`runs` and `worlds` are at least 1".into(),
                "leave them out to run what the benches say",
            ));
        }
        let scenario = self.inner.clone();
        let prepared =
            py.detach(|| scen_runner::bench::prepare(scenario, only, runs, worlds, shard));
        prepared.map_err(|e| match e {
            scen_runner::bench::Unready::Message(m) => plain_error(
                py,
                "scen::python::bad_bench",
                m,
                "see the benches of `Scenario.benches`",
            ),
            scen_runner::bench::Unready::Load(f) => failure(py, f),
        })
    }

    fn plan_index(&self, py: Python<'_>, name: &str) -> PyResult<usize> {
        self.inner
            .plans
            .iter()
            .position(|p| p.name == name)
            .ok_or_else(|| {
                let names: Vec<&str> = self.inner.plans.iter().map(|p| p.name.as_str()).collect();
                plain_error(
                    py,
                    "scen::python::no_plan",
                    format!("the scenario has no plan `{name}`"),
                    &format!("its plans: {}", names.join(", ")),
                )
            })
    }
}

#[pymethods]
impl Scenario {
    /// The scenario's title (`scenario "..."`), None without one.
    #[getter]
    fn title(&self) -> Option<String> {
        self.inner.title.clone()
    }

    /// The file it was read from.
    #[getter]
    fn file(&self) -> String {
        self.inner.file.display().to_string()
    }

    /// For a family (`param`, `scatter`): the sample's number and its
    /// drawn params (`{"sample": K, "family_seed": S, "params": {...}}`);
    /// None for a scenario that draws nothing.
    #[getter]
    fn family(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let Some(drawn) = &self.inner.family else {
            return Ok(py.None());
        };
        let d = PyDict::new(py);
        d.set_item("sample", drawn.sample)?;
        d.set_item("family_seed", drawn.family_seed)?;
        let params = PyDict::new(py);
        for (name, x) in &drawn.params {
            params.set_item(name, x)?;
        }
        d.set_item("params", params)?;
        Ok(d.into_any().unbind())
    }

    /// Sample `k` of the family this scenario was drawn from (same family
    /// seed); a scenario that draws nothing is its own only sample.
    fn sample(&self, py: Python<'_>, k: u64) -> PyResult<Scenario> {
        let sampled = py.detach(|| self.inner.sample(k));
        sampled.map(Scenario::new).map_err(|f| failure(py, f))
    }

    /// The names of its plans, in order.
    #[getter]
    fn plans(&self) -> Vec<String> {
        self.inner.plans.iter().map(|p| p.name.clone()).collect()
    }

    /// The names of its benches, in order.
    #[getter]
    fn benches(&self) -> Vec<String> {
        self.inner.benches.iter().map(|b| b.name.clone()).collect()
    }

    /// Each plan's planner (`astar`, `rrt`, ...), by plan name.
    #[getter]
    fn planners(&self) -> Vec<(String, String)> {
        self.inner
            .plans
            .iter()
            .map(|p| (p.name.clone(), p.kind().to_string()))
            .collect()
    }

    /// Runs the plans (all, or those named in `plans`), validates every
    /// path and evaluates the checks, with the GIL released. `seed`, when
    /// given, is every plan's seed (else each plan's own `seed`, 0 by
    /// default); `draw` builds the planners' layers (the search, the
    /// roadmap) for the report's picture.
    #[pyo3(signature = (plans = None, *, seed = None, draw = false))]
    fn run(
        &self,
        py: Python<'_>,
        plans: Option<Vec<String>>,
        seed: Option<u64>,
        draw: bool,
    ) -> PyResult<Report> {
        let only = plans.unwrap_or_default();
        for name in &only {
            self.plan_index(py, name)?;
        }
        let mut scenario = self.inner.clone();
        if let Some(seed) = seed {
            for plan in &mut scenario.plans {
                plan.params.seed = seed;
            }
        }
        let report = py.detach(|| scen_runner::run_scenario_drawing(scenario, &only, draw));
        Report::new(py, report)
    }

    /// The validator on a path made elsewhere, as if plan `plan`'s planner
    /// had returned it (`scen validate`): `path` is an (N, 2) array of
    /// x, y, (N, 3) of x, y, θ (radians), or (N, 4) of x, y, θ, t (a
    /// trajectory, seconds). The report's plan has `valid`, the metrics,
    /// and `collision` where it first collides.
    fn validate(
        &self,
        py: Python<'_>,
        plan: &str,
        path: PyReadonlyArray2<'_, f64>,
    ) -> PyResult<Report> {
        let index = self.plan_index(py, plan)?;
        let view = path.as_array();
        let (rows, cols) = view.dim();
        let bad = |message: String| {
            plain_error(
                py,
                "scen::python::bad_path",
                message,
                "give an (N, 2) array of x, y, (N, 3) of x, y, theta, or (N, 4) of x, y, theta, t",
            )
        };
        if !(2..=4).contains(&cols) {
            return Err(bad(format!("a path of {cols} columns")));
        }
        if rows == 0 {
            return Err(bad("an empty path".into()));
        }
        if let Some((i, _)) = view.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(bad(format!(
                "row {} holds a value that is not a finite number",
                i / cols
            )));
        }
        let robot = &self.inner.robots[self.inner.plans[index].robot];
        if robot.steering.is_some() {
            return Err(plain_error(
                py,
                "scen::python::car_path",
                format!("plan `{plan}` is for a car robot, whose path is its segments (SPEC 3.0)"),
                "validating a car's path from poses is not supported",
            ));
        }
        let poses: Vec<Config> = view
            .rows()
            .into_iter()
            .map(|r| Config::new(r[0], r[1], if cols >= 3 { r[2] } else { 0.0 }))
            .collect();
        let times = (cols == 4).then(|| view.column(3).to_vec());
        if times.is_none() && !self.inner.moving.is_empty() {
            return Err(plain_error(
                py,
                "scen::validate::needs_times",
                format!(
                    "the world has moving obstacles (`{}`): a path without times cannot be judged among them",
                    self.inner.moving[0].name
                ),
                "give every pose its time: an (N, 4) array of x, y, theta, t",
            ));
        }
        let scenario = self.inner.clone();
        let report =
            py.detach(|| scen_runner::run::validate_user_path(scenario, index, poses, times));
        Report::new(py, report)
    }

    /// Runs the benches (all, or those named in `benches`) as `scen bench`
    /// does, with the GIL released: every configuration, world and seed,
    /// then the plain plans and every check. `runs` and `worlds` are
    /// `--runs N` and `--worlds N`. The report's `bench_runs` lists every
    /// run; `bench_table()` is the command's tables; `to_json()` its
    /// `--json` document.
    #[pyo3(signature = (benches = None, *, runs = None, worlds = None))]
    fn bench(
        &self,
        py: Python<'_>,
        benches: Option<Vec<String>>,
        runs: Option<u64>,
        worlds: Option<u64>,
    ) -> PyResult<Report> {
        let only = benches.unwrap_or_default();
        let prepared = self.prepare(py, &only, runs, worlds, None)?;
        let report = py.detach(|| {
            let ran = scen_runner::bench::run_all(
                &prepared.scenario,
                &prepared.worlds,
                &prepared.ids,
                &|| {},
            );
            scen_runner::bench::report(prepared.scenario, ran)
        });
        Report::new(py, report)
    }

    /// Shard `k` of `n` of the benches: the text of the part that `scen
    /// bench --shard K/N --out PART.jsonl` writes (a string, so it travels
    /// between processes and machines); write the parts to files and
    /// combine them with `scen.bench_merge` (or `scen bench merge`).
    #[pyo3(signature = (k, n, *, benches = None, runs = None, worlds = None))]
    fn bench_part(
        &self,
        py: Python<'_>,
        k: u64,
        n: u64,
        benches: Option<Vec<String>>,
        runs: Option<u64>,
        worlds: Option<u64>,
    ) -> PyResult<String> {
        let shard = scen_runner::bench::Shard::parse(&format!("{k}/{n}")).map_err(|e| {
            plain_error(
                py,
                "scen::python::bad_bench",
                e,
                "shards are K/N with 1 <= K <= N",
            )
        })?;
        let only = benches.unwrap_or_default();
        let prepared = self.prepare(py, &only, runs, worlds, Some(shard))?;
        Ok(py.detach(|| {
            let ran = scen_runner::bench::run_all(
                &prepared.scenario,
                &prepared.worlds,
                &prepared.ids,
                &|| {},
            );
            scen_runner::report::bench::part_text(
                &prepared.scenario,
                shard,
                &only,
                runs,
                worlds,
                &ran,
            )
        }))
    }

    /// The scenario drawn (its world, robots, starts and goals) as SVG.
    fn to_svg(&self, py: Python<'_>) -> String {
        py.detach(|| picture(&self.inner, Vec::new()))
    }

    fn _repr_svg_(&self, py: Python<'_>) -> String {
        self.to_svg(py)
    }

    fn __repr__(&self) -> String {
        format!(
            "<scen.Scenario {:?}: {} plan(s)>",
            self.inner.title,
            self.inner.plans.len()
        )
    }
}

/// What a run (or a validation) produced: each plan's result and each
/// check's verdict.
#[pyclass(frozen, module = "scen")]
struct Report {
    inner: Arc<scen_runner::RunReport>,
    /// `scen run --json`'s document, as its text.
    json: String,
    plans: Py<PyDict>,
    checks: Py<PyList>,
    /// A bench's runs, one dict each (`scen bench --json`'s results with
    /// their bench's name).
    bench_runs: Py<PyList>,
}

impl Report {
    fn new(py: Python<'_>, report: scen_runner::RunReport) -> PyResult<Report> {
        let doc = scen_runner::report::json::to_json(&report);
        // A bench's report is `scen bench --json`'s document.
        let bench_doc =
            (!report.bench_runs.is_empty()).then(|| scen_runner::report::bench::to_json(&report));
        let json = serde_json::to_string(bench_doc.as_ref().unwrap_or(&doc)).unwrap_or_default();
        let bench_runs = PyList::empty(py);
        if let Some(Value::Array(benches)) = bench_doc.as_ref().and_then(|d| d.get("benches")) {
            for b in benches {
                let name = b.get("name").cloned().unwrap_or(Value::Null);
                for r in b
                    .get("results")
                    .and_then(Value::as_array)
                    .into_iter()
                    .flatten()
                {
                    let mut row = serde_json::Map::new();
                    row.insert("bench".into(), name.clone());
                    if let Value::Object(fields) = r {
                        row.extend(fields.clone());
                    }
                    bench_runs.append(json_to_py(py, &Value::Object(row))?)?;
                }
            }
        }
        let report = Arc::new(report);
        let plans = PyDict::new(py);
        if let Some(Value::Object(map)) = doc.get("plans") {
            for (name, plan) in map {
                let result = PlanResult::new(py, &report, name, plan)?;
                plans.set_item(name, Py::new(py, result)?)?;
            }
        }
        let checks = match doc.get("checks") {
            Some(v) => json_to_py(py, v)?.cast_into::<PyList>()?,
            None => PyList::empty(py),
        };
        Ok(Report {
            inner: report,
            json,
            plans: plans.unbind(),
            checks: checks.unbind(),
            bench_runs: bench_runs.unbind(),
        })
    }
}

#[pymethods]
impl Report {
    /// Each plan's result, by name (`PlanResult`).
    #[getter]
    fn plans(&self, py: Python<'_>) -> Py<PyDict> {
        self.plans.clone_ref(py)
    }

    /// Each evaluated check: `line`, `expr`, `passed`, `values`.
    #[getter]
    fn checks(&self, py: Python<'_>) -> Py<PyList> {
        self.checks.clone_ref(py)
    }

    /// A bench's runs: one dict per run (`bench`, `plan`, the varied
    /// `config`, `world`, `run`, `seed`, `metrics`), in the order `scen
    /// bench` runs them; empty for a run of plans.
    #[getter]
    fn bench_runs(&self, py: Python<'_>) -> Py<PyList> {
        self.bench_runs.clone_ref(py)
    }

    /// A bench's tables, as `scen bench` prints them (the statistics of
    /// `metrics`, by default the command's).
    #[pyo3(signature = (metrics = None))]
    fn bench_table(&self, metrics: Option<Vec<String>>) -> String {
        let names: Vec<&str> = match &metrics {
            Some(m) => m.iter().map(String::as_str).collect(),
            None => scen_runner::bench::default_metrics(&self.inner.scenario).to_vec(),
        };
        scen_runner::report::bench::render(&self.inner, &names)
    }

    /// How many checks passed.
    #[getter]
    fn passed(&self) -> usize {
        self.inner.passed()
    }

    /// How many checks failed.
    #[getter]
    fn failed(&self) -> usize {
        self.inner.failed()
    }

    /// `scen run --json`'s document (SPEC 5), as text; for a bench,
    /// `scen bench --json`'s.
    fn to_json(&self) -> String {
        self.json.clone()
    }

    /// The run drawn as `scen run --svg` draws it.
    fn to_svg(&self, py: Python<'_>) -> String {
        py.detach(|| scen_runner::report::svg::to_svg(&self.inner))
    }

    fn _repr_svg_(&self, py: Python<'_>) -> String {
        self.to_svg(py)
    }

    fn __getitem__(&self, py: Python<'_>, name: &str) -> PyResult<Py<PyAny>> {
        match self.plans.bind(py).get_item(name)? {
            Some(plan) => Ok(plan.unbind()),
            None => Err(PyKeyError::new_err(name.to_string())),
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "<scen.Report {:?}: {} plan(s), {} passed, {} failed>",
            self.inner.scenario.title,
            self.inner.plans.len(),
            self.inner.passed(),
            self.inner.failed()
        )
    }
}

/// One plan's result.
#[pyclass(frozen, module = "scen")]
struct PlanResult {
    /// The plan's name.
    #[pyo3(get)]
    name: String,
    /// Its planner (`astar`, `rrt`, ...).
    #[pyo3(get)]
    planner: String,
    /// Whether the planner returned a path.
    #[pyo3(get)]
    found: bool,
    /// Whether the validator accepted it (False also when there is none).
    #[pyo3(get)]
    valid: bool,
    /// Every metric, by name (SPEC 3).
    #[pyo3(get)]
    metrics: Py<PyAny>,
    /// The path: (N, 2) x, y, or (N, 3) x, y, θ for a robot whose heading
    /// matters; None without one.
    #[pyo3(get)]
    path: Py<PyAny>,
    /// A time-aware plan's trajectory, (N, 4) x, y, θ, t; or the motion a
    /// run executed before it stopped short; None otherwise.
    #[pyo3(get)]
    trajectory: Py<PyAny>,
    /// A car's path as its segments, `[(turn, length), ...]`; None
    /// otherwise.
    #[pyo3(get)]
    segments: Py<PyAny>,
    /// A team plan's agents (SPEC 2.10): each agent's name → its path,
    /// (N, 2) x, y, one row per step; None for one robot, or when no
    /// solution was found.
    #[pyo3(get)]
    agents: Py<PyAny>,
    /// Where the path first failed the validator: `segment`, `at`
    /// (x, y, θ), `obstacle` (None for the bounds), `reason`; None when
    /// it passed.
    #[pyo3(get)]
    collision: Py<PyAny>,
    /// The run it is part of, and its index among the run's plans: for
    /// its picture.
    report: Arc<scen_runner::RunReport>,
    run: usize,
}

impl PlanResult {
    /// Plan `name` of `report`, from its entry `plan` in the report's
    /// JSON document.
    fn new(
        py: Python<'_>,
        report: &Arc<scen_runner::RunReport>,
        name: &str,
        plan: &Value,
    ) -> PyResult<PlanResult> {
        let run = report
            .plans
            .iter()
            .position(|r| report.scenario.plans[r.plan].name == name)
            .unwrap_or(0);
        let validation = report.plans.get(run).and_then(|r| r.validation.as_ref());
        let metrics = json_to_py(py, plan.get("metrics").unwrap_or(&Value::Null))?;
        let team = plan.get("agents").filter(|a| !a.is_null());
        let found = plan.get("path").is_some_and(|p| !p.is_null()) || team.is_some();
        let matrix = |key: &str| -> Py<PyAny> {
            plan.get(key)
                .and_then(|v| json_matrix(py, v))
                .map_or_else(|| py.None(), Bound::unbind)
        };
        let segments = match plan.get("segments") {
            Some(Value::Array(items)) => {
                let list = PyList::empty(py);
                for s in items {
                    let turn = s.get(0).and_then(Value::as_str).unwrap_or("");
                    let length = s.get(1).and_then(Value::as_f64).unwrap_or(f64::NAN);
                    list.append((turn, length))?;
                }
                list.into_any().unbind()
            }
            _ => py.None(),
        };
        let agents = match team {
            Some(Value::Array(items)) => {
                let d = PyDict::new(py);
                for a in items {
                    let name = a.get("name").and_then(Value::as_str).unwrap_or("");
                    let path = a
                        .get("path")
                        .or_else(|| a.get("trajectory"))
                        .and_then(|v| json_matrix(py, v))
                        .map_or_else(|| py.None(), Bound::unbind);
                    d.set_item(name, path)?;
                }
                d.into_any().unbind()
            }
            _ => py.None(),
        };
        let collision = match &validation {
            Some(e) => {
                let d = PyDict::new(py);
                d.set_item("segment", e.segment)?;
                d.set_item("at", (e.at.x, e.at.y, e.at.theta))?;
                d.set_item("obstacle", e.obstacle.clone())?;
                d.set_item("reason", e.reason.clone())?;
                d.into_any().unbind()
            }
            None => py.None(),
        };
        Ok(PlanResult {
            name: name.to_string(),
            planner: plan
                .get("kind")
                .and_then(Value::as_str)
                .unwrap_or("")
                .to_string(),
            found,
            valid: found && validation.is_none(),
            metrics: metrics.unbind(),
            path: matrix("path"),
            trajectory: matrix("trajectory"),
            segments,
            agents,
            collision,
            report: report.clone(),
            run,
        })
    }
}

#[pymethods]
impl PlanResult {
    /// This plan's run drawn alone, as `scen run --plan NAME --svg` draws
    /// it.
    fn to_svg(&self, py: Python<'_>) -> String {
        let run = self.report.plans.get(self.run).cloned();
        py.detach(|| picture(&self.report.scenario, run.into_iter().collect()))
    }

    fn _repr_svg_(&self, py: Python<'_>) -> String {
        self.to_svg(py)
    }

    fn __repr__(&self) -> String {
        format!(
            "<scen.PlanResult {:?} ({}): found={}, valid={}>",
            self.name,
            self.planner,
            if self.found { "True" } else { "False" },
            if self.valid { "True" } else { "False" }
        )
    }
}

/// The module `scen._scen`.
#[pymodule]
fn _scen(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("ScenError", m.py().get_type::<ScenError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(loads, m)?)?;
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    m.add_function(wrap_pyfunction!(bench_merge, m)?)?;
    m.add_class::<Scenario>()?;
    m.add_class::<Report>()?;
    m.add_class::<PlanResult>()?;
    Ok(())
}

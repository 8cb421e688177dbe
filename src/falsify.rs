//! `scen falsify` (SPEC 2.8, §4): search a family of scenarios for a sample
//! where a plain `expect` fails, shrink it, and write it as a standalone
//! scenario.
//!
//! The search proposes candidates in batches of [`BATCH`], evaluated in
//! parallel and read in order, so the result does not depend on the number
//! of threads. A candidate is either sample k of the family (`uniform`:
//! exactly what `scen run --sample k --family-seed SEED` runs) or a point
//! of the unit cube, one coordinate per drawn param, mapped through each
//! distribution's inverse distribution function (`halton`,
//! `cross_entropy`, `auto`; scattered items then come from the candidate's
//! own stream). Each check has a margin ([`crate::checks::margin`]); the
//! model-guided searches walk towards smaller margins.
//!
//! Shrinking works on the failing sample's statements (params computed,
//! scatters placed): it removes obstacles while the same check still fails
//! (halving chunks, then one at a time until removing any one makes it
//! pass: 1-minimal), then rounds each computed number to the fewest
//! decimals that still fail. Every candidate is analysed and run for real.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use rayon::prelude::*;

use crate::bench::Shard;
use crate::checks::{self, Values};
use crate::contract::Metrics;
use crate::contract::schema::Word;
use crate::diagnostics::{Diag, FileId, SourceMap, Span};
use crate::rng::SplitMix64;
use crate::scenario::family::{
    Family, Instance, SampleChoice, ScatterRule, computed_spans, scattered_distance,
};
use crate::scenario::loader::{SourcedStmt, analyze_statements};
use crate::syntax::ast::{
    AngleUnit, ExprKind, ObstacleDecl, ObstacleShape, Selection, Stmt, Value, ValueKind, WorldItem,
};

/// Candidates evaluated together (in parallel), whatever the thread count.
pub const BATCH: usize = 16;
/// The most runs shrinking may spend.
pub const SHRINK_RUNS: usize = 2_000;

crate::word_enum! {
    /// How candidates are proposed (`--search`).
    pub enum Search {
        Auto = "auto",
        Uniform = "uniform",
        Halton = "halton",
        CrossEntropy = "cross_entropy",
    }
}

/// The options of one search.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    pub budget: u64,
    pub search: Search,
    pub seed: u64,
    /// The part of the search this process runs (`--shard K/N`; 1/1 for
    /// all of it).
    pub shard: Shard,
}

/// The scenario's statements as read, before any draw.
pub struct Source {
    pub path: PathBuf,
    pub statements: Vec<SourcedStmt>,
    pub sources: SourceMap,
    pub maps: HashMap<Span, Result<FileId, Diag>>,
    family: Family,
    /// The plain checks' spans, in order (what "the same check" means).
    checks: Vec<Span>,
}

/// What a candidate did.
#[derive(Clone, Debug)]
enum Outcome {
    /// Rejected by a `require`, or a start or goal out of bounds or in
    /// collision.
    Rejected,
    /// Every plain check held; the smallest margin.
    Passed { margin: f64 },
    /// The first plain check that failed (its index among the plain
    /// checks) and its margin.
    Failed { check: usize, margin: f64 },
}

impl Outcome {
    fn margin(&self) -> Option<f64> {
        match self {
            Outcome::Rejected => None,
            Outcome::Passed { margin } | Outcome::Failed { margin, .. } => Some(*margin),
        }
    }
}

/// A candidate evaluated.
struct Tried {
    index: u64,
    unit: Option<Vec<f64>>,
    params: Vec<(String, f64)>,
    outcome: Outcome,
    statements: Option<Vec<SourcedStmt>>,
}

/// The failing sample and its shrunk scenario.
#[derive(Debug)]
pub struct Failure {
    /// The candidate's number (for `uniform`, the family's sample).
    pub sample: u64,
    pub params: Vec<(String, f64)>,
    /// The command line that runs the failing world (`scen run FILE
    /// --set ...` or `--sample K`).
    pub reproduce: String,
    /// The check's source text and line.
    pub check: String,
    pub line: usize,
    pub margin: f64,
    /// Obstacles before and after shrinking.
    pub obstacles: (usize, usize),
    /// Runs spent shrinking.
    pub shrink_runs: usize,
    /// The standalone scenario's text.
    pub text: String,
}

/// The smallest margin seen, the candidate that had it and its params.
pub type Smallest = (f64, u64, Vec<(String, f64)>);

/// The result of a search.
#[derive(Debug)]
pub struct Falsified {
    pub tried: u64,
    pub rejected: u64,
    pub search: Search,
    /// The smallest margin seen, and the candidate that had it.
    pub smallest: Option<Smallest>,
    pub failure: Option<Failure>,
}

impl Source {
    /// The family of a parsed scenario, ready to search; an error (exit 2)
    /// when it has no param or no plain `expect`.
    pub fn new(
        path: &Path,
        statements: Vec<SourcedStmt>,
        sources: SourceMap,
        maps: HashMap<Span, Result<FileId, Diag>>,
    ) -> Result<Source, (SourceMap, Vec<Diag>)> {
        let family = match Family::of(&statements) {
            Ok(f) => f,
            Err(diags) => return Err((sources, diags)),
        };
        let checks: Vec<Span> = statements
            .iter()
            .filter_map(|s| match &s.stmt {
                Stmt::Expect(e) if !reads_bench(e) => Some(e.span),
                _ => None,
            })
            .collect();
        let mut problems = Vec::new();
        if !family.draws() {
            problems.push(
                Diag::error(
                    "scen::falsify::not_a_family",
                    "`scen falsify` searches a family, and this scenario draws nothing",
                )
                .at(Span::new(0, 0, 0), "no `param` or `scatter` here")
                .help("declare what varies: `param gap = uniform(0.5, 3)`, or a `scatter`"),
            );
        }
        if checks.is_empty() {
            problems.push(
                Diag::error(
                    "scen::falsify::no_check",
                    "`scen falsify` looks for a failing `expect`, and this scenario has none that `scen run` evaluates",
                )
                .at(Span::new(0, 0, 0), "no plain `expect`")
                .help("state what must hold in every world: `expect p.found`; checks of benches are not searched"),
            );
        }
        if !problems.is_empty() {
            return Err((sources, problems));
        }
        Ok(Source {
            path: path.to_path_buf(),
            statements,
            sources,
            maps,
            family,
            checks,
        })
    }

    /// Analyses and runs a sample's statements: its plain checks' outcome.
    fn evaluate(&self, statements: Vec<SourcedStmt>) -> Result<Outcome, Vec<Diag>> {
        let scenario = match analyze_statements(
            &self.path,
            statements,
            self.sources.clone(),
            self.maps.clone(),
        ) {
            Ok(s) => s,
            Err(f) => {
                let pose = f.diags.iter().filter(|d| d.is_error()).all(|d| {
                    matches!(
                        d.code,
                        "scen::analyze::pose_outside" | "scen::analyze::pose_in_collision"
                    )
                });
                return if pose {
                    Ok(Outcome::Rejected)
                } else {
                    Err(f.diags)
                };
            }
        };
        // Only the plans the plain checks read.
        let mut plans = Vec::new();
        for c in scenario.checks.iter().filter(|c| !c.bench) {
            checks::plans_used(&c.expr, &mut plans);
        }
        let report = crate::run::run_scenario_drawing(scenario, &plans, false);
        let values = PlanValues {
            plans: report
                .plans
                .iter()
                .map(|r| {
                    (
                        report.scenario.plans[r.plan].name.clone(),
                        r.metrics.clone(),
                    )
                })
                .collect(),
        };
        let mut smallest = f64::INFINITY;
        for (k, c) in report
            .scenario
            .checks
            .iter()
            .filter(|c| !c.bench)
            .enumerate()
        {
            let passed = report
                .checks
                .iter()
                .find(|o| std::ptr::eq(&report.scenario.checks[o.check], c))
                .is_none_or(|o| o.passed);
            let margin = checks::margin(&c.expr, &values);
            if !passed {
                // A failed check's margin is never positive.
                return Ok(Outcome::Failed {
                    check: k,
                    margin: margin.min(0.0),
                });
            }
            smallest = smallest.min(margin);
        }
        Ok(Outcome::Passed { margin: smallest })
    }

    /// Candidate `index`: its statements and params (`None`: rejected).
    fn draw(&self, opts: &Options, index: u64, unit: Option<&[f64]>) -> Result<Tried, Vec<Diag>> {
        let (statements, params, outcome) = match unit {
            // Sample `index` of the family, drawn again while rejected.
            None => {
                let choice = SampleChoice {
                    sample: index,
                    family_seed: opts.seed,
                };
                let mut kept = None;
                let sampled = self
                    .family
                    .sample(&self.statements, choice, &[], |instance| {
                        match self.evaluate(instance.clone())? {
                            Outcome::Rejected => Err(vec![Diag::error(
                                "scen::analyze::pose_in_collision",
                                "rejected",
                            )]),
                            outcome => {
                                kept = Some(instance);
                                Ok(outcome)
                            }
                        }
                    });
                match sampled {
                    Ok((outcome, drawn)) => (kept, drawn.params, outcome),
                    Err(diags)
                        if diags
                            .iter()
                            .all(|d| d.code == "scen::family::rejects_every_draw") =>
                    {
                        (None, Vec::new(), Outcome::Rejected)
                    }
                    Err(diags) => return Err(diags),
                }
            }
            Some(u) => match self.family.candidate(
                &self.statements,
                SampleChoice {
                    sample: index,
                    family_seed: opts.seed,
                },
                u,
            )? {
                None => (None, Vec::new(), Outcome::Rejected),
                Some((statements, params)) => {
                    let outcome = self.evaluate(statements.clone())?;
                    (Some(statements), params, outcome)
                }
            },
        };
        Ok(Tried {
            index,
            unit: unit.map(<[f64]>::to_vec),
            params,
            outcome,
            statements,
        })
    }
}

/// The metrics of the plans that ran, for the checks.
struct PlanValues {
    plans: HashMap<String, Metrics>,
}

impl Values for PlanValues {
    fn metrics(&self, plan: &str) -> Option<&Metrics> {
        self.plans.get(plan)
    }

    fn series(
        &self,
        _: &str,
        _: &str,
        _: &[Selection],
        _: &str,
    ) -> Option<Vec<crate::contract::MetricValue>> {
        None
    }
}

/// Whether an expression reads a bench's series.
fn reads_bench(e: &crate::syntax::ast::Expr) -> bool {
    let mut found = false;
    e.walk(&mut |n| found |= matches!(n.kind, ExprKind::Series { .. }));
    found
}

/// The Halton sequence's point `i` (from 1) in `d` dimensions, shifted by
/// `shift` modulo 1 (a Cranley–Patterson rotation, so each seed covers the
/// cube differently).
fn halton(i: u64, shift: &[f64]) -> Vec<f64> {
    const PRIMES: [u64; 24] = [
        2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59, 61, 67, 71, 73, 79, 83, 89,
    ];
    shift
        .iter()
        .enumerate()
        .map(|(j, s)| {
            let base = PRIMES[j % PRIMES.len()] + 2 * (j / PRIMES.len()) as u64 * 97;
            let (mut f, mut r, mut n) = (1.0, 0.0, i);
            while n > 0 {
                f /= base as f64;
                r += f * (n % base) as f64;
                n /= base;
            }
            (r + s).fract()
        })
        .collect()
}

/// A standard normal number (Box–Muller).
fn gaussian(rng: &mut SplitMix64) -> f64 {
    let u = 1.0 - rng.next_f64();
    let v = rng.next_f64();
    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
}

/// Reflects `x` into [0, 1).
fn reflect(x: f64) -> f64 {
    let y = x.rem_euclid(2.0);
    let y = if y > 1.0 { 2.0 - y } else { y };
    y.min(1.0 - f64::EPSILON)
}

/// Proposes the unit-cube points of the model-guided searches.
struct Proposer {
    search: Search,
    dims: usize,
    shift: Vec<f64>,
    /// The next cover point is Halton's point `shard.nth(halton_next) + 1`:
    /// the shards of a search interleave one sequence.
    halton_next: u64,
    shard: Shard,
    /// The model's mean and spread (cross-entropy), after its first fit.
    model: Option<(Vec<f64>, Vec<f64>)>,
    /// `auto`: the basins given up (their best points), the best margin
    /// outside them, and the batches since it last improved.
    tabu: Vec<Vec<f64>>,
    best: f64,
    stagnant: u32,
}

/// `auto` gives a basin up after this many batches without a better margin.
const PATIENCE: u32 = 4;
/// The radius (in the unit cube) of a basin given up.
const TABU_RADIUS: f64 = 0.15;

/// Points drawn from Halton before the model is fitted.
const COVER: usize = 2 * BATCH;
/// The fraction of all points kept as elites.
const ELITE: f64 = 0.1;

impl Proposer {
    fn new(search: Search, dims: usize, seed: u64, shard: Shard) -> Self {
        let mut rng = SplitMix64::new(seed ^ 0x5EED_F00D);
        Proposer {
            search,
            dims,
            shift: (0..dims).map(|_| rng.next_f64()).collect(),
            halton_next: 0,
            shard,
            model: None,
            tabu: Vec::new(),
            best: f64::INFINITY,
            stagnant: 0,
        }
    }

    fn cover(&mut self) -> Vec<f64> {
        let p = halton(self.shard.nth(self.halton_next) + 1, &self.shift);
        self.halton_next += 1;
        p
    }

    /// The next batch's points, given every point tried so far and its
    /// margin.
    fn batch(&mut self, batch: u64, history: &[(Vec<f64>, f64)]) -> Vec<Vec<f64>> {
        // `auto`'s second batch: the corners of the box, where many
        // failures live (a parameter at its extreme), then the cover.
        if self.search == Search::Auto && batch == 1 {
            let corners = corners(
                self.dims,
                &mut SplitMix64::new(self.shift.len() as u64 ^ 0xC0FE),
            );
            let rest = BATCH - corners.len();
            return corners
                .into_iter()
                .chain((0..rest).map(|_| self.cover()))
                .collect();
        }
        if self.search == Search::Halton || history.len() < COVER {
            return (0..BATCH).map(|_| self.cover()).collect();
        }
        let (auto, floor, smoothing) = match self.search {
            // Classic cross-entropy: the last fit smoothed, a tiny floor.
            Search::CrossEntropy => (false, 1e-3, 0.7),
            _ => (true, 0.02, 1.0),
        };
        // `auto` leaves out the basins it gave up.
        let near = |p: &[f64], c: &[f64]| distance(p, c) < TABU_RADIUS;
        let mut sorted: Vec<&(Vec<f64>, f64)> = history
            .iter()
            .filter(|(p, _)| !auto || !self.tabu.iter().any(|c| near(p, c)))
            .collect();
        if sorted.len() < 4 {
            return (0..BATCH).map(|_| self.cover()).collect();
        }
        sorted.sort_by(|a, b| a.1.total_cmp(&b.1));
        // `auto`: a basin whose best margin stops improving is given up,
        // and the model starts afresh outside it.
        if auto {
            if sorted[0].1 < self.best {
                self.best = sorted[0].1;
                self.stagnant = 0;
            } else {
                self.stagnant += 1;
            }
            if self.stagnant >= PATIENCE {
                self.tabu.push(sorted[0].0.clone());
                self.best = f64::INFINITY;
                self.stagnant = 0;
                self.model = None;
                return (0..BATCH).map(|_| self.cover()).collect();
            }
        }
        // Fit the model to the elites: the points of smallest margin.
        let n = ((sorted.len() as f64 * ELITE).ceil() as usize).clamp(4, sorted.len());
        let elites = &sorted[..n];
        let mut mean = vec![0.0; self.dims];
        let mut spread = vec![0.0; self.dims];
        for j in 0..self.dims {
            let m = elites.iter().map(|e| e.0[j]).sum::<f64>() / n as f64;
            let v = elites.iter().map(|e| (e.0[j] - m).powi(2)).sum::<f64>() / n as f64;
            mean[j] = m;
            spread[j] = v.sqrt();
        }
        if let Some((old_mean, old_spread)) = &self.model {
            for j in 0..self.dims {
                mean[j] = smoothing * mean[j] + (1.0 - smoothing) * old_mean[j];
                spread[j] = smoothing * spread[j] + (1.0 - smoothing) * old_spread[j];
            }
        }
        for s in &mut spread {
            *s = s.max(floor);
        }
        self.model = Some((mean.clone(), spread.clone()));
        let mut rng = SplitMix64::new(
            self.shift.len() as u64
                ^ batch.wrapping_mul(0x9E37_79B9)
                ^ (self.shard.k - 1).wrapping_mul(0xD1B5_4A32_D192_ED03),
        );
        let best = &sorted[0].0;
        // `auto`: Newton steps on the margin from the best point of each
        // of up to four basins (best points at least 0.1 apart).
        let mut basins: Vec<&(Vec<f64>, f64)> = Vec::new();
        if auto {
            for p in &sorted {
                if basins.len() == 4 {
                    break;
                }
                if basins.iter().all(|b| distance(&b.0, &p.0) >= 0.1) {
                    basins.push(p);
                }
            }
        }
        (0..BATCH)
            .map(|k| {
                // `auto`: a quarter of every batch keeps covering the cube,
                // a quarter searches around the best point so far, a
                // quarter steps towards where the margin's linear fit
                // crosses zero, the rest follows the model; it never
                // collapses onto one region.
                if auto && k % 4 == 0 {
                    return self.cover();
                }
                if auto
                    && k % 4 == 2
                    && let Some(b) = basins.get(k / 4)
                    && let Some(p) = newton_step(history, &b.0, b.1)
                {
                    return p;
                }
                let centre = if auto && k % 4 == 1 { best } else { &mean };
                (0..self.dims)
                    .map(|j| {
                        let s = if auto && k % 4 == 1 {
                            spread[j] * 0.5
                        } else {
                            spread[j]
                        };
                        reflect(centre[j] + s * gaussian(&mut rng))
                    })
                    .collect()
            })
            .collect()
    }
}

/// The Euclidean distance of two points of the cube.
fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// The corners of the unit cube (all of them up to 4 dimensions, else
/// 16 drawn), just inside it.
fn corners(dims: usize, rng: &mut SplitMix64) -> Vec<Vec<f64>> {
    let corner = |bits: u64| -> Vec<f64> {
        (0..dims)
            .map(|j| {
                if bits >> (j % 64) & 1 == 1 {
                    1.0 - f64::EPSILON
                } else {
                    0.0
                }
            })
            .collect()
    };
    if dims == 0 {
        return Vec::new();
    }
    if dims <= 4 {
        (0..1u64 << dims).map(corner).collect()
    } else {
        (0..BATCH).map(|_| corner(rng.next_u64())).collect()
    }
}

/// One step of Newton's method on the margin from `p0` (margin `m0`): the
/// margin's gradient fitted by least squares on the 2d + 2 points tried
/// nearest `p0`, then a step to where that linear fit reaches −1 % of
/// `m0` (a little past zero, so that a thin failure region is entered, not
/// only touched). `None` when the fit has no slope.
fn newton_step(history: &[(Vec<f64>, f64)], p0: &[f64], m0: f64) -> Option<Vec<f64>> {
    let d = p0.len();
    if d == 0 || !m0.is_finite() || m0 <= 0.0 {
        return None;
    }
    let mut near: Vec<(f64, &(Vec<f64>, f64))> = history
        .iter()
        .map(|h| (distance(&h.0, p0), h))
        .filter(|(r, h)| *r > 0.0 && h.1.is_finite())
        .collect();
    if near.len() < d + 1 {
        return None;
    }
    near.sort_by(|a, b| a.0.total_cmp(&b.0));
    near.truncate(2 * d + 2);
    // The normal equations (AᵀA + λI) g = Aᵀb, rows p − p0, b = m − m0.
    let mut a = vec![vec![0.0; d + 1]; d];
    for (_, (p, m)) in &near {
        let row: Vec<f64> = p.iter().zip(p0).map(|(x, y)| x - y).collect();
        for i in 0..d {
            for j in 0..d {
                a[i][j] += row[i] * row[j];
            }
            a[i][d] += row[i] * (m - m0);
        }
    }
    for (i, r) in a.iter_mut().enumerate() {
        r[i] += 1e-12;
    }
    // Gaussian elimination with partial pivoting.
    for c in 0..d {
        let pivot = (c..d).max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))?;
        a.swap(c, pivot);
        if a[c][c].abs() < 1e-300 {
            return None;
        }
        let pivot_row = a[c].clone();
        for (r, row) in a.iter_mut().enumerate() {
            if r != c {
                let f = row[c] / pivot_row[c];
                for (x, p) in row[c..].iter_mut().zip(&pivot_row[c..]) {
                    *x -= f * p;
                }
            }
        }
    }
    let g: Vec<f64> = (0..d).map(|i| a[i][d] / a[i][i]).collect();
    let norm2: f64 = g.iter().map(|x| x * x).sum();
    if !(norm2 > 0.0 && norm2.is_finite()) {
        return None;
    }
    let step = 1.01 * m0 / norm2;
    Some(
        p0.iter()
            .zip(&g)
            .map(|(x, gi)| reflect(x - step * gi))
            .collect(),
    )
}

/// Searches the family for a failing sample within the budget; shrinks
/// and writes the first one found.
pub fn falsify(source: &Source, opts: Options) -> Result<Falsified, Vec<Diag>> {
    let dims = source.family.dims();
    // Without drawn params (only scatters) every search is sample by sample.
    let search = if dims == 0 {
        Search::Uniform
    } else {
        opts.search
    };
    let mut proposer = Proposer::new(search, dims, opts.seed, opts.shard);
    // This shard's candidates: those numbered K − 1 modulo N below the budget.
    let budget = opts.shard.share(opts.budget);
    let mut history: Vec<(Vec<f64>, f64)> = Vec::new();
    let mut out = Falsified {
        tried: 0,
        rejected: 0,
        search,
        smallest: None,
        failure: None,
    };
    let mut batch = 0u64;
    while out.tried < budget {
        let n = (budget - out.tried).min(BATCH as u64) as usize;
        let points: Vec<Option<Vec<f64>>> = if search == Search::Uniform {
            vec![None; n]
        } else {
            proposer
                .batch(batch, &history)
                .into_iter()
                .take(n)
                .map(Some)
                .collect()
        };
        let first = out.tried;
        let tried: Vec<Result<Tried, Vec<Diag>>> = points
            .par_iter()
            .enumerate()
            .map(|(k, p)| source.draw(&opts, opts.shard.nth(first + k as u64), p.as_deref()))
            .collect();
        batch += 1;
        for t in tried {
            let t = t?;
            out.tried += 1;
            let Some(margin) = t.outcome.margin() else {
                out.rejected += 1;
                continue;
            };
            if out.smallest.as_ref().is_none_or(|(m, _, _)| margin < *m) {
                out.smallest = Some((margin, t.index, t.params.clone()));
            }
            if let Some(u) = &t.unit {
                history.push((u.clone(), margin));
            }
            if let Outcome::Failed { check, margin } = t.outcome {
                let found = Found {
                    sample: t.index,
                    params: t.params,
                    statements: t.statements.expect("an evaluated candidate has statements"),
                    unit: t.unit.is_some(),
                };
                out.failure = Some(shrink(source, &opts, found, check, margin)?);
                return Ok(out);
            }
        }
    }
    Ok(out)
}

/// Whether plain check `check` (its index among the plain checks) fails
/// on `statements`, running only the plans it reads.
fn fails(source: &Source, statements: &[SourcedStmt], check: usize) -> bool {
    let Ok(scenario) = analyze_statements(
        &source.path,
        statements.to_vec(),
        source.sources.clone(),
        source.maps.clone(),
    ) else {
        return false;
    };
    let Some(target) = scenario
        .checks
        .iter()
        .enumerate()
        .filter(|(_, c)| !c.bench)
        .nth(check)
        .map(|(k, _)| k)
    else {
        return false;
    };
    let mut plans = Vec::new();
    checks::plans_used(&scenario.checks[target].expr, &mut plans);
    let report = crate::run::run_scenario_drawing(scenario, &plans, false);
    report.checks.iter().any(|o| o.check == target && !o.passed)
}

/// An obstacle of a sample, across re-instantiations: its declaration's
/// span and its name (scattered items share their scatter's span).
type Key = (Span, Option<String>);

fn key(o: &ObstacleDecl) -> Key {
    (o.span, o.name.as_ref().map(|n| n.value.clone()))
}

/// The obstacles of the main file's world, in order.
fn obstacle_keys(statements: &[SourcedStmt]) -> Vec<Key> {
    main_obstacles(statements).iter().map(key).collect()
}

/// `x` rounded to `decimals` decimals.
fn rounded(x: f64, decimals: i32) -> f64 {
    let scale = 10f64.powi(decimals);
    (x * scale).round() / scale
}

/// What shrinking works on: the failing candidate and the family member
/// it is.
struct Shrinker<'a> {
    source: &'a Source,
    /// The check that must still fail (its index among the plain checks).
    check: usize,
    /// The sample whose stream places the scattered items.
    choice: SampleChoice,
    /// The failing candidate's statements and params, as drawn.
    original: Instance,
}

/// What shrinking varies: the drawn params, the scattered items'
/// numbers, the obstacles removed.
#[derive(Clone)]
struct Shrinking {
    /// The drawn params' values, as `scen run --set` gives them; `None`:
    /// the candidate as drawn (a `uniform` sample, whose accepted draw may
    /// not be its first).
    drawn: Option<Vec<f64>>,
    /// Scattered items whose numbers were simplified.
    items: HashMap<Key, ObstacleDecl>,
    gone: HashSet<Key>,
}

impl Shrinker<'_> {
    /// The state's statements and every param's value; `None` when the
    /// params name no family member (outside a support, against a
    /// `require`, every draw rejected).
    fn build(&self, state: &Shrinking) -> Option<(Vec<SourcedStmt>, Vec<f64>)> {
        let (statements, params) = match &state.drawn {
            None => self.original.clone(),
            Some(drawn) => self.source.member(self.choice, drawn)?,
        };
        Some((
            edited(&statements, &state.items, &state.gone),
            params.iter().map(|(_, x)| *x).collect(),
        ))
    }

    fn fails(&self, state: &Shrinking) -> bool {
        self.build(state)
            .is_some_and(|(s, _)| fails(self.source, &s, self.check))
    }
}

impl Source {
    /// The family member with these drawn params' values and sample
    /// `choice`'s scattered items: what `scen run --sample K --set ...`
    /// runs.
    fn member(&self, choice: SampleChoice, drawn: &[f64]) -> Option<Instance> {
        let set = self.family.set_of_drawn(drawn);
        self.family
            .sample(&self.statements, choice, &set, |instance| {
                analyze_statements(
                    &self.path,
                    instance.clone(),
                    self.sources.clone(),
                    self.maps.clone(),
                )
                .map(|_| instance)
                .map_err(|f| f.diags)
            })
            .ok()
            .map(|(statements, d)| (statements, d.params))
    }

    /// The command line that runs a candidate's world: its sample
    /// (`drawn` = `None`), or its drawn params' values, with the sample
    /// whose stream places the scattered items when there are any.
    fn reproduce(&self, opts: &Options, sample: u64, drawn: Option<&[f64]>) -> String {
        let mut args = vec![
            "scen".to_string(),
            "run".to_string(),
            shell_word(&self.path.display().to_string()),
        ];
        if let Some(drawn) = drawn {
            for (name, x) in self.family.drawn_names().iter().zip(drawn) {
                // `{}` of an f64 is its shortest exact form.
                args.push(format!("--set {name}={x}"));
            }
        }
        if drawn.is_none() || self.family.scatters() {
            args.push(format!("--sample {sample}"));
            if opts.seed != 0 {
                args.push(format!("--family-seed {}", opts.seed));
            }
        }
        args.join(" ")
    }
}

/// A word as a shell reads it: quoted when it holds anything but plain
/// characters.
fn shell_word(w: &str) -> String {
    if !w.is_empty()
        && w.chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./+=:,@".contains(c))
    {
        w.to_string()
    } else {
        format!("'{}'", w.replace('\'', "'\\''"))
    }
}

/// `statements` with the scattered items `items` in place of theirs and
/// without the obstacles `gone`.
fn edited(
    statements: &[SourcedStmt],
    items: &HashMap<Key, ObstacleDecl>,
    gone: &HashSet<Key>,
) -> Vec<SourcedStmt> {
    statements
        .iter()
        .map(|stmt| match &stmt.stmt {
            Stmt::World(w) if stmt.in_main_file => {
                let mut w = w.clone();
                w.items.retain(
                    |item| !matches!(item, WorldItem::Obstacle(o) if gone.contains(&key(o))),
                );
                for item in &mut w.items {
                    if let WorldItem::Obstacle(o) = item
                        && let Some(simpler) = items.get(&key(o))
                    {
                        *o = simpler.clone();
                    }
                }
                SourcedStmt {
                    stmt: Stmt::World(w),
                    in_main_file: stmt.in_main_file,
                }
            }
            _ => stmt.clone(),
        })
        .collect()
}

/// A scattered item's numbers as its scatter drew them: a disk's centre
/// and radius, a rect's centre, width and height.
fn item_numbers(o: &ObstacleDecl) -> Option<Vec<f64>> {
    let num = |v: &Value| match v.kind {
        ValueKind::Number(x) => Some(x),
        _ => None,
    };
    let point = |v: &Value| match &v.kind {
        ValueKind::Tuple(p) if p.len() == 2 => Some((num(&p[0])?, num(&p[1])?)),
        _ => None,
    };
    match &o.shape {
        ObstacleShape::Disk(c, r) => {
            let (x, y) = point(c)?;
            Some(vec![x, y, num(r)?])
        }
        ObstacleShape::Rect(a, b) => {
            let ((x0, y0), (x1, y1)) = (point(a)?, point(b)?);
            Some(vec![(x0 + x1) / 2.0, (y0 + y1) / 2.0, x1 - x0, y1 - y0])
        }
        _ => None,
    }
}

/// The scattered item `o` with the numbers `n` (of [`item_numbers`]).
fn with_numbers(o: &ObstacleDecl, n: &[f64]) -> ObstacleDecl {
    let mut o = o.clone();
    let set = |v: &mut Value, x: f64| v.kind = ValueKind::Number(x);
    let set_point = |v: &mut Value, x: f64, y: f64| {
        if let ValueKind::Tuple(p) = &mut v.kind {
            set(&mut p[0], x);
            set(&mut p[1], y);
        }
    };
    match (&mut o.shape, n) {
        (ObstacleShape::Disk(c, r), [x, y, radius]) => {
            set_point(c, *x, *y);
            set(r, *radius);
        }
        (ObstacleShape::Rect(a, b), [x, y, w, h]) => {
            set_point(a, x - w / 2.0, y - h / 2.0);
            set_point(b, x + w / 2.0, y + h / 2.0);
        }
        _ => {}
    }
    o
}

/// Whether a scattered item with the numbers `n` is one its scatter could
/// have placed: its centre in the box, its sizes in their supports, at
/// least the gap from every other scattered item kept.
fn placeable(
    rule: &ScatterRule,
    n: &[f64],
    was: &[f64],
    item: &ObstacleDecl,
    others: &[(&ObstacleDecl, f64)],
) -> bool {
    let inside =
        rule.min.0 <= n[0] && n[0] <= rule.max.0 && rule.min.1 <= n[1] && n[1] <= rule.max.1;
    let sizes = rule
        .sizes
        .iter()
        .zip(n[2..].iter().zip(&was[2..]))
        .all(|(s, (&x, &w))| x == w || s.holds(x));
    inside
        && sizes
        && others
            .iter()
            .all(|(o, gap)| scattered_distance(item, o).is_some_and(|d| d >= rule.gap.max(*gap)))
}

/// Removes obstacles while the check still fails: chunks of halving size,
/// then one at a time until removing any one makes it pass (1-minimal).
fn remove_obstacles(shrinker: &Shrinker, state: &mut Shrinking, runs: &mut usize) {
    let Some((statements, _)) = shrinker.build(state) else {
        return;
    };
    let all = obstacle_keys(&statements);
    let mut chunk = all.len() / 2;
    while chunk > 1 && *runs < SHRINK_RUNS {
        let alive: Vec<Key> = all
            .iter()
            .filter(|k| !state.gone.contains(k))
            .cloned()
            .collect();
        for part in alive.chunks(chunk) {
            if *runs >= SHRINK_RUNS {
                break;
            }
            let mut trial = state.clone();
            trial.gone.extend(part.iter().cloned());
            *runs += 1;
            if shrinker.fails(&trial) {
                *state = trial;
            }
        }
        chunk /= 2;
    }
    // One at a time, in parallel: the first (in order) whose removal keeps
    // the failure goes, until none does.
    loop {
        let alive: Vec<Key> = all
            .iter()
            .filter(|k| !state.gone.contains(k))
            .cloned()
            .collect();
        if alive.is_empty() || *runs + alive.len() > SHRINK_RUNS {
            break;
        }
        *runs += alive.len();
        let keeps: Vec<bool> = alive
            .par_iter()
            .map(|k| {
                let mut trial = state.clone();
                trial.gone.insert(k.clone());
                shrinker.fails(&trial)
            })
            .collect();
        match keeps.iter().position(|&k| k) {
            Some(k) => {
                state.gone.insert(alive[k].clone());
            }
            None => break,
        }
    }
}

/// Shrinks the failing sample and writes the standalone scenario: first
/// the drawn params to the fewest decimals that still fail, each value
/// inside its distribution's support and every `require` holding (the
/// world is then the family member `scen run --set ...` runs, computed
/// values following the params so that it keeps its shape), then the
/// obstacles to a 1-minimal set, then the scattered items' numbers (each
/// item one its scatter could have placed), and a last check that no
/// obstacle became removable.
fn shrink(
    source: &Source,
    opts: &Options,
    found: Found,
    check: usize,
    margin: f64,
) -> Result<Failure, Vec<Diag>> {
    let Found {
        sample,
        params,
        statements,
        unit,
    } = found;
    let before = obstacle_keys(&statements).len();
    let scattered = scatter_spans(&source.statements);
    let drawn = source.family.drawn_values(&params);
    let shrinker = Shrinker {
        source,
        check,
        choice: SampleChoice {
            sample,
            family_seed: opts.seed,
        },
        original: (statements.clone(), params.clone()),
    };
    // A `uniform` sample is the candidate as drawn; a point of the cube
    // is the member of its params' values.
    let mut state = Shrinking {
        drawn: unit.then(|| drawn.clone()),
        items: HashMap::new(),
        gone: HashSet::new(),
    };
    let reproduce = source.reproduce(opts, sample, state.drawn.as_deref());
    let mut runs = 0usize;
    // 1. The drawn params.
    let mut values = drawn.clone();
    for k in 0..values.len() {
        for decimals in 0..=6 {
            let x = rounded(values[k], decimals);
            if x == values[k] || runs >= SHRINK_RUNS {
                break;
            }
            let mut trial = state.clone();
            let mut v = values.clone();
            v[k] = x;
            trial.drawn = Some(v.clone());
            runs += 1;
            if shrinker.fails(&trial) {
                state = trial;
                values = v;
                break;
            }
        }
    }
    let member = source.reproduce(opts, sample, state.drawn.as_deref());
    // 2. The obstacles.
    remove_obstacles(&shrinker, &mut state, &mut runs);
    // 3. The numbers of the scattered items that remain, each kept one
    // its scatter could have placed.
    let mut simplified = false;
    if let Some((current, all_values)) = shrinker.build(&state) {
        let rules = source.family.scatter_rules(&source.statements, &all_values);
        let scattered_items: Vec<ObstacleDecl> = main_obstacles(&current)
            .into_iter()
            .filter(|o| scattered.contains(&o.span))
            .collect();
        for (i, item) in scattered_items.iter().enumerate() {
            let (Some(rule), Some(mut numbers)) = (rules.get(&item.span), item_numbers(item))
            else {
                continue;
            };
            let was = numbers.clone();
            let others: Vec<(&ObstacleDecl, f64)> = scattered_items
                .iter()
                .enumerate()
                .filter(|(j, _)| *j != i)
                .map(|(_, o)| (o, rules.get(&o.span).map_or(f64::INFINITY, |r| r.gap)))
                .collect();
            for slot in 0..numbers.len() {
                for decimals in 0..=6 {
                    let x = rounded(numbers[slot], decimals);
                    if x == numbers[slot] || runs >= SHRINK_RUNS {
                        break;
                    }
                    let mut n = numbers.clone();
                    n[slot] = x;
                    let changed = with_numbers(item, &n);
                    if !placeable(rule, &n, &was, &changed, &others) {
                        continue;
                    }
                    let mut trial = state.clone();
                    trial.items.insert(key(item), changed);
                    runs += 1;
                    if shrinker.fails(&trial) {
                        state = trial;
                        numbers = n;
                        simplified = true;
                        break;
                    }
                }
            }
        }
    }
    // 4. Rounding may have made another obstacle removable.
    remove_obstacles(&shrinker, &mut state, &mut runs);
    let current = shrinker.build(&state).map_or(statements, |(s, _)| s);
    let after = obstacle_keys(&current).len();
    let computed = computed_spans(&source.statements, source.family.index());
    let check_span = source.checks[check];
    let (check_text, line) = match source.sources.get(check_span.file) {
        Some(f) => (
            f.text[check_span.start..check_span.end].to_string(),
            f.text[..check_span.start].matches('\n').count() + 1,
        ),
        None => (String::new(), 0),
    };
    let mut header = format!(
        "# Falsified by `scen falsify` (search {}, seed {}): `expect {check_text}` (line {line} of {})\n\
         # fails on candidate {sample} of the search ({}), which `{reproduce}` runs.\n",
        opts.search.word(),
        opts.seed,
        source.path.display(),
        params
            .iter()
            .map(|(n, x)| format!("{n} = {}", checks::format_num(*x)))
            .collect::<Vec<_>>()
            .join(", "),
    );
    header.push_str(&format!(
        "# This file is the family member `{member}`{}, shrunk from {before} to {after} obstacle(s){}.\n",
        if state.drawn.is_some() && values != drawn {
            " (its params simplified; it fails too)"
        } else {
            ""
        },
        if simplified {
            ", the scattered items' numbers simplified inside their scatter's box, sizes and gap"
        } else {
            ""
        },
    ));
    // Numbers to 12 significant digits when the file still fails with
    // them, else exact.
    let pretty = write_standalone(source, &current, &computed, &header, true)?;
    let text = if still_failing(source, &pretty) {
        pretty
    } else {
        write_standalone(source, &current, &computed, &header, false)?
    };
    Ok(Failure {
        sample,
        params,
        reproduce,
        check: check_text,
        line,
        margin,
        obstacles: (before, after),
        shrink_runs: runs,
        text,
    })
}

/// The obstacles of the main file's world, in order.
fn main_obstacles(statements: &[SourcedStmt]) -> Vec<ObstacleDecl> {
    let mut out = Vec::new();
    for s in statements {
        if let (true, Stmt::World(w)) = (s.in_main_file, &s.stmt) {
            for item in &w.items {
                if let WorldItem::Obstacle(o) = item {
                    out.push(o.clone());
                }
            }
        }
    }
    out
}

/// The failing candidate, as the search found it.
struct Found {
    sample: u64,
    params: Vec<(String, f64)>,
    statements: Vec<SourcedStmt>,
    /// A point of the cube (else a `uniform` sample).
    unit: bool,
}

/// The spans of the scatters (their items' declarations carry them).
fn scatter_spans(statements: &[SourcedStmt]) -> HashSet<Span> {
    let mut out = HashSet::new();
    for s in statements {
        if let Stmt::World(w) = &s.stmt {
            for item in &w.items {
                if let WorldItem::Scatter(sc) = item {
                    out.insert(sc.span);
                }
            }
        }
    }
    out
}

/// Whether `text`, read as the scenario file itself (its includes and
/// maps where they were), has a plain check that fails.
pub fn still_failing(source: &Source, text: &str) -> bool {
    let canon = crate::scenario::loader::canonical(&source.path);
    let overlay = |p: &Path| (p == canon).then(|| std::sync::Arc::<str>::from(text));
    let Ok(scenario) = crate::scenario::load_with(&source.path, None, &overlay) else {
        return false;
    };
    let report = crate::run::run_scenario_drawing(scenario, &[], false);
    report
        .checks
        .iter()
        .any(|c| !c.passed && !report.scenario.checks[c.check].bench)
}

/// A number as written: to 12 significant digits (`pretty`), or its
/// shortest exact form.
fn number_text(x: f64, pretty: bool) -> String {
    if pretty && x != 0.0 && x.is_finite() {
        let digits = 11 - x.abs().log10().floor() as i32;
        if (0..=15).contains(&digits) {
            let s = format!("{:.*}", digits as usize, x);
            let s = if s.contains('.') {
                s.trim_end_matches('0').trim_end_matches('.').to_string()
            } else {
                s
            };
            return if s == "-0" { "0".to_string() } else { s };
        }
    }
    format!("{x}")
}

/// A number as a literal.
fn literal(kind: &ValueKind, pretty: bool) -> Option<String> {
    Some(match kind {
        ValueKind::Number(x) => number_text(*x, pretty),
        ValueKind::Angle(a) => format!(
            "{}{}",
            number_text(a.written, pretty),
            if a.unit == AngleUnit::Deg {
                "deg"
            } else {
                "rad"
            }
        ),
        _ => return None,
    })
}

/// One obstacle as a line of a `world` block.
fn obstacle_line(o: &ObstacleDecl, pretty: bool) -> String {
    let v = |v: &Value| value_text(v, pretty);
    let name = o
        .name
        .as_ref()
        .map_or(String::new(), |n| format!(" {}", n.value));
    match &o.shape {
        ObstacleShape::Rect(a, b) => format!("rect{name} {} {}", v(a), v(b)),
        ObstacleShape::Disk(a, b) => format!("disk{name} {} {}", v(a), v(b)),
        ObstacleShape::Segment(a, b) => format!("segment{name} {} {}", v(a), v(b)),
        ObstacleShape::Polygon(p) => format!("polygon{name} {}", v(p)),
        ObstacleShape::Grid(_) => String::new(),
    }
}

fn value_text(v: &Value, pretty: bool) -> String {
    let all = |items: &[Value]| {
        items
            .iter()
            .map(|i| value_text(i, pretty))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match &v.kind {
        ValueKind::Tuple(items) => format!("({})", all(items)),
        ValueKind::List(items) => format!("[{}]", all(items)),
        kind => literal(kind, pretty).unwrap_or_default(),
    }
}

/// The standalone scenario: the main file with its params and requires
/// removed, every computed value written as its number, each scatter as the
/// obstacles it placed that shrinking kept, the removed obstacles and the
/// benches left out; then laid out by the formatter.
fn write_standalone(
    source: &Source,
    sample: &[SourcedStmt],
    computed: &HashSet<Span>,
    header: &str,
    pretty: bool,
) -> Result<String, Vec<Diag>> {
    let text = source
        .sources
        .get(0)
        .map(|f| f.text.clone())
        .unwrap_or_default();
    // The sample's computed numbers, by span.
    let mut numbers: HashMap<Span, String> = HashMap::new();
    collect_literals(sample, computed, pretty, &mut numbers);
    // The sample's obstacles, by declaration span (scattered ones by their
    // scatter's span, in order).
    let mut kept: HashMap<Span, Vec<&ObstacleDecl>> = HashMap::new();
    for s in sample {
        if let Stmt::World(w) = &s.stmt {
            for item in &w.items {
                if let WorldItem::Obstacle(o) = item {
                    kept.entry(o.span).or_default().push(o);
                }
            }
        }
    }
    let mut edits: Vec<(Span, String)> = Vec::new();
    let mut outside = Vec::new();
    for s in &source.statements {
        let span = s.stmt.span();
        if span.file != 0 {
            // Statements of included files stay as they are, unless they
            // hold something computed.
            if computed
                .iter()
                .any(|c| c.file == span.file && span.start <= c.start && c.end <= span.end)
            {
                outside.push(span);
            }
            continue;
        }
        match &s.stmt {
            Stmt::Param(_) | Stmt::Require { .. } | Stmt::Bench(_) => {
                edits.push((span, String::new()))
            }
            Stmt::Expect(e) if reads_bench(e) => {
                // The statement starts at its keyword.
                let start = text[..span.start].rfind("expect").unwrap_or(span.start);
                edits.push((Span::new(0, start, span.end), String::new()));
            }
            Stmt::World(w) => {
                for item in &w.items {
                    match item {
                        WorldItem::Obstacle(o) if !kept.contains_key(&o.span) => {
                            edits.push((o.span, String::new()));
                        }
                        WorldItem::Scatter(sc) => {
                            let lines: Vec<String> = kept
                                .get(&sc.span)
                                .map(|os| os.iter().map(|o| obstacle_line(o, pretty)).collect())
                                .unwrap_or_default();
                            edits.push((sc.span, lines.join("\n")));
                        }
                        _ => {}
                    }
                }
            }
            _ => {}
        }
    }
    if let Some(span) = outside.first() {
        return Err(vec![Diag::error(
            "scen::falsify::family_in_include",
            "`scen falsify` writes its scenario from the main file, and an included file uses the family's params",
        )
        .at(*span, "computed from params, in an included file")
        .help("declare what varies in the main file (or copy the included part into it)")]);
    }
    let deleted: Vec<Span> = edits.iter().map(|(s, _)| *s).collect();
    for (span, lit) in &numbers {
        if span.file == 0
            && !deleted
                .iter()
                .any(|d| d.start <= span.start && span.end <= d.end)
        {
            edits.push((*span, lit.clone()));
        }
    }
    edits.sort_by_key(|(s, _)| std::cmp::Reverse(s.start));
    let mut out = text.to_string();
    for (span, replacement) in edits {
        out.replace_range(span.start..span.end, &replacement);
    }
    let out = format!("{header}{out}");
    Ok(crate::format::format_text(&out).unwrap_or(out))
}

/// The literal of every number at a computed span.
fn collect_literals(
    sample: &[SourcedStmt],
    computed: &HashSet<Span>,
    pretty: bool,
    out: &mut HashMap<Span, String>,
) {
    fn value(v: &Value, computed: &HashSet<Span>, pretty: bool, out: &mut HashMap<Span, String>) {
        if computed.contains(&v.span)
            && let Some(l) = literal(&v.kind, pretty)
        {
            out.insert(v.span, l);
            return;
        }
        if let ValueKind::Tuple(items) | ValueKind::List(items) = &v.kind {
            for i in items {
                value(i, computed, pretty, out);
            }
        }
    }
    for s in sample {
        s.stmt
            .each_value(&mut |v, _| value(v, computed, pretty, out));
        if let Stmt::Expect(e) = &s.stmt {
            e.walk(&mut |n| {
                if let ExprKind::Number(x) = &n.kind
                    && computed.contains(&n.span)
                {
                    out.insert(n.span, number_text(*x, pretty));
                }
            });
        }
    }
}

//! `potential` (SPEC 3.4, SEEDS §E): gradient descent on an attractive and
//! repulsive potential, with local-minimum detection and a seeded
//! random-walk escape, for point and disk robots.
//!
//! # The walk
//! From the start, each step moves ε along F = F_att + ΣF_rep (forces of
//! [`FieldIndex::forces`]). When the goal is within `tolerance`, one last
//! motion lands on it exactly. Every motion (steps, the last one, jumps) is checked with the
//! planners' collision queries ([`ObstacleIndex::sweep_free`]) and must keep
//! the reference point in `bounds`, so the trajectory passes the validator.
//!
//! # Local minima
//! A position is a local minimum when
//! - the angle between F_att and ΣF_rep is within 1° of 180° (the seed's
//!   cos = −1 test; not when ΣF_rep is a cancellation down to rounding
//!   noise, e.g. midway between two parallel walls) and |ΣF_rep| ≥ |F_att|
//!   (a weaker opposed repulsion, e.g. at the edge of `influence` on a
//!   head-on approach to a wall, only slows the walk: it is no minimum),
//! - the position moved less than ε/2 over the last 8 steps (oscillation),
//! - the step would collide or leave the bounds (SPEC: never taken), or
//! - F = 0.
//!
//! # Escape (`escape random_walk`)
//! Candidate jumps, in this order: the seed's "smart" jumps past the
//! vertices of the nearest obstacle (nearest vertex first, as long as the
//! distance plus 0.1 plus the robot's radius, direction offset by a random
//! 2°–7° plus the angle the robot's radius needs, on a random side first),
//! then jumps parallel to the nearest obstacle (both ways, random length in
//! [jump/2, jump]), then uniformly random jumps (angle in [0, 2π), length in
//! [ε, jump]). A
//! candidate must be at most `jump` long and collision-free. It is taken
//! when a short look-ahead descent from its end (without escapes) reaches
//! the goal, or ends more than ρ0 + radius + 2ε away from the minimum (not
//! back in the same basin). If no candidate passes, the walk jumps to the
//! collision-free candidate farthest from the minimum and draws again from
//! there (a random walk of up to 8 jumps, each tested the same way against
//! the original minimum's basin), then descends; if no candidate is even
//! collision-free at the minimum, the run stops (not found).
//!
//! # Limits
//! `limit steps N` (or `limit expansions N`) caps the moves (steps, jumps
//! and the final landing; `steps` counts them); without one, [`DEFAULT_STEP_LIMIT`] applies, so a run that
//! overshoots and circles the goal (SEEDS §E) always ends. `limit time`
//! is checked every 1024 steps and between escape candidates. The escapes'
//! look-ahead descents have a budget of their own (a multiple of the step
//! limit), so a walk that keeps escaping ends too. The time counts from the
//! plan's start, building the field and collision indexes included.
//!
//! # Memory
//! The executed motion is kept in full up to 4 million moves; beyond, the
//! list is thinned and the motion is validated and measured as it is made
//! ([`motion`]), so memory does not grow with `limit steps`. The trace
//! keeps at most a few thousand force samples and the first 100 000
//! minima and jumps.

mod field;
mod motion;

use std::any::Any;
use std::f64::consts::TAU;

pub use field::{FieldIndex, Forces, Gains, Near, Source};

use crate::contract::PlanArgs;
use crate::contract::schema::{DefaultValue, MetricSpec, ParamSpec, RobotKind, Word, num};
use crate::geometry::collide::ObstacleIndex;
use crate::geometry::{Aabb, Config, Point, RobotShape, Vector, World};
use crate::rng::SplitMix64;
use crate::word_enum;

use super::deadline::Deadline;
use crate::contract::layers::{Colour, Drawing, Layer, Style, Svg, Timeline};
use crate::contract::{MetricValue, PlanOutcome};
use crate::contract::{Planner, Settings, Task};

/// `potential` in the registry.
pub static PLANNER: Planner = Planner {
    kind: "potential",
    summary: "potential field with random-walk escape",
    robots: &[RobotKind::Point, RobotKind::Disk],
    params: &[
        ParamSpec::positive("attract", num(1.0, "1"), "attractive gain η"),
        ParamSpec::positive("repulse", num(1.0, "1"), "repulsive gain d"),
        ParamSpec::positive("influence", num(2.0, "2"), "influence distance ρ0"),
        ParamSpec::positive("step", num(0.05, "0.05"), "step length ε"),
        ParamSpec::positive(
            "tolerance",
            DefaultValue::Derived("= step"),
            "goal tolerance",
        ),
        ParamSpec::word(
            "escape",
            EscapeMode::WORDS,
            "random_walk",
            "how to leave local minima",
        ),
        ParamSpec::positive(
            "jump",
            DefaultValue::Derived("5 × influence"),
            "longest random-walk jump",
        ),
    ],
    metrics: &[
        MetricSpec::num(
            "steps",
            "moves on the path: gradient steps, jumps and the landing on the goal",
        ),
        MetricSpec::num(
            "minima",
            "local minima detected: the repulsion opposed to the attraction within 1° and at least as strong, moving less than ε/2 in 8 steps, or a blocked step",
        ),
        MetricSpec::num("escapes", "random-walk jumps taken"),
        MetricSpec::num(
            "traveled",
            "length of the motion executed: the path, or the walk so far when it stopped short",
        ),
    ],
    limits: &["steps", "expansions", "time"],
    needs_goal: true,
    randomized: true,
    grids: true,
    time: false,
    check,
};

word_enum! {
    /// How to leave a local minimum (SPEC 3.4 `escape`).
    pub enum EscapeMode {
        None = "none",
        RandomWalk = "random_walk",
    }
}

/// The settings of a `potential` plan.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Potential {
    pub gains: Gains,
    /// ε.
    pub step: f64,
    pub tolerance: f64,
    pub escape: EscapeMode,
    /// Longest jump.
    pub jump: f64,
}

fn check(args: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    let influence = args.num("influence");
    let step = args.num("step");
    Some(Box::new(Potential {
        gains: Gains {
            attract: args.num("attract"),
            repulse: args.num("repulse"),
            influence,
        },
        step,
        tolerance: args.opt_num("tolerance").unwrap_or(step),
        escape: args.word("escape"),
        jump: args.opt_num("jump").unwrap_or(5.0 * influence),
    }))
}

impl Settings for Potential {
    fn plan(&self, task: &Task<'_>) -> PlanOutcome {
        plan(task, self)
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// Moves allowed when the plan sets no `limit steps` (SPEC: nothing hangs).
pub const DEFAULT_STEP_LIMIT: u64 = 1_000_000;

/// Look-ahead descent steps (escape candidates' basin tests) allowed per
/// move of the step limit, and at least [`MIN_LOOK_AHEAD_BUDGET`] in all:
/// escapes cost many steps each, and a walk that keeps escaping must end too.
const LOOK_AHEAD_PER_STEP: u64 = 20;
const MIN_LOOK_AHEAD_BUDGET: u64 = 2_000_000;

/// ΣF_rep shorter than this fraction of Σ|F_rep| is taken for cancelled
/// forces (rounding noise, whose direction means nothing) by the opposition
/// test.
const CANCELLED: f64 = 1e-9;

/// The steps compared by the oscillation test.
const OSCILLATION_WINDOW: usize = 8;

/// Uniformly random candidates drawn per escape, after the smart ones.
const RANDOM_CANDIDATES: usize = 64;

/// Most jumps in one escape: when no candidate leaves the minimum's basin,
/// the walk jumps on from the candidate that ended farthest from the
/// minimum, up to this many times.
const MAX_CHAIN: usize = 8;

/// Most obstacle vertices aimed at by smart jumps, nearest first.
const SMART_VERTICES: usize = 4;

/// The trace keeps at most this many force samples (then every other one
/// is dropped and the sampling stride doubles).
const MAX_FORCE_SAMPLES: usize = 4096;

/// The trace draws at most this many minima and as many escape jumps (the
/// first ones); the metrics count them all.
const MAX_TRACED_EVENTS: usize = 100_000;

/// A run's settings: the plan's, its limits and its seed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Run {
    pub gains: Gains,
    /// ε.
    pub step: f64,
    pub tolerance: f64,
    /// `escape random_walk`.
    pub escape: bool,
    /// Longest jump.
    pub jump: f64,
    /// Moves (steps and jumps) before giving up.
    pub max_steps: u64,
    /// `max_steps` is [`DEFAULT_STEP_LIMIT`], the plan set no limit.
    pub default_steps: bool,
    /// `limit time`, from the plan's start.
    pub deadline: Deadline,
    pub seed: u64,
    /// The walk's trace is drawn ([`Task::draw`]): forces, minima, escapes.
    pub draw: bool,
}

impl Run {
    /// The run of a plan starting now.
    pub fn new(p: &Potential, task: &Task<'_>) -> Self {
        let limits = task.limits;
        let max_steps = match (limits.steps, limits.expansions) {
            (Some(a), Some(b)) => a.min(b),
            (Some(a), None) | (None, Some(a)) => a,
            (None, None) => DEFAULT_STEP_LIMIT,
        };
        Run {
            gains: p.gains,
            step: p.step,
            tolerance: p.tolerance,
            escape: p.escape == EscapeMode::RandomWalk,
            jump: p.jump,
            max_steps,
            default_steps: limits.steps.is_none() && limits.expansions.is_none(),
            deadline: Deadline::start(&limits),
            seed: task.seed,
            draw: task.draw,
        }
    }
}

/// Why a position is a local minimum.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Why {
    /// F_att and ΣF_rep within 1° of opposite, the repulsion at least as
    /// strong.
    Opposed,
    /// Moved less than ε/2 over the last 8 steps.
    Oscillation,
    /// The step would collide or leave the bounds.
    Blocked,
    /// F = 0.
    Balanced,
}

impl Why {
    fn describe(self) -> &'static str {
        match self {
            Why::Opposed => {
                "attraction and repulsion opposed within 1°, the repulsion at least as strong"
            }
            Why::Oscillation => "oscillating: moved less than ε/2 in 8 steps",
            Why::Blocked => "the next step would collide",
            Why::Balanced => "the forces cancel",
        }
    }
}

/// What one call of [`Descent::advance`] did.
#[derive(Clone, Copy, Debug)]
enum Advance {
    /// Stepped from the previous position, under these forces.
    Moved(Point, Forces),
    /// Landed on the goal.
    Arrived,
    /// A local minimum at the current position.
    Stuck(Why),
}

/// The fixed context of a walk: the world's indexes and the settings.
struct Walker<'a> {
    world: &'a World,
    /// The runner's referee, for a walk too long to return whole.
    referee: Option<&'a dyn crate::contract::Referee>,
    field: &'a FieldIndex,
    obstacles: &'a ObstacleIndex,
    bounds: Aabb,
    radius: f64,
    goal: Point,
    s: &'a Run,
    /// cos 179°: the opposition test's threshold.
    cos_opposed: f64,
}

impl Walker<'_> {
    /// Whether the straight motion a → b is collision-free and ends inside
    /// the bounds (which are convex, so the motion stays inside).
    fn motion_free(&self, a: Point, b: Point) -> bool {
        self.bounds.contains(b) && self.obstacles.sweep_free(a, b, self.radius)
    }
}

/// A gradient descent in progress: the position and the recent ones.
#[derive(Clone, Debug)]
struct Descent {
    x: Point,
    /// `recent[n % 9]` = the position after move n (move 0: the start), so
    /// that the position 8 moves back is at hand.
    recent: [Point; OSCILLATION_WINDOW + 1],
    moves: usize,
}

impl Descent {
    fn new(x: Point) -> Self {
        Descent {
            x,
            recent: [x; OSCILLATION_WINDOW + 1],
            moves: 0,
        }
    }

    /// One step of pure descent from the current position.
    #[inline]
    fn advance(&mut self, w: &Walker) -> Advance {
        let x = self.x;
        if (x - w.goal).norm() <= w.s.tolerance {
            if w.motion_free(x, w.goal) {
                self.x = w.goal;
                return Advance::Arrived;
            }
            return Advance::Stuck(Why::Blocked);
        }
        const SLOTS: usize = OSCILLATION_WINDOW + 1;
        if self.moves >= OSCILLATION_WINDOW
            && (x - self.recent[(self.moves - OSCILLATION_WINDOW) % SLOTS]).norm() < 0.5 * w.s.step
        {
            return Advance::Stuck(Why::Oscillation);
        }
        let f = w.field.forces(x, w.goal);
        let (na, nr) = (f.attract.norm(), f.repulse.norm());
        // Opposed but weaker, the repulsion only slows the walk down: it
        // still advances until the two balance (SPEC 3.4).
        if na > 0.0
            && nr >= na
            && nr > CANCELLED * f.repulse_sum
            && f.attract.dot(&f.repulse) <= w.cos_opposed * na * nr
        {
            return Advance::Stuck(Why::Opposed);
        }
        let total = f.total();
        let n = total.norm();
        if !(n > 0.0 && n.is_finite()) {
            return Advance::Stuck(Why::Balanced);
        }
        let next = x + total * (w.s.step / n);
        if !w.motion_free(x, next) {
            return Advance::Stuck(Why::Blocked);
        }
        self.x = next;
        self.moves += 1;
        self.recent[self.moves % SLOTS] = next;
        Advance::Moved(x, f)
    }
}

/// How a look-ahead descent from a jump's end went.
enum Outlook {
    /// It reached the goal.
    Arrives,
    /// It ended (stuck, or out of look-ahead steps) this far from the
    /// minimum being escaped.
    EndsAt(f64),
}

/// What an escape attempt found.
enum Escape {
    /// The jumps' ends, in order (the last one out of the basin, unless the
    /// chain reached [`MAX_CHAIN`] jumps first).
    Jumps(Vec<Point>),
    /// No candidate was collision-free.
    NoJump,
    /// The time limit passed.
    OutOfTime,
    /// The look-ahead budget is spent.
    OutOfWork,
}

/// Runs a `potential` plan for a point or disk robot.
pub fn plan(task: &Task<'_>, settings: &Potential) -> PlanOutcome {
    let world = task.world;
    let radius = match task.robot {
        RobotShape::Point => 0.0,
        RobotShape::Disk(r) => *r,
        RobotShape::Polygon(_) => {
            return PlanOutcome {
                notes: vec!["`potential` plans for point and disk robots only".into()],
                ..PlanOutcome::default()
            };
        }
    };
    let s = Run::new(settings, task);
    if task.start_is_goal() {
        let mut out = PlanOutcome::at_goal(task.start);
        for m in ["steps", "minima", "escapes", "traveled"] {
            out.extra.insert(m.into(), MetricValue::Num(0.0));
        }
        return out;
    }
    let field = FieldIndex::new(world, radius, s.gains);
    let obstacles = ObstacleIndex::new(world);
    let goal = task.goal.unwrap_or(task.start);
    let walker = Walker {
        world,
        referee: task.referee,
        field: &field,
        obstacles: &obstacles,
        bounds: world.bounds,
        radius,
        goal: goal.xy(),
        s: &s,
        cos_opposed: 179f64.to_radians().cos(),
    };
    walk(&walker, task.start, goal)
}

/// The main loop: descend, detect minima, escape, until the goal or a limit.
fn walk(w: &Walker, start: Config, goal: Config) -> PlanOutcome {
    let s = w.s;
    let theta = start.theta;
    let mut rng = SplitMix64::new(s.seed);
    let mut out = PlanOutcome::default();
    let mut trace = FieldTrace::default();
    let mut motion = motion::Motion::new(w.referee, start);
    let mut descent = Descent::new(start.xy());
    let (mut minima, mut escapes) = (0u64, 0u64);
    let mut stride = 1usize;
    let mut closest = (start.xy() - w.goal).norm();
    let mut found = false;
    let mut budget = s
        .max_steps
        .saturating_mul(LOOK_AHEAD_PER_STEP)
        .max(MIN_LOOK_AHEAD_BUDGET);
    loop {
        let steps = motion.moves();
        if steps >= s.max_steps {
            out.gave_up = true;
            out.notes.push(limit_note(
                if s.default_steps {
                    format!(
                        "the default step limit ({}; set another with `limit steps N`)",
                        s.max_steps
                    )
                } else {
                    format!("the step limit ({})", s.max_steps)
                },
                closest,
                w,
            ));
            break;
        }
        if steps.is_multiple_of(1024) && s.deadline.passed() {
            out.gave_up = true;
            out.notes
                .push(limit_note("the time limit".into(), closest, w));
            break;
        }
        match descent.advance(w) {
            Advance::Arrived => {
                motion.push(goal);
                found = true;
                break;
            }
            Advance::Moved(from, f) => {
                let step = steps as usize;
                if s.draw && step.is_multiple_of(stride) {
                    trace.forces.push(ForceSample {
                        step,
                        at: from,
                        attract: f.attract,
                        repulse: f.repulse,
                        total: f.total(),
                    });
                    if trace.forces.len() >= MAX_FORCE_SAMPLES {
                        thin_samples(&mut trace.forces, &mut stride);
                    }
                }
                motion.push(Config::new(descent.x.x, descent.x.y, theta));
                closest = closest.min((descent.x - w.goal).norm());
            }
            Advance::Stuck(why) => {
                let at = descent.x;
                minima += 1;
                trace.minimum(steps as usize, at);
                if !s.escape {
                    out.notes.push(format!(
                        "stopped in a local minimum at ({:.3}, {:.3}) ({}) with `escape none`",
                        at.x,
                        at.y,
                        why.describe()
                    ));
                    break;
                }
                match escape(w, at, &mut rng, &mut budget) {
                    Escape::Jumps(ends) => {
                        let mut from = at;
                        for to in ends {
                            if motion.moves() >= s.max_steps {
                                break; // the loop's limit check gives up
                            }
                            trace.escape(motion.moves() as usize, from, to);
                            escapes += 1;
                            motion.push(Config::new(to.x, to.y, theta));
                            closest = closest.min((to - w.goal).norm());
                            from = to;
                        }
                        descent = Descent::new(from);
                    }
                    Escape::NoJump => {
                        out.notes.push(format!(
                            "no collision-free jump out of the local minimum at ({:.3}, {:.3})",
                            at.x, at.y
                        ));
                        break;
                    }
                    Escape::OutOfTime => {
                        out.gave_up = true;
                        out.notes
                            .push(limit_note("the time limit".into(), closest, w));
                        break;
                    }
                    Escape::OutOfWork => {
                        out.gave_up = true;
                        out.notes.push(limit_note(
                            "the escapes' look-ahead budget (20 descent steps per allowed step)"
                                .into(),
                            closest,
                            w,
                        ));
                        break;
                    }
                }
            }
        }
    }
    let steps = motion.moves();
    out.expanded = steps;
    out.extra
        .insert("steps".into(), MetricValue::Num(steps as f64));
    out.extra
        .insert("minima".into(), MetricValue::Num(minima as f64));
    out.extra
        .insert("escapes".into(), MetricValue::Num(escapes as f64));
    let (poses, measured) = motion.finish();
    // As the runner measures `length` (the same sum when found).
    let traveled = match &measured {
        Some(m) => m.length,
        None => crate::geometry::path::path_length(&poses),
    };
    out.extra
        .insert("traveled".into(), MetricValue::Num(traveled));
    if let Some(m) = &measured {
        out.notes.push(format!(
            "the motion has {steps} moves, more than the {} kept in full: it was validated and measured as it was made, and is listed thinned (every {}th configuration and the last)",
            motion::FULL_MOVES,
            m.stride
        ));
    }
    if s.draw
        && (trace.minima.len() >= MAX_TRACED_EVENTS || trace.escapes.len() >= MAX_TRACED_EVENTS)
    {
        out.notes.push(format!(
            "the picture shows the first {MAX_TRACED_EVENTS} minima and escape jumps"
        ));
    }
    out.measured = measured;
    if found {
        out.cost = Some(traveled);
        out.path = Some(poses);
    } else {
        out.trajectory = poses;
    }
    if s.draw {
        let b = w.bounds;
        out.layers = field_layers(&trace, 0.03 * b.width().max(b.height()));
    }
    out
}

/// One sampled step of a walk: where, and the forces there.
#[derive(Clone, Copy, Debug, PartialEq)]
struct ForceSample {
    /// Index into the path.
    step: usize,
    at: Point,
    attract: Vector,
    repulse: Vector,
    total: Vector,
}

/// What a walk leaves for the viewer.
#[derive(Clone, Debug, Default)]
struct FieldTrace {
    /// Forces at sampled steps (not every step: at most a few thousand).
    forces: Vec<ForceSample>,
    /// Local minima detected: the path index and the position (the first
    /// [`MAX_TRACED_EVENTS`]).
    minima: Vec<(usize, Point)>,
    /// Escape jumps taken: the path index where the jump starts, from, to
    /// (the first [`MAX_TRACED_EVENTS`]).
    escapes: Vec<(usize, Point, Point)>,
}

impl FieldTrace {
    fn minimum(&mut self, step: usize, at: Point) {
        if self.minima.len() < MAX_TRACED_EVENTS {
            self.minima.push((step, at));
        }
    }

    fn escape(&mut self, step: usize, from: Point, to: Point) {
        if self.escapes.len() < MAX_TRACED_EVENTS {
            self.escapes.push((step, from, to));
        }
    }
}

/// The forces as arrows on timeline `step` (`field/attract`, `repulse`,
/// `total`: directions only, all `length` long, since forces span orders of
/// magnitude), the minima (`field/minima`) and the escape jumps with where
/// they land (`field/escapes`).
fn field_layers(trace: &FieldTrace, length: f64) -> Vec<Layer> {
    let arrow = |v: Vector| {
        let n = v.norm();
        if n > 0.0 && n.is_finite() {
            v * (length / n)
        } else {
            Vector::zeros()
        }
    };
    let mut out = Vec::new();
    for f in &trace.forces {
        for (entity, v, colour) in [
            ("field/attract", f.attract, Colour::Green),
            ("field/repulse", f.repulse, Colour::Red),
            ("field/total", f.total, Colour::Blue),
        ] {
            out.push(
                Layer::new(
                    entity,
                    Drawing::Arrows(vec![(f.at, arrow(v))]),
                    Style::new(colour, 0.0, 35.0),
                )
                .at(Timeline::Step, f.step as i64),
            );
        }
    }
    if !trace.minima.is_empty() {
        out.push(Layer::new(
            "field/minima",
            Drawing::Points(trace.minima.iter().map(|&(_, p)| p).collect()),
            Style::new(Colour::Red, 5.0, 36.0).svg(Svg::line(1.0).key("local minima")),
        ));
    }
    if !trace.escapes.is_empty() {
        out.push(Layer::new(
            "field/escapes",
            Drawing::Segments(trace.escapes.iter().map(|&(_, a, b)| (a, b)).collect()),
            Style::new(Colour::Plan, 1.0, 36.0)
                .svg(Svg::line(1.0).dashed().key("escapes from minima")),
        ));
        out.push(Layer::new(
            "field/escapes",
            Drawing::Points(trace.escapes.iter().map(|&(_, _, b)| b).collect()),
            Style::new(Colour::Plan, 4.0, 36.0),
        ));
    }
    out
}

/// The note of a run stopped by a limit; it says when the walk came close
/// to the goal without landing (overshooting, SEEDS §E).
/// When the goal is within reach of an obstacle's repulsion, the forces do
/// not vanish there and the walk may settle off the goal: the note says so.
fn limit_note(limit: String, closest: f64, w: &Walker) -> String {
    let mut note =
        format!("{limit} was reached before the goal; the walk came within {closest:.3} of it");
    if closest <= 2.0 * w.s.step {
        note.push_str(" (it overshoots and circles the goal: raise `tolerance` or lower `step`)");
    }
    if let Some(near) = w.field.forces(w.goal, w.goal).nearest {
        let name = &w.world.obstacles[w.field.sources[near.source].obstacle].name;
        note.push_str(&format!(
            "; obstacle `{name}` lies within `influence` of the goal, so the forces do not vanish \
             there (lower `influence` or `repulse`, or raise `tolerance`)"
        ));
    }
    note
}

/// Keeps every other force sample and doubles the sampling stride.
fn thin_samples(samples: &mut Vec<ForceSample>, stride: &mut usize) {
    *stride *= 2;
    samples.retain(|f| f.step % *stride == 0);
}

/// Draws jumps out of the local minimum at `m` (see the module docs).
fn escape(w: &Walker, m: Point, rng: &mut SplitMix64, budget: &mut u64) -> Escape {
    let s = w.s;
    let basin = s.gains.influence + w.radius + 2.0 * s.step;
    let mut chain = Vec::new();
    let mut from = m;
    for _ in 0..MAX_CHAIN {
        // The candidate that passed, or else the one ending farthest from
        // the minimum, to walk on from.
        let mut fallback: Option<(f64, Point)> = None;
        for e in jump_candidates(w, from, rng) {
            if s.deadline.passed() {
                return Escape::OutOfTime;
            }
            if *budget == 0 {
                return Escape::OutOfWork;
            }
            if (e - from).norm() > s.jump * (1.0 + 1e-12) || !w.motion_free(from, e) {
                continue;
            }
            match look_ahead(w, e, m, budget) {
                Outlook::Arrives => {
                    chain.push(e);
                    return Escape::Jumps(chain);
                }
                Outlook::EndsAt(d) if d > basin => {
                    chain.push(e);
                    return Escape::Jumps(chain);
                }
                Outlook::EndsAt(_) => {
                    let away = (e - m).norm();
                    if fallback.is_none_or(|(best, _)| away > best) {
                        fallback = Some((away, e));
                    }
                }
            }
        }
        match fallback {
            Some((_, e)) => {
                chain.push(e);
                from = e;
            }
            None => break,
        }
    }
    if chain.is_empty() {
        Escape::NoJump
    } else {
        Escape::Jumps(chain)
    }
}

/// The candidate jump ends from `m`, in the order they are tried.
fn jump_candidates(w: &Walker, m: Point, rng: &mut SplitMix64) -> Vec<Point> {
    let s = w.s;
    let mut out = Vec::new();
    let at = |angle: f64, len: f64| m + Vector::new(angle.cos(), angle.sin()) * len;
    if let Some(near) = w.field.forces(m, w.goal).nearest {
        // Smart jumps (SEEDS §E): past the nearest obstacle's vertices.
        let mut vertices = w.field.sources[near.source].vertices.clone();
        vertices.sort_by(|a, b| (a - m).norm().total_cmp(&(b - m).norm()));
        for v in vertices.into_iter().take(SMART_VERTICES) {
            let dist = (v - m).norm();
            if dist <= 1e-12 {
                continue;
            }
            let base = (v.y - m.y).atan2(v.x - m.x);
            let clearance = (w.radius / dist).min(1.0).asin();
            let len = dist + 0.1 + w.radius;
            let first = if rng.coin() { 1.0 } else { -1.0 };
            for side in [first, -first] {
                let offset = rng.range(2.0, 7.0).to_radians() + clearance;
                out.push(at(base + side * offset, len));
            }
        }
        // Parallel to the obstacle, both ways.
        let away = m - near.point;
        if away.norm() > 0.0 {
            let along = Vector::new(-away.y, away.x).normalize();
            let first = if rng.coin() { 1.0 } else { -1.0 };
            for side in [first, -first] {
                let len = rng.range(0.5 * s.jump, s.jump);
                out.push(m + along * (side * len));
            }
        }
    }
    let shortest = s.step.min(s.jump);
    for _ in 0..RANDOM_CANDIDATES {
        let angle = rng.range(0.0, TAU);
        let len = rng.range(shortest, s.jump);
        out.push(at(angle, len));
    }
    out
}

/// Pure descent from `e` for a bounded number of steps: does it come back
/// to the minimum at `m`?
fn look_ahead(w: &Walker, e: Point, m: Point, budget: &mut u64) -> Outlook {
    let s = w.s;
    let max = (2.0 * (s.jump + s.gains.influence) / s.step)
        .ceil()
        .clamp(50.0, 1000.0) as u64;
    let max = max.min(*budget);
    let mut d = Descent::new(e);
    let mut used = 0;
    let mut outlook = None;
    while used < max {
        used += 1;
        match d.advance(w) {
            Advance::Arrived => {
                outlook = Some(Outlook::Arrives);
                break;
            }
            Advance::Moved(..) => {}
            Advance::Stuck(_) => break,
        }
    }
    *budget -= used;
    if let Some(o) = outlook {
        return o;
    }
    Outlook::EndsAt((d.x - m).norm())
}

#[cfg(test)]
mod tests;

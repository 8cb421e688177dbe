//! Per-planner schemas: the parameters each planner kind accepts (name,
//! value type, default, range, help), the robots it handles and the metrics
//! it reports. The analyzer validates plans against these tables; a new
//! planner is a new table here plus one line in [`PLANNERS`].

use crate::diagnostics::edit_distance;

/// What a robot is, for the robot compatibility tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RobotKind {
    Point,
    Disk,
    Polygon,
}

impl RobotKind {
    pub fn name(self) -> &'static str {
        match self {
            RobotKind::Point => "point",
            RobotKind::Disk => "disk",
            RobotKind::Polygon => "polygon",
        }
    }
}

/// The type and range of a parameter's value.
#[derive(Clone, Copy, Debug)]
pub enum ValueSpec {
    /// `(x, y)` or `(x, y, θ)`.
    Pose,
    /// A number in a range; `min_open` excludes `min` itself.
    Number {
        min: f64,
        min_open: bool,
        max: f64,
        integer: bool,
    },
    /// One of a few integers (`connect 4|8|6|26`).
    IntChoice(&'static [i64]),
    /// One of a few words.
    Word(&'static [&'static str]),
    /// A positive integer or one of a few words (`layers 51|auto`).
    IntOrWord(&'static [&'static str]),
    /// The name of a world obstacle (`on G`).
    ObstacleName,
    /// `expansions N | steps N | time DURATION | cells N`.
    Limit,
    /// A word with an optional `{ ... }` block (`drive unicycle { dt 0.02 }`).
    Drive,
    /// A positive number of seconds or a duration (`10ms`), at most `max`.
    Seconds { max: f64 },
    /// A positive angle written with its unit (`0.5deg`), at most `max`
    /// radians; stored in radians.
    Angle { max: f64 },
}

impl ValueSpec {
    /// Describes the accepted values, for messages and help lines.
    pub fn describe(&self) -> String {
        match self {
            ValueSpec::Pose => "a pose `(x, y)` or `(x, y, θ)` with θ in `deg` or `rad`".into(),
            ValueSpec::Number {
                min,
                min_open,
                max,
                integer,
            } => {
                let what = if *integer { "an integer" } else { "a number" };
                let lo = if *min_open { ">" } else { ">=" };
                if max.is_finite() {
                    format!("{what} {lo} {min} and <= {max}")
                } else {
                    format!("{what} {lo} {min}")
                }
            }
            ValueSpec::IntChoice(c) => format!(
                "one of {}",
                c.iter()
                    .map(|x| format!("`{x}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            ValueSpec::Word(w) => format!("one of {}", backticked(w)),
            ValueSpec::IntOrWord(w) => format!("a positive integer or {}", backticked(w)),
            ValueSpec::ObstacleName => "the name of a `grid` obstacle of the world".into(),
            ValueSpec::Limit => {
                "`expansions N`, `steps N`, `time DURATION` (e.g. `2s`, `500ms`) or `cells N`"
                    .into()
            }
            ValueSpec::Drive => "`unicycle`, optionally followed by `{ ... }`".into(),
            ValueSpec::Seconds { max } => {
                format!("a positive number of seconds or a duration (`10ms`), at most {max}s")
            }
            ValueSpec::Angle { max } => format!(
                "a positive angle with its unit (`0.5deg`), at most {}deg",
                max.to_degrees()
            ),
        }
    }
}

pub fn backticked(words: &[&str]) -> String {
    words
        .iter()
        .map(|w| format!("`{w}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// One parameter of a planner.
#[derive(Clone, Copy, Debug)]
pub struct ParamSpec {
    pub key: &'static str,
    pub value: ValueSpec,
    /// The default, as the user would write it ("" when required or none).
    pub default: &'static str,
    pub help: &'static str,
    /// May be given several times (`limit`).
    pub repeatable: bool,
}

const fn p(
    key: &'static str,
    value: ValueSpec,
    default: &'static str,
    help: &'static str,
) -> ParamSpec {
    ParamSpec {
        key,
        value,
        default,
        help,
        repeatable: false,
    }
}

const fn positive(integer: bool) -> ValueSpec {
    ValueSpec::Number {
        min: 0.0,
        min_open: true,
        max: f64::INFINITY,
        integer,
    }
}

const fn at_least(min: f64, integer: bool) -> ValueSpec {
    ValueSpec::Number {
        min,
        min_open: false,
        max: f64::INFINITY,
        integer,
    }
}

/// The kinds of `limit` (SPEC 2.5): `limit expansions N`, `steps N`,
/// `time DURATION`, `cells N`.
pub const LIMIT_KINDS: &[&str] = &["expansions", "steps", "time", "cells"];

/// Parameters every planner accepts (SPEC 2.5).
pub const COMMON_PARAMS: &[ParamSpec] = &[
    p("start", ValueSpec::Pose, "", "start configuration"),
    p("goal", ValueSpec::Pose, "", "goal configuration"),
    ParamSpec {
        key: "limit",
        value: ValueSpec::Limit,
        default: "",
        help: "give up when reached: `expansions N`, `steps N`, `time 2s`, `cells N`",
        repeatable: true,
    },
    p(
        "seed",
        ValueSpec::Number {
            min: 0.0,
            min_open: false,
            max: 9.007_199_254_740_992e15,
            integer: true,
        },
        "0",
        "random seed",
    ),
    p(
        "drive",
        ValueSpec::Drive,
        "",
        "simulate a differential-drive robot following the path",
    ),
];

const fn up_to(max: f64) -> ValueSpec {
    ValueSpec::Number {
        min: 0.0,
        min_open: true,
        max,
        integer: false,
    }
}

/// The sub-parameters of `drive unicycle { ... }` (SPEC 3.6). The values
/// the simulation takes for keys not given are
/// [`crate::drive::Unicycle::default`]'s, the defaults written here.
pub const DRIVE_PARAMS: &[ParamSpec] = &[
    p(
        "dt",
        ValueSpec::Seconds { max: 1.0 },
        "10ms",
        "integration step in seconds (a number or a duration such as `10ms`)",
    ),
    p(
        "max_speed",
        up_to(1e6),
        "1",
        "largest linear speed, world units per second",
    ),
    p(
        "max_turn_rate",
        ValueSpec::Angle { max: 1e6 },
        "2rad",
        "largest turn rate, an angle per second (e.g. `120deg`)",
    ),
    p(
        "gain",
        up_to(1e6),
        "2",
        "go-to-cell gain: speed = gain × distance (1/s)",
    ),
    p(
        "turn_gain",
        up_to(1e6),
        "8",
        "go-to-orientation gain: turn rate = turn_gain × heading error (1/s)",
    ),
    p(
        "reach",
        up_to(1e6),
        "0.0009",
        "distance to a path point at which it counts as reached",
    ),
    p(
        "align",
        ValueSpec::Angle {
            max: std::f64::consts::FRAC_PI_2,
        },
        "0.5deg",
        "heading error under which the robot stops turning in place and drives",
    ),
];

/// The type of a metric, for typing `expect` expressions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MetricType {
    Bool,
    Num,
}

use MetricType::{Bool, Num};

/// Metrics every planner reports (SPEC 3).
pub const COMMON_METRICS: &[(&str, MetricType)] = &[
    ("found", Bool),
    ("gave_up", Bool),
    ("cost", Num),
    ("length", Num),
    ("turn", Num),
    ("nodes", Num),
    ("expanded", Num),
    ("time_ms", Num),
    ("collision_free", Bool),
    ("reaches_goal", Bool),
];

/// Metrics of a plan with `drive` (SPEC 3.6), whatever its planner.
pub const DRIVE_METRICS: &[(&str, MetricType)] = &[
    ("drive_time", Num),
    ("drive_max_deviation", Num),
    ("drive_collision_free", Bool),
];

/// A planner kind.
#[derive(Clone, Copy, Debug)]
pub struct PlannerSchema {
    pub kind: &'static str,
    /// One line for help texts.
    pub summary: &'static str,
    /// Which robots it plans for, and whether this version implements that.
    pub robots: &'static [RobotKind],
    pub params: &'static [ParamSpec],
    pub metrics: &'static [(&'static str, MetricType)],
    pub needs_goal: bool,
}

impl PlannerSchema {
    pub fn param(&self, key: &str) -> Option<&'static ParamSpec> {
        COMMON_PARAMS
            .iter()
            .chain(self.params.iter())
            .find(|p| p.key == key)
    }

    pub fn all_params(&self) -> impl Iterator<Item = &'static ParamSpec> {
        COMMON_PARAMS.iter().chain(self.params.iter())
    }

    pub fn metric(&self, name: &str) -> Option<MetricType> {
        COMMON_METRICS
            .iter()
            .chain(self.metrics.iter())
            .find(|(m, _)| *m == name)
            .map(|(_, t)| *t)
    }

    pub fn all_metrics(&self) -> impl Iterator<Item = &'static (&'static str, MetricType)> {
        COMMON_METRICS.iter().chain(self.metrics.iter())
    }
}

const LATTICE_PARAMS: [ParamSpec; 3] = [
    p("cell", positive(false), "1", "lattice spacing δ in x and y"),
    p(
        "sample",
        ValueSpec::Word(&["center", "corner"]),
        "center",
        "lattice points at cell centres or corners",
    ),
    p(
        "connect",
        ValueSpec::IntChoice(&[4, 8, 6, 26]),
        "8 (26 for rotating robots)",
        "lattice neighbours: 4 or 8 in (x, y), 6 or 26 in (x, y, θ)",
    ),
];

pub const ASTAR: PlannerSchema = PlannerSchema {
    kind: "astar",
    summary: "A* on a lattice of configurations",
    robots: &[RobotKind::Point, RobotKind::Disk, RobotKind::Polygon],
    params: &[
        LATTICE_PARAMS[0],
        LATTICE_PARAMS[1],
        LATTICE_PARAMS[2],
        p(
            "layers",
            ValueSpec::IntOrWord(&["auto"]),
            "auto",
            "θ layers for rotating robots; `auto` = ⌈2πR/δ⌉",
        ),
        p(
            "cost",
            ValueSpec::Word(&["euclid", "l1"]),
            "euclid",
            "edge cost metric",
        ),
        p(
            "turn_cost",
            at_least(0.0, false),
            "R of the robot",
            "cost of one radian of rotation",
        ),
        p(
            "weight",
            at_least(1.0, false),
            "1",
            "heuristic inflation w ≥ 1",
        ),
        p(
            "heuristic",
            ValueSpec::Word(&["metric", "zero"]),
            "metric",
            "`metric` (admissible) or `zero` (Dijkstra)",
        ),
        p(
            "rotate",
            ValueSpec::Word(&["yes", "no"]),
            "yes for polygons",
            "search in θ too",
        ),
    ],
    metrics: &[
        ("cells", Num),
        ("free_cells", Num),
        ("layers", Num),
        ("generated", Num),
    ],
    needs_goal: true,
};

pub const ONLINE: PlannerSchema = PlannerSchema {
    kind: "online",
    summary: "navigation in an unknown world",
    robots: &[RobotKind::Point, RobotKind::Disk],
    params: &[
        LATTICE_PARAMS[0],
        LATTICE_PARAMS[1],
        LATTICE_PARAMS[2],
        p(
            "strategy",
            ValueSpec::Word(&["backtrack", "shortcut", "replan", "dstar_lite"]),
            "replan",
            "how the robot explores",
        ),
        p(
            "sense",
            at_least(1.0, true),
            "1",
            "sensing range in cells (Chebyshev)",
        ),
    ],
    metrics: &[
        ("traveled", Num),
        ("steps", Num),
        ("replans", Num),
        ("sensed", Num),
    ],
    needs_goal: true,
};

pub const ROADMAP: PlannerSchema = PlannerSchema {
    kind: "roadmap",
    summary: "visibility graph and Dijkstra",
    robots: &[RobotKind::Point, RobotKind::Disk, RobotKind::Polygon],
    params: &[p(
        "arc_segments",
        ValueSpec::Number {
            min: 8.0,
            min_open: false,
            max: crate::planners::roadmap::MAX_ARC_SEGMENTS as f64,
            integer: true,
        },
        "32",
        "segments per full circle for grown disks",
    )],
    metrics: &[("graph_nodes", Num), ("graph_edges", Num)],
    needs_goal: true,
};

pub const POTENTIAL: PlannerSchema = PlannerSchema {
    kind: "potential",
    summary: "potential field with random-walk escape",
    robots: &[RobotKind::Point, RobotKind::Disk],
    params: &[
        p("attract", positive(false), "1", "attractive gain η"),
        p("repulse", positive(false), "1", "repulsive gain d"),
        p("influence", positive(false), "2", "influence distance ρ0"),
        p("step", positive(false), "0.05", "step length ε"),
        p("tolerance", positive(false), "= step", "goal tolerance"),
        p(
            "escape",
            ValueSpec::Word(&["none", "random_walk"]),
            "random_walk",
            "how to leave local minima",
        ),
        p(
            "jump",
            positive(false),
            "5 × influence",
            "longest random-walk jump",
        ),
    ],
    metrics: &[("steps", Num), ("minima", Num), ("escapes", Num)],
    needs_goal: true,
};

pub const COVERAGE: PlannerSchema = PlannerSchema {
    kind: "coverage",
    summary: "spanning tree coverage of a grid",
    robots: &[RobotKind::Disk, RobotKind::Polygon],
    params: &[
        p(
            "on",
            ValueSpec::ObstacleName,
            "",
            "the `grid` obstacle to cover",
        ),
        p(
            "tool",
            positive(false),
            "the grid's cell",
            "side D of the square the robot covers",
        ),
        p(
            "weights",
            ValueSpec::Word(&["max", "sum"]),
            "max",
            "mega-cell edge weights",
        ),
    ],
    metrics: &[
        ("coverage", Num),
        ("cells_total", Num),
        ("cells_visited", Num),
        ("revisits", Num),
        ("returns_to_start", Bool),
        ("uncovered", Num),
        ("tree_edges", Num),
        ("tree_weight", Num),
    ],
    needs_goal: false,
};

/// Every planner kind of SPEC 3.
pub const PLANNERS: &[PlannerSchema] = &[ASTAR, ONLINE, ROADMAP, POTENTIAL, COVERAGE];

pub fn planner(kind: &str) -> Option<&'static PlannerSchema> {
    PLANNERS.iter().find(|s| s.kind == kind)
}

/// The closest of `candidates` to `word` by edit distance, if close enough
/// to be a likely typo.
pub fn did_you_mean<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    let word: Vec<char> = word.chars().collect();
    candidates
        .into_iter()
        .map(|c| (edit_distance(&word, &c.chars().collect::<Vec<_>>()), c))
        .filter(|(d, c)| *d <= 2.max(c.len() / 3) && *d < c.len())
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_are_unique_per_planner() {
        for s in PLANNERS {
            let keys: Vec<_> = s.all_params().map(|p| p.key).collect();
            let mut sorted = keys.clone();
            sorted.sort();
            sorted.dedup();
            assert_eq!(keys.len(), sorted.len(), "duplicate key in {}", s.kind);
        }
    }

    #[test]
    fn did_you_mean_finds_typos() {
        assert_eq!(did_you_mean("cel", ["cell", "sample"]), Some("cell"));
        assert_eq!(did_you_mean("zzzz", ["cell", "sample"]), None);
    }
}

//! The language of plan parameters and metrics: what a parameter's value
//! may be (type, range), its default, its help; what a metric is. Each
//! planner declares its own parameters and metrics with these types in its
//! file ([`crate::planners::registry`]); the analyzer validates plans
//! against them, and the editors' word lists, the generated planner docs
//! and the language server read them. The parameters and metrics every
//! planner has (SPEC 2.5, SPEC 3) are declared here.

use crate::diagnostics::edit_distance;

/// What a robot is, for the robot compatibility tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RobotKind {
    Point,
    Disk,
    Polygon,
    /// A disk or polygon robot with `steer` (SPEC 2.4).
    Car,
    /// A `team` of agents of one shape (SPEC 2.10).
    Team,
}

impl RobotKind {
    pub fn name(self) -> &'static str {
        match self {
            RobotKind::Point => "point",
            RobotKind::Disk => "disk",
            RobotKind::Polygon => "polygon",
            RobotKind::Car => "car",
            RobotKind::Team => "team",
        }
    }

    /// The kind of a shape without steering (see
    /// [`Robot::kind`](crate::contract::Robot::kind) for cars).
    pub fn of(shape: &crate::geometry::RobotShape) -> Self {
        use crate::geometry::RobotShape;
        match shape {
            RobotShape::Point => RobotKind::Point,
            RobotShape::Disk(_) => RobotKind::Disk,
            RobotShape::Polygon(_) => RobotKind::Polygon,
        }
    }
}

/// The largest magnitude of a coordinate, length, radius, cell size or
/// tolerance (SPEC 2.1): beyond it f64 geometry loses the precision the
/// validator needs (its contact tolerance is 1e-9).
pub const MAX_MAGNITUDE: f64 = 1e9;

/// The type and range of a parameter's value.
#[derive(Clone, Copy, Debug, PartialEq)]
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
    /// One of a few words: a [`Word`] enum's [`Word::WORDS`].
    Word(&'static [&'static str]),
    /// A positive integer or one of a few words (`layers 51|auto`).
    IntOrWord(&'static [&'static str]),
    /// A number > 0 (at most [`MAX_MAGNITUDE`]) or one of a few words
    /// (`sense 2.5|inf`).
    NumOrWord(&'static [&'static str]),
    /// The name of a world obstacle (`on G`).
    ObstacleName,
    /// `expansions N | steps N | time DURATION | cells N | iterations N`.
    Limit,
    /// A word with an optional `{ ... }` block (`drive unicycle { dt 0.02 }`).
    Drive,
    /// A positive number of seconds or a duration (`10ms`), at most `max`.
    Seconds { max: f64 },
    /// A positive angle written with its unit (`0.5deg`), at most `max`
    /// radians; stored in radians.
    Angle { max: f64 },
    /// A percentage (`5%`, stored as 0.05) or a plain fraction, in
    /// [`min`, `max`].
    Fraction { min: f64, max: f64 },
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
                if *max == MAX_MAGNITUDE {
                    format!("{what} {lo} {min} and <= 1e9")
                } else if max.is_finite() {
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
            ValueSpec::NumOrWord(w) => format!("a number > 0 and <= 1e9, or {}", backticked(w)),
            ValueSpec::ObstacleName => "the name of a `grid` obstacle of the world".into(),
            ValueSpec::Limit => format!(
                "{} (e.g. `time 2s`, `expansions 10000`)",
                LIMIT_KINDS
                    .iter()
                    .map(|k| if *k == "time" {
                        "`time DURATION`".to_string()
                    } else {
                        format!("`{k} N`")
                    })
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            ValueSpec::Drive => format!(
                "a model ({}), optionally followed by `{{ ... }}`",
                backticked(DRIVE_MODELS)
            ),
            ValueSpec::Seconds { max } => {
                format!("a positive number of seconds or a duration (`10ms`), at most {max}s")
            }
            ValueSpec::Angle { max } if *max >= 1e3 => {
                "a positive angle with its unit (`0.5deg`)".into()
            }
            ValueSpec::Angle { max } => format!(
                "a positive angle with its unit (`0.5deg`), at most {}deg",
                max.to_degrees()
            ),
            ValueSpec::Fraction { min, max } => format!(
                "a percentage from {}% to {}% (or a fraction from {min} to {max})",
                min * 100.0,
                max * 100.0
            ),
        }
    }

    /// Whether a plain word may be this parameter's value (so that a word
    /// right after the key is read as its value, not as the next key).
    pub fn takes_word(&self) -> bool {
        matches!(
            self,
            ValueSpec::Word(_)
                | ValueSpec::IntOrWord(_)
                | ValueSpec::NumOrWord(_)
                | ValueSpec::ObstacleName
                | ValueSpec::Limit
                | ValueSpec::Drive
        )
    }

    /// The words this value may be, for completion and the editors.
    pub fn words(&self) -> &'static [&'static str] {
        match self {
            ValueSpec::Word(w) | ValueSpec::IntOrWord(w) | ValueSpec::NumOrWord(w) => w,
            ValueSpec::Limit => LIMIT_KINDS,
            ValueSpec::Drive => DRIVE_MODELS,
            _ => &[],
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

/// A parameter's default: written once, here, in the schema.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DefaultValue {
    /// Required, or absent unless given (`start`, `on`).
    None,
    /// A number (durations in seconds, angles in radians), and how it is
    /// written in a scenario (`10ms`, `0.5deg`); a test checks that the
    /// written form reads as the number.
    Num(f64, &'static str),
    /// A word of the parameter's [`ValueSpec::Word`] list.
    Word(&'static str),
    /// Derived from the robot or from other parameters by the planner's
    /// `check` (`R of the robot`, `= step`); the text says how.
    Derived(&'static str),
}

impl DefaultValue {
    /// The default as a user reads it in docs and help lines (empty for
    /// [`DefaultValue::None`]).
    pub fn text(&self) -> &'static str {
        match self {
            DefaultValue::None => "",
            DefaultValue::Num(_, written) => written,
            DefaultValue::Word(w) | DefaultValue::Derived(w) => w,
        }
    }
}

/// One parameter of a planner.
#[derive(Clone, Copy, Debug)]
pub struct ParamSpec {
    pub key: &'static str,
    pub value: ValueSpec,
    pub default: DefaultValue,
    pub help: &'static str,
    /// May be given several times (`limit`).
    pub repeatable: bool,
}

impl ParamSpec {
    /// A parameter with its type, default and one line of help.
    pub const fn new(
        key: &'static str,
        value: ValueSpec,
        default: DefaultValue,
        help: &'static str,
    ) -> Self {
        ParamSpec {
            key,
            value,
            default,
            help,
            repeatable: false,
        }
    }

    /// A number > 0 (integer or not), default `default` written as `written`.
    pub const fn positive(key: &'static str, default: DefaultValue, help: &'static str) -> Self {
        Self::new(key, positive(false), default, help)
    }

    /// One of the words of `W`, default `default` (which must be one of them).
    pub const fn word(
        key: &'static str,
        words: &'static [&'static str],
        default: &'static str,
        help: &'static str,
    ) -> Self {
        Self::new(
            key,
            ValueSpec::Word(words),
            DefaultValue::Word(default),
            help,
        )
    }
}

/// A number > 0, at most [`MAX_MAGNITUDE`] (lengths, gains, counts: no
/// parameter needs more, and SPEC 2.1 refuses larger lengths).
pub const fn positive(integer: bool) -> ValueSpec {
    ValueSpec::Number {
        min: 0.0,
        min_open: true,
        max: MAX_MAGNITUDE,
        integer,
    }
}

/// A number ≥ `min`, at most [`MAX_MAGNITUDE`].
pub const fn at_least(min: f64, integer: bool) -> ValueSpec {
    ValueSpec::Number {
        min,
        min_open: false,
        max: MAX_MAGNITUDE,
        integer,
    }
}

/// A number in (0, `max`].
pub const fn up_to(max: f64) -> ValueSpec {
    ValueSpec::Number {
        min: 0.0,
        min_open: true,
        max,
        integer: false,
    }
}

/// A number with its written form, for [`DefaultValue::Num`].
pub const fn num(value: f64, written: &'static str) -> DefaultValue {
    DefaultValue::Num(value, written)
}

/// The word values of a parameter as a Rust enum: the analyzer checks the
/// written word against [`Word::WORDS`], and the planner reads the enum, so
/// a word can never be missing on one side. Declare one with
/// [`word_enum!`](crate::word_enum).
pub trait Word: Copy + std::fmt::Debug + 'static {
    /// The words, in the order of the enum's variants.
    const WORDS: &'static [&'static str];
    /// The variant of `WORDS[index]`.
    fn from_index(index: usize) -> Option<Self>;
    /// The word of this variant.
    fn word(self) -> &'static str;
}

/// Declares an enum whose variants are the words of a parameter:
/// `word_enum! { pub enum Sample { Center = "center", Corner = "corner" } }`
/// gives `Sample::WORDS == ["center", "corner"]` and the [`Word`] impl.
#[macro_export]
macro_rules! word_enum {
    ($(#[$meta:meta])* $vis:vis enum $name:ident {
        $($(#[$vmeta:meta])* $variant:ident = $word:literal),+ $(,)?
    }) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        $vis enum $name {
            $($(#[$vmeta])* $variant),+
        }

        impl $crate::contract::schema::Word for $name {
            const WORDS: &'static [&'static str] = &[$($word),+];

            fn from_index(index: usize) -> Option<Self> {
                const ALL: &[$name] = &[$($name::$variant),+];
                ALL.get(index).copied()
            }

            fn word(self) -> &'static str {
                match self {
                    $($name::$variant => $word),+
                }
            }
        }
    };
}

word_enum! {
    /// `yes` / `no` parameters (`rotate`, `informed`).
    pub enum YesNo {
        Yes = "yes",
        No = "no",
    }
}

/// The kinds of `limit` (SPEC 2.5, 3.7): `limit expansions N`, `steps N`,
/// `time DURATION`, `cells N`, `iterations N`.
pub const LIMIT_KINDS: &[&str] = &["expansions", "steps", "time", "cells", "iterations"];

/// The models of `drive` (SPEC 3.6, 3.8), in the order of [`DRIVE`].
pub const DRIVE_MODELS: &[&str] = &["unicycle", "pure_pursuit"];

/// One model of `drive`: its word, what it is, and the sub-parameters of
/// its `{ ... }` block (the keys of one model are not the other's).
#[derive(Clone, Copy, Debug)]
pub struct DriveModel {
    pub name: &'static str,
    pub help: &'static str,
    pub params: &'static [ParamSpec],
}

/// Every model of `drive`, in the order of [`DRIVE_MODELS`].
pub const DRIVE: &[DriveModel] = &[
    DriveModel {
        name: "unicycle",
        help: "turn in place towards each path point, then drive to it (SPEC 3.6)",
        params: UNICYCLE_PARAMS,
    },
    DriveModel {
        name: "pure_pursuit",
        help: "follow the path continuously, steering towards a point `lookahead` ahead on it; a car keeps its curvature bound and reverses at its cusps (SPEC 3.8)",
        params: PURE_PURSUIT_PARAMS,
    },
];

/// The model of `drive NAME`.
pub fn drive_model(name: &str) -> Option<&'static DriveModel> {
    DRIVE.iter().find(|m| m.name == name)
}

/// Every key of every model's block, each once (the first model's spec of
/// a shared key such as `dt`): how a block groups and what the editors
/// colour, whatever its model.
pub fn drive_params() -> impl Iterator<Item = &'static ParamSpec> {
    DRIVE.iter().enumerate().flat_map(|(k, m)| {
        m.params.iter().filter(move |p| {
            !DRIVE[..k]
                .iter()
                .any(|earlier| earlier.params.iter().any(|q| q.key == p.key))
        })
    })
}

/// Parameters every planner accepts (SPEC 2.5).
pub const COMMON_PARAMS: &[ParamSpec] = &[
    ParamSpec::new(
        "start",
        ValueSpec::Pose,
        DefaultValue::None,
        "start configuration",
    ),
    ParamSpec::new(
        "goal",
        ValueSpec::Pose,
        DefaultValue::None,
        "goal configuration",
    ),
    ParamSpec {
        key: "limit",
        value: ValueSpec::Limit,
        default: DefaultValue::None,
        help: "give up when reached: `expansions N`, `steps N`, `time 2s`, `cells N`, `iterations N`",
        repeatable: true,
    },
    ParamSpec::new(
        "seed",
        ValueSpec::Number {
            min: 0.0,
            min_open: false,
            max: 9.007_199_254_740_992e15,
            integer: true,
        },
        num(0.0, "0"),
        "random seed",
    ),
    ParamSpec::new(
        "drive",
        ValueSpec::Drive,
        DefaultValue::None,
        "simulate a robot following the path: `unicycle` (turn, then go to each point) or `pure_pursuit` (continuously)",
    ),
];

/// `dt` of every drive model: the integration step.
const DRIVE_DT: ParamSpec = ParamSpec::new(
    "dt",
    ValueSpec::Seconds { max: 1.0 },
    num(0.01, "10ms"),
    "integration step in seconds (a number or a duration such as `10ms`)",
);

/// The sub-parameters of `drive unicycle { ... }` (SPEC 3.6), with the
/// defaults the simulation takes for keys not given.
pub const UNICYCLE_PARAMS: &[ParamSpec] = &[
    DRIVE_DT,
    ParamSpec::new(
        "max_speed",
        up_to(1e6),
        num(1.0, "1"),
        "largest linear speed, world units per second",
    ),
    ParamSpec::new(
        "max_turn_rate",
        ValueSpec::Angle { max: 1e6 },
        num(2.0, "2rad"),
        "largest turn rate, an angle per second (e.g. `120deg`)",
    ),
    ParamSpec::new(
        "gain",
        up_to(1e6),
        num(2.0, "2"),
        "go-to-cell gain: speed = gain × distance (1/s)",
    ),
    ParamSpec::new(
        "turn_gain",
        up_to(1e6),
        num(8.0, "8"),
        "go-to-orientation gain: turn rate = turn_gain × heading error (1/s)",
    ),
    ParamSpec::new(
        "reach",
        up_to(1e6),
        num(0.0009, "0.0009"),
        "distance to a path point at which it counts as reached",
    ),
    ParamSpec::new(
        "align",
        ValueSpec::Angle {
            max: std::f64::consts::FRAC_PI_2,
        },
        num(0.008_726_646_259_971_648, "0.5deg"),
        "heading error under which the robot stops turning in place and drives",
    ),
];

/// The sub-parameters of `drive pure_pursuit { ... }` (SPEC 3.8), with the
/// defaults the simulation takes for keys not given.
pub const PURE_PURSUIT_PARAMS: &[ParamSpec] = &[
    ParamSpec::new(
        "lookahead",
        up_to(1e6),
        num(1.0, "1"),
        "arc length along the path from the robot's projection to the point it steers towards; the robot brakes over the last `lookahead` of each piece",
    ),
    ParamSpec::new(
        "speed",
        up_to(1e6),
        num(1.0, "1"),
        "cruising speed, world units per second (forward and in reverse)",
    ),
    DRIVE_DT,
    ParamSpec::new(
        "reach",
        up_to(1e6),
        num(0.0009, "0.0009"),
        "arc length short of a piece's end (the path's end, or a cusp) at which the robot stops",
    ),
    ParamSpec::new(
        "max_curvature",
        up_to(1e6),
        DefaultValue::Derived("1/R for a car, else none"),
        "largest curvature the robot steers with (1/world units); a car's is at most 1/R of its `steer`",
    ),
];

/// The type of a metric, for typing `expect` expressions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MetricType {
    Bool,
    Num,
}

/// One metric a planner reports.
#[derive(Clone, Copy, Debug)]
pub struct MetricSpec {
    pub name: &'static str,
    pub ty: MetricType,
    pub help: &'static str,
}

impl MetricSpec {
    pub const fn num(name: &'static str, help: &'static str) -> Self {
        MetricSpec {
            name,
            ty: MetricType::Num,
            help,
        }
    }

    pub const fn bool(name: &'static str, help: &'static str) -> Self {
        MetricSpec {
            name,
            ty: MetricType::Bool,
            help,
        }
    }
}

/// The metrics of a car robot's plan (SPEC 3.8), measured by the runner
/// from its segments (no value without a path); the planners that plan for
/// cars declare them.
pub const CAR_METRICS: &[MetricSpec] = &[
    MetricSpec::num(
        "cusps",
        "changes of direction (forward ↔ reverse) along a car's path",
    ),
    MetricSpec::num("reverse_length", "arc length a car drives in reverse"),
    MetricSpec::num("segments", "arcs and straights of a car's path"),
];

/// The metrics of a time-aware plan (SPEC 2.9), measured by the runner
/// from its trajectory (+∞ and no value without one); the planners that
/// know time declare them.
pub const TIME_METRICS: &[MetricSpec] = &[
    MetricSpec::num(
        "arrival",
        "when the robot reaches the goal: the trajectory's last time, in seconds (+∞ without one)",
    ),
    MetricSpec::num(
        "waited",
        "total time the robot stands still along the trajectory, in seconds",
    ),
];

/// The metrics of a team plan (SPEC 2.10), measured by the runner from the
/// agents' paths; they stand for [`COMMON_METRICS`], which are about one
/// robot's path.
pub const TEAM_METRICS: &[MetricSpec] = &[
    MetricSpec::bool("found", "every agent has a path to its goal"),
    MetricSpec::bool("gave_up", "a limit was reached first"),
    MetricSpec::num("agents", "agents in the team"),
    MetricSpec::num(
        "sum_of_costs",
        "the sum over agents of the step at which each reaches its goal for the last time (+∞ without a solution)",
    ),
    MetricSpec::num(
        "makespan",
        "the largest of the agents' costs (+∞ without a solution)",
    ),
    MetricSpec::num(
        "soc_lower_bound",
        "the sum of each agent's own shortest cost, by breadth-first search on the referee's lattice (+∞ when some agent cannot reach its goal; no value beyond 2^30 cells × agents); a continuous team's: straight lines at full speed",
    ),
    MetricSpec::num(
        "expanded",
        "search nodes expanded, low-level searches included",
    ),
    MetricSpec::num("time_ms", "wall time of the plan, in milliseconds"),
    MetricSpec::bool(
        "collision_free",
        "the agents' paths passed the referee: obstacles, vertex and edge conflicts",
    ),
];

/// The speed of a robot written without `speed` (SPEC 2.9), in units per
/// second.
pub const DEFAULT_SPEED: f64 = 1.0;

/// Metrics every planner reports (SPEC 3), computed by the runner from the
/// path the same way for every planner.
pub const COMMON_METRICS: &[MetricSpec] = &[
    MetricSpec::bool("found", "a path from start to goal was found"),
    MetricSpec::bool("gave_up", "a limit was reached first"),
    MetricSpec::num(
        "cost",
        "the path's cost in the planner's own metric (+∞ without a path)",
    ),
    MetricSpec::num(
        "length",
        "Euclidean length of the path's (x, y) polyline (+∞ without a path)",
    ),
    MetricSpec::num("turn", "total absolute rotation along the path, in radians"),
    MetricSpec::num("nodes", "number of configurations in the path"),
    MetricSpec::num(
        "expanded",
        "search nodes expanded, or iterations for non-search planners",
    ),
    MetricSpec::num("time_ms", "wall time of the plan, in milliseconds"),
    MetricSpec::bool(
        "collision_free",
        "the path passed the independent validator (SPEC 3.0)",
    ),
    MetricSpec::bool(
        "reaches_goal",
        "the path's last configuration is within 1e-9 of `goal`",
    ),
    MetricSpec::num(
        "clearance",
        "smallest distance between the robot and any obstacle along the path (0 when it touches, +∞ with no obstacle; no value — `null` in JSON, `—` in the report — without a path); a trajectory's also to the moving obstacles, at every instant, the parked robot included",
    ),
    MetricSpec::num(
        "smoothness",
        "OMPL's smoothness of the (x, y) polyline: Σ k² of the turns (0 when straight, +∞ without a path)",
    ),
];

/// Metrics of a plan with `drive` (SPEC 3.6), whatever its planner.
pub const DRIVE_METRICS: &[MetricSpec] = &[
    MetricSpec::num(
        "drive_time",
        "seconds the simulated robot took to the path's end",
    ),
    MetricSpec::num(
        "drive_max_deviation",
        "largest distance of the driven robot from the planned path",
    ),
    MetricSpec::bool(
        "drive_collision_free",
        "the driven trajectory passed the validator",
    ),
];

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
    fn did_you_mean_finds_typos() {
        assert_eq!(did_you_mean("cel", ["cell", "sample"]), Some("cell"));
        assert_eq!(did_you_mean("zzzz", ["cell", "sample"]), None);
    }

    word_enum! {
        enum Fruit { Apple = "apple", Pear = "pear" }
    }

    #[test]
    fn word_enums_map_words_and_variants_both_ways() {
        assert_eq!(Fruit::WORDS, &["apple", "pear"]);
        for (i, w) in Fruit::WORDS.iter().enumerate() {
            let f = Fruit::from_index(i).expect("a variant per word");
            assert_eq!(f.word(), *w);
        }
        assert_eq!(Fruit::from_index(2), None);
        assert_eq!(Fruit::Pear.word(), "pear");
    }
}

//! The typed syntax tree of a `.scen` file. Every node carries a [`Span`].
//! Values keep their units resolved (angles in radians, durations in
//! seconds, percentages as fractions) but not their meaning: the analyzer
//! decides whether a tuple is a point or a pose, and which words are keys.

use crate::diagnostics::{Span, Spanned};

pub type Ident = Spanned<String>;

/// A parsed file: its statements and its comments, each in source order.
#[derive(Clone, Debug, Default)]
pub struct File {
    pub statements: Vec<Stmt>,
    /// Every comment, from its `#` to the end of its line; whitespace and
    /// comments mean nothing to the language, but the formatter keeps them.
    pub comments: Vec<Span>,
}

#[derive(Clone, Debug)]
pub enum Stmt {
    /// `scenario "title"`
    Scenario {
        title: Spanned<String>,
        span: Span,
    },
    /// `include "other.scen"`
    Include {
        path: Spanned<String>,
        span: Span,
    },
    World(WorldBlock),
    Robot(RobotDecl),
    Plan(PlanDecl),
    Expect(Expr),
    Bench(BenchDecl),
    /// `param NAME = ...` (SPEC 2.8).
    Param(ParamDecl),
    /// `require CONDITION` (SPEC 2.8): a constraint on a family's draws.
    Require {
        condition: Expr,
        span: Span,
    },
}

impl Stmt {
    /// The statement's span (for `expect`, its expression's).
    pub fn span(&self) -> Span {
        match self {
            Stmt::Scenario { span, .. }
            | Stmt::Include { span, .. }
            | Stmt::Require { span, .. } => *span,
            Stmt::World(w) => w.span,
            Stmt::Robot(r) => r.span,
            Stmt::Plan(p) => p.span,
            Stmt::Expect(e) => e.span,
            Stmt::Bench(b) => b.span,
            Stmt::Param(p) => p.span,
        }
    }

    /// Calls `f` on every value written in this statement (its top-level
    /// values: a tuple is one value), in source order, with whether the
    /// value is a scattered item's size (where a distribution may stand).
    /// `expect` and `require` hold expressions, not values; a plan's or a
    /// bench's words are in [`ParamToken::flatten`].
    pub fn each_value<'a>(&'a self, f: &mut dyn FnMut(&'a Value, bool)) {
        match self {
            Stmt::World(w) => {
                for item in &w.items {
                    match item {
                        WorldItem::Bounds { min, max, .. } => {
                            f(min, false);
                            f(max, false);
                        }
                        WorldItem::Obstacle(o) => match &o.shape {
                            ObstacleShape::Rect(a, b)
                            | ObstacleShape::Segment(a, b)
                            | ObstacleShape::Disk(a, b) => {
                                f(a, false);
                                f(b, false);
                            }
                            ObstacleShape::Polygon(v) => f(v, false),
                            ObstacleShape::Grid(g) => {
                                for v in g.cell.iter().chain(&g.origin) {
                                    f(v, false);
                                }
                            }
                        },
                        WorldItem::Moving(m) => {
                            for v in &m.shape.args {
                                f(v, false);
                            }
                            for w in &m.waypoints {
                                f(&w.time, false);
                                f(&w.at, false);
                            }
                        }
                        WorldItem::Scatter(sc) => {
                            f(&sc.count, false);
                            match &sc.shape {
                                ScatterShape::Disk { radius, .. } => f(radius, true),
                                ScatterShape::Rect { width, height, .. } => {
                                    f(width, true);
                                    f(height, true);
                                }
                            }
                            f(&sc.min, false);
                            f(&sc.max, false);
                            if let Some(g) = &sc.gap {
                                f(g, false);
                            }
                        }
                    }
                }
            }
            Stmt::Robot(r) => {
                for v in &r.shape.args {
                    f(v, false);
                }
                if let Some(steer) = &r.steer {
                    f(&steer.radius, false);
                }
                if let Some((_, v)) = &r.speed {
                    f(v, false);
                }
                match r.team.as_deref() {
                    Some(TeamBody::Agents { agents, .. }) => {
                        for a in agents {
                            f(&a.start, false);
                            f(&a.goal, false);
                        }
                    }
                    Some(TeamBody::From { count, .. }) => f(count, false),
                    None => {}
                }
            }
            Stmt::Plan(PlanDecl { body, .. }) | Stmt::Bench(BenchDecl { body, .. }) => {
                ParamToken::flatten(body, &mut |t| {
                    if let ParamToken::Value(v) = t {
                        f(v, false);
                    }
                });
            }
            Stmt::Param(p) => match &p.value {
                ParamSource::Value(v) | ParamSource::Choice { values: v, .. } => f(v, false),
            },
            Stmt::Scenario { .. }
            | Stmt::Include { .. }
            | Stmt::Expect(_)
            | Stmt::Require { .. } => {}
        }
    }
}

/// `param NAME = DISTRIBUTION | choice [v, ...] | EXPR`.
#[derive(Clone, Debug)]
pub struct ParamDecl {
    pub name: Ident,
    pub value: ParamSource,
    pub span: Span,
}

/// What a param is drawn from, as written; whether a call is a
/// distribution (`uniform`, `normal`, `int`) is the analyzer's call.
#[derive(Clone, Debug)]
pub enum ParamSource {
    /// `choice [v, ...]`: the `choice` keyword and the list.
    Choice { keyword: Span, values: Value },
    /// A distribution call or an expression of other params (a plain
    /// number is a `Value` of kind `Number`).
    Value(Value),
}

/// `bench NAME { tokens }` (SPEC 2.7): like a plan's body, a flat token
/// list grouped by the analyzer (`plans [...]`, `vary KEY [...]`, `runs N`,
/// `limit KIND AMOUNT`).
#[derive(Clone, Debug)]
pub struct BenchDecl {
    pub name: Ident,
    pub body: Vec<ParamToken>,
    pub span: Span,
}

#[derive(Clone, Debug)]
pub struct WorldBlock {
    pub items: Vec<WorldItem>,
    /// The `world` keyword (used to point at duplicate world blocks).
    pub keyword: Span,
    pub span: Span,
}

#[derive(Clone, Debug)]
pub enum WorldItem {
    /// `bounds (x0, y0) (x1, y1)`
    Bounds {
        min: Value,
        max: Value,
        span: Span,
    },
    Obstacle(ObstacleDecl),
    /// `scatter NAME N SHAPE in (x0, y0) (x1, y1) [gap G]` (SPEC 2.8).
    Scatter(ScatterDecl),
    /// `moving NAME SHAPE { at T (x, y) ... then stay|vanish }` (SPEC 2.9).
    Moving(MovingDecl),
}

/// `moving NAME SHAPE { at T (x, y) ... then stay|vanish }`: an obstacle
/// that translates along timed waypoints.
#[derive(Clone, Debug)]
pub struct MovingDecl {
    pub name: Ident,
    /// `disk R`, `rect W H` (centred on the route's point) or
    /// `polygon [...]` (its frame's origin on the point), as a robot's.
    pub shape: RobotShape,
    pub waypoints: Vec<MovingWaypoint>,
    /// `then stay` or `then vanish`, with the word's span; `None`: stay.
    pub then: Option<Ident>,
    /// The `{ ... }` block.
    pub block: Span,
    pub span: Span,
}

/// `at T (x, y)`.
#[derive(Clone, Debug)]
pub struct MovingWaypoint {
    pub time: Value,
    pub at: Value,
    pub span: Span,
}

/// `scatter NAME N SHAPE in (x0, y0) (x1, y1) [gap G]`: N obstacles at
/// uniformly drawn positions in the box, named `NAME_1` … `NAME_N`.
#[derive(Clone, Debug)]
pub struct ScatterDecl {
    pub name: Ident,
    pub count: Value,
    pub shape: ScatterShape,
    pub min: Value,
    pub max: Value,
    pub gap: Option<Value>,
    pub span: Span,
}

/// The shape of each scattered obstacle; sizes may be distributions.
#[derive(Clone, Debug)]
pub enum ScatterShape {
    /// `disk R`
    Disk { keyword: Span, radius: Value },
    /// `rect W H`, centred on the drawn position.
    Rect {
        keyword: Span,
        width: Value,
        height: Value,
    },
}

#[derive(Clone, Debug)]
pub struct ObstacleDecl {
    /// `rect`, `polygon`, `segment`, `disk` or `grid`, with the keyword's span.
    pub kind: Spanned<ObstacleKind>,
    pub name: Option<Ident>,
    pub shape: ObstacleShape,
    pub span: Span,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ObstacleKind {
    Rect,
    Polygon,
    Segment,
    Disk,
    Grid,
}

impl ObstacleKind {
    pub fn keyword(self) -> &'static str {
        match self {
            ObstacleKind::Rect => "rect",
            ObstacleKind::Polygon => "polygon",
            ObstacleKind::Segment => "segment",
            ObstacleKind::Disk => "disk",
            ObstacleKind::Grid => "grid",
        }
    }

    /// The name of an unnamed obstacle: its kind and its 1-based index
    /// among the scenario's obstacles (`rect_3`).
    pub fn unnamed(self, index: usize) -> String {
        format!("{}_{index}", self.keyword())
    }
}

#[derive(Clone, Debug)]
pub enum ObstacleShape {
    /// Two opposite corners.
    Rect(Value, Value),
    /// A list of points (the `[...]` value).
    Polygon(Value),
    Segment(Value, Value),
    /// Centre and radius.
    Disk(Value, Value),
    Grid(GridSpec),
}

/// `grid NAME? "file.map"? (cell N | origin P)* { "row" ... }?`
#[derive(Clone, Debug)]
pub struct GridSpec {
    pub file: Option<Spanned<String>>,
    pub cell: Option<Value>,
    pub origin: Option<Value>,
    /// Inline rows, top row first; `None` when there is no `{ }` block.
    pub rows: Option<Vec<Spanned<String>>>,
    /// Options given more than once, or unknown words, reported by the parser
    /// as they are met; kept here only for completeness.
    pub span: Span,
}

/// `robot NAME KIND ARGS... [steer MODEL RADIUS]`
#[derive(Clone, Debug)]
pub struct RobotDecl {
    pub name: Ident,
    pub shape: RobotShape,
    /// `steer MODEL RADIUS` after the shape: a car-like robot (SPEC 2.4).
    pub steer: Option<SteerClause>,
    /// `speed V` after the shape (SPEC 2.9): the `speed` keyword's span and
    /// the value.
    pub speed: Option<(Span, Value)>,
    /// For `team NAME ...` (SPEC 2.10): its agents; `None` for a robot.
    pub team: Option<Box<TeamBody>>,
    pub span: Span,
}

/// A team's agents: listed in a block, or read from a MovingAI scenario.
#[derive(Clone, Debug)]
pub enum TeamBody {
    /// `{ NAME (x, y) -> (x, y) ... }`, with the block's span.
    Agents { agents: Vec<TeamAgent>, block: Span },
    /// `from "FILE.scen" agents N`: the keywords' spans, the file, the count.
    From {
        from: Span,
        file: Spanned<String>,
        agents: Span,
        count: Value,
    },
}

/// `NAME (x, y) -> (x, y)` in a team's block.
#[derive(Clone, Debug)]
pub struct TeamAgent {
    pub name: Ident,
    pub start: Value,
    pub arrow: Span,
    pub goal: Value,
    pub span: Span,
}

/// `steer MODEL RADIUS`: the steering model (`dubins`, `reeds_shepp`) and
/// the turning radius, as written.
#[derive(Clone, Debug)]
pub struct SteerClause {
    /// The `steer` keyword.
    pub keyword: Span,
    pub model: Ident,
    pub radius: Value,
    /// From `steer` to the radius.
    pub span: Span,
}

/// The body of `robot NAME KIND ARGS...`: a kind of the robot registry
/// (`scen_geometry::robots`) and its values, as written.
#[derive(Clone, Debug)]
pub struct RobotShape {
    pub kind: Ident,
    pub args: Vec<Value>,
    /// From the kind to its last value.
    pub span: Span,
}

/// `plan NAME KIND ROBOT { tokens }`
#[derive(Clone, Debug)]
pub struct PlanDecl {
    pub name: Ident,
    pub kind: Ident,
    pub robot: Ident,
    /// The block's contents as a flat token list; the analyzer groups them
    /// into `key value...` parameters using the planner's schema.
    pub body: Vec<ParamToken>,
    pub span: Span,
}

#[derive(Clone, Debug)]
pub enum ParamToken {
    /// A bare word: a key, or a word value such as `center`, `auto`, `yes`.
    Word(Ident),
    /// Any other value.
    Value(Value),
    /// A nested `{ ... }` block.
    Block { tokens: Vec<ParamToken>, span: Span },
}

impl ParamToken {
    /// Calls `f` on every word and value of `tokens`, those of nested
    /// blocks included, in source order.
    pub fn flatten<'a>(tokens: &'a [ParamToken], f: &mut dyn FnMut(&'a ParamToken)) {
        for t in tokens {
            match t {
                ParamToken::Block { tokens: inner, .. } => ParamToken::flatten(inner, f),
                t => f(t),
            }
        }
    }

    pub fn span(&self) -> Span {
        match self {
            ParamToken::Word(w) => w.span,
            ParamToken::Value(v) => v.span,
            ParamToken::Block { span, .. } => *span,
        }
    }
}

/// A literal value.
#[derive(Clone, Debug, PartialEq)]
pub struct Value {
    pub kind: ValueKind,
    pub span: Span,
}

impl Value {
    /// Whether two values are the same, whatever their spans (a
    /// selection's value against a `vary` list's).
    pub fn same(&self, other: &Value) -> bool {
        match (&self.kind, &other.kind) {
            (ValueKind::Tuple(x), ValueKind::Tuple(y))
            | (ValueKind::List(x), ValueKind::List(y)) => {
                x.len() == y.len() && x.iter().zip(y).all(|(a, b)| a.same(b))
            }
            (x, y) => x == y,
        }
    }
}

/// An angle as written: its number and its unit. SPEC 2.1 bounds the number
/// in its own unit and reduces it to [0, 2π) in that unit, where the
/// reduction is exact (`fmod` is), before any geometry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Angle {
    pub written: f64,
    pub unit: AngleUnit,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AngleUnit {
    Deg,
    Rad,
}

impl Angle {
    pub fn deg(written: f64) -> Angle {
        Angle {
            written,
            unit: AngleUnit::Deg,
        }
    }

    pub fn rad(written: f64) -> Angle {
        Angle {
            written,
            unit: AngleUnit::Rad,
        }
    }

    /// The angle in radians, unreduced (a parameter such as `align 5deg`).
    pub fn radians(self) -> f64 {
        match self.unit {
            AngleUnit::Deg => self.written.to_radians(),
            AngleUnit::Rad => self.written,
        }
    }

    /// The angle reduced to [0, 2π), in radians (a pose's heading): the
    /// remainder is taken in the written unit (exactly), then converted.
    pub fn reduced(self) -> f64 {
        let r = match self.unit {
            AngleUnit::Deg => self.written.rem_euclid(360.0).to_radians(),
            AngleUnit::Rad => self.written.rem_euclid(std::f64::consts::TAU),
        };
        // A tiny negative remainder rounds up to a full turn.
        if r >= std::f64::consts::TAU { 0.0 } else { r }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum ValueKind {
    /// A plain number.
    Number(f64),
    /// An angle (`90deg`, `1.5rad`), as written.
    Angle(Angle),
    /// A percentage as a fraction (`100%` = 1.0).
    Percent(f64),
    /// A duration in seconds (`500ms`, `2s`).
    Duration(f64),
    Str(String),
    /// A bare word used as a value (only inside plan bodies).
    Word(String),
    /// `(a, b)` or `(a, b, c)`.
    Tuple(Vec<Value>),
    /// `[a, b, c]`.
    List(Vec<Value>),
    /// An arithmetic expression of numbers and params (SPEC 2.8), with the
    /// angle unit written after it (`(a + 10)deg`); a family's sample
    /// replaces it by its number before analysis.
    Calc {
        expr: Box<Expr>,
        unit: Option<AngleUnit>,
    },
}

impl ValueKind {
    /// What the value is, for messages: "a number", "an angle", ...
    pub fn describe(&self) -> &'static str {
        match self {
            ValueKind::Number(_) => "a number",
            ValueKind::Angle(_) => "an angle",
            ValueKind::Percent(_) => "a percentage",
            ValueKind::Duration(_) => "a duration",
            ValueKind::Str(_) => "a string",
            ValueKind::Word(_) => "a word",
            ValueKind::Tuple(_) => "a point",
            ValueKind::List(_) => "a list",
            ValueKind::Calc { unit: Some(_), .. } => "an angle expression",
            ValueKind::Calc { unit: None, .. } => "an expression",
        }
    }
}

/// An `expect` expression.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

impl Expr {
    /// The operands of this node, in source order (none for a leaf).
    pub fn children(&self) -> Vec<&Expr> {
        match &self.kind {
            ExprKind::Number(_)
            | ExprKind::Percent(_)
            | ExprKind::Bool(_)
            | ExprKind::Metric { .. }
            | ExprKind::Name(_)
            | ExprKind::Series { .. } => Vec::new(),
            ExprKind::Call { args, .. } => args.iter().collect(),
            ExprKind::Neg(x) | ExprKind::Not(x) => vec![x],
            ExprKind::Where(a, b)
            | ExprKind::And(a, b)
            | ExprKind::Or(a, b)
            | ExprKind::Arith { lhs: a, rhs: b, .. }
            | ExprKind::Compare { lhs: a, rhs: b, .. } => vec![a, b],
            ExprKind::Approx { lhs, rhs, tol } => vec![lhs, rhs, tol],
        }
    }

    /// Calls `f` on this node and every node below it, parents first.
    pub fn walk<'e>(&'e self, f: &mut impl FnMut(&'e Expr)) {
        f(self);
        for child in self.children() {
            child.walk(f);
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    Number(f64),
    /// `100%`, as a fraction.
    Percent(f64),
    Bool(bool),
    /// A param's name (SPEC 2.8): in `require`, in `expect`, and in the
    /// expressions of number positions.
    Name(Ident),
    /// `PLAN.METRIC`
    Metric {
        plan: Ident,
        metric: Ident,
    },
    /// A bench's series: `BENCH.PLAN.METRIC`, or with a selection
    /// `BENCH.PLAN[KEY = VALUE, ...].METRIC`.
    Series {
        bench: Ident,
        plan: Ident,
        select: Vec<Selection>,
        metric: Ident,
    },
    /// An aggregate: `median(SERIES)`, `quantile(SERIES, Q)`.
    Call {
        function: Ident,
        args: Vec<Expr>,
    },
    /// `SERIES where CONDITION`: the runs where the boolean series holds.
    Where(Box<Expr>, Box<Expr>),
    Neg(Box<Expr>),
    Not(Box<Expr>),
    Arith {
        op: ArithOp,
        lhs: Box<Expr>,
        rhs: Box<Expr>,
    },
    Compare {
        op: CompareOp,
        lhs: Box<Expr>,
        rhs: Box<Expr>,
    },
    /// `lhs ~ rhs +- tol`
    Approx {
        lhs: Box<Expr>,
        rhs: Box<Expr>,
        tol: Box<Expr>,
    },
    And(Box<Expr>, Box<Expr>),
    Or(Box<Expr>, Box<Expr>),
}

/// `KEY = VALUE` in a series' selection.
#[derive(Clone, Debug, PartialEq)]
pub struct Selection {
    pub key: Ident,
    pub value: Value,
    pub span: Span,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArithOp {
    Add,
    Sub,
    Mul,
    Div,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CompareOp {
    Lt,
    Le,
    Gt,
    Ge,
    Eq,
    Ne,
}

impl CompareOp {
    pub fn symbol(self) -> &'static str {
        match self {
            CompareOp::Lt => "<",
            CompareOp::Le => "<=",
            CompareOp::Gt => ">",
            CompareOp::Ge => ">=",
            CompareOp::Eq => "==",
            CompareOp::Ne => "!=",
        }
    }
}

impl ArithOp {
    pub fn symbol(self) -> &'static str {
        match self {
            ArithOp::Add => "+",
            ArithOp::Sub => "-",
            ArithOp::Mul => "*",
            ArithOp::Div => "/",
        }
    }
}

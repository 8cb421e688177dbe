//! pest pairs → typed AST nodes with file-relative spans, for every
//! statement; the `expect` expressions are built in [`super::expr`].
//!
//! The builder also reports what the grammar accepts but the language does
//! not: malformed or out-of-range numbers, unknown units and escapes, a
//! repeated grid option, a unit written apart from its number.

use crate::syntax::ast::{TeamAgent, TeamBody};
use pest::iterators::Pair;

use super::ast::{
    Angle, BenchDecl, GridSpec, Ident, MovingDecl, MovingWaypoint, ObstacleDecl, ObstacleKind,
    ObstacleShape, ParamDecl, ParamSource, ParamToken, PlanDecl, RobotDecl, RobotShape,
    ScatterDecl, ScatterShape, SteerClause, Stmt, Value, ValueKind, WorldBlock, WorldItem,
};
use super::parser::Rule;
use super::scanner::is_ident_byte;
use super::syntax_error::{closest_keyword, show};
use crate::diagnostics::{Diag, FileId, Span, Spanned};

/// Words that are units when written right after a number.
pub const UNIT_WORDS: [&str; 4] = ["deg", "rad", "ms", "s"];

const UNITS_HELP: &str = "units are `deg` and `rad` for angles, `%` for percentages, `ms` and `s` \
                          for durations, written right after the number: `90deg`";

/// Turns the pairs of one chunk into AST nodes. Spans are offset by `base`,
/// the chunk's offset in the file.
pub(super) struct Builder<'t, 'd> {
    text: &'t str,
    pub(super) file: FileId,
    base: usize,
    pub(super) diags: &'d mut Vec<Diag>,
    /// Whether this statement's "expression too deep" was reported already.
    pub(super) expr_too_deep: bool,
}

pub(super) type P<'i> = Pair<'i, Rule>;

fn is_punctuation(rule: Rule) -> bool {
    matches!(
        rule,
        Rule::lbrace
            | Rule::rbrace
            | Rule::lparen
            | Rule::rparen
            | Rule::lbracket
            | Rule::rbracket
            | Rule::comma
            | Rule::EOI
    )
}

/// Where the text of `pair` ends, in the chunk. A pest rule that ends with
/// an optional or repeated part (`grid ... cell 1`, an expression) also spans
/// the blanks and comments skipped before pest found that part absent.
fn content_end(pair: &P<'_>) -> usize {
    match pair.clone().into_inner().next_back() {
        Some(last) => content_end(&last),
        None => pair.as_span().end(),
    }
}

/// The children of `pair` that carry meaning (punctuation left out).
pub(super) fn children(pair: P<'_>) -> impl Iterator<Item = P<'_>> {
    pair.into_inner().filter(|p| !is_punctuation(p.as_rule()))
}

impl<'t, 'd> Builder<'t, 'd> {
    pub(super) fn new(text: &'t str, file: FileId, base: usize, diags: &'d mut Vec<Diag>) -> Self {
        Builder {
            text,
            file,
            base,
            diags,
            expr_too_deep: false,
        }
    }

    pub(super) fn span(&self, pair: &P<'_>) -> Span {
        let s = pair.as_span();
        Span::new(self.file, self.base + s.start(), self.base + s.end())
    }

    /// The span of a rule that may end with an absent optional part (see
    /// [`content_end`]).
    fn trimmed_span(&self, pair: &P<'_>) -> Span {
        let start = pair.as_span().start();
        Span::new(self.file, self.base + start, self.base + content_end(pair))
    }

    /// The byte of the file right before `offset`.
    pub(super) fn byte_before(&self, offset: usize) -> Option<u8> {
        offset
            .checked_sub(1)
            .and_then(|k| self.text.as_bytes().get(k).copied())
    }

    pub(super) fn ident(&self, pair: &P<'_>) -> Ident {
        Spanned::new(pair.as_str().to_string(), self.span(pair))
    }

    pub(super) fn statement(&mut self, pair: P<'_>) -> Option<Stmt> {
        let span = self.span(&pair);
        Some(match pair.as_rule() {
            Rule::scenario => {
                let title =
                    self.string(&children(pair).nth(1).expect("grammar guarantees a title"));
                Stmt::Scenario { title, span }
            }
            Rule::include => {
                let path = self.string(&children(pair).nth(1).expect("grammar guarantees a path"));
                Stmt::Include { path, span }
            }
            Rule::world => Stmt::World(self.world(pair)),
            Rule::robot | Rule::team => Stmt::Robot(self.robot(pair)),
            Rule::plan => Stmt::Plan(self.plan(pair)),
            Rule::bench => {
                let mut inner = children(pair).skip(1);
                let name = self.ident(&inner.next().expect("grammar guarantees a bench name"));
                let body =
                    self.param_tokens(inner.next().expect("grammar guarantees a bench body"));
                Stmt::Bench(BenchDecl { name, body, span })
            }
            Rule::expect => {
                let expr = children(pair)
                    .nth(1)
                    .expect("grammar guarantees an expression");
                Stmt::Expect(self.expect_expr(expr)?)
            }
            Rule::require => {
                let expr = children(pair)
                    .nth(1)
                    .expect("grammar guarantees a condition");
                Stmt::Require {
                    condition: self.expect_expr(expr)?,
                    span,
                }
            }
            Rule::param => {
                let mut inner = children(pair).skip(1);
                let name = self.ident(&inner.next().expect("grammar guarantees a param name"));
                let source = inner
                    .find(|p| p.as_rule() != Rule::equals)
                    .expect("grammar guarantees the param's value");
                let value = if source.as_rule() == Rule::param_choice {
                    let mut parts = children(source);
                    let keyword = self.span(&parts.next().expect("grammar guarantees `choice`"));
                    let values = self.value(parts.next().expect("grammar guarantees a list"));
                    ParamSource::Choice { keyword, values }
                } else {
                    ParamSource::Value(self.value(source))
                };
                Stmt::Param(ParamDecl { name, value, span })
            }
            rule => unreachable!("grammar guarantees a statement, got {rule:?}"),
        })
    }

    fn world(&mut self, pair: P<'_>) -> WorldBlock {
        let span = self.span(&pair);
        let mut inner = children(pair);
        let keyword = self.span(&inner.next().expect("grammar guarantees `world`"));
        let items = inner.map(|item| self.world_item(item)).collect();
        WorldBlock {
            items,
            keyword,
            span,
        }
    }

    fn world_item(&mut self, pair: P<'_>) -> WorldItem {
        let span = self.trimmed_span(&pair);
        let rule = pair.as_rule();
        let mut inner = children(pair).peekable();
        let keyword = inner.next().expect("grammar guarantees a keyword");
        if rule == Rule::scatter {
            return WorldItem::Scatter(self.scatter(inner, span));
        }
        if rule == Rule::moving {
            return WorldItem::Moving(self.moving(inner, span));
        }
        if rule == Rule::bounds {
            let min = self.value(inner.next().expect("grammar guarantees a min corner"));
            let max = self.value(inner.next().expect("grammar guarantees a max corner"));
            return WorldItem::Bounds { min, max, span };
        }
        let kind = match rule {
            Rule::rect_obstacle => ObstacleKind::Rect,
            Rule::polygon_obstacle => ObstacleKind::Polygon,
            Rule::segment_obstacle => ObstacleKind::Segment,
            Rule::disk_obstacle => ObstacleKind::Disk,
            Rule::grid_obstacle => ObstacleKind::Grid,
            rule => unreachable!("grammar guarantees a world item, got {rule:?}"),
        };
        let name = inner
            .next_if(|p| p.as_rule() == Rule::ident)
            .map(|p| self.ident(&p));
        let mut next_value = |this: &mut Self| {
            this.value(
                inner
                    .next()
                    .expect("grammar guarantees the obstacle's values"),
            )
        };
        let shape = match kind {
            ObstacleKind::Rect => ObstacleShape::Rect(next_value(self), next_value(self)),
            ObstacleKind::Polygon => ObstacleShape::Polygon(next_value(self)),
            ObstacleKind::Segment => ObstacleShape::Segment(next_value(self), next_value(self)),
            ObstacleKind::Disk => ObstacleShape::Disk(next_value(self), next_value(self)),
            ObstacleKind::Grid => ObstacleShape::Grid(self.grid(inner, span)),
        };
        WorldItem::Obstacle(ObstacleDecl {
            kind: Spanned::new(kind, self.span(&keyword)),
            name,
            shape,
            span,
        })
    }

    /// The rest of a `scatter` item after its keyword.
    fn scatter<'i>(&mut self, mut inner: impl Iterator<Item = P<'i>>, span: Span) -> ScatterDecl {
        let mut next = || {
            inner
                .next()
                .expect("grammar guarantees the scatter's parts")
        };
        let name = self.ident(&next());
        let count = self.value(next());
        let shape_pair = next();
        let shape_rule = shape_pair.as_rule();
        let mut parts = children(shape_pair);
        let keyword = self.span(
            &parts
                .next()
                .expect("grammar guarantees the shape's keyword"),
        );
        let mut size = || self.value(parts.next().expect("grammar guarantees the shape's sizes"));
        let shape = if shape_rule == Rule::scatter_disk {
            ScatterShape::Disk {
                keyword,
                radius: size(),
            }
        } else {
            let width = size();
            ScatterShape::Rect {
                keyword,
                width,
                height: size(),
            }
        };
        let _in = next();
        let min = self.value(next());
        let max = self.value(next());
        let gap = inner.next().map(|g| {
            self.value(
                children(g)
                    .nth(1)
                    .expect("grammar guarantees the gap's value"),
            )
        });
        ScatterDecl {
            name,
            count,
            shape,
            min,
            max,
            gap,
            span,
        }
    }

    /// The rest of a `grid` item after its name. A repeated `cell` or
    /// `origin` is an error; the first one is kept.
    fn grid<'i>(&mut self, options: impl Iterator<Item = P<'i>>, span: Span) -> GridSpec {
        let mut grid = GridSpec {
            file: None,
            cell: None,
            origin: None,
            rows: None,
            span,
        };
        let mut cell_span: Option<Span> = None;
        let mut origin_span: Option<Span> = None;
        for option in options {
            let option_span = self.span(&option);
            match option.as_rule() {
                Rule::string => grid.file = Some(self.string(&option)),
                Rule::grid_rows => {
                    grid.rows = Some(children(option).map(|row| self.string(&row)).collect());
                }
                rule @ (Rule::grid_cell | Rule::grid_origin) => {
                    let (first, slot, key) = if rule == Rule::grid_cell {
                        (&mut cell_span, &mut grid.cell, "cell")
                    } else {
                        (&mut origin_span, &mut grid.origin, "origin")
                    };
                    let value = children(option).nth(1).expect("grammar guarantees a value");
                    let value = self.value(value);
                    match *first {
                        Some(first) => self.diags.push(
                            Diag::error(
                                "scen::syntax::duplicate_option",
                                format!("`{key}` is given twice for this grid"),
                            )
                            .at(option_span, "given again here")
                            .with_related(first, "first given here")
                            .help(format!("keep one `{key}`")),
                        ),
                        None => {
                            *first = Some(option_span);
                            *slot = Some(value);
                        }
                    }
                }
                rule => unreachable!("grammar guarantees a grid option, got {rule:?}"),
            }
        }
        grid
    }

    fn robot(&mut self, pair: P<'_>) -> RobotDecl {
        // Without `steer`, pest's span runs over the blank after the shape.
        let span = self.trimmed_span(&pair);
        let mut inner = children(pair).skip(1);
        let name = self.ident(&inner.next().expect("grammar guarantees a robot name"));
        let shape_pair = inner.next().expect("grammar guarantees a robot shape");
        // Every shape rule is its kind's word, then its values.
        let shape_span = self.trimmed_span(&shape_pair);
        let mut parts = children(shape_pair);
        let kind = self.ident(&parts.next().expect("grammar guarantees a robot kind"));
        let shape = RobotShape {
            kind,
            args: parts.map(|v| self.value(v)).collect(),
            span: shape_span,
        };
        let (mut steer, mut speed): (Option<SteerClause>, Option<(Span, Value)>) = (None, None);
        let mut team = None;
        for clause in inner {
            match clause.as_rule() {
                Rule::team_from => {
                    let mut parts = children(clause);
                    let from = self.span(&parts.next().expect("grammar guarantees `from`"));
                    let file = self.string(&parts.next().expect("grammar guarantees a file"));
                    let agents = self.span(&parts.next().expect("grammar guarantees `agents`"));
                    let count = self.value(parts.next().expect("grammar guarantees a count"));
                    team = Some(Box::new(TeamBody::From {
                        from,
                        file,
                        agents,
                        count,
                    }));
                    continue;
                }
                Rule::team_agents => {
                    let block = self.span(&clause);
                    let mut agents = Vec::new();
                    for part in children(clause) {
                        if part.as_rule() != Rule::team_agent {
                            continue;
                        }
                        let span = self.span(&part);
                        let mut v = children(part);
                        let name = self.ident(&v.next().expect("grammar guarantees a name"));
                        let start = self.value(v.next().expect("grammar guarantees a start"));
                        let arrow = self.span(&v.next().expect("grammar guarantees `->`"));
                        let goal = self.value(v.next().expect("grammar guarantees a goal"));
                        agents.push(TeamAgent {
                            name,
                            start,
                            arrow,
                            goal,
                            span,
                        });
                    }
                    team = Some(Box::new(TeamBody::Agents { agents, block }));
                    continue;
                }
                _ => {}
            }
            let span = self.span(&clause);
            let rule = clause.as_rule();
            let mut parts = children(clause);
            let keyword = self.span(&parts.next().expect("grammar guarantees the keyword"));
            let (word, first) = match rule {
                Rule::steer_clause => ("steer", steer.as_ref().map(|s| s.keyword)),
                _ => ("speed", speed.as_ref().map(|(k, _)| *k)),
            };
            if let Some(first) = first {
                self.diags.push(
                    Diag::error(
                        "scen::syntax::duplicate_option",
                        format!("`{word}` is given twice for this robot"),
                    )
                    .at(span, "given again here")
                    .with_related(first, "first given here")
                    .help(format!("keep one `{word}`")),
                );
                continue;
            }
            if rule == Rule::steer_clause {
                let model = self.ident(&parts.next().expect("grammar guarantees the model"));
                let radius = self.value(parts.next().expect("grammar guarantees the radius"));
                steer = Some(SteerClause {
                    keyword,
                    model,
                    radius,
                    span,
                });
            } else {
                let value = self.value(parts.next().expect("grammar guarantees the speed"));
                speed = Some((keyword, value));
            }
        }
        RobotDecl {
            name,
            shape,
            steer,
            speed,
            team,
            span,
        }
    }

    /// `moving NAME SHAPE { at T (x, y) ... then stay|vanish }`.
    fn moving<'i>(&mut self, mut inner: impl Iterator<Item = P<'i>>, span: Span) -> MovingDecl {
        let name = self.ident(&inner.next().expect("grammar guarantees a name"));
        let shape_pair = inner.next().expect("grammar guarantees a shape");
        let shape_span = self.trimmed_span(&shape_pair);
        let mut parts = children(shape_pair);
        let kind = self.ident(
            &parts
                .next()
                .expect("grammar guarantees the shape's keyword"),
        );
        let shape = RobotShape {
            kind,
            args: parts.map(|v| self.value(v)).collect(),
            span: shape_span,
        };
        let open = inner.next().expect("grammar guarantees `{`");
        let mut waypoints = Vec::new();
        let mut then = None;
        let mut close = self.span(&open);
        for part in inner {
            match part.as_rule() {
                Rule::moving_at => {
                    let span = self.span(&part);
                    let mut v = children(part).skip(1);
                    let time = self.value(v.next().expect("grammar guarantees a time"));
                    let at = self.value(v.next().expect("grammar guarantees a point"));
                    waypoints.push(MovingWaypoint { time, at, span });
                }
                Rule::moving_then => {
                    let word = children(part)
                        .nth(1)
                        .expect("grammar guarantees `stay` or `vanish`");
                    then = Some(self.ident(&word));
                }
                _ => close = self.span(&part),
            }
        }
        let open = self.span(&open);
        MovingDecl {
            name,
            shape,
            waypoints,
            then,
            block: Span::new(open.file, open.start, close.end),
            span,
        }
    }

    fn plan(&mut self, pair: P<'_>) -> PlanDecl {
        let span = self.span(&pair);
        let mut inner = children(pair).skip(1);
        let mut next = || {
            inner
                .next()
                .expect("grammar guarantees `plan NAME KIND ROBOT { }`")
        };
        let name = self.ident(&next());
        let kind = self.ident(&next());
        let robot = self.ident(&next());
        let body = self.param_tokens(next());
        PlanDecl {
            name,
            kind,
            robot,
            body,
            span,
        }
    }

    /// The tokens of a `{ ... }` block of plan parameters.
    fn param_tokens(&mut self, block: P<'_>) -> Vec<ParamToken> {
        let mut tokens = Vec::new();
        for pair in children(block) {
            if pair.as_rule() == Rule::body_calc {
                let more = self.body_calc_tokens(pair);
                tokens.extend(more);
                continue;
            }
            tokens.push(match pair.as_rule() {
                Rule::param_block => {
                    let span = self.span(&pair);
                    ParamToken::Block {
                        tokens: self.param_tokens(pair),
                        span,
                    }
                }
                Rule::word => ParamToken::Word(self.ident(&pair)),
                Rule::plain_number | Rule::string | Rule::tuple | Rule::list => {
                    ParamToken::Value(self.value(pair))
                }
                rule => unreachable!("grammar guarantees a parameter token, got {rule:?}"),
            });
        }
        self.check_detached_units(&tokens);
        tokens
    }

    /// `90 deg` in a plan body parses as a number and a word; say what was meant.
    pub(super) fn check_detached_units(&mut self, tokens: &[ParamToken]) {
        for pair in tokens.windows(2) {
            let [ParamToken::Value(number), ParamToken::Word(unit)] = pair else {
                continue;
            };
            let between = &self.text[number.span.end..unit.span.start];
            if matches!(number.kind, ValueKind::Number(_))
                && UNIT_WORDS.contains(&unit.value.as_str())
                && between.chars().all(|c| c == ' ' || c == '\t')
            {
                let number_text = &self.text[number.span.start..number.span.end];
                self.diags.push(
                    Diag::error(
                        "scen::syntax::detached_unit",
                        format!("the unit `{}` is separated from its number", unit.value),
                    )
                    .at(number.span.to(unit.span), "a number, then a separate word")
                    .help(format!(
                        "write the unit right after the number: `{number_text}{}`",
                        unit.value
                    )),
                );
            }
        }
    }

    /// A value: a `number`, `string`, `tuple` or `list` pair, or a `word` in a
    /// container.
    pub(super) fn value(&mut self, pair: P<'_>) -> Value {
        let span = self.span(&pair);
        let kind = match pair.as_rule() {
            Rule::number | Rule::plain_number => self.quantity(pair),
            Rule::string => ValueKind::Str(self.string(&pair).value),
            Rule::word => ValueKind::Word(pair.as_str().to_string()),
            Rule::tuple => ValueKind::Tuple(children(pair).map(|p| self.value(p)).collect()),
            Rule::list => ValueKind::List(children(pair).map(|p| self.value(p)).collect()),
            // An expression in error (reported) leaves a placeholder.
            Rule::calc | Rule::body_calc => self.calc_value(pair).unwrap_or(ValueKind::Number(0.0)),
            rule => unreachable!("grammar guarantees a value, got {rule:?}"),
        };
        Value { kind, span }
    }

    /// A `number` or `expr_number` pair: a number and its unit, converted to
    /// radians, seconds or a fraction. Errors leave a `Number` placeholder.
    pub(super) fn quantity(&mut self, pair: P<'_>) -> ValueKind {
        let span = self.span(&pair);
        let token = pair.as_str();
        let (literal, unit) = split_number(token);
        let unit_span = Span::new(self.file, span.start + literal.len(), span.end);
        let unit_is_word = unit.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
            && unit.bytes().all(is_ident_byte);
        if !(unit.is_empty() || unit == "%" || unit_is_word) {
            let help = if unit.starts_with(['e', 'E']) {
                "an exponent needs digits, as in `1e-3`"
            } else {
                "write numbers as `12`, `-3.5`, `1e-3` or `.5`"
            };
            self.diags.push(
                Diag::error(
                    "scen::syntax::bad_number",
                    format!("malformed number {}", show(token)),
                )
                .at(span, "not a number")
                .help(help),
            );
            return ValueKind::Number(0.0);
        }
        let x = match literal.parse::<f64>() {
            Ok(x) if x.is_finite() => x,
            _ => {
                self.diags.push(
                    Diag::error("scen::syntax::bad_number", "number out of range")
                        .at(
                            Span::new(self.file, span.start, span.start + literal.len()),
                            "too large for a 64-bit floating-point number",
                        )
                        .help("numbers must lie within ±1.8e308"),
                );
                return ValueKind::Number(0.0);
            }
        };
        match unit {
            "" => ValueKind::Number(x),
            "deg" => ValueKind::Angle(Angle::deg(x)),
            "rad" => ValueKind::Angle(Angle::rad(x)),
            "%" => ValueKind::Percent(x / 100.0),
            "ms" => ValueKind::Duration(x / 1000.0),
            "s" => ValueKind::Duration(x),
            other => {
                let help = if other.eq_ignore_ascii_case("e") {
                    "an exponent needs digits, as in `1e-3`".to_string()
                } else if let Some(unit) = closest_keyword(other, &UNIT_WORDS) {
                    format!("did you mean `{literal}{unit}`?")
                } else {
                    UNITS_HELP.to_string()
                };
                self.diags.push(
                    Diag::error(
                        "scen::syntax::bad_unit",
                        format!("unknown unit {}", show(other)),
                    )
                    .at(unit_span, "not a unit")
                    .help(help),
                );
                ValueKind::Number(x)
            }
        }
    }

    /// A string literal without its quotes, with `\"` and `\\` unescaped.
    fn string(&mut self, pair: &P<'_>) -> Spanned<String> {
        let span = self.span(pair);
        let raw = pair.as_str();
        let body = &raw[1..raw.len() - 1];
        let mut value = String::with_capacity(body.len());
        let mut chars = body.char_indices();
        while let Some((k, c)) = chars.next() {
            if c != '\\' {
                value.push(c);
                continue;
            }
            let Some((_, escaped)) = chars.next() else {
                break;
            };
            match escaped {
                '"' | '\\' => value.push(escaped),
                other => {
                    let start = span.start + 1 + k;
                    let end = start + 1 + other.len_utf8();
                    self.diags.push(
                        Diag::error(
                            "scen::syntax::bad_escape",
                            format!("unknown escape `\\{other}` in a string"),
                        )
                        .at(Span::new(self.file, start, end), "not an escape")
                        .help("the only escapes are `\\\"` and `\\\\`; write paths with `/`"),
                    );
                    value.push('\\');
                    value.push(other);
                }
            }
        }
        Spanned::new(value, span)
    }
}

/// Splits a number token (grammar rule `number`) into its literal, as Rust's
/// `f64` parser reads it (`-`? digits, `.` digits, exponent), and the rest,
/// which should be a unit.
fn split_number(token: &str) -> (&str, &str) {
    let b = token.as_bytes();
    let digits_from = |mut i: usize| {
        while b.get(i).is_some_and(u8::is_ascii_digit) {
            i += 1;
        }
        i
    };
    let mut end = digits_from(usize::from(b.first() == Some(&b'-')));
    if b.get(end) == Some(&b'.') && b.get(end + 1).is_some_and(u8::is_ascii_digit) {
        end = digits_from(end + 1);
    }
    if matches!(b.get(end), Some(b'e' | b'E')) {
        let sign = usize::from(matches!(b.get(end + 1), Some(b'+' | b'-')));
        let exponent_end = digits_from(end + 1 + sign);
        if exponent_end > end + 1 + sign {
            end = exponent_end;
        }
    }
    token.split_at(end)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::testing::{
        APARTMENT, errors, expr, number, parse_ok, plan_body, sexp, snippet, world_items,
    };

    #[test]
    fn parses_every_construct_of_the_spec() {
        let statements = parse_ok(APARTMENT);
        assert_eq!(statements.len(), 16);
        let Stmt::Scenario { title, span } = &statements[0] else {
            panic!()
        };
        assert_eq!(title.value, "Apartment: the 8x1 rod");
        assert_eq!(
            snippet(APARTMENT, *span),
            r#"scenario "Apartment: the 8x1 rod""#
        );
        let Stmt::Include { path, .. } = &statements[1] else {
            panic!()
        };
        assert_eq!(path.value, "common.scen");
        assert_eq!(snippet(APARTMENT, path.span), r#""common.scen""#);

        let Stmt::World(world) = &statements[2] else {
            panic!()
        };
        assert_eq!(snippet(APARTMENT, world.keyword), "world");
        assert!(snippet(APARTMENT, world.span).starts_with("world {"));
        assert!(snippet(APARTMENT, world.span).ends_with('}'));
        assert_eq!(world.items.len(), 7);
        let WorldItem::Bounds { min, max, span } = &world.items[0] else {
            panic!()
        };
        assert_eq!(snippet(APARTMENT, *span), "bounds (0, 0) (32, 30)");
        assert_eq!(snippet(APARTMENT, min.span), "(0, 0)");
        let ValueKind::Tuple(xy) = &max.kind else {
            panic!()
        };
        assert_eq!((number(&xy[0]), number(&xy[1])), (32.0, 30.0));

        let names: Vec<_> = world.items[1..]
            .iter()
            .map(|item| match item {
                WorldItem::Obstacle(o) => (o.kind.value, o.name.as_ref().map(|n| n.value.clone())),
                _ => panic!(),
            })
            .collect();
        use ObstacleKind::*;
        let expected = [
            (Rect, "B1"),
            (Polygon, "P1"),
            (Segment, "W1"),
            (Disk, "C1"),
            (Grid, "G"),
            (Grid, "F"),
        ];
        assert_eq!(names, expected.map(|(k, n)| (k, Some(n.to_string()))));

        let WorldItem::Obstacle(disk) = &world.items[4] else {
            panic!()
        };
        assert_eq!(snippet(APARTMENT, disk.span), "disk    C1 (5, 5) 1.5");
        assert_eq!(snippet(APARTMENT, disk.kind.span), "disk");
        let ObstacleShape::Disk(_, radius) = &disk.shape else {
            panic!()
        };
        assert_eq!(number(radius), 1.5);
        let WorldItem::Obstacle(polygon) = &world.items[2] else {
            panic!()
        };
        let ObstacleShape::Polygon(Value {
            kind: ValueKind::List(points),
            ..
        }) = &polygon.shape
        else {
            panic!()
        };
        assert_eq!(points.len(), 3);

        let WorldItem::Obstacle(g) = &world.items[5] else {
            panic!()
        };
        assert_eq!(
            snippet(APARTMENT, g.span),
            r#"grid    G  "maps/arena.map" cell 1 origin (0, 0)"#
        );
        let WorldItem::Obstacle(g) = &world.items[5] else {
            panic!()
        };
        let ObstacleShape::Grid(g) = &g.shape else {
            panic!()
        };
        assert_eq!(
            g.file.as_ref().map(|f| f.value.as_str()),
            Some("maps/arena.map")
        );
        assert_eq!(g.cell.as_ref().map(number), Some(1.0));
        assert!(matches!(
            g.origin,
            Some(Value {
                kind: ValueKind::Tuple(_),
                ..
            })
        ));
        assert!(g.rows.is_none());
        let WorldItem::Obstacle(f) = &world.items[6] else {
            panic!()
        };
        let ObstacleShape::Grid(f) = &f.shape else {
            panic!()
        };
        assert!(f.file.is_none());
        assert_eq!(f.cell.as_ref().map(number), Some(0.5));
        let rows: Vec<_> = f
            .rows
            .as_ref()
            .unwrap()
            .iter()
            .map(|r| r.value.as_str())
            .collect();
        assert_eq!(rows, ["....##....", "..3......."]);

        let robots: Vec<_> = statements[3..7]
            .iter()
            .map(|s| match s {
                Stmt::Robot(r) => r,
                _ => panic!(),
            })
            .collect();
        assert_eq!(robots[0].name.value, "rod");
        let kinds: Vec<&str> = robots.iter().map(|r| r.shape.kind.value.as_str()).collect();
        assert_eq!(kinds, ["polygon", "rect", "disk", "point"]);
        assert!(matches!(
            robots[0].shape.args[..],
            [Value {
                kind: ValueKind::List(_),
                ..
            }]
        ));
        let [w, h] = &robots[1].shape.args[..] else {
            panic!()
        };
        assert_eq!((number(w), number(h)), (2.0, 1.0));
        let [r] = &robots[2].shape.args[..] else {
            panic!()
        };
        assert_eq!(number(r), 0.5);
        assert!(robots[3].shape.args.is_empty());
        let span = robots[3].shape.kind.span;
        assert_eq!(snippet(APARTMENT, span), "point");
        assert_eq!(snippet(APARTMENT, robots[3].shape.span), "point");
        assert_eq!(snippet(APARTMENT, robots[3].span), "robot p    point");

        let Stmt::Plan(plan) = &statements[7] else {
            panic!()
        };
        assert_eq!(
            (plan.name.value.as_str(), plan.kind.value.as_str()),
            ("offline", "astar")
        );
        assert_eq!(plan.robot.value, "rod");
        assert!(snippet(APARTMENT, plan.span).starts_with("plan offline"));
        assert!(snippet(APARTMENT, plan.span).ends_with('}'));
        let words: Vec<String> = plan
            .body
            .iter()
            .map(|t| match t {
                ParamToken::Word(w) => w.value.clone(),
                ParamToken::Value(v) => format!("<{}>", v.kind.describe()),
                ParamToken::Block { tokens, .. } => format!("{{{}}}", tokens.len()),
            })
            .collect();
        assert_eq!(
            words.join(" "),
            "start <a point> goal <a point> cell <a number> layers auto limit expansions <a number> \
             time <a duration> drive unicycle {4}"
        );

        let checks: Vec<String> = statements[8..]
            .iter()
            .map(|s| match s {
                Stmt::Expect(e) => sexp(e),
                _ => panic!(),
            })
            .collect();
        assert_eq!(
            checks,
            [
                "offline.found",
                "offline.collision_free",
                "(<= offline.cost 90)",
                "(and (< offline.expanded 6000) (>= offline.nodes 10))",
                "(not tight.found)",
                "(<= live.traveled (* 50 offline.length))",
                "(~ vg.length 27.3137 0.001)",
                "(== cover.coverage 1%)",
            ]
        );
        let Stmt::Expect(e) = &statements[14] else {
            panic!()
        };
        assert_eq!(snippet(APARTMENT, e.span), "vg.length ~ 27.3137 +- 0.001");
    }

    #[test]
    fn unnamed_obstacles_and_grid_names() {
        let items = world_items(
            "world { rect (0,0) (1,1) disk (2, 2) 0.5 polygon [(0,0),(1,0),(0,1)] segment (0,0) (1,1) }",
        );
        for item in &items {
            let WorldItem::Obstacle(o) = item else {
                panic!()
            };
            assert!(o.name.is_none(), "{o:?}");
        }
        let grid = |text: &str| match &world_items(text)[0] {
            WorldItem::Obstacle(ObstacleDecl {
                name,
                shape: ObstacleShape::Grid(g),
                ..
            }) => (name.as_ref().map(|n| n.value.clone()), g.clone()),
            other => panic!("{other:?}"),
        };
        let (name, g) = grid("world { grid cell 1 origin (0, 0) { \"..\" } }");
        assert_eq!(name, None);
        assert_eq!(g.cell.as_ref().map(number), Some(1.0));
        let (name, g) = grid("world { grid cell cell 2 }");
        assert_eq!(name.as_deref(), Some("cell"));
        assert_eq!(g.cell.as_ref().map(number), Some(2.0));
        let (name, g) = grid("world { grid \"a.map\" }");
        assert_eq!(name, None);
        assert_eq!(g.file.unwrap().value, "a.map");
        let (name, g) = grid("world { grid origin (1, 2) cell 0.5 {} }");
        assert_eq!(name, None);
        assert_eq!(g.rows, Some(vec![]));
    }

    #[test]
    fn a_repeated_grid_option_is_an_error_at_the_repetition() {
        let text = "world {\n  grid G cell 1 origin (0,0)\n  cell 2\n}";
        let diags = errors(text);
        assert_eq!(diags.len(), 1);
        assert_eq!(diags[0].code, "scen::syntax::duplicate_option");
        assert_eq!(snippet(text, diags[0].span.unwrap()), "cell 2");
        assert_eq!(snippet(text, diags[0].related[0].0), "cell 1");
    }

    #[test]
    fn plan_bodies_are_flat_token_lists() {
        let body = plan_body(
            "plan p astar r {\n  start (0, -1.5, 90deg) goal (1e-3, .5)\n  weights [1, 2, 3,] \
             names [center, corner] empty []\n  file \"a \\\"b\\\" \\\\c\"\n  drive unicycle { dt 20ms gain { x 1 } }\n  coverage 100%\n}",
        );
        let ParamToken::Value(start) = &body[1] else {
            panic!()
        };
        let ValueKind::Tuple(xs) = &start.kind else {
            panic!()
        };
        assert_eq!(number(&xs[0]), 0.0);
        assert_eq!(number(&xs[1]), -1.5);
        assert_eq!(xs[2].kind, ValueKind::Angle(Angle::deg(90.0)));
        let ParamToken::Value(goal) = &body[3] else {
            panic!()
        };
        let ValueKind::Tuple(xs) = &goal.kind else {
            panic!()
        };
        assert_eq!((number(&xs[0]), number(&xs[1])), (1e-3, 0.5));
        let ParamToken::Value(Value {
            kind: ValueKind::List(ws),
            span,
        }) = &body[5]
        else {
            panic!()
        };
        assert_eq!(ws.len(), 3);
        assert_eq!(span.len(), "[1, 2, 3,]".len());
        let ParamToken::Value(Value {
            kind: ValueKind::List(names),
            ..
        }) = &body[7]
        else {
            panic!()
        };
        assert_eq!(names[1].kind, ValueKind::Word("corner".into()));
        let ParamToken::Value(Value {
            kind: ValueKind::List(empty),
            ..
        }) = &body[9]
        else {
            panic!()
        };
        assert!(empty.is_empty());
        let ParamToken::Value(Value {
            kind: ValueKind::Str(s),
            ..
        }) = &body[11]
        else {
            panic!()
        };
        assert_eq!(s, r#"a "b" \c"#);
        let ParamToken::Block { tokens, .. } = &body[14] else {
            panic!()
        };
        assert_eq!(tokens.len(), 4);
        assert!(
            matches!(&tokens[1], ParamToken::Value(Value { kind: ValueKind::Duration(d), .. }) if (*d - 0.02).abs() < 1e-15)
        );
        assert!(matches!(&tokens[3], ParamToken::Block { tokens, .. } if tokens.len() == 2));
        let ParamToken::Value(Value {
            kind: ValueKind::Percent(p),
            ..
        }) = &body[16]
        else {
            panic!()
        };
        assert_eq!(*p, 1.0);
    }

    #[test]
    fn units_are_converted() {
        let value = |text: &str| match &plan_body(&format!("plan p k r {{ {text} }}"))[0] {
            ParamToken::Value(v) => v.kind.clone(),
            other => panic!("{other:?}"),
        };
        assert_eq!(value("180deg"), ValueKind::Angle(Angle::deg(180.0)));
        assert_eq!(value("-90deg"), ValueKind::Angle(Angle::deg(-90.0)));
        assert_eq!(value("1.5rad"), ValueKind::Angle(Angle::rad(1.5)));
        assert_eq!(value("50%"), ValueKind::Percent(0.5));
        assert_eq!(value("500ms"), ValueKind::Duration(0.5));
        assert_eq!(value("2s"), ValueKind::Duration(2.0));
        assert_eq!(value("12"), ValueKind::Number(12.0));
        assert_eq!(value("-3.5"), ValueKind::Number(-3.5));
        assert_eq!(value("1e-3"), ValueKind::Number(1e-3));
        assert_eq!(value("2E+2"), ValueKind::Number(200.0));
        assert_eq!(value(".5"), ValueKind::Number(0.5));
        assert_eq!(value("\"\""), ValueKind::Str(String::new()));
        assert_eq!(
            sexp(&expr("a.turn < 90deg")),
            format!("(< a.turn {})", std::f64::consts::FRAC_PI_2)
        );
        assert_eq!(sexp(&expr("a.coverage >= 50%")), "(>= a.coverage 0.5%)");
    }

    #[test]
    fn literal_errors() {
        let text = "robot r disk 1e999\nplan p k r { x 90degx y 1e }";
        let diags = errors(text);
        let codes: Vec<_> = diags.iter().map(|d| d.code).collect();
        assert_eq!(
            codes,
            [
                "scen::syntax::bad_number",
                "scen::syntax::bad_unit",
                "scen::syntax::bad_unit"
            ]
        );
        assert_eq!(snippet(text, diags[0].span.unwrap()), "1e999");
        assert_eq!(diags[0].message, "number out of range");
        assert_eq!(snippet(text, diags[1].span.unwrap()), "degx");
        assert_eq!(diags[1].message, "unknown unit `degx`");
        assert_eq!(
            diags[2].help.as_deref(),
            Some("an exponent needs digits, as in `1e-3`")
        );

        let text = "include \"maps\\arena.map\"";
        let diags = errors(text);
        assert_eq!(diags[0].code, "scen::syntax::bad_escape");
        assert_eq!(snippet(text, diags[0].span.unwrap()), "\\a");

        let diags = errors("expect a.time_ms < 2s");
        assert_eq!(diags[0].code, "scen::syntax::unit_not_allowed");
        assert!(diags[0].help.as_deref().unwrap().contains("`2000`"));
    }

    #[test]
    fn malformed_numbers_are_one_bad_token() {
        for (text, token) in [
            ("1.2.3", "1.2.3"),
            ("5-3", "5-3"),
            ("1e-", "1e-"),
            ("2.", "2."),
        ] {
            let source = format!("plan p k r {{ x {text} }}");
            let diags = errors(&source);
            assert_eq!(diags.len(), 1, "{text}: {diags:#?}");
            assert_eq!(diags[0].code, "scen::syntax::bad_number", "{text}");
            assert_eq!(snippet(&source, diags[0].span.unwrap()), token);
        }
        // In an expression `-` is an operator, and `e-3` an exponent.
        assert_eq!(sexp(&expr("a.x < 5-3")), "(< a.x (- 5 3))");
        assert_eq!(sexp(&expr("a.x < 2e-3-1")), "(< a.x (- 0.002 1))");
    }
}

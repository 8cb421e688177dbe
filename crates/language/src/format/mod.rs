//! `scen fmt`: a file in the canonical layout of SPEC §4 — two-space
//! indentation, one statement, world item and plan parameter per line, one
//! space around operators, nothing aligned — with every comment kept.
//!
//! The layout is computed from the AST (the one parser of `src/syntax/`)
//! and the comments the scanner found; every token is printed as it was
//! written (`.5`, `90deg`, `"a\"b"` stay so), so only blanks, newlines and
//! the parentheses that a double pair made redundant change. Lists and
//! `expect` expressions that do not fit in [`WIDTH`] columns break, a list
//! one element per line and an expression before its loosest operators.
//!
//! Comments are placed by position: each is printed before the first token
//! that followed it in the source, at the end of the previous token's line
//! when it was there (a trailing comment), else on a line of its own. Where
//! a comment ends a line that was to go on (inside a list, between a key
//! and its value), the line breaks after it. A single blank line between
//! statements, world items or parameters is kept.
//!
//! Formatting refuses a file with syntax errors, and checks its own output:
//! it must parse to the same AST with the same comments (see
//! [`format_text`]).

mod doc;

use crate::contract::schema::ValueSpec;
use crate::diagnostics::{Diag, Span};
use crate::scenario::grouping::{ParamKeys, group_bench, group_params};
use crate::syntax::ast::{
    self, Expr, ExprKind, ObstacleShape, ParamSource, ParamToken, ScatterShape, Stmt, TeamBody,
    Value, ValueKind, WorldItem,
};
use crate::syntax::{Lexer, TokenKind, UNIT_WORDS};

use doc::Doc;

/// The width in columns that lists and expressions are broken to fit.
pub const WIDTH: usize = 100;

/// Why a text could not be formatted.
#[derive(Debug)]
pub enum FormatError {
    /// The text has syntax errors (the parser's diagnostics).
    Syntax(Vec<Diag>),
    /// The formatter's output would not parse to the same scenario: a bug
    /// in the formatter, reported rather than written.
    Changed(String),
}

/// The text in the canonical layout. `Err` when the text has syntax errors,
/// or (a bug) when the layout would change the parse or lose a comment.
pub fn format_text(text: &str) -> Result<String, FormatError> {
    let (file, diags) = crate::syntax::parse(text, 0);
    if diags.iter().any(Diag::is_error) {
        return Err(FormatError::Syntax(diags));
    }
    let formatted = layout(text, &file);
    let (again, diags) = crate::syntax::parse(&formatted, 0);
    if diags.iter().any(Diag::is_error) {
        return Err(FormatError::Changed(format!(
            "the formatted text does not parse: {}",
            diags[0].message
        )));
    }
    if shape(&file.statements) != shape(&again.statements) {
        return Err(FormatError::Changed(
            "the formatted text parses to a different scenario".into(),
        ));
    }
    let comments = |t: &str, f: &ast::File| -> Vec<String> {
        f.comments.iter().map(|c| comment_text(t, *c)).collect()
    };
    if comments(text, &file) != comments(&formatted, &again) {
        return Err(FormatError::Changed(
            "the formatted text lost or reordered a comment".into(),
        ));
    }
    Ok(formatted)
}

/// The statements without their spans: what the parse means, for
/// comparing two layouts of one file.
pub fn shape(statements: &[Stmt]) -> String {
    let debug = format!("{statements:?}");
    let mut out = String::with_capacity(debug.len());
    let mut rest = debug.as_str();
    while let Some(k) = rest.find("Span {") {
        out.push_str(&rest[..k]);
        rest = &rest[k..];
        rest = rest.find('}').map_or("", |end| &rest[end + 1..]);
    }
    out.push_str(rest);
    out
}

/// A comment as printed: its text without trailing blanks (a CRLF file's `\r`).
fn comment_text(text: &str, span: Span) -> String {
    text[span.start..span.end].trim_end().to_string()
}

/// The canonical layout of a parsed file.
fn layout(text: &str, file: &ast::File) -> String {
    let mut w = Writer {
        text,
        comments: &file.comments,
        next_comment: 0,
        last_end: 0,
        emitted: false,
        pending: Sep::None,
        forced: false,
    };
    let mut docs = Vec::new();
    for stmt in &file.statements {
        w.pending = Sep::Hard { blank: true };
        w.statement(&mut docs, stmt);
    }
    w.pending = Sep::Hard { blank: true };
    w.comments_before(&mut docs, usize::MAX);
    let mut out = doc::print(&docs, WIDTH);
    let kept = out.trim_end().len();
    out.truncate(kept);
    if !out.is_empty() {
        out.push('\n');
    }
    out
}

/// What separates the next token from the previous one.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Sep {
    /// Nothing: `(` and its first element, a value and its `,`.
    None,
    /// A space that never breaks (`rect B1 (0, 0)`).
    Space,
    /// A space, or a newline when the group breaks.
    Line,
    /// Nothing, or a newline when the group breaks.
    Soft,
    /// A newline; `blank` keeps one empty line where the source had one.
    Hard { blank: bool },
}

/// Builds the document of a file, token by token, placing comments and
/// separators (see the module docs).
struct Writer<'t> {
    text: &'t str,
    comments: &'t [Span],
    next_comment: usize,
    /// The source offset just past the last token or comment printed.
    last_end: usize,
    emitted: bool,
    /// The separator before the next token.
    pending: Sep,
    /// A comment was printed: the next token starts a new line.
    forced: bool,
}

impl Writer<'_> {
    fn src(&self, span: Span) -> &str {
        &self.text[span.start..span.end]
    }

    fn has_comment_before(&self, pos: usize) -> bool {
        self.comments
            .get(self.next_comment)
            .is_some_and(|c| c.start < pos)
    }

    /// A newline in place of the pending separator: a continuation line for
    /// a separator that never breaks, an empty line kept where one was.
    fn push_break(&self, out: &mut Vec<Doc>, next: usize) {
        match self.pending {
            Sep::None | Sep::Space => out.push(Doc::Indent(vec![Doc::HardLine])),
            Sep::Hard { blank: true } if self.blank_before(next) => out.push(Doc::BlankLine),
            _ => out.push(Doc::HardLine),
        }
    }

    /// Whether the source has an empty line between the last token printed
    /// and `next`.
    fn blank_before(&self, next: usize) -> bool {
        let gap = self.text.get(self.last_end..next).unwrap_or("");
        gap.matches('\n').count() >= 2
    }

    /// Prints the comments that start before `pos`.
    fn comments_before(&mut self, out: &mut Vec<Doc>, pos: usize) {
        while let Some(&c) = self.comments.get(self.next_comment) {
            if c.start >= pos {
                break;
            }
            self.next_comment += 1;
            let trailing = self.emitted
                && !self
                    .text
                    .get(self.last_end..c.start)
                    .unwrap_or("")
                    .contains('\n');
            if trailing {
                out.push(Doc::Text(" ".into()));
            } else if self.emitted {
                self.push_break(out, c.start);
            }
            out.push(Doc::Text(comment_text(self.text, c)));
            self.last_end = c.end;
            self.emitted = true;
            self.forced = true;
        }
    }

    /// Prints `token`, which stood at `pos` in the source (the comments
    /// before `pos` come first).
    fn tok(&mut self, out: &mut Vec<Doc>, pos: usize, token: &str) {
        self.comments_before(out, pos);
        if self.forced {
            self.push_break(out, pos);
            self.forced = false;
        } else if self.emitted {
            match self.pending {
                Sep::None => {}
                Sep::Space => out.push(Doc::Text(" ".into())),
                Sep::Line => out.push(Doc::Line),
                Sep::Soft => out.push(Doc::SoftLine),
                Sep::Hard { .. } => self.push_break(out, pos),
            }
        }
        out.push(Doc::Text(token.to_string()));
        self.pending = Sep::None;
        self.last_end = self.last_end.max(pos);
        self.emitted = true;
    }

    /// Prints the source text of `span` as one token.
    fn leaf(&mut self, out: &mut Vec<Doc>, span: Span) {
        let token = self.src(span).to_string();
        self.tok(out, span.start, &token);
        self.last_end = span.end;
    }

    fn space(&mut self) {
        self.pending = Sep::Space;
    }

    /// The separator before the `k`-th line of a block: no empty line
    /// right after the `{`.
    fn line(&mut self, k: usize) {
        self.pending = Sep::Hard { blank: k > 0 };
    }

    /// Where the first token of `kind` at or after `from` starts (`from`
    /// starts or ends a token); the end of the text if none.
    fn find_token(&self, from: usize, wanted: impl Fn(&str) -> bool) -> usize {
        Lexer::starting_at(self.text, from)
            .find(|t| t.kind != TokenKind::Comment && wanted(&self.text[t.start..t.end]))
            .map_or(self.text.len(), |t| t.start)
    }

    // ------------------------------------------------------------ statements

    /// One statement. A new statement kind is one more arm here, built from
    /// the helpers below (`leaf`, `value`, `block`, `expr`).
    fn statement(&mut self, out: &mut Vec<Doc>, stmt: &Stmt) {
        match stmt {
            Stmt::Scenario { title, span } => {
                self.tok(out, span.start, "scenario");
                self.space();
                self.leaf(out, title.span);
            }
            Stmt::Include { path, span } => {
                self.tok(out, span.start, "include");
                self.space();
                self.leaf(out, path.span);
            }
            Stmt::World(world) => {
                self.tok(out, world.keyword.start, "world");
                self.space();
                let open = self.find_token(world.keyword.end, |t| t == "{");
                self.block(out, open, world.span.end - 1, |w, inner| {
                    for (k, item) in world.items.iter().enumerate() {
                        w.line(k);
                        w.world_item(inner, item);
                    }
                    !world.items.is_empty()
                });
            }
            Stmt::Robot(robot) => {
                let keyword = if robot.team.is_some() {
                    "team"
                } else {
                    "robot"
                };
                self.tok(out, robot.span.start, keyword);
                self.space();
                self.leaf(out, robot.name.span);
                self.space();
                self.leaf(out, robot.shape.kind.span);
                let args: Vec<&Value> = robot.shape.args.iter().collect();
                self.values(out, &args);
                // The clauses in the order written.
                let steer_at = robot.steer.as_ref().map(|s| s.keyword.start);
                let speed_at = robot.speed.as_ref().map(|(k, _)| k.start);
                let speed_first = match (steer_at, speed_at) {
                    (Some(a), Some(b)) => b < a,
                    _ => true,
                };
                let print_speed = |w: &mut Self, out: &mut Vec<Doc>| {
                    if let Some((keyword, value)) = &robot.speed {
                        w.space();
                        w.leaf(out, *keyword);
                        w.values(out, &[value]);
                    }
                };
                if speed_first {
                    print_speed(self, out);
                }
                if let Some(steer) = &robot.steer {
                    self.space();
                    self.leaf(out, steer.keyword);
                    self.space();
                    self.leaf(out, steer.model.span);
                    self.values(out, &[&steer.radius]);
                }
                if !speed_first {
                    print_speed(self, out);
                }
                match robot.team.as_deref() {
                    Some(TeamBody::Agents { agents, block }) => {
                        self.space();
                        self.block(out, block.start, block.end - 1, |w, inner| {
                            for (k, a) in agents.iter().enumerate() {
                                w.line(k);
                                w.leaf(inner, a.name.span);
                                w.values(inner, &[&a.start]);
                                w.space();
                                w.tok(inner, a.arrow.start, "->");
                                w.values(inner, &[&a.goal]);
                            }
                            !agents.is_empty()
                        });
                    }
                    Some(TeamBody::From {
                        from,
                        file,
                        agents,
                        count,
                    }) => {
                        self.space();
                        self.leaf(out, *from);
                        self.space();
                        self.leaf(out, file.span);
                        self.space();
                        self.leaf(out, *agents);
                        self.values(out, &[count]);
                    }
                    None => {}
                }
            }
            Stmt::Plan(plan) => {
                self.tok(out, plan.span.start, "plan");
                for name in [&plan.name, &plan.kind, &plan.robot] {
                    self.space();
                    self.leaf(out, name.span);
                }
                self.space();
                let keys = ParamKeys::Plan(&plan.kind.value);
                let open = self.find_token(plan.robot.span.end, |t| t == "{");
                self.params(out, open, plan.span.end - 1, &plan.body, keys);
            }
            Stmt::Bench(bench) => {
                self.tok(out, bench.span.start, "bench");
                self.space();
                self.leaf(out, bench.name.span);
                self.space();
                let open = self.find_token(bench.name.span.end, |t| t == "{");
                self.block(out, open, bench.span.end - 1, |w, inner| {
                    for (k, group) in group_bench(&bench.body).into_iter().enumerate() {
                        w.line(k);
                        for (k, token) in bench.body[group].iter().enumerate() {
                            if k > 0 {
                                w.space();
                            }
                            match token {
                                ParamToken::Word(word) => w.leaf(inner, word.span),
                                ParamToken::Value(value) => w.value(inner, value),
                                ParamToken::Block { tokens, span } => w.params(
                                    inner,
                                    span.start,
                                    span.end - 1,
                                    tokens,
                                    ParamKeys::Drive,
                                ),
                            }
                        }
                    }
                    !bench.body.is_empty()
                });
            }
            Stmt::Expect(expr) => {
                let keyword = self.find_token(self.last_end, |t| t == "expect");
                self.tok(out, keyword.min(expr.span.start), "expect");
                self.space();
                self.expr(out, expr);
            }
            Stmt::Require { condition, span } => {
                self.tok(out, span.start, "require");
                self.space();
                self.expr(out, condition);
            }
            Stmt::Param(param) => {
                self.tok(out, param.span.start, "param");
                self.space();
                self.leaf(out, param.name.span);
                self.space();
                let equals = self.find_token(param.name.span.end, |t| t == "=");
                self.tok(out, equals, "=");
                match &param.value {
                    ParamSource::Choice { keyword, values } => {
                        self.space();
                        self.leaf(out, *keyword);
                        self.values(out, &[values]);
                    }
                    ParamSource::Value(v) => self.values(out, &[v]),
                }
            }
        }
    }

    /// `{ ... }` from `open` to `close` (source offsets of the braces): its
    /// contents on indented lines, or `{}` when `contents` printed nothing
    /// and no comment is inside.
    fn block(
        &mut self,
        out: &mut Vec<Doc>,
        open: usize,
        close: usize,
        contents: impl FnOnce(&mut Self, &mut Vec<Doc>) -> bool,
    ) {
        self.tok(out, open, "{");
        let mut inner = Vec::new();
        let printed = contents(self, &mut inner);
        if !printed && !self.has_comment_before(close) {
            self.tok(out, close, "}");
            return;
        }
        self.pending = Sep::Hard { blank: true };
        self.comments_before(&mut inner, close);
        out.push(Doc::Indent(inner));
        self.pending = Sep::Hard { blank: false };
        self.tok(out, close, "}");
    }

    fn world_item(&mut self, out: &mut Vec<Doc>, item: &WorldItem) {
        let o = match item {
            WorldItem::Bounds { min, max, span } => {
                self.tok(out, span.start, "bounds");
                self.values(out, &[min, max]);
                return;
            }
            WorldItem::Obstacle(o) => o,
            WorldItem::Moving(m) => {
                self.tok(out, m.span.start, "moving");
                self.space();
                self.leaf(out, m.name.span);
                self.space();
                self.leaf(out, m.shape.kind.span);
                let args: Vec<&Value> = m.shape.args.iter().collect();
                self.values(out, &args);
                self.space();
                self.block(out, m.block.start, m.block.end - 1, |w, inner| {
                    for (k, wp) in m.waypoints.iter().enumerate() {
                        w.line(k);
                        w.tok(inner, wp.span.start, "at");
                        w.values(inner, &[&wp.time, &wp.at]);
                    }
                    if let Some(then) = &m.then {
                        w.line(m.waypoints.len());
                        let at = w.find_token(w.last_end, |t| t == "then");
                        w.tok(inner, at, "then");
                        w.space();
                        w.leaf(inner, then.span);
                    }
                    !m.waypoints.is_empty() || m.then.is_some()
                });
                return;
            }
            WorldItem::Scatter(s) => {
                self.tok(out, s.span.start, "scatter");
                self.space();
                self.leaf(out, s.name.span);
                self.values(out, &[&s.count]);
                self.space();
                match &s.shape {
                    ScatterShape::Disk { keyword, radius } => {
                        self.leaf(out, *keyword);
                        self.values(out, &[radius]);
                    }
                    ScatterShape::Rect {
                        keyword,
                        width,
                        height,
                    } => {
                        self.leaf(out, *keyword);
                        self.values(out, &[width, height]);
                    }
                }
                self.space();
                let at = self.find_token(self.last_end, |t| t == "in");
                self.tok(out, at, "in");
                self.values(out, &[&s.min, &s.max]);
                if let Some(gap) = &s.gap {
                    self.space();
                    let at = self.find_token(s.max.span.end, |t| t == "gap");
                    self.tok(out, at, "gap");
                    self.values(out, &[gap]);
                }
                return;
            }
        };
        self.leaf(out, o.kind.span);
        if let Some(name) = &o.name {
            self.space();
            self.leaf(out, name.span);
        }
        match &o.shape {
            ObstacleShape::Rect(a, b)
            | ObstacleShape::Segment(a, b)
            | ObstacleShape::Disk(a, b) => self.values(out, &[a, b]),
            ObstacleShape::Polygon(v) => self.values(out, &[v]),
            ObstacleShape::Grid(g) => {
                if let Some(file) = &g.file {
                    self.space();
                    self.leaf(out, file.span);
                }
                let mut options: Vec<(&str, &Value)> = [("cell", &g.cell), ("origin", &g.origin)]
                    .into_iter()
                    .filter_map(|(k, v)| Some((k, v.as_ref()?)))
                    .collect();
                options.sort_by_key(|(_, v)| v.span.start);
                for (key, value) in options {
                    self.space();
                    self.tok(out, value.span.start, key);
                    self.values(out, &[value]);
                }
                if let Some(rows) = &g.rows {
                    self.space();
                    let open = self.find_token(self.last_end, |t| t == "{");
                    self.block(out, open, g.span.end - 1, |w, inner| {
                        for (k, row) in rows.iter().enumerate() {
                            w.line(k);
                            w.leaf(inner, row.span);
                        }
                        !rows.is_empty()
                    });
                }
            }
        }
    }

    /// A plan's body or a nested block: one parameter per line.
    fn params(
        &mut self,
        out: &mut Vec<Doc>,
        open: usize,
        close: usize,
        tokens: &[ParamToken],
        keys: ParamKeys<'_>,
    ) {
        self.block(out, open, close, |w, inner| {
            for (k, group) in group_params(tokens, keys).into_iter().enumerate() {
                w.line(k);
                let nested = match group.spec.map(|s| s.value) {
                    Some(ValueSpec::Drive) => keys.nested(),
                    _ => keys,
                };
                let first = group.tokens.start;
                for (k, token) in tokens[group.tokens.clone()].iter().enumerate() {
                    if k > 0 {
                        w.space();
                        // `1` then `s` on one line would read as `1 s`, a
                        // unit apart from its number: keep them apart.
                        if let (ParamToken::Value(number), ParamToken::Word(unit)) =
                            (&tokens[first + k - 1], token)
                            && matches!(number.kind, ValueKind::Number(_))
                            && UNIT_WORDS.contains(&unit.value.as_str())
                        {
                            w.forced = true;
                        }
                    }
                    match token {
                        ParamToken::Word(word) => w.leaf(inner, word.span),
                        ParamToken::Value(value) => w.value(inner, value),
                        ParamToken::Block { tokens, span } => {
                            w.params(inner, span.start, span.end - 1, tokens, nested)
                        }
                    }
                }
            }
            !tokens.is_empty()
        });
    }

    // ---------------------------------------------------------------- values

    /// Values after a keyword, each after a space.
    fn values(&mut self, out: &mut Vec<Doc>, values: &[&Value]) {
        for value in values {
            self.space();
            self.value(out, value);
        }
    }

    fn value(&mut self, out: &mut Vec<Doc>, value: &Value) {
        match &value.kind {
            ValueKind::Tuple(items) => self.list(out, value.span, "(", items, ")", false),
            ValueKind::List(items) => self.list(out, value.span, "[", items, "]", true),
            ValueKind::Calc { expr, unit: None } => self.expr(out, expr),
            ValueKind::Calc {
                expr,
                unit: Some(_),
            } => {
                // `(EXPR)deg`: the unit is glued to the `)`.
                let close = value.span.end - "deg".len() - 1;
                self.tok(out, value.span.start, "(");
                let mut group = Vec::new();
                self.expr_inside(&mut group, expr);
                self.tok(&mut group, close, ")");
                out.push(Doc::Group(group));
                let unit = Span::new(value.span.file, close + 1, value.span.end);
                self.leaf(out, unit);
            }
            _ => self.leaf(out, value.span),
        }
    }

    /// `(a, b)` or `[a, b]`: on one line, or one element per line (a list
    /// then with a trailing comma; a tuple's grammar has none).
    fn list(
        &mut self,
        out: &mut Vec<Doc>,
        span: Span,
        open: &str,
        items: &[Value],
        close: &str,
        trailing_comma: bool,
    ) {
        let close_at = span.end - 1;
        self.tok(out, span.start, open);
        if items.is_empty() && !self.has_comment_before(close_at) {
            self.tok(out, close_at, close);
            return;
        }
        let mut inner = Vec::new();
        self.pending = Sep::Soft;
        for (k, item) in items.iter().enumerate() {
            if k > 0 {
                self.tok(&mut inner, items[k - 1].span.end, ",");
                self.pending = Sep::Line;
            }
            self.value(&mut inner, item);
        }
        if trailing_comma && !items.is_empty() {
            inner.push(Doc::IfBreak(","));
        }
        self.pending = Sep::Soft;
        self.comments_before(&mut inner, close_at);
        let mut group = vec![Doc::Indent(inner)];
        self.pending = Sep::Soft;
        self.tok(&mut group, close_at, close);
        out.push(Doc::Group(group));
    }

    // ----------------------------------------------------------- expressions

    /// Whether `e` was written in parentheses (the AST keeps their span
    /// only: a parenthesised node's span starts before its first child's).
    fn parenthesized(&self, e: &Expr) -> bool {
        match &e.kind {
            ExprKind::Arith { lhs, .. }
            | ExprKind::Compare { lhs, .. }
            | ExprKind::Approx { lhs, .. }
            | ExprKind::And(lhs, _)
            | ExprKind::Or(lhs, _)
            | ExprKind::Where(lhs, _) => e.span.start < lhs.span.start,
            _ => self.text[e.span.start..].starts_with('('),
        }
    }

    fn expr(&mut self, out: &mut Vec<Doc>, e: &Expr) {
        if !self.parenthesized(e) {
            return self.expr_inside(out, e);
        }
        self.tok(out, e.span.start, "(");
        let mut group = Vec::new();
        self.expr_inside(&mut group, e);
        self.tok(&mut group, e.span.end - 1, ")");
        out.push(Doc::Group(group));
    }

    /// An expression without its own parentheses.
    fn expr_inside(&mut self, out: &mut Vec<Doc>, e: &Expr) {
        match &e.kind {
            ExprKind::Number(_) | ExprKind::Percent(_) | ExprKind::Bool(_) | ExprKind::Name(_) => {
                let span = self.token_in(e.span);
                self.leaf(out, span);
            }
            ExprKind::Metric { plan, metric } => self.leaf(out, plan.span.to(metric.span)),
            ExprKind::Series {
                bench,
                plan,
                select,
                metric,
            } => {
                // `BENCH.PLAN[KEY = VALUE, ...].METRIC`: the names, the
                // brackets and the dot touch (the grammar allows no blanks
                // there), the selection is laid out like a list.
                self.leaf(out, bench.span.to(plan.span));
                if self.text[plan.span.end..].starts_with('[') {
                    let close = metric.span.start - 2;
                    self.tok(out, plan.span.end, "[");
                    for (k, selection) in select.iter().enumerate() {
                        if k > 0 {
                            self.tok(out, select[k - 1].value.span.end, ",");
                            self.space();
                        }
                        self.leaf(out, selection.key.span);
                        self.space();
                        let equals = self.find_token(selection.key.span.end, |t| t == "=");
                        self.tok(out, equals, "=");
                        self.space();
                        self.value(out, &selection.value);
                    }
                    self.tok(out, close, "]");
                }
                self.tok(out, metric.span.start - 1, ".");
                self.leaf(out, metric.span);
            }
            ExprKind::Call { function, args } => {
                self.leaf(out, function.span);
                self.tok(out, function.span.end, "(");
                let mut inner = Vec::new();
                self.pending = Sep::Soft;
                for (k, arg) in args.iter().enumerate() {
                    if k > 0 {
                        self.tok(&mut inner, args[k - 1].span.end, ",");
                        self.pending = Sep::Line;
                    }
                    self.expr(&mut inner, arg);
                }
                let close = self.find_token(self.last_end, |t| t == ")");
                self.pending = Sep::Soft;
                self.comments_before(&mut inner, close);
                let mut group = vec![Doc::Indent(inner)];
                self.pending = Sep::Soft;
                self.tok(&mut group, close, ")");
                out.push(Doc::Group(group));
            }
            ExprKind::Neg(operand) => {
                self.tok(out, e.span.start, "-");
                self.expr(out, operand);
            }
            ExprKind::Not(operand) => {
                let at = self.text[e.span.start..].find("not").unwrap_or(0);
                self.tok(out, e.span.start + at, "not");
                self.space();
                self.expr(out, operand);
            }
            ExprKind::Approx { lhs, rhs, tol } => {
                let operands = [(None, &**lhs), (Some("~"), &**rhs), (Some("+-"), &**tol)];
                self.chain(out, &operands);
            }
            _ => {
                let mut operands = Vec::new();
                self.flatten(e, &mut operands);
                self.chain(out, &operands);
            }
        }
    }

    /// The operands of a chain of operators of one precedence (`a + b - c`,
    /// `a and b and c`), each with the operator before it.
    fn flatten<'e>(&self, e: &'e Expr, operands: &mut Vec<(Option<&'static str>, &'e Expr)>) {
        let (op, lhs, rhs) = match &e.kind {
            ExprKind::Arith { op, lhs, rhs } => (op.symbol(), lhs, rhs),
            ExprKind::Compare { op, lhs, rhs } => (op.symbol(), lhs, rhs),
            ExprKind::And(lhs, rhs) => ("and", lhs, rhs),
            ExprKind::Or(lhs, rhs) => ("or", lhs, rhs),
            ExprKind::Where(lhs, rhs) => ("where", lhs, rhs),
            _ => {
                operands.push((None, e));
                return;
            }
        };
        let same_level = precedence(&lhs.kind) == precedence(&e.kind)
            && !matches!(lhs.kind, ExprKind::Compare { .. })
            && !self.parenthesized(lhs);
        if same_level {
            self.flatten(lhs, operands);
        } else {
            operands.push((None, lhs));
        }
        operands.push((Some(op), rhs));
    }

    /// `a OP b OP c` on one line, or broken before each operator.
    fn chain(&mut self, out: &mut Vec<Doc>, operands: &[(Option<&'static str>, &Expr)]) {
        let mut group = Vec::new();
        let mut rest = Vec::new();
        for (op, operand) in operands {
            match op {
                None => self.expr(&mut group, operand),
                Some(op) => {
                    self.pending = Sep::Line;
                    // Comments between the operands come before the operator.
                    self.tok(&mut rest, operand.span.start, op);
                    self.space();
                    self.expr(&mut rest, operand);
                }
            }
        }
        group.push(Doc::Indent(rest));
        out.push(Doc::Group(group));
    }

    /// The span of the number or word token that a parenthesised leaf
    /// `((3))` holds (the AST keeps the parentheses' span).
    fn token_in(&self, span: Span) -> Span {
        let text = &self.text[span.start..span.end];
        let mut start = 0;
        let bytes = text.as_bytes();
        while start < bytes.len() {
            match bytes[start] {
                b'(' | b' ' | b'\t' | b'\r' | b'\n' | 0x0B | 0x0C => start += 1,
                b'#' => start = text[start..].find('\n').map_or(bytes.len(), |k| start + k),
                _ => break,
            }
        }
        let len = text[start..]
            .find(|c: char| c.is_whitespace() || c == ')' || c == '#')
            .unwrap_or(text.len() - start);
        Span::new(span.file, span.start + start, span.start + start + len)
    }
}

/// The binding level of an operator node (higher binds tighter); leaves 0.
fn precedence(kind: &ExprKind) -> u8 {
    match kind {
        ExprKind::Where(..) => 1,
        ExprKind::Or(..) => 2,
        ExprKind::And(..) => 3,
        ExprKind::Compare { .. } | ExprKind::Approx { .. } => 4,
        ExprKind::Arith { op, .. } => match op {
            ast::ArithOp::Add | ast::ArithOp::Sub => 5,
            ast::ArithOp::Mul | ast::ArithOp::Div => 6,
        },
        _ => 0,
    }
}

#[cfg(test)]
mod tests;

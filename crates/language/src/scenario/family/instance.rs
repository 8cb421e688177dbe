//! A sample's statements written out: every expression replaced by its
//! number, every param's name in a plan or bench body by its value.

#![allow(clippy::result_large_err)]

use std::collections::{HashMap, HashSet};

use crate::diagnostics::{Diag, Span};
use crate::syntax::ast::{
    Angle, BenchDecl, Expr, ExprKind, ObstacleShape, ParamToken, PlanDecl, Stmt, Value, ValueKind,
    WorldItem,
};

use crate::scenario::placed::Placements;
use crate::scenario::statements::SourcedStmt;

use super::*;

/// Writes one instance.
pub(super) struct Ctx<'a> {
    pub(super) family: &'a Family,
    pub(super) draw: &'a mut Draw,
    pub(super) diags: &'a mut Vec<Diag>,
}

impl Ctx<'_> {
    pub(super) fn eval(&mut self, e: &Expr) -> Option<f64> {
        match eval_drawing(e, &self.draw.values, &self.family.index, &mut self.draw.rng) {
            Ok(x) => Some(x),
            Err(err) => {
                self.diags.push(err.diag(self.family, &self.draw.values));
                None
            }
        }
    }

    pub(super) fn value(&mut self, v: &mut Value) {
        match &mut v.kind {
            ValueKind::Calc { expr, unit } => {
                let unit = *unit;
                let Some(x) = self.eval(expr) else { return };
                v.kind = match unit {
                    Some(unit) => ValueKind::Angle(Angle { written: x, unit }),
                    None => ValueKind::Number(x),
                };
            }
            ValueKind::Word(w) => {
                if let Some(&k) = self.family.index.get(w.as_str()) {
                    v.kind = ValueKind::Number(self.draw.values[k]);
                }
            }
            ValueKind::Tuple(items) | ValueKind::List(items) => {
                for item in items {
                    self.value(item);
                }
            }
            _ => {}
        }
    }

    pub(super) fn tokens(&mut self, tokens: &mut [ParamToken]) {
        for t in tokens {
            match t {
                ParamToken::Word(w) => {
                    if let Some(&k) = self.family.index.get(&w.value) {
                        *t = ParamToken::Value(Value {
                            kind: ValueKind::Number(self.draw.values[k]),
                            span: w.span,
                        });
                    }
                }
                ParamToken::Value(v) => self.value(v),
                ParamToken::Block { tokens, .. } => self.tokens(tokens),
            }
        }
    }

    pub(super) fn expr(&mut self, e: &mut Expr) {
        if let ExprKind::Name(name) = &e.kind {
            if let Some(&k) = self.family.index.get(&name.value) {
                e.kind = ExprKind::Number(self.draw.values[k]);
            }
            return;
        }
        match &mut e.kind {
            ExprKind::Series { select, .. } => {
                for s in select {
                    self.value(&mut s.value);
                }
            }
            ExprKind::Call { args, .. } => args.iter_mut().for_each(|a| self.expr(a)),
            ExprKind::Neg(x) | ExprKind::Not(x) => self.expr(x),
            ExprKind::Where(a, b)
            | ExprKind::And(a, b)
            | ExprKind::Or(a, b)
            | ExprKind::Arith { lhs: a, rhs: b, .. }
            | ExprKind::Compare { lhs: a, rhs: b, .. } => {
                self.expr(a);
                self.expr(b);
            }
            ExprKind::Approx { lhs, rhs, tol } => {
                self.expr(lhs);
                self.expr(rhs);
                self.expr(tol);
            }
            _ => {}
        }
    }

    pub(super) fn item(&mut self, item: &mut WorldItem) {
        match item {
            WorldItem::Bounds { min, max, .. } => {
                self.value(min);
                self.value(max);
            }
            WorldItem::Obstacle(o) => match &mut o.shape {
                ObstacleShape::Rect(a, b)
                | ObstacleShape::Segment(a, b)
                | ObstacleShape::Disk(a, b) => {
                    self.value(a);
                    self.value(b);
                }
                ObstacleShape::Polygon(v) => self.value(v),
                ObstacleShape::Grid(g) => {
                    if let Some(v) = &mut g.cell {
                        self.value(v);
                    }
                    if let Some(v) = &mut g.origin {
                        self.value(v);
                    }
                }
            },
            WorldItem::Moving(m) => {
                for v in &mut m.shape.args {
                    self.value(v);
                }
                for w in &mut m.waypoints {
                    self.value(&mut w.time);
                    self.value(&mut w.at);
                }
            }
            WorldItem::Scatter(_) => unreachable!("scatters are placed by `scatter`"),
        }
    }
}

pub(super) fn number_value(x: f64, span: Span) -> Value {
    Value {
        kind: ValueKind::Number(x),
        span,
    }
}

pub(super) fn point_value(x: f64, y: f64, span: Span) -> Value {
    Value {
        kind: ValueKind::Tuple(vec![number_value(x, span), number_value(y, span)]),
        span,
    }
}

/// The spans of everything a sample computes: expressions, params' names
/// in bodies, lists and expectations. A standalone file of a sample writes
/// each one's number in its place.
pub fn computed_spans(
    statements: &[SourcedStmt],
    params: &HashMap<String, usize>,
) -> HashSet<Span> {
    fn value(v: &Value, params: &HashMap<String, usize>, out: &mut HashSet<Span>) {
        match &v.kind {
            ValueKind::Calc { .. } => {
                out.insert(v.span);
            }
            ValueKind::Word(w) if params.contains_key(w) => {
                out.insert(v.span);
            }
            ValueKind::Tuple(items) | ValueKind::List(items) => {
                items.iter().for_each(|i| value(i, params, out));
            }
            _ => {}
        }
    }
    let mut out = HashSet::new();
    for s in statements {
        // A param's own value is not written out; the statement goes.
        if matches!(s.stmt, Stmt::Param(_)) {
            continue;
        }
        s.stmt.each_value(&mut |v, _| value(v, params, &mut out));
        match &s.stmt {
            Stmt::Plan(PlanDecl { body, .. }) | Stmt::Bench(BenchDecl { body, .. }) => {
                ParamToken::flatten(body, &mut |t| {
                    if let ParamToken::Word(w) = t
                        && params.contains_key(&w.value)
                    {
                        out.insert(w.span);
                    }
                });
            }
            Stmt::Expect(e) => e.walk(&mut |n| {
                if let ExprKind::Name(name) = &n.kind
                    && params.contains_key(&name.value)
                {
                    out.insert(n.span);
                }
            }),
            _ => {}
        }
    }
    out
}

impl Family {
    /// The statements of one draw: expressions computed, params' names in
    /// bodies replaced, scatters placed.
    pub(super) fn instantiate(
        &self,
        statements: &[SourcedStmt],
        draw: &mut Draw,
    ) -> Result<Vec<SourcedStmt>, Vec<Diag>> {
        let mut out = Vec::with_capacity(statements.len());
        let mut diags = Vec::new();
        let mut placed = Placements::default();
        let mut ctx = Ctx {
            family: self,
            draw,
            diags: &mut diags,
        };
        for s in statements {
            let stmt = match &s.stmt {
                Stmt::Param(_) | Stmt::Require { .. } => continue,
                Stmt::World(w) => {
                    let mut w = w.clone();
                    let mut items = Vec::with_capacity(w.items.len());
                    for item in std::mem::take(&mut w.items) {
                        match item {
                            WorldItem::Scatter(sc) => {
                                ctx.scatter(&sc, &mut placed, &mut items);
                            }
                            mut item => {
                                ctx.item(&mut item);
                                items.push(item);
                            }
                        }
                    }
                    w.items = items;
                    Stmt::World(w)
                }
                Stmt::Robot(r) => {
                    let mut r = r.clone();
                    for v in &mut r.shape.args {
                        ctx.value(v);
                    }
                    if let Some(steer) = &mut r.steer {
                        ctx.value(&mut steer.radius);
                    }
                    if let Some((_, v)) = &mut r.speed {
                        ctx.value(v);
                    }
                    match r.team.as_deref_mut() {
                        Some(crate::syntax::ast::TeamBody::Agents { agents, .. }) => {
                            for a in agents {
                                ctx.value(&mut a.start);
                                ctx.value(&mut a.goal);
                            }
                        }
                        Some(crate::syntax::ast::TeamBody::From { count, .. }) => ctx.value(count),
                        None => {}
                    }
                    Stmt::Robot(r)
                }
                Stmt::Plan(p) => {
                    let mut p = p.clone();
                    ctx.tokens(&mut p.body);
                    Stmt::Plan(p)
                }
                Stmt::Bench(b) => {
                    let mut b = b.clone();
                    ctx.tokens(&mut b.body);
                    Stmt::Bench(b)
                }
                Stmt::Expect(e) => {
                    let mut e = e.clone();
                    ctx.expr(&mut e);
                    Stmt::Expect(e)
                }
                other => other.clone(),
            };
            out.push(SourcedStmt {
                stmt,
                in_main_file: s.in_main_file,
            });
        }
        if diags.is_empty() {
            Ok(out)
        } else {
            Err(diags)
        }
    }
}

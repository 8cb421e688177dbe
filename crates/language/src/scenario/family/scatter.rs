//! `scatter`: items placed at random in a box, a gap apart; and the rules
//! shrinking keeps a scattered item inside.

#![allow(clippy::result_large_err)]

use std::collections::HashMap;

use crate::diagnostics::{Diag, Span, Spanned};
use crate::syntax::ast::{
    ExprKind, ObstacleDecl, ObstacleKind, ObstacleShape, ScatterDecl, ScatterShape, Stmt, Value,
    ValueKind, WorldItem,
};

use crate::scenario::placed::{Placed, Placements};
use crate::scenario::statements::SourcedStmt;

use super::*;

/// What a scattered item's numbers may be for the scatter to have placed
/// it (with the params' values of one member): its centre inside the box,
/// each size in its distribution's support, at least the gap from the
/// other items. Shrinking keeps a simplified item inside it.
#[derive(Clone, Debug)]
pub struct ScatterRule {
    pub min: (f64, f64),
    pub max: (f64, f64),
    pub gap: f64,
    /// Per size (a disk's radius; a rect's width and height).
    pub sizes: Vec<Support>,
}

/// The values a scattered size may take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Support {
    /// A constant or a computed size: only the value placed.
    Fixed,
    /// `uniform(lo, hi)`, or `int(lo, hi)` (`whole`).
    Range { lo: f64, hi: f64, whole: bool },
    /// `normal(m, s)`: any positive number.
    Any,
}

impl Support {
    /// Whether a size of `x` is one this support may draw (`x` positive).
    pub fn holds(self, x: f64) -> bool {
        x > 0.0
            && match self {
                Support::Fixed => false,
                Support::Range { lo, hi, whole } => {
                    lo <= x && x <= hi && (!whole || x.fract() == 0.0)
                }
                Support::Any => true,
            }
    }
}

/// The distance between two scattered items as their scatter measures it
/// for its gap (`None`: not a scattered disk or rect).
pub fn scattered_distance(a: &ObstacleDecl, b: &ObstacleDecl) -> Option<f64> {
    Some(Placed::of(a)?.distance(&Placed::of(b)?))
}

impl Placed {
    pub(super) fn of(o: &ObstacleDecl) -> Option<Placed> {
        let num = |v: &Value| match &v.kind {
            ValueKind::Number(x) => Some(*x),
            _ => None,
        };
        let point = |v: &Value| match &v.kind {
            ValueKind::Tuple(items) if items.len() == 2 => Some((num(&items[0])?, num(&items[1])?)),
            _ => None,
        };
        match &o.shape {
            ObstacleShape::Disk(c, r) => {
                let (x, y) = point(c)?;
                Some(Placed::Disk { x, y, r: num(r)? })
            }
            ObstacleShape::Rect(a, b) => {
                let ((x0, y0), (x1, y1)) = (point(a)?, point(b)?);
                Some(Placed::Rect { x0, y0, x1, y1 })
            }
            _ => None,
        }
    }
}

impl Family {
    /// The rules of every scatter (by its span) with the params' values
    /// `values` (all params, in order); a scatter whose box or gap is not a
    /// number here is left out (its items are not simplified).
    pub fn scatter_rules(
        &self,
        statements: &[SourcedStmt],
        values: &[f64],
    ) -> HashMap<Span, ScatterRule> {
        let number = |v: &Value| -> Option<f64> {
            match &v.kind {
                ValueKind::Number(x) => Some(*x),
                ValueKind::Calc { expr, unit: None } => eval(expr, values, &self.index).ok(),
                ValueKind::Word(w) => self
                    .index
                    .get(w.as_str())
                    .and_then(|&k| values.get(k).copied()),
                _ => None,
            }
        };
        let point = |v: &Value| match &v.kind {
            ValueKind::Tuple(items) if items.len() == 2 => {
                Some((number(&items[0])?, number(&items[1])?))
            }
            _ => None,
        };
        let support = |v: &Value| -> Support {
            let ValueKind::Calc { expr, unit: None } = &v.kind else {
                return Support::Fixed;
            };
            let ExprKind::Call { function, args } = &expr.kind else {
                return Support::Fixed;
            };
            let bounds = match args.as_slice() {
                [a, b] => eval(a, values, &self.index)
                    .ok()
                    .zip(eval(b, values, &self.index).ok()),
                _ => None,
            };
            match (function.value.as_str(), bounds) {
                ("uniform", Some((lo, hi))) => Support::Range {
                    lo,
                    hi,
                    whole: false,
                },
                ("int", Some((lo, hi))) => Support::Range {
                    lo: lo.ceil(),
                    hi: hi.floor(),
                    whole: true,
                },
                ("normal", Some(_)) => Support::Any,
                _ => Support::Fixed,
            }
        };
        let mut out = HashMap::new();
        for s in statements {
            let Stmt::World(w) = &s.stmt else { continue };
            for item in &w.items {
                let WorldItem::Scatter(sc) = item else {
                    continue;
                };
                let gap = match &sc.gap {
                    Some(g) => number(g),
                    None => Some(0.0),
                };
                let (Some(min), Some(max), Some(gap)) = (point(&sc.min), point(&sc.max), gap)
                else {
                    continue;
                };
                let sizes = match &sc.shape {
                    ScatterShape::Disk { radius, .. } => vec![support(radius)],
                    ScatterShape::Rect { width, height, .. } => {
                        vec![support(width), support(height)]
                    }
                };
                out.insert(
                    sc.span,
                    ScatterRule {
                        min,
                        max,
                        gap,
                        sizes,
                    },
                );
            }
        }
        out
    }

    /// Whether a `scatter` draws obstacles (whose places come from a
    /// sample's stream, not from the params).
    pub fn scatters(&self) -> bool {
        self.scatters
    }
}

impl Ctx<'_> {
    /// A number of a scatter (its count, box, gap or a size).
    pub(super) fn scatter_number(
        &mut self,
        v: &Value,
        what: &str,
        sc: &ScatterDecl,
    ) -> Option<f64> {
        let x = match &v.kind {
            ValueKind::Number(x) => *x,
            ValueKind::Calc { expr, unit: None } => self.eval(expr)?,
            ValueKind::Word(w) => match self.family.index.get(w.as_str()) {
                Some(&k) => self.draw.values[k],
                None => return self.scatter_error(v.span, what, sc),
            },
            _ => return self.scatter_error(v.span, what, sc),
        };
        Some(x)
    }

    pub(super) fn scatter_error(
        &mut self,
        span: Span,
        what: &str,
        sc: &ScatterDecl,
    ) -> Option<f64> {
        self.diags.push(
            Diag::error(
                "scen::family::bad_scatter",
                format!("the {what} of scatter `{}` must be a number", sc.name.value),
            )
            .at(span, "not a number")
            .help("`scatter NAME N disk R in (x0, y0) (x1, y1) gap G`, sizes may be distributions: `disk uniform(0.2, 0.6)`"),
        );
        None
    }

    pub(super) fn scatter_point(
        &mut self,
        v: &Value,
        what: &str,
        sc: &ScatterDecl,
    ) -> Option<(f64, f64)> {
        let ValueKind::Tuple(items) = &v.kind else {
            self.scatter_error(v.span, what, sc);
            return None;
        };
        if items.len() != 2 {
            self.scatter_error(v.span, what, sc);
            return None;
        }
        let x = self.scatter_number(&items[0], what, sc)?;
        let y = self.scatter_number(&items[1], what, sc)?;
        Some((x, y))
    }

    pub(super) fn bad_scatter(
        &mut self,
        span: Span,
        sc: &ScatterDecl,
        message: String,
        help: &str,
    ) {
        self.diags.push(
            Diag::error("scen::family::bad_scatter", message)
                .at(span, format!("in scatter `{}`", sc.name.value))
                .help(help.to_string()),
        );
    }

    /// Places the items of a scatter, appending them as obstacles.
    pub(super) fn scatter(
        &mut self,
        sc: &ScatterDecl,
        placed: &mut Placements,
        items: &mut Vec<WorldItem>,
    ) {
        let Some(count) = self.scatter_number(&sc.count, "count", sc) else {
            return;
        };
        if !(count >= 0.0 && count.fract() == 0.0 && count <= MAX_SCATTER_ITEMS) {
            self.bad_scatter(
                sc.count.span,
                sc,
                format!("a scatter places a whole number of items from 0 to {MAX_SCATTER_ITEMS}, not {count}"),
                "write the count as a whole number: `scatter rocks 30 disk 0.3 in (0, 0) (20, 8)`",
            );
            return;
        }
        let Some((x0, y0)) = self.scatter_point(&sc.min, "box corner", sc) else {
            return;
        };
        let Some((x1, y1)) = self.scatter_point(&sc.max, "box corner", sc) else {
            return;
        };
        if !(x0 < x1 && y0 < y1) {
            self.bad_scatter(
                sc.min.span.to(sc.max.span),
                sc,
                "a scatter's box needs its lower-left corner first".to_string(),
                "write `in (x0, y0) (x1, y1)` with x0 < x1 and y0 < y1",
            );
            return;
        }
        let gap = match &sc.gap {
            Some(g) => {
                let Some(gap) = self.scatter_number(g, "gap", sc) else {
                    return;
                };
                if gap < 0.0 {
                    self.bad_scatter(
                        g.span,
                        sc,
                        format!("a negative gap ({gap})"),
                        "the gap is the least distance between two items: 0 or more",
                    );
                    return;
                }
                gap
            }
            None => 0.0,
        };
        let name = &sc.name;
        let size = |this: &mut Self, v: &Value| -> Option<f64> {
            let x = this.scatter_number(v, "size", sc)?;
            if x > 0.0 {
                Some(x)
            } else {
                this.bad_scatter(
                    v.span,
                    sc,
                    format!("a scattered item's size must be positive, drew {x}"),
                    "use sizes (or distributions of sizes) above 0",
                );
                None
            }
        };
        for i in 1..=count as usize {
            let mut done = false;
            for _ in 0..MAX_PLACEMENT_TRIES {
                let (shape, item) = match &sc.shape {
                    ScatterShape::Disk { keyword, radius } => {
                        let Some(r) = size(self, radius) else { return };
                        let x = self.draw.rng.range(x0, x1);
                        let y = self.draw.rng.range(y0, y1);
                        (
                            ObstacleShape::Disk(
                                point_value(x, y, radius.span),
                                number_value(r, radius.span),
                            ),
                            (Placed::Disk { x, y, r }, ObstacleKind::Disk, *keyword),
                        )
                    }
                    ScatterShape::Rect {
                        keyword,
                        width,
                        height,
                    } => {
                        let Some(w) = size(self, width) else { return };
                        let Some(h) = size(self, height) else { return };
                        let x = self.draw.rng.range(x0, x1);
                        let y = self.draw.rng.range(y0, y1);
                        let (ax, ay, bx, by) = (x - w / 2.0, y - h / 2.0, x + w / 2.0, y + h / 2.0);
                        (
                            ObstacleShape::Rect(
                                point_value(ax, ay, width.span),
                                point_value(bx, by, height.span),
                            ),
                            (
                                Placed::Rect {
                                    x0: ax,
                                    y0: ay,
                                    x1: bx,
                                    y1: by,
                                },
                                ObstacleKind::Rect,
                                *keyword,
                            ),
                        )
                    }
                };
                let (here, kind, keyword) = item;
                if placed.crowds(&here, gap) {
                    continue;
                }
                placed.push(here);
                items.push(WorldItem::Obstacle(ObstacleDecl {
                    kind: Spanned::new(kind, keyword),
                    name: Some(Spanned::new(format!("{}_{i}", name.value), name.span)),
                    shape,
                    span: sc.span,
                }));
                done = true;
                break;
            }
            if !done {
                self.bad_scatter(
                    sc.span,
                    sc,
                    format!(
                        "scatter `{}` could not place item {i} of {count} at least {gap} from the others in {MAX_PLACEMENT_TRIES} tries",
                        name.value
                    ),
                    "place fewer or smaller items, a smaller gap, or a larger box",
                );
                return;
            }
        }
    }
}

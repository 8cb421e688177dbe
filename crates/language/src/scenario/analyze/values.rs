//! Values as the analyzer reads them: numbers within ±1e9, points, poses
//! (headings reduced exactly), polygon vertex lists.

use crate::diagnostics::{Diag, Span};
use crate::geometry::polygon::{self, PolygonError};
use crate::geometry::{Config, Point};
use crate::syntax::ast::{self, Value, ValueKind};

use crate::contract::schema::MAX_MAGNITUDE;

use super::*;

impl Analyzer {
    /// A coordinate, length, radius or cell size: a number within ±1e9
    /// (SPEC 2.1).
    pub(super) fn expect_number(&mut self, v: &Value, what: &str) -> Option<f64> {
        match &v.kind {
            ValueKind::Number(x) if x.abs() > MAX_MAGNITUDE => {
                self.error(
                    Diag::error(
                        "scen::analyze::number_too_large",
                        format!("{what} is {}, beyond ±1e9", short_number(*x)),
                    )
                    .at(v.span, "more than 1e9 in magnitude")
                    .help(MAGNITUDE_HELP),
                );
                None
            }
            ValueKind::Number(x) => Some(*x),
            ValueKind::Angle(_) => {
                self.error(
                    Diag::error(
                        "scen::analyze::wrong_unit",
                        format!("{what} is a length, not an angle"),
                    )
                    .at(v.span, "an angle")
                    .help("remove the `deg`/`rad` unit"),
                );
                None
            }
            other => {
                self.error(
                    Diag::error(
                        "scen::analyze::wrong_type",
                        format!("{what} must be a number, found {}", other.describe()),
                    )
                    .at(v.span, "expected a number")
                    .help("write a number such as `1.5`"),
                );
                None
            }
        }
    }

    pub(super) fn expect_positive(&mut self, v: &Value, what: &str) -> Option<f64> {
        let x = self.expect_number(v, what)?;
        if x > 0.0 {
            Some(x)
        } else {
            self.error(
                Diag::error(
                    "scen::analyze::out_of_range",
                    format!("{what} must be positive, got {x}"),
                )
                .at(v.span, "not > 0")
                .help("use a value greater than 0"),
            );
            None
        }
    }

    pub(super) fn expect_point(&mut self, v: &Value, what: &str) -> Option<Point> {
        match &v.kind {
            ValueKind::Tuple(items) if items.len() == 2 => {
                let x = self.expect_number(&items[0], "a coordinate");
                let y = self.expect_number(&items[1], "a coordinate");
                Some(Point::new(x?, y?))
            }
            ValueKind::Tuple(items) => {
                self.error(
                    Diag::error(
                        "scen::analyze::wrong_type",
                        format!(
                            "{what} must be a point `(x, y)`, found {} values",
                            items.len()
                        ),
                    )
                    .at(v.span, "expected `(x, y)`")
                    .help("a point has two coordinates: `(x, y)`"),
                );
                None
            }
            other => {
                self.error(
                    Diag::error(
                        "scen::analyze::wrong_type",
                        format!(
                            "{what} must be a point `(x, y)`, found {}",
                            other.describe()
                        ),
                    )
                    .at(v.span, "expected `(x, y)`")
                    .help("write a point as `(x, y)`"),
                );
                None
            }
        }
    }

    pub(super) fn expect_points(
        &mut self,
        v: &Value,
        what: &str,
    ) -> Option<(Vec<Point>, Vec<Span>)> {
        match &v.kind {
            ValueKind::List(items) => {
                let mut pts = Vec::new();
                let mut spans = Vec::new();
                let mut ok = true;
                for it in items {
                    match self.expect_point(it, "a vertex") {
                        Some(p) => {
                            pts.push(p);
                            spans.push(it.span);
                        }
                        None => ok = false,
                    }
                }
                ok.then_some((pts, spans))
            }
            other => {
                self.error(
                    Diag::error(
                        "scen::analyze::wrong_type",
                        format!(
                            "{what} must be a list of points, found {}",
                            other.describe()
                        ),
                    )
                    .at(v.span, "expected `[(x, y), ...]`")
                    .help("write the vertices as `[(0, 0), (1, 0), (0, 1)]`"),
                );
                None
            }
        }
    }

    /// A polygon's vertices, at most [`polygon::MAX_POLYGON_VERTICES`] of
    /// them (SPEC 2.2), refused before they are read one by one.
    pub(super) fn polygon_points(
        &mut self,
        v: &Value,
        what: &str,
    ) -> Option<(Vec<Point>, Vec<Span>)> {
        if let ValueKind::List(items) = &v.kind
            && items.len() > polygon::MAX_POLYGON_VERTICES
        {
            self.error(
                Diag::error(
                    "scen::analyze::polygon_too_large",
                    format!(
                        "{what} has {} vertices, more than the limit of {}",
                        items.len(),
                        polygon::MAX_POLYGON_VERTICES
                    ),
                )
                .at(v.span, "too many vertices")
                .help("simplify the outline, or split the obstacle into several polygons"),
            );
            return None;
        }
        self.expect_points(v, what)
    }

    pub(super) fn expect_pose(&mut self, v: &Value, what: &str) -> Option<Config> {
        match &v.kind {
            ValueKind::Tuple(items) if items.len() == 2 || items.len() == 3 => {
                let x = self.expect_number(&items[0], "a coordinate");
                let y = self.expect_number(&items[1], "a coordinate");
                let theta = match items.get(2) {
                    None => Some(0.0),
                    Some(t) => match &t.kind {
                        ValueKind::Angle(a) => self.bounded_angle(t, *a).map(ast::Angle::reduced),
                        ValueKind::Number(n) => {
                            self.angle_without_unit(
                                t.span,
                                *n,
                                format!("the angle of {what} needs a unit"),
                            );
                            None
                        }
                        other => {
                            self.error(
                                Diag::error(
                                    "scen::analyze::wrong_type",
                                    format!(
                                        "the angle of {what} must be an angle, found {}",
                                        other.describe()
                                    ),
                                )
                                .at(t.span, "expected an angle")
                                .help("write an angle as `90deg` or `1.5708rad`"),
                            );
                            None
                        }
                    },
                };
                Some(Config::new(x?, y?, theta?))
            }
            other => {
                self.error(
                    Diag::error(
                        "scen::analyze::wrong_type",
                        format!(
                            "{what} must be a pose `(x, y)` or `(x, y, θ)`, found {}",
                            other.describe()
                        ),
                    )
                    .at(v.span, "expected a pose")
                    .help("write a pose as `(4, 24)` or `(4, 24, 90deg)`"),
                );
                None
            }
        }
    }

    pub(super) fn polygon_error(
        &mut self,
        e: PolygonError,
        span: Span,
        vertex_spans: &[Span],
        what: &str,
    ) {
        let d = match e {
            PolygonError::TooFewVertices => Diag::error(
                "scen::analyze::degenerate_polygon",
                format!("{what} has fewer than 3 distinct, non-collinear vertices"),
            )
            .at(span, "not a polygon")
            .help("a polygon needs at least 3 vertices that are not on one line"),
            PolygonError::ZeroArea => Diag::error(
                "scen::analyze::degenerate_polygon",
                format!("{what} encloses no area"),
            )
            .at(span, "zero area")
            .help("check the vertices: they must not all lie on one line"),
            PolygonError::SelfIntersecting { edges: (i, j) } => {
                let n = vertex_spans.len().max(1);
                let at = vertex_spans.get(i).copied().unwrap_or(span);
                let mut d = Diag::error(
                    "scen::analyze::self_intersecting",
                    format!(
                        "{what} is not simple: edge {} crosses edge {}",
                        i + 1,
                        j + 1
                    ),
                )
                .at(at, format!("edge {} starts here", i + 1))
                .help("list the vertices in order around the boundary, without crossings");
                if let Some(s) = vertex_spans.get(j % n) {
                    d = d.with_related(*s, format!("edge {} starts here", j + 1));
                }
                d
            }
        };
        self.error(d);
    }
}

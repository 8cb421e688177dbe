//! Robots: their names and shapes (a robot polygon must be convex).

use std::collections::HashMap;

use crate::diagnostics::{Diag, Span};
use crate::geometry::polygon;
use crate::geometry::{ConvexPolygon, Point, RobotShape};
use crate::syntax::ast::{self, Value};

use crate::contract::Robot;
use crate::scenario::loader::SourcedStmt;

use super::*;

impl Analyzer {
    pub(super) fn robots(&mut self, statements: &[SourcedStmt]) -> Vec<Robot> {
        let mut robots: Vec<Robot> = Vec::new();
        let mut seen: HashMap<String, Span> = HashMap::new();
        for s in statements {
            let ast::Stmt::Robot(r) = &s.stmt else {
                continue;
            };
            if let Some(first) = seen.get(&r.name.value) {
                self.error(
                    Diag::error(
                        "scen::analyze::duplicate_name",
                        format!("robot `{}` is declared twice", r.name.value),
                    )
                    .at(r.name.span, "second declaration")
                    .with_related(*first, "first declaration")
                    .help("robot names must be unique; rename one of them"),
                );
                continue;
            }
            seen.insert(r.name.value.clone(), r.name.span);
            let shape = match &r.shape {
                ast::RobotShape::Point(_) => Some(RobotShape::Point),
                ast::RobotShape::Disk(v) => self
                    .expect_positive(v, "the robot's radius")
                    .map(RobotShape::Disk),
                ast::RobotShape::Rect(w, h) => {
                    let (w, h) = (
                        self.expect_positive(w, "the width"),
                        self.expect_positive(h, "the height"),
                    );
                    match (w, h) {
                        (Some(w), Some(h)) => Some(RobotShape::Polygon(ConvexPolygon {
                            vertices: vec![
                                Point::new(0.0, 0.0),
                                Point::new(w, 0.0),
                                Point::new(w, h),
                                Point::new(0.0, h),
                            ],
                        })),
                        _ => None,
                    }
                }
                ast::RobotShape::Polygon(v) => self.robot_polygon(v),
            };
            if shape.is_none() {
                self.invalid_robots.push(r.name.value.clone());
            }
            if let Some(shape) = shape {
                robots.push(Robot {
                    name: r.name.value.clone(),
                    shape,
                    span: r.span,
                });
            }
        }
        robots
    }

    pub(super) fn robot_polygon(&mut self, v: &Value) -> Option<RobotShape> {
        let (pts, vspans) = self.polygon_points(v, "the robot polygon")?;
        match polygon::normalize_simple_polygon(&pts) {
            Ok(outline) if polygon::is_convex(&outline) => {
                Some(RobotShape::Polygon(ConvexPolygon { vertices: outline }))
            }
            Ok(_) => {
                self.error(
                    Diag::error("scen::analyze::robot_not_convex", "a robot polygon must be convex")
                        .at(v.span, "not convex")
                        .help("planners need convex robots: use the convex hull of this shape, or a smaller convex part"),
                );
                None
            }
            Err(e) => {
                self.polygon_error(e, v.span, &vspans, "the robot polygon");
                None
            }
        }
    }
}

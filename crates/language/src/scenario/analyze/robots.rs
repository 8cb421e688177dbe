//! Robots: their names and shapes (a robot polygon must be convex).

use std::collections::HashMap;

use crate::diagnostics::{Diag, Span};
use crate::geometry::polygon;
use crate::geometry::steer::{MODEL_NAMES, Model, Steering};
use crate::geometry::{ConvexPolygon, Point, RobotShape};
use crate::syntax::ast::{self, Value};

use crate::contract::Robot;
use crate::scenario::statements::SourcedStmt;

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
            let steering = match (&r.steer, &shape) {
                (None, _) => Ok(None),
                (Some(clause), shape) => self.steering(clause, shape.as_ref()).map(Some).ok_or(()),
            };
            if shape.is_none() || steering.is_err() {
                self.invalid_robots.push(r.name.value.clone());
            }
            if let (Some(shape), Ok(steering)) = (shape, steering) {
                robots.push(Robot {
                    name: r.name.value.clone(),
                    shape,
                    steering,
                    span: r.span,
                });
            }
        }
        robots
    }

    /// `steer MODEL RADIUS` (SPEC 2.4): a known model, a positive radius,
    /// and a body (a point has none to steer).
    fn steering(
        &mut self,
        clause: &ast::SteerClause,
        shape: Option<&RobotShape>,
    ) -> Option<Steering> {
        let model = match clause.model.value.as_str() {
            "dubins" => Some(Model::Dubins),
            "reeds_shepp" => Some(Model::ReedsShepp),
            other => {
                let mut d = Diag::error(
                    "scen::analyze::unknown_steering",
                    format!("unknown steering model `{other}`"),
                )
                .at(clause.model.span, "not a steering model");
                d = match crate::contract::schema::did_you_mean(other, MODEL_NAMES.iter().copied()) {
                    Some(m) => d.help(format!(
                        "did you mean `{m}`? The models are `dubins` (forward only) and `reeds_shepp` (forward and reverse)"
                    )),
                    None => d.help(
                        "the models are `dubins` (forward only) and `reeds_shepp` (forward and reverse), e.g. `steer reeds_shepp 4.5`",
                    ),
                };
                self.error(d);
                None
            }
        };
        let radius = self.expect_positive(&clause.radius, "the turning radius");
        if matches!(shape, Some(RobotShape::Point)) {
            self.error(
                Diag::error(
                    "scen::analyze::car_point",
                    "a point robot cannot steer like a car",
                )
                .at(clause.span, "`steer` on a point robot")
                .help(
                    "give the car a body: `robot car rect 4 2 steer reeds_shepp 4.5` or `robot car disk 1 steer dubins 3`",
                ),
            );
            return None;
        }
        Some(Steering::new(model?, radius?))
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

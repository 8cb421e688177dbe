//! Robots: their names and shapes (a robot polygon must be convex).

use std::collections::HashMap;

use crate::diagnostics::{Diag, Span};
use crate::geometry::RobotShape;
use crate::geometry::polygon;
use crate::geometry::robots::{self, Arg, ArgValue};
use crate::geometry::steer::{MODEL_NAMES, Model, Steering};
use crate::syntax::ast;

use crate::contract::Robot;
use crate::scenario::statements::SourcedStmt;

use super::*;

impl Analyzer {
    pub(super) fn robots(
        &mut self,
        statements: &[SourcedStmt],
        world: Option<&crate::geometry::World>,
    ) -> Vec<Robot> {
        // The map file of the world's grid, for a team's MovingAI rows.
        let grid_file = statements.iter().find_map(|s| match &s.stmt {
            ast::Stmt::World(w) => w.items.iter().find_map(|item| match item {
                ast::WorldItem::Obstacle(ast::ObstacleDecl {
                    shape: ast::ObstacleShape::Grid(g),
                    ..
                }) => g.file.as_ref().map(|f| f.value.clone()),
                _ => None,
            }),
            _ => None,
        });
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
                        format!("robot or team `{}` is declared twice", r.name.value),
                    )
                    .at(r.name.span, "second declaration")
                    .with_related(*first, "first declaration")
                    .help("robot names must be unique; rename one of them"),
                );
                continue;
            }
            seen.insert(r.name.value.clone(), r.name.span);
            let shape = self.robot_body(&r.shape);
            let steering = match (&r.steer, &shape) {
                (None, _) => Ok(None),
                (Some(clause), shape) => self.steering(clause, shape.as_ref()).map(Some).ok_or(()),
            };
            let speed = match &r.speed {
                None => Ok(None),
                Some((_, v)) => self
                    .expect_positive(v, "the robot's speed")
                    .map(Some)
                    .ok_or(()),
            };
            let team = match (r.team.as_deref(), &shape) {
                (None, _) => Ok(None),
                (Some(body), Some(shape)) => self
                    .team(r, body, shape, world, grid_file.as_deref())
                    .map(|agents| Some(agents.into()))
                    .ok_or(()),
                (Some(_), None) => Err(()),
            };
            if shape.is_none() || steering.is_err() || speed.is_err() || team.is_err() {
                self.invalid_robots.push(r.name.value.clone());
            }
            if let (Some(shape), Ok(steering), Ok(speed), Ok(team)) = (shape, steering, speed, team)
            {
                robots.push(Robot {
                    name: r.name.value.clone(),
                    shape,
                    steering,
                    speed,
                    team,
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

    /// The body of `KIND ARGS...`: the kind from the registry of robot
    /// kinds, its arguments checked against what it takes, and its body.
    fn robot_body(&mut self, shape: &ast::RobotShape) -> Option<RobotShape> {
        let kind = &shape.kind;
        let Some(model) = robots::model(&kind.value) else {
            let kinds: Vec<&str> = robots::keywords().collect();
            let mut d = Diag::error(
                "scen::analyze::unknown_robot_kind",
                format!("unknown robot kind `{}`", kind.value),
            )
            .at(kind.span, "not a robot kind");
            d = match crate::contract::schema::did_you_mean(&kind.value, kinds.iter().copied()) {
                Some(k) => d.help(format!(
                    "did you mean `{k}`? robot kinds: {}",
                    crate::contract::schema::backticked(&kinds)
                )),
                None => d.help(format!(
                    "robot kinds: {}, e.g. `{}`",
                    crate::contract::schema::backticked(&kinds),
                    robots::ROBOTS[1].example
                )),
            };
            self.error(d);
            return None;
        };
        if shape.args.len() != model.args.len() {
            let wanted = match model.args.len() {
                0 => "no values".to_string(),
                1 => "1 value".to_string(),
                n => format!("{n} values"),
            };
            let names: Vec<&str> = model
                .args
                .iter()
                .map(|a| match a {
                    Arg::Length(what) | Arg::Polygon(what) => *what,
                })
                .collect();
            let (span, label) = match shape.args.get(model.args.len()) {
                Some(extra) => (
                    Span::new(extra.span.file, extra.span.start, shape.span.end),
                    "one value too many".to_string(),
                ),
                None => (shape.span, format!("{} given", shape.args.len())),
            };
            let takes = if names.is_empty() {
                String::new()
            } else {
                format!(" ({})", names.join(", "))
            };
            self.error(
                Diag::error(
                    "scen::analyze::robot_arguments",
                    format!("a `{}` robot takes {wanted}{takes}", model.keyword),
                )
                .at(span, label)
                .help(format!("write it as `{}`", model.example)),
            );
            return None;
        }
        let mut values = Vec::with_capacity(model.args.len());
        let mut spans = Vec::with_capacity(model.args.len());
        for (arg, v) in model.args.iter().zip(&shape.args) {
            let value = match arg {
                Arg::Length(what) => self.expect_positive(v, what).map(ArgValue::Length),
                Arg::Polygon(what) => {
                    let (pts, vspans) = self.polygon_points(v, what)?;
                    match polygon::normalize_simple_polygon(&pts) {
                        Ok(outline) => Some(ArgValue::Polygon(outline)),
                        Err(e) => {
                            self.polygon_error(e, v.span, &vspans, what);
                            None
                        }
                    }
                }
            };
            values.push(value);
            spans.push(v.span);
        }
        let values: Vec<ArgValue> = values.into_iter().collect::<Option<_>>()?;
        match (model.body)(&values) {
            Ok(body) => Some(body),
            Err(e) => {
                let span = spans.get(e.arg).copied().unwrap_or(shape.span);
                self.error(
                    Diag::error(e.code, e.message)
                        .at(span, e.label)
                        .help(e.help),
                );
                None
            }
        }
    }
}

//! Moving obstacles (SPEC 2.9): `moving NAME SHAPE { at T (x, y) ... then
//! stay|vanish }` — a shape, timed waypoints whose times increase from 0
//! or later and whose points lie within the bounds, and what happens after
//! the last one.

use std::collections::HashMap;

use crate::diagnostics::{Diag, Span};
use crate::geometry::polygon;
use crate::geometry::timed::{After, MovingObstacle, MovingShape, Waypoint};
use crate::geometry::{Point, World};
use crate::scenario::statements::SourcedStmt;
use crate::syntax::ast::{self, ValueKind};

use super::*;

impl Analyzer {
    /// The moving obstacles of the `world` blocks, with the span of each
    /// declaration; `world`'s obstacles' names are taken already.
    pub(super) fn moving(
        &mut self,
        statements: &[SourcedStmt],
        world: &World,
        static_spans: &[Span],
    ) -> (Vec<MovingObstacle>, Vec<Span>) {
        let mut names: HashMap<String, Span> = world
            .obstacles
            .iter()
            .zip(static_spans)
            .map(|(o, s)| (o.name.clone(), *s))
            .collect();
        let (mut out, mut spans) = (Vec::new(), Vec::new());
        for s in statements {
            let ast::Stmt::World(w) = &s.stmt else {
                continue;
            };
            for item in &w.items {
                let ast::WorldItem::Moving(m) = item else {
                    continue;
                };
                if let Some(first) = names.get(&m.name.value) {
                    self.error(
                        Diag::error(
                            "scen::analyze::duplicate_name",
                            format!("obstacle `{}` is declared twice", m.name.value),
                        )
                        .at(m.name.span, "second declaration")
                        .with_related(*first, "first declaration")
                        .help("obstacle names must be unique; rename one of them"),
                    );
                    continue;
                }
                names.insert(m.name.value.clone(), m.name.span);
                let shape = self.moving_shape(&m.shape);
                let route = self.route(m, world);
                let after = match m.then.as_ref().map(|t| t.value.as_str()) {
                    Some("vanish") => After::Vanish,
                    _ => After::Stay,
                };
                if let (Some(shape), Some(route)) = (shape, route) {
                    out.push(MovingObstacle {
                        name: m.name.value.clone(),
                        shape,
                        route,
                        after,
                    });
                    spans.push(m.span);
                }
            }
        }
        (out, spans)
    }

    /// `disk R`, `rect W H` (centred on the route's point) or
    /// `polygon [...]` (its frame's origin on the point).
    fn moving_shape(&mut self, shape: &ast::RobotShape) -> Option<MovingShape> {
        let args = &shape.args;
        match (shape.kind.value.as_str(), args.as_slice()) {
            ("disk", [r]) => self
                .expect_positive(r, "the obstacle's radius")
                .map(MovingShape::Disk),
            ("rect", [w, h]) => {
                let (w, h) = (
                    self.expect_positive(w, "the width"),
                    self.expect_positive(h, "the height"),
                );
                let (w, h) = (w? / 2.0, h? / 2.0);
                Some(MovingShape::Pieces(vec![vec![
                    Point::new(-w, -h),
                    Point::new(w, -h),
                    Point::new(w, h),
                    Point::new(-w, h),
                ]]))
            }
            ("polygon", [v]) => {
                let (pts, vspans) = self.polygon_points(v, "the obstacle's polygon")?;
                match polygon::normalize_simple_polygon(&pts) {
                    Ok(outline) => Some(MovingShape::polygon(&outline)),
                    Err(e) => {
                        self.polygon_error(e, v.span, &vspans, "the obstacle's polygon");
                        None
                    }
                }
            }
            // The grammar gives a moving obstacle only these three shapes,
            // each with its values.
            _ => None,
        }
    }

    /// The waypoints: at least one, times from 0 or later and strictly
    /// increasing, points within the bounds.
    fn route(&mut self, m: &ast::MovingDecl, world: &World) -> Option<Vec<Waypoint>> {
        if m.waypoints.is_empty() {
            self.error(
                Diag::error(
                    "scen::analyze::no_waypoint",
                    format!("the moving obstacle `{}` has no waypoint", m.name.value),
                )
                .at(m.block, "no `at T (x, y)` here")
                .help("give its route: `at 0s (2, 5)  at 4s (10, 5)`, then `then stay` or `then vanish`"),
            );
            return None;
        }
        let mut route = Vec::with_capacity(m.waypoints.len());
        let mut ok = true;
        let mut previous: Option<(f64, Span)> = None;
        for w in &m.waypoints {
            let t = self.time(&w.time);
            let at = self.expect_point(&w.at, "the waypoint");
            if let Some(p) = at
                && !world.bounds.contains(p)
            {
                self.error(
                    Diag::error(
                        "scen::analyze::waypoint_outside",
                        format!("the waypoint ({}, {}) is outside the bounds", p.x, p.y),
                    )
                    .at(w.at.span, "outside `bounds`")
                    .help(format!(
                        "every waypoint lies within the bounds ({}, {}) to ({}, {})",
                        world.bounds.min.x,
                        world.bounds.min.y,
                        world.bounds.max.x,
                        world.bounds.max.y
                    )),
                );
                ok = false;
            }
            if let (Some(t), Some((before, span))) = (t, previous)
                && t <= before
            {
                self.error(
                    Diag::error(
                        "scen::analyze::times_not_increasing",
                        format!("the waypoint at {t} s does not come after the one at {before} s"),
                    )
                    .at(w.time.span, "not later than the waypoint before")
                    .with_related(span, "the waypoint before")
                    .help("a route's times strictly increase: `at 0s (2, 5)  at 4s (10, 5)`"),
                );
                ok = false;
            }
            match (t, at) {
                (Some(t), Some(at)) => {
                    previous = Some((t, w.time.span));
                    route.push(Waypoint { t, at });
                }
                _ => ok = false,
            }
        }
        ok.then_some(route)
    }

    /// A waypoint's time: a duration (`4s`, `500ms`) or a number of
    /// seconds, finite and not negative.
    fn time(&mut self, v: &ast::Value) -> Option<f64> {
        let t = match v.kind {
            ValueKind::Duration(t) | ValueKind::Number(t) => t,
            _ => {
                self.error(
                    Diag::error(
                        "scen::analyze::wrong_type",
                        "a waypoint's time is a duration",
                    )
                    .at(v.span, "not a time")
                    .help(
                        "write it in seconds or milliseconds: `at 2.5s (4, 5)`, `at 500ms (4, 5)`",
                    ),
                );
                return None;
            }
        };
        if !(t.is_finite() && t >= 0.0) {
            self.error(
                Diag::error(
                    "scen::analyze::out_of_range",
                    format!("a waypoint's time is 0 s or later, not {t} s"),
                )
                .at(v.span, "before the start")
                .help("time starts at `0s`: an obstacle stands at its first point until its first time"),
            );
            return None;
        }
        Some(t)
    }

    /// A plan's start must be clear of the moving obstacles at t = 0 (SPEC
    /// 2.9): the robot is there then, whatever it does next.
    pub(super) fn start_hit(
        &mut self,
        plans: &[crate::scenario::Plan],
        robots: &[crate::contract::Robot],
        moving: &[MovingObstacle],
    ) {
        use crate::geometry::timed::{Timed, motion_meets};
        for plan in plans {
            let Some(robot) = robots.get(plan.robot) else {
                continue;
            };
            let at = Timed {
                pose: plan.params.start,
                t: 0.0,
            };
            if let Some(o) = moving
                .iter()
                .find(|o| motion_meets(&robot.shape, o, at, at))
            {
                self.error(
                    Diag::error(
                        "scen::analyze::start_hit",
                        format!(
                            "the start of plan `{}` is in the moving obstacle `{}` at t = 0",
                            plan.name, o.name
                        ),
                    )
                    .at(
                        plan.params.start_span,
                        format!("robot `{}` overlaps `{}` here at 0 s", robot.name, o.name),
                    )
                    .help(format!(
                        "move the start, or let `{}` start elsewhere (its first waypoint)",
                        o.name
                    )),
                );
            }
        }
    }

    /// Among moving obstacles only a planner that knows time may plan
    /// (SPEC 2.9): a plan of any other kind is refused, at its kind, with
    /// the kinds that do named.
    pub(super) fn needs_time(&mut self, statements: &[SourcedStmt], moving: &[MovingObstacle]) {
        let Some(first) = moving.first() else {
            return;
        };
        let knowing: Vec<String> = crate::planners::registry::PLANNERS
            .iter()
            .filter(|p| p.time)
            .map(|p| format!("`{}`", p.kind))
            .collect();
        for s in statements {
            let ast::Stmt::Plan(p) = &s.stmt else {
                continue;
            };
            let Some(planner) = crate::planners::registry::planner(&p.kind.value) else {
                continue;
            };
            if planner.time {
                continue;
            }
            self.error(
                Diag::error(
                    "scen::analyze::needs_time",
                    format!(
                        "`{}` does not plan among moving obstacles (`{}` moves)",
                        p.kind.value, first.name
                    ),
                )
                .at(p.kind.span, "a planner that ignores time")
                .help(format!(
                    "plan with a planner that knows time ({}), or remove the `moving` obstacles to plan in the static world",
                    knowing.join(", ")
                )),
            );
        }
    }
}

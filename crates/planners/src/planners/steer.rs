//! `steer` (SPEC 3.8): a car robot's steering path from the start to the
//! goal — the shortest Dubins or Reeds–Shepp curve, ignoring obstacles —
//! and nothing else: found when the body swept along it is free (OMPL's
//! `interpolate`; the base case and the reference for the car planners).
//! When it is not, the plan reports where the curve is blocked and draws
//! it; it never searches for another path.

use std::any::Any;

use crate::contract::layers::{Colour, Drawing, Layer, Style, Svg};
use crate::contract::schema::RobotKind;
use crate::contract::{PlanArgs, PlanOutcome, Planner, Settings, Task};
use crate::geometry::car::{CarPath, DRAW_STEP};
use crate::planners::deadline::Deadline;

pub static PLANNER: Planner = Planner {
    kind: "steer",
    summary: "a car's steering path (the shortest Dubins or Reeds–Shepp curve), found when it is free",
    robots: &[RobotKind::Car],
    params: &[],
    metrics: &[],
    limits: &["time"],
    needs_goal: true,
    randomized: false,
    grids: true,
    time: false,
    check,
};

#[derive(Debug)]
struct SteerSettings;

fn check(_: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    Some(Box::new(SteerSettings))
}

impl Settings for SteerSettings {
    fn plan(&self, task: &Task<'_>) -> PlanOutcome {
        let (Some(steering), Some(goal)) = (task.steering, task.goal) else {
            // The analysis lets only car robots with a goal through.
            return PlanOutcome {
                notes: vec!["`steer` plans for car robots (`steer` after the shape), to a goal".into()],
                ..PlanOutcome::default()
            };
        };
        if task.start_is_goal() {
            let mut out = PlanOutcome::at_goal(task.start);
            out.car = Some(CarPath {
                start: task.start,
                steering,
                segments: Vec::new(),
            });
            return out;
        }
        if Deadline::start(&task.limits).passed() {
            return PlanOutcome {
                gave_up: true,
                notes: vec!["the time limit was reached before the curve was checked".into()],
                ..PlanOutcome::default()
            };
        }
        let curve = steering.shortest(task.start, goal);
        if !curve.length().is_finite() {
            return PlanOutcome {
                notes: vec![steering.too_far_note()],
                expanded: 1,
                ..PlanOutcome::default()
            };
        }
        let car = CarPath::from_steer(task.start, steering, &curve);
        let checker = task.car_checker();
        let free = checker.path_free(&car) && car.ends_on(goal);
        let mut out = PlanOutcome {
            expanded: 1,
            ..PlanOutcome::default()
        };
        if free {
                out.cost = Some(car.length());
                // The segments end on the goal to rounding; the listed
                // path ends on it exactly, as every planner's does.
                let mut poses = car.poses(DRAW_STEP);
                if let Some(last) = poses.last_mut() {
                    *last = goal;
                }
                out.path = Some(poses);
                out.car = Some(car);
        } else {
                out.notes.push(match checker.first_blocked(&car) {
                    Some((segment, at)) => format!(
                        "the steering path is blocked on its segment {} at ({:.3}, {:.3})",
                        segment + 1,
                        at.x,
                        at.y
                    ),
                    None => "the steering path is blocked (it touches an obstacle or the bounds, to rounding)".into(),
                });
                if task.draw {
                    let xy = car.poses(DRAW_STEP).iter().map(|c| c.xy()).collect();
                    out.layers.push(Layer::new(
                        "blocked_curve",
                        Drawing::Polylines(vec![xy]),
                        Style::new(Colour::Plan, 1.0, 25.0)
                            .svg(Svg::line(0.6).dashed().key("steering path (blocked)")),
                    ));
                }
        }
        out
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

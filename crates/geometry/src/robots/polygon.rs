//! `robot NAME polygon [(x, y), ...]`: a convex polygon in the robot's
//! frame.

use super::{Arg, ArgValue, BodyError, RobotModel};
use crate::polygon::is_convex;
use crate::{ConvexPolygon, RobotShape};

pub static MODEL: RobotModel = RobotModel {
    keyword: "polygon",
    summary: "a convex polygon, its vertices in the robot's frame",
    example: "robot r polygon [(-0.5, -0.2), (0.5, -0.2), (0.5, 0.2), (-0.5, 0.2)]",
    args: &[Arg::Polygon("the robot polygon")],
    body,
};

fn body(args: &[ArgValue]) -> Result<RobotShape, BodyError> {
    let Some(ArgValue::Polygon(outline)) = args.first() else {
        unreachable!("the language checks a polygon argument");
    };
    if !is_convex(outline) {
        return Err(BodyError {
            arg: 0,
            code: "scen::analyze::robot_not_convex",
            message: "a robot polygon must be convex".into(),
            label: "not convex".into(),
            help: "planners need convex robots: use the convex hull of this shape, or a smaller convex part".into(),
        });
    }
    Ok(RobotShape::Polygon(ConvexPolygon {
        vertices: outline.clone(),
    }))
}

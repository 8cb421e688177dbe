//! `robot NAME rect W H`: a W × H rectangle with a corner on the reference
//! point, sides along the robot's axes.

use super::{Arg, ArgValue, BodyError, RobotModel};
use crate::{ConvexPolygon, Point, RobotShape};

pub static MODEL: RobotModel = RobotModel {
    keyword: "rect",
    summary: "a W × H rectangle from the reference point along the robot's x and y axes",
    example: "robot r rect 1 0.5",
    args: &[Arg::Length("the width"), Arg::Length("the height")],
    body,
};

fn body(args: &[ArgValue]) -> Result<RobotShape, BodyError> {
    let mut lengths = RobotModel::lengths(args);
    let (w, h) = (lengths.next().unwrap_or(0.0), lengths.next().unwrap_or(0.0));
    Ok(RobotShape::Polygon(ConvexPolygon {
        vertices: vec![
            Point::new(0.0, 0.0),
            Point::new(w, 0.0),
            Point::new(w, h),
            Point::new(0.0, h),
        ],
    }))
}

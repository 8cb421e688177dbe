//! `robot NAME point`: a robot without extent (its reference point).

use super::{ArgValue, BodyError, RobotModel};
use crate::RobotShape;

pub static MODEL: RobotModel = RobotModel {
    keyword: "point",
    summary: "a robot without extent: its reference point",
    example: "robot r point",
    args: &[],
    body,
};

fn body(_: &[ArgValue]) -> Result<RobotShape, BodyError> {
    Ok(RobotShape::Point)
}

//! `robot NAME disk R`: a disk of radius R about the reference point.

use super::{Arg, ArgValue, BodyError, RobotModel};
use crate::RobotShape;

pub static MODEL: RobotModel = RobotModel {
    keyword: "disk",
    summary: "a disk of radius R centred on the reference point",
    example: "robot r disk 0.3",
    args: &[Arg::Length("the robot's radius")],
    body,
};

fn body(args: &[ArgValue]) -> Result<RobotShape, BodyError> {
    let r = RobotModel::lengths(args).next().unwrap_or(0.0);
    Ok(RobotShape::Disk(r))
}

//! The robot kinds (SPEC 2.4): what may follow `robot NAME`, one file per
//! kind and one line each in [`robots!`] below.
//!
//! A kind says what it is called, what it takes (lengths, a polygon) and
//! the body it makes of them. Every body is one of three primitives —
//! a point, a disk, a convex polygon ([`RobotShape`]) — and everything
//! below the language works on those: the motion checker, the C-space, the
//! validator, the planners' robot tables ([`RobotShape`] decides whether a
//! body rotates) and the pictures (drawn from the body). So a new kind
//! whose body is one of them (an ellipse as a polygon of many sides, a
//! capsule's hull) is its file and its line, and every planner, check and
//! picture takes it; a new *primitive* is a change to the geometry.
//!
//! How a robot moves is a separate clause: `steer MODEL RADIUS` makes a
//! car of any kind with a body (SPEC 2.4).

use super::{Point, RobotShape};

/// What a kind takes after its keyword, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arg {
    /// A positive length (`disk 0.3`), named for the diagnostics.
    Length(&'static str),
    /// A simple polygon, as a list of points (`polygon [(0, 0), ...]`),
    /// named for the diagnostics.
    Polygon(&'static str),
}

/// An argument as the language checked it: a positive finite length, or
/// a simple polygon's vertices, counter-clockwise, without repeats.
#[derive(Clone, Debug, PartialEq)]
pub enum ArgValue {
    Length(f64),
    Polygon(Vec<Point>),
}

/// Why a kind cannot make a body of its arguments: a diagnostic's parts,
/// located by the language at the argument `arg`.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyError {
    /// The argument it is about (an index into the kind's [`Arg`]s).
    pub arg: usize,
    /// The diagnostic's code (`scen::analyze::...`).
    pub code: &'static str,
    pub message: String,
    pub label: String,
    pub help: String,
}

/// One robot kind.
pub struct RobotModel {
    /// The word after `robot NAME`.
    pub keyword: &'static str,
    /// One line for the docs and the language server.
    pub summary: &'static str,
    /// A declaration, for the docs and help lines (`robot r disk 0.3`).
    pub example: &'static str,
    pub args: &'static [Arg],
    /// The body of checked arguments (one per [`RobotModel::args`], of
    /// the matching variant), in the robot's own frame: the reference point
    /// is the origin, and a polygon is convex and counter-clockwise.
    pub body: fn(&[ArgValue]) -> Result<RobotShape, BodyError>,
}

impl std::fmt::Debug for RobotModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RobotModel")
            .field("keyword", &self.keyword)
            .finish()
    }
}

impl RobotModel {
    /// The lengths of checked arguments, in order (for the kinds' own
    /// `body` functions).
    pub fn lengths(args: &[ArgValue]) -> impl Iterator<Item = f64> + '_ {
        args.iter().filter_map(|a| match a {
            ArgValue::Length(x) => Some(*x),
            ArgValue::Polygon(_) => None,
        })
    }
}

macro_rules! robots {
    ($($module:ident,)*) => {
        $(mod $module;)*
        /// Every robot kind, in the order the docs list them.
        pub static ROBOTS: &[&RobotModel] = &[$(&$module::MODEL,)*];
    };
}

robots! {
    point,
    disk,
    rect,
    polygon,
}

/// The kind called `keyword`.
pub fn model(keyword: &str) -> Option<&'static RobotModel> {
    ROBOTS.iter().copied().find(|m| m.keyword == keyword)
}

/// Every kind's keyword, in the registry's order.
pub fn keywords() -> impl Iterator<Item = &'static str> {
    ROBOTS.iter().map(|m| m.keyword)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keywords_are_unique_words() {
        let mut seen = std::collections::HashSet::new();
        for m in ROBOTS {
            assert!(seen.insert(m.keyword), "{} twice", m.keyword);
            assert!(
                m.keyword
                    .chars()
                    .all(|c| c.is_ascii_lowercase() || c == '_'),
                "{}",
                m.keyword
            );
            assert!(m.example.starts_with("robot "), "{}", m.example);
            assert!(m.example.contains(m.keyword), "{}", m.example);
        }
    }

    #[test]
    fn each_kind_makes_its_body() {
        let square = vec![
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(0.0, 1.0),
        ];
        assert_eq!((model("point").unwrap().body)(&[]), Ok(RobotShape::Point));
        assert_eq!(
            (model("disk").unwrap().body)(&[ArgValue::Length(0.5)]),
            Ok(RobotShape::Disk(0.5))
        );
        let rect = (model("rect").unwrap().body)(&[ArgValue::Length(1.0), ArgValue::Length(1.0)]);
        assert_eq!(
            rect,
            Ok(RobotShape::Polygon(crate::ConvexPolygon {
                vertices: square.clone()
            }))
        );
        let poly = (model("polygon").unwrap().body)(&[ArgValue::Polygon(square.clone())]);
        assert_eq!(rect, poly);
        // Not convex: a notch in the square.
        let notch = vec![
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(0.5, 0.5),
            Point::new(1.0, 1.0),
            Point::new(0.0, 1.0),
        ];
        let e = (model("polygon").unwrap().body)(&[ArgValue::Polygon(notch)]).unwrap_err();
        assert_eq!(e.code, "scen::analyze::robot_not_convex");
    }
}

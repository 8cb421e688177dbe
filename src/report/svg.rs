//! A static SVG picture of a run (`scen run --svg`): the world, each plan's
//! layers that its planner marked for the picture (grown obstacles, graphs,
//! trees; [`crate::planners::layers`]) and its path in the plan's colour,
//! the robot's body at start and goal, a legend and the title — for people
//! without the viewer.
//!
//! The picture is drawn in pixels: the world (the bounds, grown by a margin
//! and the largest robot's radius) is scaled so its longer side is
//! [`PLOT_SIZE`] pixels, with y flipped so the world's y axis points up.
//! Colours are those of the Rerun sink ([`crate::viz::plan_colour`]).

use std::fmt::Write as _;

use crate::geometry::{Aabb, Config, Point, RobotShape, Shape};
use crate::planners::layers::{Drawing, Layer, Svg};
use crate::run::{PlanRun, RunReport};
use crate::scenario::{Plan, Scenario};
use crate::viz::{
    FAIL_RED, OBSTACLE_GREY, blocked_boxes, plan_colour, role_colour, weight_boxes, weight_colour,
};

/// Pixels along the longer side of the drawn world.
const PLOT_SIZE: f64 = 800.0;
/// Pixels around the plot.
const PAD: f64 = 12.0;
/// Height of the title band above the plot.
const HEADER: f64 = 34.0;
/// Height of one legend row below the plot.
const ROW: f64 = 20.0;
const BACKGROUND: &str = "#fcfcfa";
const INK: &str = "#333333";

/// The SVG document as text. The same report gives the same text.
pub fn to_svg(report: &RunReport) -> String {
    let scenario = &report.scenario;
    let view = View::fit(scenario);
    let mut runs: Vec<(&Plan, &PlanRun)> = report
        .plans
        .iter()
        .filter_map(|run| Some((scenario.plans.get(run.plan)?, run)))
        .collect();
    runs.sort_by_key(|(_, run)| run.plan);

    let width = (view.plot_width() + 2.0 * PAD).max(420.0);
    let legend_top = HEADER + view.plot_height() + PAD;
    let height = legend_top + ROW * (runs.len() + 1) as f64 + PAD;
    let title = title(scenario);

    let mut svg = String::new();
    svg.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        svg,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
         viewBox=\"0 0 {w} {h}\" font-family=\"sans-serif\" font-size=\"13\">",
        w = num(width),
        h = num(height),
    );
    let _ = writeln!(svg, "<title>{}</title>", escape(&title));
    let _ = writeln!(
        svg,
        "<rect width=\"{}\" height=\"{}\" fill=\"{BACKGROUND}\"/>",
        num(width),
        num(height)
    );
    let _ = writeln!(
        svg,
        "<text x=\"{PAD}\" y=\"{}\" font-size=\"16\" font-weight=\"bold\" fill=\"{INK}\">{}</text>",
        num(HEADER - 12.0),
        escape(&title)
    );
    draw_obstacles(&mut svg, &view, scenario);
    let b = view.rect(&scenario.world.bounds);
    let _ = writeln!(
        svg,
        "<rect id=\"bounds\" {b} fill=\"none\" stroke=\"{INK}\" stroke-width=\"1\"/>"
    );
    for &(plan, run) in &runs {
        draw_plan(&mut svg, &view, scenario, plan, run);
    }
    draw_legend(&mut svg, report, &runs, legend_top);
    svg.push_str("</svg>\n");
    svg
}

/// The scenario's title, or its file name when it has none.
fn title(scenario: &Scenario) -> String {
    scenario.title.clone().unwrap_or_else(|| {
        scenario.file.file_name().map_or_else(
            || scenario.file.display().to_string(),
            |n| n.to_string_lossy().into(),
        )
    })
}

/// World-to-pixel mapping: x right, y up in the world; y down in pixels.
struct View {
    extent: Aabb,
    /// Pixels per world unit.
    scale: f64,
}

impl View {
    fn fit(scenario: &Scenario) -> View {
        let bounds = scenario.world.bounds;
        let reach = scenario
            .plans
            .iter()
            .filter_map(|p| scenario.robots.get(p.robot))
            .map(|r| r.shape.radius())
            .fold(0.0, f64::max);
        let size = bounds.width().max(bounds.height());
        let margin = (0.03 * size + reach).max(f64::EPSILON);
        let extent = Aabb {
            min: Point::new(bounds.min.x - margin, bounds.min.y - margin),
            max: Point::new(bounds.max.x + margin, bounds.max.y + margin),
        };
        let scale = PLOT_SIZE / extent.width().max(extent.height());
        View { extent, scale }
    }

    fn plot_width(&self) -> f64 {
        self.extent.width() * self.scale
    }

    fn plot_height(&self) -> f64 {
        self.extent.height() * self.scale
    }

    fn x(&self, x: f64) -> f64 {
        PAD + (x - self.extent.min.x) * self.scale
    }

    fn y(&self, y: f64) -> f64 {
        HEADER + (self.extent.max.y - y) * self.scale
    }

    /// `x,y` of a world point, in pixels.
    fn xy(&self, p: Point) -> String {
        format!("{},{}", num(self.x(p.x)), num(self.y(p.y)))
    }

    /// `x y x y ...` of world points, for `points` attributes.
    fn points(&self, ps: &[Point]) -> String {
        let xs: Vec<String> = ps
            .iter()
            .filter(|p| p.x.is_finite() && p.y.is_finite())
            .map(|&p| self.xy(p))
            .collect();
        xs.join(" ")
    }

    /// The `x y width height` attributes of a world box.
    fn rect(&self, b: &Aabb) -> String {
        format!(
            "x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"",
            num(self.x(b.min.x)),
            num(self.y(b.max.y)),
            num(b.width() * self.scale),
            num(b.height() * self.scale)
        )
    }

    /// A box as a closed sub-path, for one `<path>` holding many boxes.
    fn box_path(&self, b: &Aabb) -> String {
        format!(
            "M{} {}h{}v{}h{}z",
            num(self.x(b.min.x)),
            num(self.y(b.max.y)),
            num(b.width() * self.scale),
            num(b.height() * self.scale),
            num(-b.width() * self.scale)
        )
    }
}

fn draw_obstacles(svg: &mut String, view: &View, scenario: &Scenario) {
    let _ = writeln!(
        svg,
        "<g id=\"obstacles\" fill=\"{}\" stroke=\"{}\" stroke-width=\"1\">",
        hex(OBSTACLE_GREY),
        hex(OBSTACLE_GREY.map(|c| c / 2))
    );
    for obstacle in &scenario.world.obstacles {
        let name = escape(&obstacle.name);
        match &obstacle.shape {
            Shape::Polygon { outline, .. } => {
                let _ = writeln!(
                    svg,
                    "<polygon id=\"{name}\" points=\"{}\"/>",
                    view.points(outline)
                );
            }
            Shape::Rect(b) => {
                let _ = writeln!(svg, "<rect id=\"{name}\" {}/>", view.rect(b));
            }
            Shape::Disk { center, radius } => {
                let _ = writeln!(
                    svg,
                    "<circle id=\"{name}\" cx=\"{}\" cy=\"{}\" r=\"{}\"/>",
                    num(view.x(center.x)),
                    num(view.y(center.y)),
                    num(radius * view.scale)
                );
            }
            Shape::Segment(a, b) => {
                let _ = writeln!(
                    svg,
                    "<line id=\"{name}\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" \
                     stroke-width=\"3\" stroke-linecap=\"round\"/>",
                    num(view.x(a.x)),
                    num(view.y(a.y)),
                    num(view.x(b.x)),
                    num(view.y(b.y))
                );
            }
            Shape::Grid(grid) => {
                // Weights 2–9 under the blocked cells, one path per weight.
                let weights = weight_boxes(grid);
                for w in 2..=9u8 {
                    let d: String = weights
                        .iter()
                        .filter(|(k, _)| *k == w)
                        .map(|(_, b)| view.box_path(b))
                        .collect();
                    if !d.is_empty() {
                        let [r, g, b, a] = weight_colour(w);
                        let _ = writeln!(
                            svg,
                            "<path class=\"weight-{w}\" stroke=\"none\" fill=\"{}\" fill-opacity=\"{}\" d=\"{d}\"/>",
                            hex([r, g, b]),
                            num(f64::from(a) / 255.0)
                        );
                    }
                }
                // One path of merged boxes keeps a 512×512 map small.
                let d: String = blocked_boxes(grid)
                    .iter()
                    .map(|b| view.box_path(b))
                    .collect();
                if !d.is_empty() {
                    let _ = writeln!(svg, "<path id=\"{name}\" stroke=\"none\" d=\"{d}\"/>");
                }
            }
        }
    }
    svg.push_str("</g>\n");
}

/// Grown obstacles, the path, the robot's body at start and goal, and the
/// start and goal markers of one plan.
fn draw_plan(svg: &mut String, view: &View, scenario: &Scenario, plan: &Plan, run: &PlanRun) {
    let colour = hex(plan_colour(run.plan));
    let _ = writeln!(svg, "<g id=\"plan-{}\">", escape(&plan.name));
    for layer in &run.outcome.layers {
        if let Some(style) = layer.style.svg {
            draw_layer(svg, view, layer, style, run.plan);
        }
    }
    draw_motions(svg, view, run, &colour);

    let path = run.outcome.path.as_deref().filter(|p| !p.is_empty());
    if let Some(path) = path {
        let xy: Vec<Point> = path.iter().map(Config::xy).collect();
        let _ = writeln!(
            svg,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"2.5\" \
             stroke-linejoin=\"round\" stroke-linecap=\"round\"/>",
            view.points(&xy)
        );
    }

    // A rotating robot's body at a few poses along its path, lightly: how
    // it turned on the way.
    if let (Some(path), Some(robot)) = (path, scenario.robots.get(plan.robot))
        && robot.shape.rotates()
    {
        for c in poses_along(path, BODIES_ALONG) {
            draw_body_as(svg, view, &robot.shape, c, &colour, 0.04, 0.5);
        }
    }

    // The path's own ends when there is one (they carry the θ it used).
    let start = path
        .and_then(|p| p.first().copied())
        .unwrap_or(plan.params.start);
    let goal = path.and_then(|p| p.last().copied()).or(plan.params.goal);
    if let Some(robot) = scenario.robots.get(plan.robot) {
        for c in std::iter::once(start).chain(goal) {
            draw_body(svg, view, &robot.shape, c, &colour);
        }
    }
    let _ = writeln!(
        svg,
        "<circle cx=\"{}\" cy=\"{}\" r=\"4.5\" fill=\"{colour}\" stroke=\"white\" stroke-width=\"1.5\"/>",
        num(view.x(start.x)),
        num(view.y(start.y))
    );
    if let Some(goal) = goal {
        let (x, y) = (view.x(goal.x), view.y(goal.y));
        let diamond = [(0.0, -6.0), (6.0, 0.0), (0.0, 6.0), (-6.0, 0.0)]
            .map(|(dx, dy)| format!("{},{}", num(x + dx), num(y + dy)))
            .join(" ");
        let _ = writeln!(
            svg,
            "<polygon points=\"{diamond}\" fill=\"{colour}\" stroke=\"white\" stroke-width=\"1.5\"/>"
        );
    }
    svg.push_str("</g>\n");
}

/// One layer the planner marked for the SVG ([`Layer::style`]).
fn draw_layer(svg: &mut String, view: &View, layer: &Layer, style: Svg, plan: usize) {
    let [r, g, b, _] = role_colour(layer.style.colour, plan);
    let colour = hex([r, g, b]);
    let width = if layer.style.width > 0.0 {
        layer.style.width
    } else {
        1.0
    };
    let mut attrs = String::new();
    if style.fill > 0.0 {
        let _ = write!(attrs, "fill=\"{colour}\" fill-opacity=\"{}\"", style.fill);
    } else {
        attrs.push_str("fill=\"none\"");
    }
    if style.stroke > 0.0 {
        let _ = write!(
            attrs,
            " stroke=\"{colour}\" stroke-opacity=\"{}\" stroke-width=\"{width}\"",
            style.stroke
        );
        if style.dashed {
            attrs.push_str(" stroke-dasharray=\"4 3\"");
        }
    }
    let _ = writeln!(svg, "<g {attrs}>");
    match &layer.drawing {
        Drawing::Segments(segments) => {
            for (a, b) in segments {
                let _ = writeln!(
                    svg,
                    "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/>",
                    num(view.x(a.x)),
                    num(view.y(a.y)),
                    num(view.x(b.x)),
                    num(view.y(b.y))
                );
            }
        }
        Drawing::Polylines(lines) => {
            for line in lines {
                let _ = writeln!(svg, "<polyline points=\"{}\"/>", view.points(line));
            }
        }
        Drawing::Polygons(outlines) => {
            for outline in outlines {
                let _ = writeln!(svg, "<polygon points=\"{}\"/>", view.points(outline));
            }
        }
        Drawing::Boxes(boxes) if !boxes.is_empty() => {
            let d: String = boxes.iter().map(|b| view.box_path(b)).collect();
            let _ = writeln!(svg, "<path d=\"{d}\"/>");
        }
        Drawing::Points(points) => {
            for p in points {
                let _ = writeln!(
                    svg,
                    "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"/>",
                    num(view.x(p.x)),
                    num(view.y(p.y)),
                    num(f64::from(width))
                );
            }
        }
        Drawing::Arrows(arrows) => {
            for (p, v) in arrows {
                let _ = writeln!(
                    svg,
                    "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/>",
                    num(view.x(p.x)),
                    num(view.y(p.y)),
                    num(view.x(p.x + v.x)),
                    num(view.y(p.y + v.y))
                );
            }
        }
        // Text, boxes without boxes, and 3D lines are the viewer's.
        Drawing::Boxes(_) | Drawing::Text(_) | Drawing::Polylines3D(_) => {}
    }
    svg.push_str("</g>\n");
}

/// Motions that are not the path: what a run executed before it stopped
/// short of the goal, and a driven robot's trajectory.
fn draw_motions(svg: &mut String, view: &View, run: &PlanRun, colour: &str) {
    let trajectory = &run.outcome.trajectory;
    if trajectory.len() > 1 {
        let xy: Vec<Point> = trajectory.iter().map(Config::xy).collect();
        let _ = writeln!(
            svg,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\" stroke-opacity=\"0.6\" stroke-dasharray=\"6 3\"/>",
            view.points(&xy)
        );
    }
    if let Some(drive) = run.drive.as_ref().filter(|d| !d.samples.is_empty()) {
        let xy: Vec<Point> = drive.samples.iter().map(|(_, c)| c.xy()).collect();
        let _ = writeln!(
            svg,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1\" stroke-dasharray=\"2 2\"/>",
            view.points(&xy)
        );
    }
}

/// Bodies drawn along a rotating robot's path, between start and goal.
const BODIES_ALONG: usize = 5;

/// `n` configurations evenly spread along `path` by (x, y) length plus
/// rotation (so turning in place counts), start and goal excluded; θ along
/// the shorter arc, as the validator interpolates.
fn poses_along(path: &[Config], n: usize) -> Vec<Config> {
    let step = |a: &Config, b: &Config| {
        (b.x - a.x).hypot(b.y - a.y) + crate::geometry::angle_diff(a.theta, b.theta).abs()
    };
    let total: f64 = path.windows(2).map(|w| step(&w[0], &w[1])).sum();
    if path.len() < 2 || total <= 0.0 {
        return Vec::new();
    }
    let mut out = Vec::with_capacity(n);
    let (mut i, mut before) = (0, 0.0);
    for k in 1..=n {
        let at = total * k as f64 / (n + 1) as f64;
        while i + 2 < path.len() && before + step(&path[i], &path[i + 1]) < at {
            before += step(&path[i], &path[i + 1]);
            i += 1;
        }
        let (a, b) = (path[i], path[i + 1]);
        let len = step(&a, &b);
        let t = if len > 0.0 {
            ((at - before) / len).clamp(0.0, 1.0)
        } else {
            0.0
        };
        out.push(Config::new(
            a.x + t * (b.x - a.x),
            a.y + t * (b.y - a.y),
            a.theta + t * crate::geometry::angle_diff(a.theta, b.theta),
        ));
    }
    out
}

/// The robot's body at `c`; a point robot has none (its marker shows it).
fn draw_body(svg: &mut String, view: &View, shape: &RobotShape, c: Config, colour: &str) {
    draw_body_as(svg, view, shape, c, colour, 0.15, 1.0);
}

/// [`draw_body`] with this fill and stroke opacity.
fn draw_body_as(
    svg: &mut String,
    view: &View,
    shape: &RobotShape,
    c: Config,
    colour: &str,
    fill: f32,
    stroke: f32,
) {
    let style = format!(
        "fill=\"{colour}\" fill-opacity=\"{fill}\" stroke=\"{colour}\" stroke-opacity=\"{stroke}\" stroke-width=\"1.5\""
    );
    match shape {
        RobotShape::Point => {}
        RobotShape::Disk(r) => {
            let _ = writeln!(
                svg,
                "<circle cx=\"{}\" cy=\"{}\" r=\"{}\" {style}/>",
                num(view.x(c.x)),
                num(view.y(c.y)),
                num(r * view.scale)
            );
        }
        RobotShape::Polygon(_) => {
            let _ = writeln!(
                svg,
                "<polygon points=\"{}\" {style}/>",
                view.points(&shape.placed_vertices(c))
            );
        }
    }
}

/// One row per plan (colour, name, kind, found or not, length), then the
/// checks' summary, in red when a check failed.
fn draw_legend(svg: &mut String, report: &RunReport, runs: &[(&Plan, &PlanRun)], top: f64) {
    svg.push_str("<g id=\"legend\">\n");
    for (row, &(plan, run)) in runs.iter().enumerate() {
        let y = top + ROW * row as f64 + ROW / 2.0;
        let colour = hex(plan_colour(run.plan));
        let status = match &run.outcome.path {
            Some(_) => match run.metrics.get("length") {
                Some(length) => format!("found, length {}", short(length.as_f64())),
                None => "found".to_string(),
            },
            None if run.outcome.gave_up => "not found (gave up)".to_string(),
            None => "not found".to_string(),
        };
        let _ = writeln!(
            svg,
            "<line x1=\"{PAD}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\" stroke=\"{colour}\" stroke-width=\"4\"/>",
            num(PAD + 24.0),
            y = num(y)
        );
        let _ = writeln!(
            svg,
            "<text x=\"{}\" y=\"{}\" fill=\"{INK}\">{} ({}): {}</text>",
            num(PAD + 32.0),
            num(y + 4.5),
            escape(&plan.name),
            escape(plan.kind()),
            escape(&status)
        );
    }
    let y = top + ROW * runs.len() as f64 + ROW / 2.0 + 4.5;
    let fill = if report.failed() > 0 {
        hex(FAIL_RED)
    } else {
        INK.to_string()
    };
    let _ = writeln!(
        svg,
        "<text x=\"{PAD}\" y=\"{}\" fill=\"{fill}\">checks: {} passed, {} failed \
         \u{2014} \u{25CF} start, \u{25C6} goal</text>",
        num(y),
        report.passed(),
        report.failed()
    );
    svg.push_str("</g>\n");
}

/// A pixel coordinate: two decimals, no trailing zeros, no `-0`.
fn num(x: f64) -> String {
    let s = format!("{x:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

/// A metric for the legend: at most three decimals.
fn short(x: f64) -> String {
    let s = format!("{x:.3}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

fn hex([r, g, b]: [u8; 3]) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// Text for XML content and attribute values.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for ch in text.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            // Control characters other than tab and newline are not XML.
            c if c.is_control() && c != '\t' && c != '\n' => out.push('\u{FFFD}'),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;
    use std::path::PathBuf;

    use super::*;
    use crate::diagnostics::{SourceMap, Span};
    use crate::geometry::{ConvexPolygon, Grid, Obstacle, World};
    use crate::planners::{MetricValue, PlanOutcome, layers};
    use crate::run::CheckOutcome;
    use crate::scenario::Robot;

    fn plan(name: &str, robot: usize, goal: Config) -> Plan {
        let planner = crate::planners::registry::PLANNERS[0];
        Plan::fixture(name, planner, robot, Config::new(1.0, 1.0, 0.0), Some(goal))
    }

    fn run(plan: usize, path: Option<Vec<Config>>) -> PlanRun {
        let found = path.is_some();
        PlanRun {
            plan,
            outcome: PlanOutcome {
                path,
                layers: layers::grown(vec![vec![
                    Point::new(3.0, 3.0),
                    Point::new(6.0, 3.0),
                    Point::new(6.0, 6.0),
                ]])
                .into_iter()
                .collect(),
                ..PlanOutcome::default()
            },
            metrics: [
                ("found".to_string(), MetricValue::Bool(found)),
                ("length".to_string(), MetricValue::Num(12.3456)),
            ]
            .into(),
            validation: None,
            drive: None,
        }
    }

    /// Every kind of obstacle, a rod, a disk and a point robot; plans
    /// `a` and `c` found paths, `b` did not.
    fn report(title: Option<&str>) -> RunReport {
        let rod = ConvexPolygon {
            vertices: vec![
                Point::new(-1.0, -0.1),
                Point::new(1.0, -0.1),
                Point::new(1.0, 0.1),
                Point::new(-1.0, 0.1),
            ],
        };
        let obstacle = |name: &str, shape| Obstacle {
            name: name.into(),
            shape,
        };
        let world = World {
            bounds: Aabb::from_corners(Point::new(0.0, 0.0), Point::new(20.0, 10.0)),
            obstacles: vec![
                obstacle(
                    "tri",
                    Shape::Polygon {
                        outline: vec![
                            Point::new(4.0, 4.0),
                            Point::new(6.0, 4.0),
                            Point::new(5.0, 5.0),
                        ],
                        pieces: Vec::new(),
                    },
                ),
                obstacle(
                    "box",
                    Shape::Rect(Aabb::from_corners(
                        Point::new(8.0, 1.0),
                        Point::new(9.0, 3.0),
                    )),
                ),
                obstacle(
                    "disk",
                    Shape::Disk {
                        center: Point::new(12.0, 7.0),
                        radius: 1.0,
                    },
                ),
                obstacle(
                    "wall",
                    Shape::Segment(Point::new(14.0, 0.0), Point::new(14.0, 5.0)),
                ),
                obstacle(
                    "map",
                    Shape::Grid(Grid {
                        cell: 0.5,
                        origin: Point::new(16.0, 6.0),
                        width: 4,
                        height: 2,
                        cells: vec![0, 0, 1, 0, 1, 0, 0, 0],
                    }),
                ),
            ],
        };
        let robot = |name: &str, shape| Robot {
            name: name.into(),
            shape,
            span: Span::default(),
        };
        let scenario = Scenario {
            benches: Vec::new(),
            file: PathBuf::from("scenarios/demo.scen"),
            title: title.map(String::from),
            world,
            obstacle_spans: Vec::new(),
            robots: vec![
                robot("rod", RobotShape::Polygon(rod)),
                robot("disk", RobotShape::Disk(0.5)),
                robot("dot", RobotShape::Point),
            ],
            plans: vec![
                plan("a", 0, Config::new(18.0, 2.0, 1.0)),
                plan("b", 1, Config::new(18.0, 8.0, 0.0)),
                plan("c", 2, Config::new(10.0, 9.0, 0.0)),
            ],
            checks: Vec::new(),
            sources: SourceMap::default(),
        };
        let path = |goal: Config| {
            Some(vec![
                Config::new(1.0, 1.0, 0.0),
                Config::new(7.0, 1.0, 0.5),
                goal,
            ])
        };
        RunReport {
            bench_runs: Vec::new(),
            skipped: Vec::new(),
            plans: vec![
                run(2, path(scenario.plans[2].params.start)),
                run(0, path(Config::new(18.0, 2.0, 1.0))),
                run(1, None),
            ],
            scenario,
            checks: vec![CheckOutcome {
                series: Default::default(),
                check: 0,
                passed: false,
                values: BTreeMap::new(),
            }],
        }
    }

    /// Checks that tags nest, that attribute values are quoted, and that
    /// every `&` starts an entity: enough of XML to catch a broken writer.
    fn assert_well_formed(svg: &str) {
        let mut stack: Vec<&str> = Vec::new();
        let mut rest = svg;
        assert!(rest.starts_with("<?xml"), "no XML declaration");
        while let Some(open) = rest.find('<') {
            let text = &rest[..open];
            assert_entities(text);
            let Some(close) = rest[open..].find('>') else {
                panic!("unterminated tag at {}", &rest[open..]);
            };
            let tag = &rest[open + 1..open + close];
            rest = &rest[open + close + 1..];
            assert_eq!(
                tag.matches('"').count() % 2,
                0,
                "unbalanced quotes in <{tag}>"
            );
            assert_entities(tag);
            if tag.starts_with('?') {
                continue;
            }
            if let Some(name) = tag.strip_prefix('/') {
                assert_eq!(stack.pop(), Some(name), "mismatched </{name}>");
            } else if !tag.ends_with('/') {
                let name = tag.split_whitespace().next().unwrap_or_default();
                stack.push(name);
            }
        }
        assert_entities(rest);
        assert!(stack.is_empty(), "unclosed tags: {stack:?}");
    }

    fn assert_entities(text: &str) {
        for (i, _) in text.match_indices('&') {
            let entity = &text[i..text[i..].find(';').map_or(text.len(), |e| i + e + 1)];
            assert!(
                ["&amp;", "&lt;", "&gt;", "&quot;", "&apos;"].contains(&entity),
                "bad entity {entity}"
            );
        }
    }

    #[test]
    fn svg_is_well_formed_with_hostile_title() {
        let svg = to_svg(&report(Some("<rods> & \"disks\" 'n' </svg>")));
        assert_well_formed(&svg);
        assert!(svg.contains("&lt;rods&gt; &amp; &quot;disks&quot; &apos;n&apos; &lt;/svg&gt;"));
        assert_eq!(svg.matches("<svg").count(), 1);
    }

    #[test]
    fn one_polyline_per_found_path_in_its_plans_colour() {
        let svg = to_svg(&report(Some("demo")));
        let polylines: Vec<&str> = svg.lines().filter(|l| l.starts_with("<polyline")).collect();
        assert_eq!(polylines.len(), 2);
        for (line, plan) in polylines.iter().zip([0, 2]) {
            assert!(
                line.contains(&format!("stroke=\"{}\"", hex(plan_colour(plan)))),
                "{line}"
            );
        }
    }

    #[test]
    fn draws_every_obstacle_kind_and_the_legend() {
        let svg = to_svg(&report(None));
        for id in [
            "tri", "box", "disk", "wall", "map", "bounds", "plan-a", "plan-b", "plan-c",
        ] {
            assert!(svg.contains(&format!("id=\"{id}\"")), "no {id}");
        }
        // Without a title, the file name stands in.
        assert!(svg.contains("<title>demo.scen</title>"));
        let kind = crate::planners::registry::PLANNERS[0].kind;
        assert!(svg.contains(&format!("a ({kind}): found, length 12.346")));
        assert!(svg.contains(&format!("b ({kind}): not found")));
        assert!(svg.contains("checks: 0 passed, 1 failed"));
    }

    #[test]
    fn grid_cells_become_few_boxes() {
        let svg = to_svg(&report(None));
        let map = svg
            .lines()
            .find(|l| l.contains("id=\"map\""))
            .unwrap_or_default();
        // Blocked: row 0 cols 0-1 and 3; row 1 cols 1-3: three runs.
        assert_eq!(map.matches('M').count(), 3, "{map}");
    }

    #[test]
    fn y_axis_points_up() {
        let view = View::fit(&report(None).scenario);
        assert!(view.y(10.0) < view.y(0.0));
        assert!(view.x(20.0) > view.x(0.0));
    }

    #[test]
    fn output_is_deterministic() {
        assert_eq!(to_svg(&report(Some("t"))), to_svg(&report(Some("t"))));
    }

    #[test]
    fn numbers_are_short() {
        assert_eq!(num(12.0), "12");
        assert_eq!(num(12.5), "12.5");
        assert_eq!(num(-0.001), "0");
        assert_eq!(num(1.23456), "1.23");
    }
}

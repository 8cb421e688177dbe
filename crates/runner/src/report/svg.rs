//! A static SVG picture of a run (`scen run --svg`, and `--png` through
//! [`crate::report::png`]): the world with axes in world units, each plan's
//! layers that its planner marked for the picture (C-obstacles, graphs,
//! trees; [`crate::contract::layers`]), its path in the plan's colour, the
//! robot's body at start and goal, and a legend: each plan's colour and
//! whether it found a path, and what each drawn layer means.
//!
//! The world (the bounds, grown by a margin and the largest robot's radius)
//! is scaled so its longer side is [`PLOT_SIZE`] pixels, with y flipped so
//! the world's y axis points up. Colours are those of the Rerun sink
//! ([`crate::palette::plan_colour`]). Layers go under every path, a layer of
//! thousands of edges (a PRM's roadmap) faded by its size, so paths stay
//! visible; each path has a light halo over what it crosses.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use super::sink::{Command, Product, Sink, needs_extension, the_file, write_file};
use crate::contract::layers::{Colour, Drawing, Layer, Rounded, Svg};
use crate::geometry::{Aabb, Config, Point, RobotShape, Shape};
use crate::palette::{
    FAIL_RED, OBSTACLE_GREY, agent_colour, blocked_boxes, plan_colour, role_colour, weight_boxes,
    weight_colour,
};
use crate::run::{PlanRun, RunReport};
use crate::scenario::{Plan, Scenario};

/// Pixels along the longer side of the drawn world.
const PLOT_SIZE: f64 = 800.0;
/// Pixels around the picture.
const PAD: f64 = 12.0;
/// Height of the title band above the plot.
const HEADER: f64 = 34.0;
/// Width left of the plot: the y axis's tick labels and name.
const AXIS_LEFT: f64 = 62.0;
/// Height below the plot: the x axis's tick labels and name.
const AXIS_BELOW: f64 = 46.0;
/// The narrowest picture (room for the legend of a narrow world).
const MIN_WIDTH: f64 = 460.0;
/// Height of one legend row.
const ROW: f64 = 20.0;
/// Font sizes of the text, the tick labels and the title.
const FONT: f64 = 13.0;
const TICK_FONT: f64 = 11.0;
const TITLE_FONT: f64 = 16.0;
/// The font; `--png` has exactly this one ([`crate::report::png`]).
const FONT_FAMILY: &str = "DejaVu Sans, Verdana, sans-serif";
const BACKGROUND: &str = "#fcfcfa";
const INK: &str = "#333333";
/// Key swatches of layers drawn for several plans, each in its colour.
const NEUTRAL: [u8; 3] = [100, 100, 100];
/// A kind of layer of more things than this (edges, points), over all
/// plans, is faded by its size.
const LARGE_LAYER: usize = 1_000;
/// At most about this many things of a large kind of layer are drawn
/// (every k-th edge): a denser shade says no more, and costs megabytes.
const MAX_DRAWN: usize = 4_000;
/// About this many axis ticks along the longer side.
const TICKS: f64 = 10.0;

/// The SVG document as text. The same report gives the same text.
pub fn to_svg(report: &RunReport) -> String {
    run_picture(report, None)
}

/// The picture at plan time `t` (an animation's frame, `--gif`): each
/// moving obstacle where it is then (none once it vanished), and the robot
/// of every plan with a trajectory or a drive where it is then; the title
/// says the time.
pub fn frame_at(report: &RunReport, t: f64) -> String {
    run_picture(report, Some(t))
}

fn run_picture(report: &RunReport, at: Option<f64>) -> String {
    let scenario = &report.scenario;
    let runs = plan_runs(report);
    let view = View::fit(scenario, &runs);

    let width = (AXIS_LEFT + view.plot_width() + 2.0 * PAD).max(MIN_WIDTH);
    let legend_top = HEADER + view.plot_height() + AXIS_BELOW;
    let layers = drawn_layers(&runs);
    let legend = Legend::new(report, &runs, &layers, width);
    let height = legend_top + legend.height() + PAD;
    // A family's picture says which sample it shows, and what it drew.
    let title = match super::text::sample_line(scenario) {
        Some(sample) => format!("{} — {sample}", title(scenario)),
        None => title(scenario),
    };
    let title = match at {
        Some(t) => format!("{title} — t = {t:.2} s"),
        None => title,
    };

    let mut svg = String::new();
    svg.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        svg,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
         viewBox=\"0 0 {w} {h}\" font-family=\"{FONT_FAMILY}\" font-size=\"{FONT}\">",
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
        "<text x=\"{PAD}\" y=\"{}\" font-size=\"{TITLE_FONT}\" font-weight=\"bold\" fill=\"{INK}\">{}</text>",
        num(HEADER - 12.0),
        escape(&title)
    );
    draw_axes(&mut svg, &view);
    // What lies beyond the frame (a rod's C-obstacles along the bounds) is
    // cut off there, not drawn over the axes and the legend.
    let _ = writeln!(
        svg,
        "<clipPath id=\"plot\"><rect {}/></clipPath>",
        view.rect(&view.extent)
    );
    svg.push_str("<g clip-path=\"url(#plot)\">\n");
    draw_obstacles(&mut svg, &view, scenario);
    draw_moving(&mut svg, &view, scenario, at);
    for drawn in &layers {
        draw_layer(&mut svg, &view, drawn);
    }
    svg.push_str("</g>\n");
    let b = view.rect(&scenario.world.bounds);
    let _ = writeln!(
        svg,
        "<rect id=\"bounds\" {b} fill=\"none\" stroke=\"{INK}\" stroke-width=\"1\"/>"
    );
    // A team's agents, each in its own colour (SPEC 2.10), under the
    // other plans' paths.
    let (teams, runs): (Vec<_>, Vec<_>) = runs.iter().partition(|(plan, _)| {
        scenario
            .robots
            .get(plan.robot)
            .is_some_and(|r| r.team.is_some())
    });
    for &(plan, run) in &teams {
        draw_team(&mut svg, &view, scenario, plan, run, at);
    }
    // Every plan's motions and paths over every plan's layers, then the
    // bodies and markers over every path.
    for &(_, run) in &runs {
        draw_motions(&mut svg, &view, run, &hex(plan_colour(run.plan)));
    }
    for &(_, run) in &runs {
        draw_path(&mut svg, &view, run, at.is_none());
    }
    for &(plan, run) in &runs {
        draw_plan(&mut svg, &view, scenario, plan, run);
    }
    // A frame shows where things are, not the times of their routes.
    if at.is_none() {
        draw_moving_times(&mut svg, &view, scenario);
    }
    if let Some(t) = at {
        for &(plan, run) in &runs {
            draw_robot_at(&mut svg, &view, scenario, plan, run, t);
        }
    }
    legend.draw(&mut svg, legend_top);
    svg.push_str("</svg>\n");
    svg
}

/// The runs with their plans, in the order the plans are declared.
fn plan_runs(report: &RunReport) -> Vec<(&Plan, &PlanRun)> {
    let mut runs: Vec<(&Plan, &PlanRun)> = report
        .plans
        .iter()
        .filter_map(|run| Some((report.scenario.plans.get(run.plan)?, run)))
        .collect();
    runs.sort_by_key(|(_, run)| run.plan);
    runs
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
    /// The bounds, the C-obstacles of disk robots along them, and every
    /// body and path drawn, with a small margin: a long rod's reach makes
    /// no empty border where nothing is drawn.
    fn fit(scenario: &Scenario, runs: &[(&Plan, &PlanRun)]) -> View {
        let bounds = scenario.world.bounds;
        let disk = runs
            .iter()
            .filter_map(|(p, _)| scenario.robots.get(p.robot))
            .filter_map(|r| match r.shape {
                RobotShape::Disk(r) => Some(r),
                _ => None,
            })
            .fold(0.0, f64::max);
        let mut corners = vec![
            Point::new(bounds.min.x - disk, bounds.min.y - disk),
            Point::new(bounds.max.x + disk, bounds.max.y + disk),
        ];
        for &(plan, run) in runs {
            let Some(robot) = scenario.robots.get(plan.robot) else {
                continue;
            };
            let path = run.outcome.path.as_deref().unwrap_or_default();
            corners.extend(path.iter().map(Config::xy));
            let mut poses = vec![plan.params.start];
            poses.extend(plan.params.goal);
            poses.extend(path.first().into_iter().chain(path.last()).copied());
            if robot.shape.rotates() {
                poses.extend(poses_along(path, BODIES_ALONG));
            }
            for c in poses {
                corners.extend(body_corners(&robot.shape, c));
            }
        }
        corners.retain(|p| p.x.is_finite() && p.y.is_finite());
        let drawn = Aabb::around(&corners);
        let size = bounds.width().max(bounds.height());
        let margin = (0.03 * size).max(f64::EPSILON);
        let extent = Aabb {
            min: Point::new(drawn.min.x - margin, drawn.min.y - margin),
            max: Point::new(drawn.max.x + margin, drawn.max.y + margin),
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
        AXIS_LEFT + (x - self.extent.min.x) * self.scale
    }

    fn y(&self, y: f64) -> f64 {
        HEADER + (self.extent.max.y - y) * self.scale
    }

    /// `x,y` of a world point, in pixels.
    fn xy(&self, p: Point) -> String {
        format!("{},{}", num(self.x(p.x)), num(self.y(p.y)))
    }

    /// A `<circle>` element of world radius `r` at `at`, with `attrs`
    /// (none when empty).
    fn circle(&self, at: Point, r: f64, attrs: &str) -> String {
        let sep = if attrs.is_empty() { "" } else { " " };
        format!(
            "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"{sep}{attrs}/>",
            num(self.x(at.x)),
            num(self.y(at.y)),
            num(r * self.scale)
        )
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

    /// The exact boundary of a grown region: its straight edges and, in
    /// pixels, its arcs. The picture shows the world as it is, so an arc
    /// counter-clockwise in the world is counter-clockwise on the screen,
    /// the negative-angle direction of SVG's y-down pixels: sweep flag 0.
    /// `None` for a single corner, which is a circle.
    fn rounded_path(&self, region: &Rounded) -> Option<String> {
        let arcs = region.arcs();
        let &(first, _) = arcs.first()?;
        let r = num(region.radius * self.scale);
        let mut d = format!("M{} {}", num(self.x(first.x)), num(self.y(first.y)));
        for (k, &(start, end)) in arcs.iter().enumerate() {
            if k > 0 {
                let _ = write!(d, "L{} {}", num(self.x(start.x)), num(self.y(start.y)));
            }
            let _ = write!(
                d,
                "A{r} {r} 0 0 0 {} {}",
                num(self.x(end.x)),
                num(self.y(end.y))
            );
        }
        d.push('z');
        Some(d)
    }
}

/// The step between axis ticks: 1, 2 or 5 × 10^k, the smallest that gives
/// at most about `target` ticks over `span` and at least `min_gap` world
/// units between ticks (room for their labels).
fn tick_step(span: f64, target: f64, min_gap: f64) -> f64 {
    let raw = (span / target).max(min_gap).max(f64::MIN_POSITIVE);
    let magnitude = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * magnitude)
        .find(|&s| s >= raw * (1.0 - 1e-9))
        .unwrap_or(10.0 * magnitude)
}

/// The ticks of `step` within `[lo, hi]`, as values and labels with the
/// decimals the step needs (`0.5` has one, `2` none).
fn ticks(lo: f64, hi: f64, step: f64) -> Vec<(f64, String)> {
    if !(step > 0.0 && lo.is_finite() && hi.is_finite()) {
        return Vec::new();
    }
    let decimals = (-step.log10() - 1e-9).ceil().max(0.0) as usize;
    let (first, last) = ((lo / step).ceil() as i64, (hi / step).floor() as i64);
    (first..=last)
        .map(|k| {
            let v = k as f64 * step;
            let label = format!("{v:.decimals$}");
            let label = if label
                .trim_start_matches('-')
                .chars()
                .all(|c| c == '0' || c == '.')
            {
                label.trim_start_matches('-').to_string()
            } else {
                label
            };
            (v, label)
        })
        .collect()
}

/// Light grid lines at the ticks, the plot's frame, and the ticks with
/// their labels in world units below and left of it.
fn draw_axes(svg: &mut String, view: &View) {
    let e = view.extent;
    let widest = [e.min.x, e.max.x, e.min.y, e.max.y]
        .iter()
        .map(|v| format!("{v:.2}").len())
        .max()
        .unwrap_or(4);
    // A label needs its width and a little more between its neighbours.
    let label_gap = (text_width(&"0".repeat(widest), TICK_FONT) + 12.0) / view.scale;
    let step = tick_step(e.width().max(e.height()), TICKS, label_gap);
    let xs = ticks(e.min.x, e.max.x, step);
    let ys = ticks(e.min.y, e.max.y, step);
    let (left, right) = (view.x(e.min.x), view.x(e.max.x));
    let (top, bottom) = (view.y(e.max.y), view.y(e.min.y));

    let mut grid = String::new();
    for (v, _) in &xs {
        let x = num(view.x(*v));
        let _ = write!(grid, "M{x} {}V{}", num(top), num(bottom));
    }
    for (v, _) in &ys {
        let y = num(view.y(*v));
        let _ = write!(grid, "M{} {y}H{}", num(left), num(right));
    }
    let _ = writeln!(
        svg,
        "<path id=\"grid\" d=\"{grid}\" fill=\"none\" stroke=\"#000000\" stroke-opacity=\"0.07\" stroke-width=\"1\"/>"
    );
    let _ = writeln!(
        svg,
        "<rect id=\"frame\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#9a9a9a\" stroke-width=\"1\"/>",
        num(left),
        num(top),
        num(right - left),
        num(bottom - top)
    );
    let mut marks = String::new();
    for (v, _) in &xs {
        let _ = write!(marks, "M{} {}v5", num(view.x(*v)), num(bottom));
    }
    for (v, _) in &ys {
        let _ = write!(marks, "M{} {}h-5", num(left), num(view.y(*v)));
    }
    let _ = writeln!(
        svg,
        "<path id=\"ticks\" d=\"{marks}\" stroke=\"{INK}\" stroke-width=\"1\"/>"
    );
    let _ = writeln!(
        svg,
        "<g id=\"x-axis\" font-size=\"{TICK_FONT}\" fill=\"{INK}\" text-anchor=\"middle\">"
    );
    for (v, label) in &xs {
        let _ = writeln!(
            svg,
            "<text class=\"tick\" x=\"{}\" y=\"{}\">{label}</text>",
            num(view.x(*v)),
            num(bottom + 18.0)
        );
    }
    let _ = writeln!(
        svg,
        "<text x=\"{}\" y=\"{}\" font-size=\"{FONT}\" font-style=\"italic\">x</text>",
        num((left + right) / 2.0),
        num(bottom + 36.0)
    );
    svg.push_str("</g>\n");
    let _ = writeln!(
        svg,
        "<g id=\"y-axis\" font-size=\"{TICK_FONT}\" fill=\"{INK}\" text-anchor=\"end\">"
    );
    for (v, label) in &ys {
        let _ = writeln!(
            svg,
            "<text class=\"tick\" x=\"{}\" y=\"{}\">{label}</text>",
            num(left - 8.0),
            num(view.y(*v) + 4.0)
        );
    }
    let mid = (top + bottom) / 2.0;
    let _ = writeln!(
        svg,
        "<text x=\"{PAD}\" y=\"{}\" font-size=\"{FONT}\" font-style=\"italic\" text-anchor=\"middle\" \
         transform=\"rotate(-90 {PAD} {})\">y</text>",
        num(mid),
        num(mid)
    );
    svg.push_str("</g>\n");
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

/// The moving obstacles (SPEC 2.9): each route dashed with its waypoints'
/// times, the shape where it starts (filled) and where it ends (outlined;
/// dotted when it vanishes there).
fn draw_moving(svg: &mut String, view: &View, scenario: &Scenario, at: Option<f64>) {
    use crate::geometry::timed::{After, MovingShape};
    if scenario.moving.is_empty() {
        return;
    }
    let grey = hex(OBSTACLE_GREY);
    let dark = hex(OBSTACLE_GREY.map(|c| c / 2));
    let _ = writeln!(svg, "<g id=\"moving\">");
    for o in &scenario.moving {
        let name = escape(&o.name);
        let (Some(first), Some(last)) = (o.route.first(), o.route.last()) else {
            continue;
        };
        let shape_at = |svg: &mut String, at: Point, attrs: &str| match &o.shape {
            MovingShape::Disk(r) => {
                let _ = writeln!(svg, "{}", view.circle(at, *r, attrs));
            }
            MovingShape::Pieces(pieces) => {
                for piece in pieces {
                    let placed: Vec<Point> = piece.iter().map(|v| at + v.coords).collect();
                    let _ = writeln!(
                        svg,
                        "<polygon points=\"{}\" {attrs}/>",
                        view.points(&placed)
                    );
                }
            }
        };
        let _ = writeln!(svg, "<g id=\"moving-{name}\">");
        let filled =
            format!("fill=\"{grey}\" fill-opacity=\"0.8\" stroke=\"{dark}\" stroke-width=\"1\"");
        // A frame: where it is at that instant, over its route.
        if let Some(t) = at {
            if o.route.len() > 1 {
                let points: Vec<Point> = o.route.iter().map(|w| w.at).collect();
                let _ = writeln!(
                    svg,
                    "<polyline class=\"route\" points=\"{}\" fill=\"none\" stroke=\"{dark}\" \
                     stroke-width=\"1\" stroke-opacity=\"0.5\" stroke-dasharray=\"6 4\"/>",
                    view.points(&points)
                );
            }
            if let Some(p) = o.position(t) {
                shape_at(svg, p, &filled);
            }
            svg.push_str("</g>\n");
            continue;
        }
        shape_at(svg, first.at, &filled);
        if o.route.len() > 1 {
            let points: Vec<Point> = o.route.iter().map(|w| w.at).collect();
            let _ = writeln!(
                svg,
                "<polyline class=\"route\" points=\"{}\" fill=\"none\" stroke=\"{dark}\" \
                 stroke-width=\"1.5\" stroke-dasharray=\"6 4\"/>",
                view.points(&points)
            );
            let dots = if o.after == After::Vanish {
                " stroke-dasharray=\"2 3\""
            } else {
                ""
            };
            shape_at(
                svg,
                last.at,
                &format!("fill=\"none\" stroke=\"{dark}\" stroke-width=\"1.5\"{dots}"),
            );
        }
        svg.push_str("</g>\n");
    }
    svg.push_str("</g>\n");
}

/// The times of the moving obstacles' waypoints, over everything else.
fn draw_moving_times(svg: &mut String, view: &View, scenario: &Scenario) {
    use crate::geometry::timed::After;
    if scenario.moving.is_empty() {
        return;
    }
    let _ = writeln!(
        svg,
        "<g id=\"moving-times\" stroke=\"#ffffff\" stroke-width=\"3\" paint-order=\"stroke\">"
    );
    // Every route's first and last times (and `gone`) first, then the
    // times between, each only where it overlaps no label already placed:
    // a dense route (a waypoint at every cell) keeps a readable subset.
    let size = FONT - 2.0;
    let mut placed = Labels::default();
    let mut label = |svg: &mut String, x: f64, y: f64, text: &str, always: bool| {
        if placed.take(x, y, text, size) || always {
            let _ = writeln!(
                svg,
                "<text class=\"time\" x=\"{}\" y=\"{}\" font-size=\"{}\" fill=\"{INK}\">{}</text>",
                num(x),
                num(y),
                num(size),
                escape(text)
            );
        }
    };
    let at = |p: crate::geometry::Point, dy: f64| (view.x(p.x) + 4.0, view.y(p.y) + dy);
    for o in &scenario.moving {
        let (Some(first), Some(last)) = (o.route.first(), o.route.last()) else {
            continue;
        };
        let (x, y) = at(first.at, -4.0);
        let start = format!("{}s", short(first.t));
        if o.route.len() == 1 {
            label(svg, x, y, &start, true);
        } else {
            let (lx, ly) = at(last.at, -4.0);
            let end = format!("{}s", short(last.t));
            // A route that ends where it began: one label with both times.
            let mut alone = Labels::default();
            alone.take(x, y, &start, size);
            if alone.take(lx, ly, &end, size) {
                label(svg, x, y, &start, true);
                label(svg, lx, ly, &end, true);
            } else {
                label(svg, x, y, &format!("{start}, {end}"), true);
            }
        }
        if o.after == After::Vanish {
            let (x, y) = at(last.at, FONT);
            label(svg, x, y, "gone", true);
        }
    }
    for o in &scenario.moving {
        let inner = o.route.len().saturating_sub(2);
        for w in o.route.iter().skip(1).take(inner) {
            let (x, y) = at(w.at, -4.0);
            label(svg, x, y, &format!("{}s", short(w.t)), false);
        }
    }
    svg.push_str("</g>\n");
}

/// The boxes of the labels placed so far, in pixels.
#[derive(Default)]
struct Labels(Vec<[f64; 4]>);

impl Labels {
    /// Places `text` at (x, y) (its baseline's start) unless it would
    /// overlap a label already placed; whether it was placed. A label is
    /// recorded either way when it overlaps nothing.
    fn take(&mut self, x: f64, y: f64, text: &str, size: f64) -> bool {
        // A character is about 0.6 of the font size wide.
        let b = [
            x,
            y - size,
            x + 0.6 * size * text.chars().count() as f64,
            y + 0.25 * size,
        ];
        let overlaps = |o: &[f64; 4]| b[0] < o[2] && o[0] < b[2] && b[1] < o[3] && o[1] < b[3];
        if self.0.iter().any(overlaps) {
            return false;
        }
        self.0.push(b);
        true
    }
}

/// A layer as the picture draws it: the plan it belongs to, its legend key,
/// and the stroke it gets (faded when its kind is large).
struct Drawn<'a> {
    layer: &'a Layer,
    style: Svg,
    plan: usize,
    key: String,
    /// The layer's kind, over all plans, draws more than [`LARGE_LAYER`]
    /// things.
    large: bool,
    /// Every `every`-th edge or point is drawn.
    every: usize,
}

/// The layers of every plan that the planners marked for the picture, in
/// drawing order: large kinds first (under the rest), then by the
/// planner's own order, then by plan.
fn drawn_layers<'a>(runs: &[(&Plan, &'a PlanRun)]) -> Vec<Drawn<'a>> {
    let mut sizes: BTreeMap<String, usize> = BTreeMap::new();
    let mut out = Vec::new();
    for &(_, run) in runs {
        for layer in &run.outcome.layers {
            let Some(style) = layer.style.svg else {
                continue;
            };
            if layer.drawing.is_empty() || matches!(layer.drawing, Drawing::Text(_)) {
                continue;
            }
            let key = layer_key(layer, style);
            *sizes.entry(key.clone()).or_default() += layer.drawing.len();
            out.push(Drawn {
                layer,
                style,
                plan: run.plan,
                key,
                large: false,
                every: 1,
            });
        }
    }
    for d in &mut out {
        let n = sizes.get(&d.key).copied().unwrap_or(0);
        let thinnable = matches!(d.layer.drawing, Drawing::Segments(_) | Drawing::Points(_));
        if n > LARGE_LAYER && thinnable {
            d.large = true;
            d.every = n.div_ceil(MAX_DRAWN);
            // The more edges drawn, the fainter each: the roadmap reads as
            // a shade, not a hairball over the paths.
            let drawn = n.div_ceil(d.every);
            let fade = LARGE_LAYER as f32 / drawn as f32;
            d.style.stroke = (d.style.stroke * fade).max(d.style.stroke.min(0.06));
            d.style.fill = (d.style.fill * fade).max(d.style.fill.min(0.04));
        }
    }
    out.sort_by(|a, b| {
        b.large
            .cmp(&a.large)
            .then(a.layer.style.order.total_cmp(&b.layer.style.order))
            .then(a.plan.cmp(&b.plan))
    });
    out
}

/// What a layer means in the legend: its planner's words, or its entity
/// without batch numbers (`tree/0007` is "tree", `raw_path` "raw path").
fn layer_key(layer: &Layer, style: Svg) -> String {
    if !style.key.is_empty() {
        return style.key.to_string();
    }
    layer
        .entity
        .split('/')
        .rfind(|part| !part.is_empty() && !part.chars().all(|c| c.is_ascii_digit()))
        .unwrap_or(&layer.entity)
        .replace('_', " ")
}

/// The width of a layer's lines, in pixels: its style's, thinner when
/// the layer is large.
fn line_width(drawn: &Drawn<'_>) -> f64 {
    let width = f64::from(drawn.layer.style.width);
    let width = if width > 0.0 { width } else { 1.0 };
    if drawn.large { width.min(0.5) } else { width }
}

/// One layer the planner marked for the SVG ([`Layer::style`]).
fn draw_layer(svg: &mut String, view: &View, drawn: &Drawn<'_>) {
    let style = drawn.style;
    let [r, g, b, _] = role_colour(drawn.layer.style.colour, drawn.plan);
    let colour = hex([r, g, b]);
    let width = line_width(drawn);
    let mut attrs = String::new();
    if style.fill > 0.0 {
        let _ = write!(
            attrs,
            "fill=\"{colour}\" fill-opacity=\"{}\"",
            num(f64::from(style.fill))
        );
    } else {
        attrs.push_str("fill=\"none\"");
    }
    if style.stroke > 0.0 {
        let _ = write!(
            attrs,
            " stroke=\"{colour}\" stroke-opacity=\"{}\" stroke-width=\"{}\"",
            num(f64::from(style.stroke)),
            num(width)
        );
        if style.dashed {
            attrs.push_str(" stroke-dasharray=\"4 3\"");
        }
    }
    let _ = writeln!(
        svg,
        "<g class=\"layer\" data-plan=\"{}\" data-key=\"{}\" {attrs}>",
        drawn.plan,
        escape(&drawn.key)
    );
    match &drawn.layer.drawing {
        Drawing::Segments(segments) => {
            // One path: a roadmap of ten thousand edges stays a small file.
            let mut d = String::new();
            for (a, b) in segments.iter().step_by(drawn.every) {
                if [a.x, a.y, b.x, b.y].iter().all(|v| v.is_finite()) {
                    let _ = write!(
                        d,
                        "M{} {}L{} {}",
                        num(view.x(a.x)),
                        num(view.y(a.y)),
                        num(view.x(b.x)),
                        num(view.y(b.y))
                    );
                }
            }
            let _ = writeln!(svg, "<path d=\"{d}\"/>");
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
        Drawing::Rounded(regions) => {
            for region in regions {
                match (view.rounded_path(region), region.corners.first()) {
                    (Some(d), _) => {
                        let _ = writeln!(svg, "<path d=\"{d}\"/>");
                    }
                    (None, Some(c)) => {
                        let _ = writeln!(svg, "{}", view.circle(*c, region.radius, ""));
                    }
                    (None, None) => {}
                }
            }
        }
        Drawing::Boxes(boxes) => {
            let d: String = boxes.iter().map(|b| view.box_path(b)).collect();
            let _ = writeln!(svg, "<path d=\"{d}\"/>");
        }
        Drawing::Points(points) => {
            let radius = if drawn.large { width.min(1.0) } else { width };
            for p in points.iter().step_by(drawn.every) {
                let _ = writeln!(
                    svg,
                    "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"/>",
                    num(view.x(p.x)),
                    num(view.y(p.y)),
                    num(radius)
                );
            }
        }
        Drawing::Arrows(arrows) => {
            let mut d = String::new();
            for (p, v) in arrows {
                let _ = write!(
                    d,
                    "M{} {}L{} {}",
                    num(view.x(p.x)),
                    num(view.y(p.y)),
                    num(view.x(p.x + v.x)),
                    num(view.y(p.y + v.y))
                );
            }
            let _ = writeln!(svg, "<path d=\"{d}\"/>");
        }
        // Text and 3D lines are the viewer's.
        Drawing::Text(_) | Drawing::Polylines3D(_) => {}
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
            "<polyline class=\"executed\" points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\" stroke-opacity=\"0.6\" stroke-dasharray=\"6 3\"/>",
            view.points(&xy)
        );
    }
    if let Some(drive) = run.drive.as_ref().filter(|d| !d.samples.is_empty()) {
        let xy: Vec<Point> = drive.samples.iter().map(|(_, c)| c.xy()).collect();
        let _ = writeln!(
            svg,
            "<polyline class=\"driven\" points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1\" stroke-dasharray=\"2 2\"/>",
            view.points(&xy)
        );
    }
}

/// A plan's path in its colour, over a light halo that sets it off from
/// the layers under it.
fn draw_path(svg: &mut String, view: &View, run: &PlanRun, waits: bool) {
    let Some(path) = run.outcome.path.as_deref().filter(|p| !p.is_empty()) else {
        return;
    };
    let xy: Vec<Point> = path.iter().map(Config::xy).collect();
    let points = view.points(&xy);
    let _ = writeln!(
        svg,
        "<polyline class=\"halo\" points=\"{points}\" fill=\"none\" stroke=\"#ffffff\" stroke-opacity=\"0.85\" \
         stroke-width=\"6\" stroke-linejoin=\"round\" stroke-linecap=\"round\"/>"
    );
    let _ = writeln!(
        svg,
        "<polyline class=\"path\" points=\"{points}\" fill=\"none\" stroke=\"{}\" stroke-width=\"2.5\" \
         stroke-linejoin=\"round\" stroke-linecap=\"round\"{}/>",
        hex(plan_colour(run.plan)),
        dash_attr(run.plan)
    );
    // A trajectory's waits (SPEC 2.9): where and when the robot stands.
    if let Some(times) = run
        .outcome
        .times
        .as_deref()
        .filter(|t| waits && t.len() == path.len())
    {
        for k in 1..path.len() {
            let (a, b) = (path[k - 1], path[k]);
            if a.x == b.x && a.y == b.y {
                let _ = writeln!(
                    svg,
                    "<text class=\"wait\" x=\"{}\" y=\"{}\" font-size=\"{}\" fill=\"{}\" \
                     stroke=\"#ffffff\" stroke-width=\"3\" paint-order=\"stroke\">waits {}–{} s</text>",
                    num(view.x(a.x) + 5.0),
                    num(view.y(a.y) + FONT + 2.0),
                    num(FONT - 1.0),
                    hex(plan_colour(run.plan)),
                    short(times[k - 1]),
                    short(times[k])
                );
            }
        }
    }
}

/// The dash patterns of paths, by plan (cycling): overlaid paths differ
/// in their line as well as their colour, for readers who cannot tell the
/// colours apart and for pictures printed in grey. The first is solid.
const PATH_DASHES: &[&str] = &["", "9 4", "2 4", "12 3 2 3", "5 3", "1 3 6 3"];

/// The `stroke-dasharray` attribute of plan `plan`'s path (none when solid).
fn dash_attr(plan: usize) -> String {
    match PATH_DASHES[plan % PATH_DASHES.len()] {
        "" => String::new(),
        dashes => format!(" stroke-dasharray=\"{dashes}\""),
    }
}

/// The robot's body along a rotating robot's path and at start and goal,
/// and the start and goal markers of one plan.
fn draw_plan(svg: &mut String, view: &View, scenario: &Scenario, plan: &Plan, run: &PlanRun) {
    let colour = hex(plan_colour(run.plan));
    let _ = writeln!(svg, "<g id=\"plan-{}\">", escape(&plan.name));
    let path = run.outcome.path.as_deref().filter(|p| !p.is_empty());
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
    start_marker(svg, view.x(start.x), view.y(start.y), &colour);
    if let Some(goal) = goal {
        goal_marker(svg, view.x(goal.x), view.y(goal.y), &colour);
    }
    svg.push_str("</g>\n");
}

/// A frame's robot (`--gif`): where a plan's trajectory, or its drive, has
/// it at `t`, filled in the plan's colour.
fn draw_robot_at(
    svg: &mut String,
    view: &View,
    scenario: &Scenario,
    plan: &Plan,
    run: &PlanRun,
    t: f64,
) {
    use crate::geometry::timed::robot_at;
    let Some(robot) = scenario.robots.get(plan.robot) else {
        return;
    };
    let pose = match (run.outcome.timed(), &run.drive) {
        (Some(points), _) => robot_at(&points, t),
        (None, Some(drive)) if !drive.samples.is_empty() => {
            let k = drive.samples.partition_point(|(s, _)| *s <= t);
            drive.samples[k.saturating_sub(1)].1
        }
        _ => return,
    };
    let colour = hex(plan_colour(run.plan));
    let _ = writeln!(svg, "<g class=\"now\" id=\"now-{}\">", escape(&plan.name));
    draw_body_as(svg, view, &robot.shape, pose, &colour, 0.6, 1.0);
    if matches!(robot.shape, RobotShape::Point) {
        start_marker(svg, view.x(pose.x), view.y(pose.y), &colour);
    }
    svg.push_str("</g>\n");
}

/// When a team's last agent arrives, in seconds: a continuous team's last
/// time, else a step a second.
pub(crate) fn team_end(paths: &[Vec<Point>], times: Option<&[Vec<f64>]>) -> f64 {
    match times {
        Some(times) => times
            .iter()
            .filter_map(|t| t.last().copied())
            .fold(0.0, f64::max),
        None => paths
            .iter()
            .map(|p| p.len().saturating_sub(1))
            .max()
            .unwrap_or(0) as f64,
    }
}

/// Where an agent is at `t` seconds (a step a second without `times`):
/// between its points, at its last point after its path ends.
fn agent_at(path: &[Point], times: Option<&[f64]>, t: f64) -> Option<Point> {
    let last = path.len().checked_sub(1)?;
    let t = t.max(0.0);
    let (k, f) = match times.filter(|ts| ts.len() == path.len()) {
        Some(ts) => {
            let k = ts.partition_point(|&s| s <= t).saturating_sub(1).min(last);
            let span = ts.get(k + 1).map_or(0.0, |&next| next - ts[k]);
            (
                k,
                if span > 0.0 {
                    ((t - ts[k]) / span).clamp(0.0, 1.0)
                } else {
                    0.0
                },
            )
        }
        None => {
            let k = (t.floor() as usize).min(last);
            (k, t - k as f64)
        }
    };
    if k == last {
        return Some(path[last]);
    }
    Some(path[k] + (path[k + 1] - path[k]) * f)
}

/// A team plan (SPEC 2.10): each agent's path in its own colour, its start
/// (a dot) and goal (a diamond); in a frame, each agent where it is at `at`.
fn draw_team(
    svg: &mut String,
    view: &View,
    scenario: &Scenario,
    plan: &Plan,
    run: &PlanRun,
    at: Option<f64>,
) {
    let Some(team) = plan.team(scenario) else {
        return;
    };
    let _ = writeln!(svg, "<g class=\"team\" id=\"plan-{}\">", escape(&plan.name));
    let paths = run.outcome.agents.as_deref();
    // Thinner lines for a crowd; a small team's paths drawn a few pixels
    // apart, so that two agents passing along one corridor both show, and
    // named at their starts.
    let small = team.len() <= 20;
    let width = if small { 2.0 } else { 1.2 };
    for (k, agent) in team.iter().enumerate() {
        let colour = hex(agent_colour(k));
        let shift = if small {
            (k % 5) as f64 * 4.0 - 8.0
        } else {
            0.0
        };
        if let Some(path) = paths.and_then(|p| p.get(k)).filter(|p| p.len() > 1) {
            let points = path
                .iter()
                .map(|&p| format!("{},{}", num(view.x(p.x) + shift), num(view.y(p.y) + shift)))
                .collect::<Vec<_>>()
                .join(" ");
            let _ = writeln!(
                svg,
                "<polyline class=\"agent\" points=\"{points}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"{width}\" \
                 stroke-opacity=\"0.85\" stroke-linejoin=\"round\" stroke-linecap=\"round\"/>"
            );
        }
        if at.is_none() {
            let (sx, sy) = (view.x(agent.start.x) + shift, view.y(agent.start.y) + shift);
            start_marker(svg, sx, sy, &colour);
            goal_marker(
                svg,
                view.x(agent.goal.x) + shift,
                view.y(agent.goal.y) + shift,
                &colour,
            );
            if small {
                let _ = writeln!(
                    svg,
                    "<text class=\"agent-name\" x=\"{}\" y=\"{}\" font-size=\"{}\" fill=\"{colour}\" \
                     stroke=\"#ffffff\" stroke-width=\"3\" paint-order=\"stroke\">{}</text>",
                    num(sx + 6.0),
                    num(sy - 6.0),
                    num(FONT - 1.0),
                    escape(&agent.name)
                );
            }
        }
    }
    if let (Some(t), Some(paths)) = (at, paths) {
        let times = run.outcome.agent_times.as_deref();
        for (k, path) in paths.iter().enumerate() {
            if let Some(p) = agent_at(path, times.and_then(|ts| ts.get(k)).map(Vec::as_slice), t) {
                let colour = hex(agent_colour(k));
                start_marker(svg, view.x(p.x), view.y(p.y), &colour);
            }
        }
    }
    svg.push_str("</g>\n");
}

/// The start: a dot.
fn start_marker(svg: &mut String, x: f64, y: f64, colour: &str) {
    let _ = writeln!(
        svg,
        "<circle cx=\"{}\" cy=\"{}\" r=\"4.5\" fill=\"{colour}\" stroke=\"white\" stroke-width=\"1.5\"/>",
        num(x),
        num(y)
    );
}

/// The goal: a diamond.
fn goal_marker(svg: &mut String, x: f64, y: f64, colour: &str) {
    let diamond = [(0.0, -6.0), (6.0, 0.0), (0.0, 6.0), (-6.0, 0.0)]
        .map(|(dx, dy)| format!("{},{}", num(x + dx), num(y + dy)))
        .join(" ");
    let _ = writeln!(
        svg,
        "<polygon points=\"{diamond}\" fill=\"{colour}\" stroke=\"white\" stroke-width=\"1.5\"/>"
    );
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

/// The corners of the box around the robot's body at `c`.
fn body_corners(shape: &RobotShape, c: Config) -> Vec<Point> {
    match shape {
        RobotShape::Point => vec![c.xy()],
        RobotShape::Disk(r) => vec![Point::new(c.x - r, c.y - r), Point::new(c.x + r, c.y + r)],
        RobotShape::Polygon(_) => shape.placed_vertices(c),
    }
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
            let _ = writeln!(svg, "{}", view.circle(c.xy(), *r, &style));
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

/// How a legend entry shows what it names.
enum Swatch {
    /// A plan's path: a thick line in its colour and its dashes.
    Path([u8; 3], usize),
    /// A layer, drawn small in its own style.
    Layer {
        colour: [u8; 3],
        style: Svg,
        /// Points: a dot of this radius.
        dot: Option<f64>,
    },
    Obstacle,
    Body,
    Start,
    Goal,
    /// A dashed line in ink: a trajectory.
    Dashed(&'static str),
}

/// The legend under the plot: one row per plan (its colour, name, kind,
/// found or not, length), then a key to everything else drawn, flowed
/// into rows, then the checks' summary, in red when a check failed.
struct Legend {
    plans: Vec<(Swatch, String)>,
    /// Each key entry with its place: row (after the plans) and x.
    keys: Vec<(Swatch, String, usize, f64)>,
    key_rows: usize,
    checks: (String, bool),
}

impl Legend {
    fn new(
        report: &RunReport,
        runs: &[(&Plan, &PlanRun)],
        layers: &[Drawn<'_>],
        width: f64,
    ) -> Self {
        let scenario = &report.scenario;
        let plans = runs
            .iter()
            .map(|&(plan, run)| {
                let team = plan.team(scenario);
                let status = match (&run.outcome.path, &run.outcome.agents, team) {
                    // A team (SPEC 2.10): its agents, each in its colour.
                    (_, Some(_), Some(team)) => format!(
                        "{} agents, one colour each, sum of costs {}",
                        team.len(),
                        run.metrics
                            .get("sum_of_costs")
                            .map_or("—".into(), |v| short(v.as_f64()))
                    ),
                    (_, None, Some(team)) if run.outcome.gave_up => {
                        format!("{} agents, not found (gave up)", team.len())
                    }
                    (_, None, Some(team)) => format!("{} agents, not found", team.len()),
                    (path, _, None) => match path {
                        Some(_) => match run.metrics.get("length") {
                            Some(length) => format!("found, length {}", short(length.as_f64())),
                            None => "found".to_string(),
                        },
                        None if run.outcome.gave_up => "not found (gave up)".to_string(),
                        None => "not found".to_string(),
                    },
                };
                (
                    Swatch::Path(plan_colour(run.plan), run.plan),
                    format!("{} ({}): {status}", plan.name, plan.kind()),
                )
            })
            .collect();

        let mut entries: Vec<(Swatch, String)> = Vec::new();
        if !scenario.world.obstacles.is_empty() {
            entries.push((Swatch::Obstacle, "obstacles".into()));
        }
        // One entry per meaning, in the plan's colour when one plan drew it.
        let mut keys: Vec<(&str, &Drawn<'_>, bool)> = Vec::new();
        for d in layers {
            match keys.iter_mut().find(|(k, _, _)| *k == d.key) {
                Some((_, first, shared)) => *shared |= first.plan != d.plan,
                None => keys.push((&d.key, d, false)),
            }
        }
        for (key, d, shared) in keys {
            let role = d.layer.style.colour;
            let colour = if shared && matches!(role, Colour::Plan | Colour::Faint) {
                NEUTRAL
            } else {
                let [r, g, b, _] = role_colour(role, d.plan);
                [r, g, b]
            };
            let dot = matches!(d.layer.drawing, Drawing::Points(_))
                .then(|| f64::from(d.layer.style.width).clamp(2.0, 5.0));
            // The legend shows the layer's look, not its fading.
            let style = d.layer.style.svg.unwrap_or(d.style);
            let text = if d.large {
                let n: usize = layers
                    .iter()
                    .filter(|l| l.key == key)
                    .map(|l| l.layer.drawing.len())
                    .sum();
                let things = match d.layer.drawing {
                    Drawing::Points(_) => "points",
                    _ => "edges",
                };
                if d.every > 1 {
                    format!(
                        "{key} ({} {things}, 1 in {} drawn, faint)",
                        thousands(n),
                        d.every
                    )
                } else {
                    format!("{key} ({} {things}, faint)", thousands(n))
                }
            } else {
                key.to_string()
            };
            entries.push((Swatch::Layer { colour, style, dot }, text));
        }
        if runs.iter().any(|(_, r)| r.outcome.trajectory.len() > 1) {
            entries.push((Swatch::Dashed("6 3"), "executed before stopping".into()));
        }
        if runs.iter().any(|(_, r)| r.drive.is_some()) {
            entries.push((Swatch::Dashed("2 2"), "driven trajectory".into()));
        }
        if runs.iter().any(|(plan, _)| {
            scenario
                .robots
                .get(plan.robot)
                .is_some_and(|r| !matches!(r.shape, RobotShape::Point))
        }) {
            entries.push((Swatch::Body, "robot".into()));
        }
        entries.push((Swatch::Start, "start".into()));
        entries.push((Swatch::Goal, "goal".into()));

        let mut placed = Vec::with_capacity(entries.len());
        let (mut row, mut x) = (0, PAD);
        for (swatch, text) in entries {
            let w = SWATCH + 6.0 + text_width(&text, FONT) + 18.0;
            if x > PAD && x + w > width - PAD {
                row += 1;
                x = PAD;
            }
            placed.push((swatch, text, row, x));
            x += w;
        }
        let key_rows = if placed.is_empty() { 0 } else { row + 1 };
        Legend {
            plans,
            keys: placed,
            key_rows,
            checks: (
                format!(
                    "checks: {} passed, {} failed",
                    report.passed(),
                    report.failed()
                ),
                report.failed() > 0,
            ),
        }
    }

    fn height(&self) -> f64 {
        ROW * (self.plans.len() + self.key_rows + 1) as f64
    }

    fn draw(&self, svg: &mut String, top: f64) {
        let _ = writeln!(svg, "<g id=\"legend\" fill=\"{INK}\">");
        let middle = |row: usize| top + ROW * row as f64 + ROW / 2.0;
        for (row, (swatch, text)) in self.plans.iter().enumerate() {
            let y = middle(row);
            draw_swatch(svg, swatch, PAD, y);
            let _ = writeln!(
                svg,
                "<text class=\"plan\" x=\"{}\" y=\"{}\">{}</text>",
                num(PAD + SWATCH + 6.0),
                num(y + 4.5),
                escape(text)
            );
        }
        for (swatch, text, row, x) in &self.keys {
            let y = middle(self.plans.len() + row);
            draw_swatch(svg, swatch, *x, y);
            let _ = writeln!(
                svg,
                "<text class=\"key\" x=\"{}\" y=\"{}\">{}</text>",
                num(x + SWATCH + 6.0),
                num(y + 4.5),
                escape(text)
            );
        }
        let (text, failed) = &self.checks;
        let fill = if *failed {
            hex(FAIL_RED)
        } else {
            INK.to_string()
        };
        let _ = writeln!(
            svg,
            "<text class=\"checks\" x=\"{PAD}\" y=\"{}\" fill=\"{fill}\">{}</text>",
            num(middle(self.plans.len() + self.key_rows) + 4.5),
            escape(text)
        );
        svg.push_str("</g>\n");
    }
}

/// Width of a legend swatch.
const SWATCH: f64 = 26.0;

/// A swatch [`SWATCH`] wide from `x`, centred on `y`.
fn draw_swatch(svg: &mut String, swatch: &Swatch, x: f64, y: f64) {
    let (x0, x1, mid) = (num(x), num(x + SWATCH), x + SWATCH / 2.0);
    let area = |svg: &mut String, attrs: &str| {
        let _ = writeln!(
            svg,
            "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"12\" {attrs}/>",
            num(x + 2.0),
            num(y - 6.0),
            num(SWATCH - 4.0)
        );
    };
    match swatch {
        Swatch::Path(colour, plan) => {
            let _ = writeln!(
                svg,
                "<line x1=\"{x0}\" y1=\"{y}\" x2=\"{x1}\" y2=\"{y}\" stroke=\"{}\" stroke-width=\"4\" stroke-linecap=\"round\"{}/>",
                hex(*colour),
                dash_attr(*plan),
                y = num(y)
            );
        }
        Swatch::Layer { colour, style, dot } => {
            let c = hex(*colour);
            // At least visible: a 7 % fill is a shade over a map, nothing
            // in a swatch.
            let fill = if style.fill > 0.0 {
                format!(
                    "fill=\"{c}\" fill-opacity=\"{}\"",
                    num(f64::from(style.fill.max(0.2)))
                )
            } else {
                "fill=\"none\"".to_string()
            };
            let mut stroke = if style.stroke > 0.0 {
                format!(
                    "stroke=\"{c}\" stroke-opacity=\"{}\" stroke-width=\"1.5\"",
                    num(f64::from(style.stroke.max(0.5)))
                )
            } else {
                String::new()
            };
            if style.dashed {
                stroke.push_str(" stroke-dasharray=\"4 3\"");
            }
            match dot {
                Some(r) => {
                    let _ = writeln!(
                        svg,
                        "<circle cx=\"{}\" cy=\"{}\" r=\"{}\" {fill} {stroke}/>",
                        num(mid),
                        num(y),
                        num(*r)
                    );
                }
                None if style.fill > 0.0 => area(svg, &format!("{fill} {stroke}")),
                None => {
                    let _ = writeln!(
                        svg,
                        "<line x1=\"{x0}\" y1=\"{y}\" x2=\"{x1}\" y2=\"{y}\" {stroke}/>",
                        y = num(y)
                    );
                }
            }
        }
        Swatch::Obstacle => area(
            svg,
            &format!(
                "fill=\"{}\" stroke=\"{}\" stroke-width=\"1\"",
                hex(OBSTACLE_GREY),
                hex(OBSTACLE_GREY.map(|c| c / 2))
            ),
        ),
        Swatch::Body => {
            let _ = writeln!(
                svg,
                "<circle cx=\"{}\" cy=\"{}\" r=\"6\" fill=\"{n}\" fill-opacity=\"0.15\" stroke=\"{n}\" stroke-width=\"1.5\"/>",
                num(mid),
                num(y),
                n = hex(NEUTRAL)
            );
        }
        Swatch::Start => start_marker(svg, mid, y, &hex(NEUTRAL)),
        Swatch::Goal => goal_marker(svg, mid, y, &hex(NEUTRAL)),
        Swatch::Dashed(dashes) => {
            let _ = writeln!(
                svg,
                "<line x1=\"{x0}\" y1=\"{y}\" x2=\"{x1}\" y2=\"{y}\" stroke=\"{}\" stroke-width=\"1.5\" stroke-dasharray=\"{dashes}\"/>",
                hex(NEUTRAL),
                y = num(y)
            );
        }
    }
}

/// About the width of `text` in the picture's font at `size` pixels
/// (DejaVu Sans averages a little over half an em; wider is safer).
fn text_width(text: &str, size: f64) -> f64 {
    text.chars().count() as f64 * size * 0.58
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

/// A count with thousands separated: `12,345`.
fn thousands(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
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

/// `--svg OUT.svg`: the picture of a run (the world, the paths, the
/// planners' layers), or a bench's box plots.
pub static SINK: Sink = Sink {
    option: "--svg",
    value_name: "OUT.svg",
    help: &[
        (
            Command::Run,
            "Write an SVG picture of the world and the paths",
        ),
        (
            Command::Bench,
            "Write box plots of the metrics per configuration",
        ),
    ],
    draws: true,
    folder: false,
    check: |path| {
        needs_extension(
            path,
            "--svg",
            "svg",
            "an SVG picture",
            " (`--png OUT.png` writes a PNG)",
        )
    },
    files: the_file,
    tuning: None,
    write: |product, path, _| write_file(path, picture(product, path)?),
};

/// The SVG text of a run's picture or a bench's plots (`--svg`, `--png`).
pub fn picture(product: Product<'_>, path: &Path) -> Result<String, Vec<String>> {
    match product {
        Product::Run(report) => Ok(to_svg(report)),
        Product::Bench(report, metrics) => super::plot::to_svg(report, metrics)
            .map_err(|e| vec![format!("cannot draw `{}`: {e}", path.display())]),
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;
    use std::path::PathBuf;

    use super::*;
    use crate::contract::Robot;
    use crate::contract::layers;
    use crate::contract::{MetricValue, PlanOutcome};
    use crate::diagnostics::{SourceMap, Span};
    use crate::geometry::{ConvexPolygon, Grid, Obstacle, World};
    use crate::run::CheckOutcome;

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
            steering: None,
            speed: None,
            team: None,
            span: Span::default(),
        };
        let scenario = Scenario {
            benches: Vec::new(),
            file: PathBuf::from("scenarios/demo.scen"),
            title: title.map(String::from),
            world,
            obstacle_spans: Vec::new(),
            moving: Vec::new(),
            moving_spans: Vec::new(),
            family: None,
            template: None,
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
        // Each over its halo, a white polyline.
        assert_eq!(svg.matches("<polyline class=\"halo\"").count(), 2);
        let polylines: Vec<&str> = svg
            .lines()
            .filter(|l| l.starts_with("<polyline class=\"path\""))
            .collect();
        assert_eq!(polylines.len(), 2);
        for (line, plan) in polylines.iter().zip([0, 2]) {
            assert!(
                line.contains(&format!("stroke=\"{}\"", hex(plan_colour(plan)))),
                "{line}"
            );
        }
    }

    /// Issue 39: overlaid paths differ in their dashes as well as their
    /// colours, and the legend shows each plan's line as drawn.
    #[test]
    fn overlaid_paths_have_distinct_dashes_and_the_legend_shows_them() {
        let svg = to_svg(&report(Some("demo")));
        let paths: Vec<&str> = svg
            .lines()
            .filter(|l| l.starts_with("<polyline class=\"path\""))
            .collect();
        // Plans 0 and 2 found paths: the first solid, the other dashed.
        assert!(!paths[0].contains("stroke-dasharray"), "{}", paths[0]);
        let dashes = format!("stroke-dasharray=\"{}\"", PATH_DASHES[2]);
        assert!(paths[1].contains(&dashes), "{}", paths[1]);
        // The legend's swatch of plan 2 has the same dashes and colour.
        let legend = svg.split("<g id=\"legend\"").nth(1).unwrap_or_default();
        assert!(
            legend.lines().any(|l| l.starts_with("<line")
                && l.contains(&dashes)
                && l.contains(&hex(plan_colour(2)))),
            "{legend}"
        );
        let distinct: std::collections::BTreeSet<&str> = PATH_DASHES.iter().copied().collect();
        assert_eq!(distinct.len(), PATH_DASHES.len());
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
        let r = report(None);
        let view = View::fit(&r.scenario, &plan_runs(&r));
        assert!(view.y(10.0) < view.y(0.0));
        assert!(view.x(20.0) > view.x(0.0));
    }

    #[test]
    fn output_is_deterministic() {
        assert_eq!(to_svg(&report(Some("t"))), to_svg(&report(Some("t"))));
    }

    #[test]
    fn tick_steps_are_one_two_or_five_times_a_power_of_ten() {
        assert_eq!(tick_step(23.2, 10.0, 0.0), 5.0);
        assert_eq!(tick_step(10.6, 10.0, 0.0), 2.0);
        assert_eq!(tick_step(10.0, 10.0, 0.0), 1.0);
        assert!((tick_step(0.9, 10.0, 0.0) - 0.1).abs() < 1e-12);
        assert_eq!(tick_step(512.0, 10.0, 0.0), 100.0);
        // Room for the labels first: 15 units apart at least.
        assert_eq!(tick_step(100.0, 10.0, 15.0), 20.0);
    }

    #[test]
    fn ticks_are_multiples_of_the_step_with_its_decimals() {
        let labels = |lo, hi, step| -> Vec<String> {
            ticks(lo, hi, step).into_iter().map(|(_, l)| l).collect()
        };
        assert_eq!(labels(-1.6, 21.6, 5.0), ["0", "5", "10", "15", "20"]);
        assert_eq!(labels(-0.3, 1.3, 0.5), ["0.0", "0.5", "1.0"]);
        assert_eq!(labels(-1.0, 0.0, 0.5), ["-1.0", "-0.5", "0.0"]);
        assert_eq!(labels(-0.02, 0.05, 0.02), ["-0.02", "0.00", "0.02", "0.04"]);
        assert!(ticks(0.0, 1.0, 0.0).is_empty());
    }

    #[test]
    fn the_plot_has_axes_in_world_units() {
        let svg = to_svg(&report(None));
        let r = report(None);
        let view = View::fit(&r.scenario, &plan_runs(&r));
        // World 20 × 10 with margins: ticks every 5 along x.
        let x_axis = &svg[svg.find("<g id=\"x-axis\"").unwrap_or(0)..];
        for v in [0.0, 5.0, 10.0, 15.0, 20.0] {
            let tick = format!(
                "<text class=\"tick\" x=\"{}\" y=\"{}\">{v}</text>",
                num(view.x(v)),
                num(view.y(view.extent.min.y) + 18.0)
            );
            assert!(x_axis.contains(&tick), "no {tick}");
        }
        assert!(svg.contains("id=\"frame\"") && svg.contains("id=\"grid\""));
    }

    #[test]
    fn c_obstacles_of_a_disk_robot_are_drawn_exactly() {
        let mut r = report(None);
        for p in &mut r.plans {
            p.outcome.layers.clear();
        }
        r.plans[0].outcome.layers = layers::grown_by_disk(vec![
            Rounded::new(&[Point::new(12.0, 7.0)], 1.5),
            Rounded::new(
                &[
                    Point::new(8.0, 1.0),
                    Point::new(9.0, 1.0),
                    Point::new(9.0, 3.0),
                    Point::new(8.0, 3.0),
                ],
                0.5,
            ),
        ])
        .into_iter()
        .collect();
        let svg = to_svg(&r);
        let view = View::fit(&r.scenario, &plan_runs(&r));
        let layer = svg
            .split("<g class=\"layer\"")
            .nth(1)
            .and_then(|l| l.split("</g>").next())
            .unwrap_or_default();
        let circle = format!(
            "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"/>",
            num(view.x(12.0)),
            num(view.y(7.0)),
            num(1.5 * view.scale)
        );
        assert!(layer.contains(&circle), "no {circle} in {layer}");
        // The box: four straight edges and four quarter arcs, from (7.5, 1)
        // beside the left edge's lower end around the corner.
        let r = num(0.5 * view.scale);
        let arc = format!("A{r} {r} 0 0 0 ");
        assert_eq!(layer.matches(&arc).count(), 4, "{layer}");
        assert!(layer.contains(&format!(
            "<path d=\"M{} {}{arc}{} {}L",
            num(view.x(7.5)),
            num(view.y(1.0)),
            num(view.x(8.0)),
            num(view.y(0.5))
        )));
    }

    /// Rasterised, a grown box bulges out at its corners: the arcs turn
    /// the right way round (a wrong sweep flag draws them hollow).
    #[test]
    fn grown_corners_are_round_outwards_in_the_png() {
        let mut r = report(None);
        for p in &mut r.plans {
            p.outcome.layers.clear();
        }
        let region = Rounded::new(
            &[
                Point::new(8.0, 1.0),
                Point::new(9.0, 1.0),
                Point::new(9.0, 3.0),
                Point::new(8.0, 3.0),
            ],
            0.5,
        );
        r.plans[0].outcome.layers.push(Layer::new(
            "grown",
            Drawing::Rounded(vec![region]),
            crate::contract::layers::Style::new(Colour::Plan, 0.0, 15.0).svg(Svg::fill(1.0)),
        ));
        let svg = to_svg(&r);
        let view = View::fit(&r.scenario, &plan_runs(&r));
        let png = crate::report::png::to_png(&svg).unwrap_or_default();
        let image = resvg::tiny_skia::Pixmap::decode_png(&png).expect("a PNG");
        let s = f64::from(crate::report::png::SCALE);
        let colour = plan_colour(r.plans[0].plan);
        let at = |x: f64, y: f64| {
            let p = image
                .pixel((view.x(x) * s) as u32, (view.y(y) * s) as u32)
                .expect("inside")
                .demultiply();
            [p.red(), p.green(), p.blue()]
        };
        // Out from each corner along its diagonal, 0.4 of the radius.
        let d = 0.4 * 0.5 / std::f64::consts::SQRT_2;
        for (x, y) in [
            (8.0 - d, 1.0 - d),
            (9.0 + d, 1.0 - d),
            (9.0 + d, 3.0 + d),
            (8.0 - d, 3.0 + d),
        ] {
            let got = at(x, y);
            let near = got.iter().zip(colour).all(|(a, b)| a.abs_diff(b) <= 24);
            assert!(near, "({x}, {y}) is {got:?}, not the region's {colour:?}");
        }
        // Beyond the arc, on the same diagonal: not the region.
        let far = 0.6 * 0.5 / std::f64::consts::SQRT_2 + 0.5 / std::f64::consts::SQRT_2;
        assert_ne!(at(9.0 + far, 3.0 + far), colour);
    }

    #[test]
    fn a_large_layer_is_faded_thin_and_under_the_paths() {
        let mut r = report(None);
        let edges: Vec<(Point, Point)> = (0..3000)
            .map(|i| {
                let x = f64::from(i % 20);
                (Point::new(x, 1.0), Point::new(x + 0.5, 9.0))
            })
            .collect();
        r.plans[1]
            .outcome
            .layers
            .extend(layers::graph("roadmap", edges));
        let svg = to_svg(&r);
        let line = svg
            .lines()
            .find(|l| l.contains("data-key=\"roadmap\""))
            .unwrap_or_default();
        // 0.35 × 1000 / 3000.
        assert!(line.contains("stroke-opacity=\"0.12\""), "{line}");
        assert!(line.contains("stroke-width=\"0.5\""), "{line}");
        let (roadmap, grown) = (
            svg.find("data-key=\"roadmap\"").unwrap_or(usize::MAX),
            svg.find("data-key=\"C-obstacles").unwrap_or(0),
        );
        assert!(roadmap < grown, "the large layer is not underneath");
        let first_path = svg.find("<polyline class=\"path\"").unwrap_or(0);
        assert!(svg.rfind("<g class=\"layer\"").unwrap_or(usize::MAX) < first_path);
        assert!(svg.contains("roadmap (3,000 edges, faint)"));
        // One path element for all the edges.
        let after = &svg[roadmap..];
        let group = &after[..after.find("</g>").unwrap_or(after.len())];
        assert_eq!(group.matches("<path").count(), 1);
    }

    #[test]
    fn the_legend_keys_each_kind_of_layer_once() {
        let svg = to_svg(&report(None));
        let keys: Vec<&str> = svg
            .lines()
            .filter(|l| l.starts_with("<text class=\"key\""))
            .filter_map(|l| l.split('>').nth(1)?.split('<').next())
            .collect();
        assert_eq!(
            keys,
            [
                "obstacles",
                "C-obstacles (obstacles grown by the robot)",
                "robot",
                "start",
                "goal"
            ]
        );
        assert_eq!(thousands(1234567), "1,234,567");
        assert_eq!(thousands(999), "999");
    }

    #[test]
    fn numbers_are_short() {
        assert_eq!(num(12.0), "12");
        assert_eq!(num(12.5), "12.5");
        assert_eq!(num(-0.001), "0");
        assert_eq!(num(1.23456), "1.23");
    }
}

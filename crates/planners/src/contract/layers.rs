//! What a planner leaves for the viewer and the SVG: drawable layers.
//!
//! A planner knows nothing of output. Besides its path and metrics it
//! returns [`Layer`]s — segments, polylines, polygons, boxes, points,
//! arrows, text, 3D polylines — each with an entity name under
//! `plans/NAME/` (SPEC §6), a colour role, a width and, optionally, an index
//! on a timeline. The Rerun sink logs every layer and the SVG draws those
//! with an [`Svg`] style; neither knows which planner made them.

use crate::geometry::cspace::CLayer;
use crate::geometry::union::union_boundary;
use crate::geometry::{Aabb, Point, Vector, World, polygon};

/// A timeline of the Rerun stream (SPEC §6).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Timeline {
    /// A path step: the robot at path configuration `i`, or an online
    /// robot's move.
    Step,
    /// Search expansions.
    Expansion,
    /// Iterations of a sampling-based planner.
    Iteration,
}

impl Timeline {
    /// The timeline's name in the recording.
    pub fn name(self) -> &'static str {
        match self {
            Timeline::Step => "step",
            Timeline::Expansion => "expansion",
            Timeline::Iteration => "iteration",
        }
    }
}

/// The colour of a layer, by role; the sinks pick the RGB values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Colour {
    /// The plan's own colour.
    Plan,
    /// The plan's colour, translucent (search, grown obstacles, graphs).
    Faint,
    /// Obstacle grey.
    Grey,
    /// Known-free cells.
    Free,
    /// Known-blocked cells.
    Blocked,
    Red,
    Green,
    Blue,
}

/// How the SVG draws a layer (layers without one are viewer-only).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Svg {
    /// Fill opacity, 0 for no fill (lines and outlines).
    pub fill: f32,
    /// Stroke opacity, 0 for no stroke.
    pub stroke: f32,
    /// Dashed strokes.
    pub dashed: bool,
    /// What the layer means, for the picture's legend; empty: the entity
    /// name says it (`raw_path` reads "raw path").
    pub key: &'static str,
}

impl Svg {
    /// A stroke of this opacity.
    pub const fn line(opacity: f32) -> Self {
        Svg {
            fill: 0.0,
            stroke: opacity,
            dashed: false,
            key: "",
        }
    }

    /// A fill of this opacity, no outline.
    pub const fn fill(opacity: f32) -> Self {
        Svg {
            fill: opacity,
            stroke: 0.0,
            dashed: false,
            key: "",
        }
    }

    /// The legend's words for the layer.
    pub const fn key(self, key: &'static str) -> Self {
        Svg { key, ..self }
    }

    pub const fn dashed(self) -> Self {
        Svg {
            dashed: true,
            ..self
        }
    }

    pub const fn outlined(self, opacity: f32) -> Self {
        Svg {
            stroke: opacity,
            ..self
        }
    }
}

/// How a layer looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Style {
    pub colour: Colour,
    /// Line width or point radius in points (UI points in the viewer, pixels
    /// in the SVG); 0: the viewer's default.
    pub width: f32,
    /// Draw order in the viewer: higher is drawn on top.
    pub order: f32,
    /// How the SVG draws it; `None`: viewer only.
    pub svg: Option<Svg>,
}

impl Style {
    pub const fn new(colour: Colour, width: f32, order: f32) -> Self {
        Style {
            colour,
            width,
            order,
            svg: None,
        }
    }

    /// Also drawn in the SVG, this way.
    pub const fn svg(self, svg: Svg) -> Self {
        Style {
            svg: Some(svg),
            ..self
        }
    }
}

/// The geometry of a layer, in world coordinates.
#[derive(Clone, Debug, PartialEq)]
pub enum Drawing {
    Segments(Vec<(Point, Point)>),
    /// Open polylines.
    Polylines(Vec<Vec<Point>>),
    /// Closed outlines (the last vertex joins the first).
    Polygons(Vec<Vec<Point>>),
    Boxes(Vec<Aabb>),
    Points(Vec<Point>),
    /// Arrows from a point along a vector.
    Arrows(Vec<(Point, Vector)>),
    Text(String),
    /// Polylines in (x, y, θ), θ in radians as z.
    Polylines3D(Vec<Vec<[f64; 3]>>),
    /// Convex regions grown by a disk, drawn exactly where the sink has
    /// arcs (a disk grown by a disk robot is a circle).
    Rounded(Vec<Rounded>),
}

impl Drawing {
    pub fn is_empty(&self) -> bool {
        match self {
            Drawing::Segments(v) => v.is_empty(),
            Drawing::Polylines(v) | Drawing::Polygons(v) => v.is_empty(),
            Drawing::Boxes(v) => v.is_empty(),
            Drawing::Points(v) => v.is_empty(),
            Drawing::Arrows(v) => v.is_empty(),
            Drawing::Text(t) => t.is_empty(),
            Drawing::Polylines3D(v) => v.is_empty(),
            Drawing::Rounded(v) => v.is_empty(),
        }
    }

    /// How many things it draws (segments, outlines, boxes, points...): a
    /// sink thins or fades a layer of many.
    pub fn len(&self) -> usize {
        match self {
            Drawing::Segments(v) => v.len(),
            Drawing::Polylines(v) | Drawing::Polygons(v) => v.len(),
            Drawing::Boxes(v) => v.len(),
            Drawing::Points(v) => v.len(),
            Drawing::Arrows(v) => v.len(),
            Drawing::Text(t) => usize::from(!t.is_empty()),
            Drawing::Polylines3D(v) => v.len(),
            Drawing::Rounded(v) => v.len(),
        }
    }
}

/// The convex hull of some points grown by a disk of radius `radius`
/// (their Minkowski sum): a C-obstacle of a disk robot. One corner is a
/// disk, two a stadium.
#[derive(Clone, Debug, PartialEq)]
pub struct Rounded {
    /// The hull's corners, counter-clockwise, no three on a line.
    pub corners: Vec<Point>,
    pub radius: f64,
}

impl Rounded {
    /// The convex hull of the finite `points`, grown by `radius`.
    pub fn new(points: &[Point], radius: f64) -> Self {
        Rounded {
            corners: polygon::convex_hull(points),
            radius,
        }
    }

    /// The arc around each corner, counter-clockwise from where it leaves
    /// the edge into the corner to where it joins the edge out of it; the
    /// straight part of the boundary joins one arc's end to the next arc's
    /// start. Empty for a single corner (the boundary is the whole circle).
    pub fn arcs(&self) -> Vec<(Point, Point)> {
        let n = self.corners.len();
        if n < 2 {
            return Vec::new();
        }
        let normals: Vec<Vector> = (0..n)
            .map(|i| outward_normal(self.corners[i], self.corners[(i + 1) % n]))
            .collect();
        (0..n)
            .map(|i| {
                let c = self.corners[i];
                let before = normals[(i + n - 1) % n];
                (c + before * self.radius, c + normals[i] * self.radius)
            })
            .collect()
    }

    /// The boundary as a closed polygon (the first vertex not repeated)
    /// whose edges touch the exact boundary from outside: each arc is cut
    /// into pieces of at most `max_turn` radians and drawn along their
    /// tangents, so the polygon contains the region (an obstacle never
    /// pokes out of its drawn C-obstacle) and is at most
    /// `radius · (1 / cos(max_turn / 2) − 1)` larger.
    pub fn outline(&self, max_turn: f64) -> Vec<Point> {
        let max_turn = max_turn.clamp(1e-3, std::f64::consts::FRAC_PI_2);
        let r = self.radius;
        let around = |c: Point, from: f64, span: f64, out: &mut Vec<Point>| {
            // Less a rounding error, so that a quarter arc in pieces of
            // π/8 is four pieces, not five.
            let k = (span / max_turn - 1e-9).ceil().max(1.0);
            let step = span / k;
            let reach = r / (step / 2.0).cos();
            for j in 0..k as usize {
                let a = from + (j as f64 + 0.5) * step;
                out.push(Point::new(c.x + reach * a.cos(), c.y + reach * a.sin()));
            }
        };
        let mut out = Vec::new();
        match self.corners.as_slice() {
            [] => {}
            [c] => around(*c, 0.0, std::f64::consts::TAU, &mut out),
            corners => {
                for ((start, end), &c) in self.arcs().into_iter().zip(corners) {
                    let from = (start.y - c.y).atan2(start.x - c.x);
                    let to = (end.y - c.y).atan2(end.x - c.x);
                    let span = (to - from).rem_euclid(std::f64::consts::TAU);
                    // Two corners turn by exactly π at each end, which the
                    // remainder can round to 0 or 2π.
                    let span = if corners.len() == 2 {
                        std::f64::consts::PI
                    } else {
                        span
                    };
                    out.push(start);
                    around(c, from, span, &mut out);
                    out.push(end);
                }
            }
        }
        out
    }
}

/// The unit normal on the right of the edge `a → b` (outward for a
/// counter-clockwise polygon).
fn outward_normal(a: Point, b: Point) -> Vector {
    let d = b - a;
    let len = d.norm();
    if len > 0.0 {
        Vector::new(d.y / len, -d.x / len)
    } else {
        Vector::zeros()
    }
}

/// One drawable part of a plan's trace.
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    /// The entity path under `plans/NAME/`, parts separated by `/`
    /// (`roadmap`, `cspace/layer_3`, `known/free/0002`).
    pub entity: String,
    pub drawing: Drawing,
    pub style: Style,
    /// Shown from this index of a timeline on; `None`: static.
    pub time: Option<(Timeline, i64)>,
}

impl Layer {
    /// A static layer.
    pub fn new(entity: impl Into<String>, drawing: Drawing, style: Style) -> Self {
        Layer {
            entity: entity.into(),
            drawing,
            style,
            time: None,
        }
    }

    /// Shown from index `at` of `timeline` on.
    pub fn at(self, timeline: Timeline, at: i64) -> Self {
        Layer {
            time: Some((timeline, at)),
            ..self
        }
    }
}

/// The most batches a stream of points is sent in ([`batched_points`]).
pub const BATCHES: usize = 100;

/// Points that appear one by one (expansions, samples) as at most
/// [`BATCHES`] layers of entity `entity`: each batch holds the points since
/// the previous one and is logged at the timeline index of its last point.
/// The viewer shows the latest batch at the current time (the frontier
/// moving); its visible time range shows the whole set.
pub fn batched_points(
    entity: &str,
    points: &[Point],
    timeline: Timeline,
    style: Style,
) -> Vec<Layer> {
    if points.is_empty() {
        return Vec::new();
    }
    let batch = points.len().div_ceil(BATCHES);
    points
        .chunks(batch)
        .enumerate()
        .map(|(k, chunk)| {
            let last = k * batch + chunk.len() - 1;
            Layer::new(entity, Drawing::Points(chunk.to_vec()), style).at(timeline, last as i64)
        })
        .collect()
}

/// The search's expanded configurations: `search`, faint, on timeline
/// `expansion` (SPEC §6).
pub fn search(expanded: &[Point]) -> Vec<Layer> {
    batched_points(
        "search",
        expanded,
        Timeline::Expansion,
        Style::new(Colour::Faint, 2.0, 20.0),
    )
}

/// How C-obstacles look: faint outlines, lightly filled and dashed in the
/// SVG.
const GROWN: Style = Style::new(Colour::Faint, 0.0, 15.0).svg(
    Svg::fill(0.07)
        .outlined(0.6)
        .dashed()
        .key("C-obstacles (obstacles grown by the robot)"),
);

/// Obstacles grown by the robot (C-obstacles of a translating robot):
/// `grown`.
pub fn grown(outlines: Vec<Vec<Point>>) -> Option<Layer> {
    (!outlines.is_empty()).then(|| Layer::new("grown", Drawing::Polygons(outlines), GROWN))
}

/// Obstacles grown by a disk robot, exactly ([`Rounded`]): `grown`.
pub fn grown_by_disk(regions: Vec<Rounded>) -> Option<Layer> {
    (!regions.is_empty()).then(|| Layer::new("grown", Drawing::Rounded(regions), GROWN))
}

/// A graph's edges drawn lightly under the path (a roadmap, a tree).
pub fn graph(entity: &str, edges: Vec<(Point, Point)>) -> Option<Layer> {
    (!edges.is_empty()).then(|| {
        Layer::new(
            entity,
            Drawing::Segments(edges),
            Style::new(Colour::Faint, 0.5, 16.0).svg(Svg::line(0.35)),
        )
    })
}

/// The configuration space for the viewer (SPEC §6): per θ layer K the
/// boundary of the union of its C-obstacles at height θ_K
/// (`cspace/layer_K`; stacked, the layered C-space), and per world obstacle
/// its C-obstacles over all layers (`cspace/obstacles/NAME`, the "twisted
/// worm").
pub fn cspace(world: &World, layers: &[CLayer]) -> Vec<Layer> {
    use rayon::prelude::*;
    let grey = Style::new(Colour::Grey, 0.0, 10.0);
    let at = |p: &Point, z: f64| [p.x, p.y, z];
    let boundaries: Vec<Vec<Vec<[f64; 3]>>> = layers
        .par_iter()
        .map(|l| {
            let outlines: Vec<Vec<Point>> =
                l.c_obstacles.iter().map(|c| c.vertices.clone()).collect();
            union_boundary(&outlines)
                .iter()
                .map(|(a, b)| vec![at(a, l.theta), at(b, l.theta)])
                .collect()
        })
        .collect();
    let mut out: Vec<Layer> = boundaries
        .into_iter()
        .enumerate()
        .map(|(k, strips)| {
            Layer::new(
                format!("cspace/layer_{k}"),
                Drawing::Polylines3D(strips),
                grey,
            )
        })
        .collect();
    let mut worms: Vec<Vec<Vec<[f64; 3]>>> = vec![Vec::new(); world.obstacles.len()];
    for l in layers {
        for (&obstacle, c) in l.sources.iter().zip(&l.c_obstacles) {
            let mut strip: Vec<[f64; 3]> = c.vertices.iter().map(|p| at(p, l.theta)).collect();
            if let Some(&first) = strip.first() {
                strip.push(first);
            }
            if let Some(w) = worms.get_mut(obstacle) {
                w.push(strip);
            }
        }
    }
    for (o, strips) in world.obstacles.iter().zip(worms) {
        if !strips.is_empty() {
            out.push(Layer::new(
                format!("cspace/obstacles/{}", o.name),
                Drawing::Polylines3D(strips),
                grey,
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{PI, TAU};

    fn dist_to_segment(p: Point, a: Point, b: Point) -> f64 {
        let d = b - a;
        let t = if d.norm_squared() > 0.0 {
            ((p - a).dot(&d) / d.norm_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p - (a + d * t)).norm()
    }

    /// The distance from `p` outside a convex region to its hull (a point,
    /// a segment or a polygon).
    fn dist_to_hull(p: Point, hull: &[Point]) -> f64 {
        (0..hull.len())
            .map(|i| dist_to_segment(p, hull[i], hull[(i + 1) % hull.len()]))
            .fold(f64::INFINITY, f64::min)
    }

    /// Points along every edge of `outline`, ends included.
    fn along(outline: &[Point]) -> Vec<Point> {
        let n = outline.len();
        (0..n)
            .flat_map(|i| {
                let (a, b) = (outline[i], outline[(i + 1) % n]);
                (0..=20).map(move |k| a + (b - a) * (f64::from(k) / 20.0))
            })
            .collect()
    }

    /// The outline contains the region (no point of it is nearer the hull
    /// than the radius) and hugs it (no vertex farther than the tangent
    /// polygon's corners).
    fn assert_hugs(region: &Rounded, max_turn: f64) {
        let outline = region.outline(max_turn);
        let r = region.radius;
        for p in along(&outline) {
            let d = dist_to_hull(p, &region.corners);
            assert!(
                d >= r * (1.0 - 1e-12),
                "{p:?} is {d} from the hull, inside r = {r}"
            );
        }
        for &p in &outline {
            let d = dist_to_hull(p, &region.corners);
            assert!(d <= r / (max_turn / 2.0).cos() + 1e-12, "{p:?} is {d} away");
        }
    }

    #[test]
    fn a_grown_disk_is_a_circle_and_its_polygon_surrounds_it() {
        let disk = Rounded::new(&[Point::new(2.0, 3.0)], 1.5);
        assert_eq!(disk.corners, [Point::new(2.0, 3.0)]);
        assert!(disk.arcs().is_empty());
        assert_eq!(disk.outline(TAU / 64.0).len(), 64);
        assert_hugs(&disk, TAU / 64.0);
        assert_hugs(&disk, PI / 3.0);
    }

    #[test]
    fn a_grown_square_has_four_quarter_arcs_on_its_offset_edges() {
        let square = [
            Point::new(0.0, 0.0),
            Point::new(2.0, 0.0),
            Point::new(2.0, 2.0),
            Point::new(0.0, 2.0),
            Point::new(1.0, 1.0),
        ];
        let region = Rounded::new(&square, 0.5);
        assert_eq!(region.corners.len(), 4);
        let arcs = region.arcs();
        assert_eq!(arcs.len(), 4);
        // Around corner (0, 0): from below the left edge to below the
        // bottom edge; around (2, 0): from below to the right.
        assert_eq!(arcs[0], (Point::new(-0.5, 0.0), Point::new(0.0, -0.5)));
        assert_eq!(arcs[1], (Point::new(2.0, -0.5), Point::new(2.5, 0.0)));
        for (k, (start, end)) in arcs.iter().enumerate() {
            let c = region.corners[k];
            assert!(((start - c).norm() - 0.5).abs() < 1e-12);
            assert!(((end - c).norm() - 0.5).abs() < 1e-12);
        }
        assert_hugs(&region, TAU / 64.0);
        // A quarter arc in pieces of at most π/4: two tangent pieces.
        assert_eq!(region.outline(PI / 4.0).len(), 4 * (2 + 2));
    }

    #[test]
    fn a_grown_segment_is_a_stadium() {
        let region = Rounded::new(&[Point::new(0.0, 0.0), Point::new(3.0, 0.0)], 1.0);
        let arcs = region.arcs();
        assert_eq!(arcs.len(), 2);
        // Half circles: from the top side around the left end to the bottom.
        assert_eq!(arcs[0], (Point::new(0.0, 1.0), Point::new(0.0, -1.0)));
        assert_eq!(arcs[1], (Point::new(3.0, -1.0), Point::new(3.0, 1.0)));
        assert_hugs(&region, TAU / 64.0);
        // Collinear points make the same stadium.
        let more = Rounded::new(
            &[
                Point::new(0.0, 0.0),
                Point::new(1.0, 0.0),
                Point::new(3.0, 0.0),
            ],
            1.0,
        );
        assert_eq!(more.corners.len(), 2);
    }

    #[test]
    fn grown_layers_say_what_they_are() {
        let layer = grown_by_disk(vec![Rounded::new(&[Point::new(0.0, 0.0)], 1.0)]);
        let svg = layer.and_then(|l| l.style.svg);
        assert!(svg.is_some_and(|s| s.key.starts_with("C-obstacles")));
        assert!(grown_by_disk(Vec::new()).is_none());
    }
}

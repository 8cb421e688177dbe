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
use crate::geometry::{Aabb, Point, Vector, World};

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
}

impl Svg {
    /// A stroke of this opacity.
    pub const fn line(opacity: f32) -> Self {
        Svg {
            fill: 0.0,
            stroke: opacity,
            dashed: false,
        }
    }

    /// A fill of this opacity, no outline.
    pub const fn fill(opacity: f32) -> Self {
        Svg {
            fill: opacity,
            stroke: 0.0,
            dashed: false,
        }
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
        }
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

/// Obstacles grown by the robot (C-obstacles of a translating robot):
/// `grown`, faint outlines, lightly filled and dashed in the SVG.
pub fn grown(outlines: Vec<Vec<Point>>) -> Option<Layer> {
    (!outlines.is_empty()).then(|| {
        Layer::new(
            "grown",
            Drawing::Polygons(outlines),
            Style::new(Colour::Faint, 0.0, 15.0).svg(Svg::fill(0.07).outlined(0.6).dashed()),
        )
    })
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

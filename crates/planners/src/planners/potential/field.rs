//! The repulsive field of SPEC 3.4: for each obstacle near the robot, its
//! closest point B and the distance ρ from the robot's boundary to it.
//!
//! # Force sources
//! SPEC 3.4 sums one repulsive force per obstacle, from the obstacle's
//! closest point. A *source* is one obstacle (segment, rect, polygon, disk),
//! except for grids, where each 8-connected group of blocked cells is a
//! source of its own (a map's separate blocks are separate obstacles to a
//! person; summing one force per cell would make walls repel in proportion
//! to their resolution).
//!
//! Each source is made of *primitives* whose closest points are closed-form:
//! segments (segment walls and the outline edges of polygons), boxes (rects
//! and horizontal runs of blocked grid cells that touch free space) and
//! disks. The robot is never inside an obstacle (every motion is checked),
//! so the closest point of a closed obstacle is on its boundary, that is, on
//! one of these primitives.
//!
//! # Index
//! Primitives sit in a uniform bucket grid over the bounds; a primitive is
//! listed in every bucket that its region of influence (the primitive grown
//! by `reach` = ρ0 + robot radius) meets, so a query reads one bucket.
//! Primitives are numbered source by source, so a bucket lists a source's
//! primitives together and the per-source minimum is a running minimum.

use crate::geometry::polygon::closest_point_on_segment;
use crate::geometry::{Aabb, Grid, Point, Shape, Vector, World};

/// The closed-form shapes whose closest points make up a source's.
#[derive(Clone, Copy, Debug)]
enum Prim {
    Segment(Point, Point),
    Box(Aabb),
    Disk(Point, f64),
}

impl Prim {
    /// The point of the primitive closest to `x`, and its distance.
    #[inline]
    fn closest(&self, x: Point) -> (Point, f64) {
        let b = match *self {
            Prim::Segment(a, b) => closest_point_on_segment(x, a, b),
            Prim::Box(b) => Point::new(x.x.clamp(b.min.x, b.max.x), x.y.clamp(b.min.y, b.max.y)),
            Prim::Disk(c, r) => {
                let d = x - c;
                let n = d.norm();
                if n > 0.0 { c + d * (r / n) } else { c }
            }
        };
        (b, (x - b).norm())
    }

    fn aabb(&self) -> Aabb {
        match *self {
            Prim::Segment(a, b) => Aabb::from_corners(a, b),
            Prim::Box(b) => b,
            Prim::Disk(c, r) => Aabb {
                min: Point::new(c.x - r, c.y - r),
                max: Point::new(c.x + r, c.y + r),
            },
        }
    }
}

/// One force source (an obstacle, or a group of blocked grid cells).
#[derive(Clone, Debug)]
pub struct Source {
    /// Index of the obstacle in `world.obstacles`.
    pub obstacle: usize,
    /// Corners of the source, aimed at by the "smart" jumps of SEEDS §E
    /// (empty for disks and grid cells).
    pub vertices: Vec<Point>,
}

/// The closest point of one source within reach.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Near {
    /// Index into [`FieldIndex::sources`].
    pub source: usize,
    /// The source's closest point to the robot's centre.
    pub point: Point,
    /// Distance from the robot's boundary to `point` (≥ 0 up to rounding).
    pub rho: f64,
}

/// The forces at one position (SPEC 3.4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Forces {
    pub attract: Vector,
    pub repulse: Vector,
    /// Σ|F_rep| over the sources: `repulse` is only rounding noise when it
    /// is tiny next to this (forces that cancel, as between two parallel
    /// walls).
    pub repulse_sum: f64,
    /// The source nearest to the robot, if any is within the influence ρ0.
    pub nearest: Option<Near>,
}

impl Forces {
    pub fn total(&self) -> Vector {
        self.attract + self.repulse
    }
}

/// The gains of SPEC 3.4.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gains {
    /// η of F_att = −η (x − x_goal).
    pub attract: f64,
    /// d of F_rep.
    pub repulse: f64,
    /// ρ0, the influence distance.
    pub influence: f64,
}

/// The smallest ρ used in the force law: a robot touching an obstacle
/// (ρ = 0, allowed) feels a huge but finite push.
const MIN_RHO: f64 = 1e-9;

/// Most buckets per side of the index.
const MAX_BUCKETS_PER_SIDE: usize = 512;

/// Obstacles as force sources, indexed for queries at one position.
pub struct FieldIndex {
    pub sources: Vec<Source>,
    prims: Vec<Prim>,
    /// `prim_source[i]`: the source of `prims[i]`.
    prim_source: Vec<u32>,
    /// Robot radius: distances are measured from the robot's boundary.
    radius: f64,
    gains: Gains,
    origin: Point,
    inv: f64,
    nx: usize,
    ny: usize,
    /// Compressed rows: bucket i lists `items[start[i] .. start[i + 1]]`.
    start: Vec<u32>,
    items: Vec<u32>,
}

impl FieldIndex {
    /// Prepares the sources of `world` for a robot of radius `radius` (0 for
    /// a point robot).
    pub fn new(world: &World, radius: f64, gains: Gains) -> Self {
        let mut sources = Vec::new();
        let mut prims = Vec::new();
        let mut prim_source = Vec::new();
        let mut add =
            |obstacle: usize, vertices: Vec<Point>, ps: &mut dyn Iterator<Item = Prim>| {
                let s = sources.len() as u32;
                let before = prims.len();
                prims.extend(ps);
                prim_source.resize(prims.len(), s);
                if prims.len() > before {
                    sources.push(Source { obstacle, vertices });
                }
            };
        for (i, o) in world.obstacles.iter().enumerate() {
            match &o.shape {
                Shape::Segment(a, b) => {
                    add(i, vec![*a, *b], &mut std::iter::once(Prim::Segment(*a, *b)))
                }
                Shape::Rect(b) => add(i, b.corners().to_vec(), &mut std::iter::once(Prim::Box(*b))),
                Shape::Polygon { outline, .. } => {
                    let n = outline.len();
                    add(
                        i,
                        outline.clone(),
                        &mut (0..n).map(|k| Prim::Segment(outline[k], outline[(k + 1) % n])),
                    )
                }
                Shape::Disk { center, radius } => add(
                    i,
                    Vec::new(),
                    &mut std::iter::once(Prim::Disk(*center, *radius)),
                ),
                Shape::Grid(g) => {
                    for group in grid_groups(g) {
                        add(i, Vec::new(), &mut group.into_iter().map(Prim::Box));
                    }
                }
            }
        }
        let mut index = FieldIndex {
            sources,
            prims,
            prim_source,
            radius,
            gains,
            origin: world.bounds.min,
            inv: 1.0,
            nx: 1,
            ny: 1,
            start: Vec::new(),
            items: Vec::new(),
        };
        index.build_buckets(world.bounds);
        index
    }

    /// How far from a primitive its force reaches (from the robot's centre).
    fn reach(&self) -> f64 {
        self.gains.influence + self.radius
    }

    fn build_buckets(&mut self, bounds: Aabb) {
        let reach = self.reach();
        let side = (bounds.width().max(bounds.height()) / MAX_BUCKETS_PER_SIDE as f64).max(reach);
        let side = if side.is_finite() && side > 0.0 {
            side
        } else {
            1.0
        };
        self.inv = 1.0 / side;
        self.origin = bounds.min;
        self.nx = ((bounds.width() / side).ceil() as usize).clamp(1, MAX_BUCKETS_PER_SIDE);
        self.ny = ((bounds.height() / side).ceil() as usize).clamp(1, MAX_BUCKETS_PER_SIDE);
        let (nx, ny) = (self.nx, self.ny);
        // Count, then fill (the same visits twice).
        let mut counts = vec![0u32; nx * ny];
        for p in &self.prims {
            self.visit_buckets(p, |i| counts[i] += 1);
        }
        self.start = vec![0; nx * ny + 1];
        for (i, c) in counts.iter().enumerate() {
            self.start[i + 1] = self.start[i] + c;
        }
        let mut next = self.start[..nx * ny].to_vec();
        let mut items = vec![0u32; self.start[nx * ny] as usize];
        for (j, p) in self.prims.iter().enumerate() {
            self.visit_buckets(p, |i| {
                items[next[i] as usize] = j as u32;
                next[i] += 1;
            });
        }
        self.items = items;
    }

    /// Calls `visit` with each bucket that the primitive grown by `reach`
    /// meets, once each. Supersets are fine (a listed primitive out of reach
    /// adds no force); per bucket column: for a segment, the rows spanned by
    /// its part within reach of the column; for a box, only the rows near
    /// its boundary (the closest point of a box to a robot outside it is on
    /// its boundary), so that a large box is not listed all over its inside.
    fn visit_buckets(&self, p: &Prim, mut visit: impl FnMut(usize)) {
        let reach = self.reach();
        let side = 1.0 / self.inv;
        let col = |x: f64| ((x - self.origin.x) * self.inv).floor();
        let b = p.aabb();
        let (c_lo, c_hi) = (col(b.min.x - reach), col(b.max.x + reach));
        if c_hi < 0.0 || c_lo >= self.nx as f64 {
            return;
        }
        let c0 = c_lo.max(0.0) as usize;
        let c1 = (c_hi as usize).min(self.nx - 1);
        for c in c0..=c1 {
            // The column's x-range grown by reach.
            let xa = self.origin.x + c as f64 * side - reach;
            let xb = xa + side + 2.0 * reach;
            match *p {
                Prim::Segment(a, q) if a.x != q.x => {
                    let ta = (xa - a.x) / (q.x - a.x);
                    let tb = (xb - a.x) / (q.x - a.x);
                    let (t0, t1) = (ta.min(tb).max(0.0), ta.max(tb).min(1.0));
                    if t0 <= t1 {
                        let (ya, yb) = (a.y + t0 * (q.y - a.y), a.y + t1 * (q.y - a.y));
                        self.visit_rows(c, ya.min(yb), ya.max(yb), &mut visit);
                    }
                }
                Prim::Box(bx) => {
                    let near_side = |x: f64| xa <= x && x <= xb;
                    let band = 2.0 * reach;
                    if near_side(bx.min.x) || near_side(bx.max.x) || bx.height() <= band {
                        self.visit_rows(c, bx.min.y, bx.max.y, &mut visit);
                    } else {
                        // The bands along the bottom and top edges; they
                        // are apart since the box is taller than 2·reach,
                        // but may share a bucket row.
                        let (lo, hi) = (self.row_range(bx.min.y), self.row_range(bx.max.y));
                        if let Some((r0, r1)) = lo {
                            (r0..=r1).for_each(|r| visit(r * self.nx + c));
                        }
                        if let Some((r0, r1)) = hi {
                            let from = lo.map_or(r0, |(_, l1)| r0.max(l1 + 1));
                            (from..=r1).for_each(|r| visit(r * self.nx + c));
                        }
                    }
                }
                _ => self.visit_rows(c, b.min.y, b.max.y, &mut visit),
            }
        }
    }

    /// Visits the buckets of column `c` whose rows meet [y_lo − reach,
    /// y_hi + reach].
    fn visit_rows(&self, c: usize, y_lo: f64, y_hi: f64, visit: &mut impl FnMut(usize)) {
        let reach = self.reach();
        let row = |y: f64| ((y - self.origin.y) * self.inv).floor();
        let (r_lo, r_hi) = (row(y_lo - reach), row(y_hi + reach));
        if r_hi < 0.0 || r_lo >= self.ny as f64 {
            return;
        }
        let r0 = r_lo.max(0.0) as usize;
        let r1 = (r_hi as usize).min(self.ny - 1);
        for r in r0..=r1 {
            visit(r * self.nx + c);
        }
    }

    /// The inclusive bucket rows that meet [y − reach, y + reach], if any.
    fn row_range(&self, y: f64) -> Option<(usize, usize)> {
        let reach = self.reach();
        let row = |y: f64| ((y - self.origin.y) * self.inv).floor();
        let (r_lo, r_hi) = (row(y - reach), row(y + reach));
        if r_hi < 0.0 || r_lo >= self.ny as f64 {
            return None;
        }
        Some((r_lo.max(0.0) as usize, (r_hi as usize).min(self.ny - 1)))
    }

    /// The primitives listed for the bucket holding `x` (none outside the
    /// bounds' buckets).
    #[inline]
    fn bucket(&self, x: Point) -> &[u32] {
        let cx = ((x.x - self.origin.x) * self.inv).floor();
        let cy = ((x.y - self.origin.y) * self.inv).floor();
        if !(cx >= 0.0 && cy >= 0.0) {
            return &[];
        }
        let (c, r) = (
            (cx as usize).min(self.nx - 1),
            (cy as usize).min(self.ny - 1),
        );
        let i = r * self.nx + c;
        &self.items[self.start[i] as usize..self.start[i + 1] as usize]
    }

    /// The forces at `x` towards `goal` (SPEC 3.4). For each source within
    /// reach, B is its closest point and ρ = |x − B| − radius; if ρ ≤ ρ0 it
    /// adds d·(1/ρ³)(1/ρ − 1/ρ0)·ρ·u, u the unit vector from B to x (for a
    /// point robot, ρ·u = x − B as in the seed; a disk robot feels what a
    /// point at the same distance from the obstacle would).
    #[inline]
    pub fn forces(&self, x: Point, goal: Point) -> Forces {
        let g = self.gains;
        let mut repulse = Vector::zeros();
        let mut repulse_sum = 0.0;
        let mut nearest: Option<Near> = None;
        let mut push = |source: u32, b: Point, dist: f64| {
            let rho = dist - self.radius;
            if rho > g.influence || dist <= 0.0 {
                return;
            }
            let rc = rho.max(MIN_RHO);
            let magnitude = g.repulse / (rc * rc * rc) * (1.0 / rc - 1.0 / g.influence) * rc;
            repulse += (x - b) * (magnitude / dist);
            repulse_sum += magnitude;
            if nearest.is_none_or(|n| rho < n.rho) {
                nearest = Some(Near {
                    source: source as usize,
                    point: b,
                    rho,
                });
            }
        };
        let mut current = u32::MAX;
        let mut best = (Point::origin(), f64::INFINITY);
        for &item in self.bucket(x) {
            let s = self.prim_source[item as usize];
            if s != current {
                if current != u32::MAX {
                    push(current, best.0, best.1);
                }
                current = s;
                best = (Point::origin(), f64::INFINITY);
            }
            let (b, d) = self.prims[item as usize].closest(x);
            if d < best.1 {
                best = (b, d);
            }
        }
        if current != u32::MAX {
            push(current, best.0, best.1);
        }
        Forces {
            attract: (goal - x) * g.attract,
            repulse,
            repulse_sum,
            nearest,
        }
    }
}

/// The force sources of a grid: its 8-connected groups of blocked cells,
/// each as the boxes of its horizontal runs of blocked cells that touch free
/// space (or the outside of the raster); runs entirely inside a group never
/// hold a closest point.
fn grid_groups(g: &Grid) -> Vec<Vec<Aabb>> {
    let (w, h) = (g.width, g.height);
    let blocked = |c: isize, r: isize| -> bool {
        c >= 0
            && r >= 0
            && (c as usize) < w
            && (r as usize) < h
            && g.is_blocked(c as usize, r as usize)
    };
    // Label groups by flood fill (rows top first, as in the grid).
    let mut label = vec![u32::MAX; w * h];
    let mut groups = 0u32;
    let mut stack = Vec::new();
    for r in 0..h {
        for c in 0..w {
            if label[r * w + c] != u32::MAX || !g.is_blocked(c, r) {
                continue;
            }
            label[r * w + c] = groups;
            stack.push((c, r));
            while let Some((c, r)) = stack.pop() {
                for dr in -1isize..=1 {
                    for dc in -1isize..=1 {
                        let (nc, nr) = (c as isize + dc, r as isize + dr);
                        if blocked(nc, nr) {
                            let i = nr as usize * w + nc as usize;
                            if label[i] == u32::MAX {
                                label[i] = groups;
                                stack.push((nc as usize, nr as usize));
                            }
                        }
                    }
                }
            }
            groups += 1;
        }
    }
    let mut out = vec![Vec::new(); groups as usize];
    for r in 0..h {
        let mut c = 0;
        while c < w {
            if !g.is_blocked(c, r) {
                c += 1;
                continue;
            }
            let first = c;
            let mut exposed = false;
            while c < w && g.is_blocked(c, r) {
                let (ci, ri) = (c as isize, r as isize);
                exposed |= !blocked(ci - 1, ri)
                    || !blocked(ci + 1, ri)
                    || !blocked(ci, ri - 1)
                    || !blocked(ci, ri + 1);
                c += 1;
            }
            if exposed {
                let a = g.cell_box(first, r);
                let b = g.cell_box(c - 1, r);
                out[label[r * w + first] as usize].push(Aabb {
                    min: a.min,
                    max: b.max,
                });
            }
        }
    }
    out
}

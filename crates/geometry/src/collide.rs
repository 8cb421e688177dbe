//! The planners' collision queries for point and disk robots, with a broad
//! phase over all obstacles.
//!
//! The geometry here is written by hand and shares no code with the
//! validator ([`super::validator`]), which is built on parry: the two check
//! each other (see the property tests at the bottom).
//!
//! # Semantics (the validator's, but stricter for points at segments)
//! A query shape is a point or a segment (its *core*) grown by a radius
//! `r ≥ 0`: a disk at `p`, or the capsule swept by that disk from `p` to `q`.
//! It collides with an obstacle piece when `r + ρ − signed_distance(core,
//! piece core) > TOUCH_EPS`, where the signed distance is negative by the
//! penetration depth when the cores overlap, and ρ is the piece's own radius
//! (a disk obstacle's; 0 otherwise). So touching is allowed, except for
//! segment obstacles and queries with `r ≤ TOUCH_EPS` (points): those collide
//! with a segment obstacle as soon as they touch it (distance at most
//! `TOUCH_EPS`). The validator lets a point touch a segment and only refuses
//! a path that passes from one side of the segments to the other, which a
//! single motion cannot tell (it may cross a chain of segments at a shared
//! vertex, or reach a segment that the next motion leaves on the other side);
//! refusing every contact is stricter, and sound for any path made of such
//! motions. Queries with `r ≤ TOUCH_EPS` also collide with the
//! *seams* of multi-piece obstacles — the open band of half-width
//! `TOUCH_EPS` around an edge shared by two pieces of a polygon or by two
//! blocked cells of a grid (stopping `TOUCH_EPS` short of the obstacle's
//! boundary), and the square of half-width `2·TOUCH_EPS` around a grid corner
//! whose four cells are blocked — because those lie inside the obstacle.

use super::buckets::Buckets;
use super::polygon::proximity::{VertexIndex, shared_edges};
use super::polygon::{self, distance_point_segment};
use super::{Aabb, Point, Shape, TOUCH_EPS, Vector, World};

/// Obstacles of a world prepared for fast queries by the planners.
///
/// Convex pieces (polygon pieces, rects, disks, segments, seams) sit in a
/// uniform bucket grid over the world's bounds (grown to hold every
/// obstacle); grid obstacles are looked up cell by cell. Queries allocate
/// nothing.
pub struct ObstacleIndex {
    pieces: Vec<Piece>,
    /// Edges of all convex polygon pieces, piece after piece.
    edges: Vec<Edge>,
    buckets: Buckets,
    grids: Vec<IndexedGrid>,
}

/// An edge `a → next a` of a counter-clockwise convex piece, with its unit
/// outward normal `n` and `c = n·a` (the piece is `n·x ≤ c` for all edges).
#[derive(Clone, Copy, Debug)]
struct Edge {
    a: Point,
    n: Vector,
    c: f64,
}

#[derive(Clone, Copy, Debug)]
struct Piece {
    /// Bounding box, grown by `3·TOUCH_EPS`.
    aabb: Aabb,
    /// Index of the obstacle in `world.obstacles`.
    owner: u32,
    kind: Kind,
}

#[derive(Clone, Copy, Debug)]
enum Kind {
    /// `edges[first .. first + len]`.
    Convex {
        first: u32,
        len: u32,
    },
    Rect(Aabb),
    Disk {
        center: Point,
        radius: f64,
    },
    Wall {
        a: Point,
        b: Point,
    },
    /// The open band { a + u·d + w·d⊥ : u0 < u < u1, |w| < TOUCH_EPS }.
    Seam {
        a: Point,
        d: Vector,
        u0: f64,
        u1: f64,
    },
}

struct IndexedGrid {
    owner: u32,
    origin: Point,
    cell: f64,
    /// 1 / `cell`.
    inv: f64,
    width: usize,
    height: usize,
    /// `width` and `height` as floats.
    size: Vector,
    /// Row-major from the *bottom* row (k = 0), unlike [`super::Grid`].
    blocked: Vec<bool>,
}

impl IndexedGrid {
    #[inline]
    fn blocked(&self, col: usize, k: usize) -> bool {
        self.blocked[k * self.width + col]
    }

    /// Whether blocked cells meet `b`, looking at 16 cells at most (the
    /// cells whose closed squares meet `b`).
    #[inline]
    fn blocked_cells_near(&self, b: &Aabb) -> Near {
        let x_lo = (b.min.x - self.origin.x) * self.inv;
        let x_hi = (b.max.x - self.origin.x) * self.inv;
        let y_lo = (b.min.y - self.origin.y) * self.inv;
        let y_hi = (b.max.y - self.origin.y) * self.inv;
        if !(x_hi >= 0.0 && x_lo < self.size.x && y_hi >= 0.0 && y_lo < self.size.y) {
            return Near::None;
        }
        let (c0, c1) = (cell_index(x_lo, self.width), cell_index(x_hi, self.width));
        let (k0, k1) = (cell_index(y_lo, self.height), cell_index(y_hi, self.height));
        if (c1 - c0 + 1) * (k1 - k0 + 1) > 16 {
            return Near::Unknown;
        }
        // Plain loops: iterator adapters cost more than the 1 to 4 lookups.
        for k in k0..k1 + 1 {
            for c in c0..c1 + 1 {
                if self.blocked(c, k) {
                    return Near::Some {
                        cols: (c0, c1),
                        rows: (k0, k1),
                    };
                }
            }
        }
        Near::None
    }
}

/// What [`IndexedGrid::blocked_cells_near`] found.
#[derive(Clone, Copy)]
enum Near {
    None,
    /// Some, among the cells of these inclusive ranges.
    Some {
        cols: (usize, usize),
        rows: (usize, usize),
    },
    /// Too many cells to look at.
    Unknown,
}

/// One query: the core `p → q` (a point when `p == q`) grown by `r`.
struct Probe {
    p: Point,
    q: Point,
    r: f64,
    /// `q − p`.
    d: Vector,
    moving: bool,
    thin: bool,
    /// The box of everything the probe can reach, grown by `3·TOUCH_EPS`.
    aabb: Aabb,
}

impl Probe {
    /// The capsule from `p` to `q` of radius `r` (negative radii count as
    /// 0); a disk when `p == q`.
    #[inline]
    fn new(p: Point, q: Point, r: f64) -> Self {
        let r = r.max(0.0);
        let reach = r + 3.0 * TOUCH_EPS;
        let aabb = Aabb {
            min: Point::new(p.x.min(q.x) - reach, p.y.min(q.y) - reach),
            max: Point::new(p.x.max(q.x) + reach, p.y.max(q.y) + reach),
        };
        Probe {
            p,
            q,
            r,
            d: q - p,
            moving: p != q,
            thin: r <= TOUCH_EPS,
            aabb,
        }
    }

    /// Unit normal of the core (only for a moving probe); computed on use,
    /// since most queries never need it.
    #[inline]
    fn normal(&self) -> Vector {
        Vector::new(-self.d.y, self.d.x) / self.d.norm()
    }

    /// Distance from `x` to the core.
    #[inline]
    fn distance_to(&self, x: Point) -> f64 {
        distance_point_segment(x, self.p, self.q)
    }
}

impl ObstacleIndex {
    /// Prepares `world` for queries: O(total size of the obstacles); grids
    /// are copied. Polygons without pieces are decomposed here.
    pub fn new(world: &World) -> Self {
        let mut pieces = Vec::new();
        let mut edges = Vec::new();
        let mut grids = Vec::new();
        for (i, o) in world.obstacles.iter().enumerate() {
            let owner = i as u32;
            let mut push = |kind: Kind, aabb: Aabb| {
                pieces.push(Piece {
                    aabb: grow(aabb, 3.0 * TOUCH_EPS),
                    owner,
                    kind,
                })
            };
            match &o.shape {
                Shape::Polygon {
                    outline,
                    pieces: convex,
                } => {
                    let decomposed;
                    let convex = if convex.is_empty() {
                        decomposed = polygon::convex_decomposition(outline);
                        &decomposed
                    } else {
                        convex
                    };
                    for piece in convex {
                        let first = edges.len() as u32;
                        let v = &piece.vertices;
                        for j in 0..v.len() {
                            let (a, b) = (v[j], v[(j + 1) % v.len()]);
                            let e = b - a;
                            let l = e.norm();
                            if l > 0.0 {
                                let n = Vector::new(e.y, -e.x) / l;
                                edges.push(Edge {
                                    a,
                                    n,
                                    c: n.dot(&a.coords),
                                });
                            }
                        }
                        let len = edges.len() as u32 - first;
                        if len >= 3 {
                            push(Kind::Convex { first, len }, Aabb::around(v));
                        } else {
                            edges.truncate(first as usize);
                        }
                    }
                    let vertices = VertexIndex::new(outline);
                    let shared = seams(
                        outline,
                        &vertices,
                        convex.iter().map(|p| p.vertices.as_slice()),
                    );
                    for (a, b) in shared {
                        let (u0, u1) = (
                            seam_end_margin(outline, &vertices, a, b),
                            (b - a).norm() - seam_end_margin(outline, &vertices, b, a),
                        );
                        if u0 < u1 {
                            let d = (b - a).normalize();
                            push(
                                Kind::Seam { a, d, u0, u1 },
                                grow(Aabb::from_corners(a, b), TOUCH_EPS),
                            );
                        }
                    }
                }
                Shape::Rect(b) => push(Kind::Rect(*b), *b),
                Shape::Disk { center, radius } => {
                    let v = Vector::new(*radius, *radius);
                    push(
                        Kind::Disk {
                            center: *center,
                            radius: *radius,
                        },
                        Aabb {
                            min: center - v,
                            max: center + v,
                        },
                    );
                }
                Shape::Segment(a, b) => {
                    push(Kind::Wall { a: *a, b: *b }, Aabb::from_corners(*a, *b))
                }
                Shape::Grid(g) if g.width == 0 || g.height == 0 => {}
                Shape::Grid(g) => {
                    let mut blocked = vec![false; g.width * g.height];
                    for row in 0..g.height {
                        let k = g.height - 1 - row;
                        for col in 0..g.width {
                            blocked[k * g.width + col] = g.is_blocked(col, row);
                        }
                    }
                    grids.push(IndexedGrid {
                        owner,
                        origin: g.origin,
                        cell: g.cell,
                        inv: 1.0 / g.cell,
                        width: g.width,
                        height: g.height,
                        size: Vector::new(g.width as f64, g.height as f64),
                        blocked,
                    });
                }
            }
        }
        let boxes: Vec<Aabb> = pieces.iter().map(|p| p.aabb).collect();
        let buckets = Buckets::new(world.bounds, &boxes, 128);
        ObstacleIndex {
            pieces,
            edges,
            buckets,
            grids,
        }
    }

    /// Whether a disk of radius `r` (0 = a point) centred at `p` stays out of
    /// every obstacle interior (touching allowed, tolerance TOUCH_EPS); a
    /// point (`r ≤ TOUCH_EPS`) must also stay off every segment obstacle.
    ///
    /// See the module documentation for the exact rule. Bounds are not
    /// checked.
    pub fn disk_free(&self, p: Point, r: f64) -> bool {
        self.disk_blocker(p, r).is_none()
    }

    /// The index in `world.obstacles` of an obstacle that a disk of radius
    /// `r` at `p` overlaps (not necessarily the smallest such index), if any.
    pub fn disk_blocker(&self, p: Point, r: f64) -> Option<usize> {
        self.blocker(&Probe::new(p, p, r))
    }

    /// Whether the disk of radius `r` swept from `p` to `q` stays out of
    /// every obstacle interior and crosses no segment obstacle.
    ///
    /// Exact (up to rounding) for the straight motion, with the rule of the
    /// module documentation: the swept capsule (the segment `pq` for `r = 0`)
    /// may touch obstacles but not overlap them deeper than TOUCH_EPS; a
    /// moving point (`r ≤ TOUCH_EPS`) may not even touch a segment obstacle
    /// (conservative: the validator accepts every path made of such motions).
    /// Bounds are not checked.
    pub fn sweep_free(&self, p: Point, q: Point, r: f64) -> bool {
        self.sweep_blocker(p, q, r).is_none()
    }

    /// The index in `world.obstacles` of an obstacle that the disk of radius
    /// `r` swept from `p` to `q` hits (not necessarily the smallest such
    /// index), if any.
    pub fn sweep_blocker(&self, p: Point, q: Point, r: f64) -> Option<usize> {
        self.blocker(&Probe::new(p, q, r))
    }

    #[inline]
    fn blocker(&self, probe: &Probe) -> Option<usize> {
        for g in &self.grids {
            // The common case, no blocked cell near a short probe, stays in
            // this small inlined loop; the rest is out of line.
            let near = g.blocked_cells_near(&probe.aabb);
            if !matches!(near, Near::None) && grid_hit(g, probe, near) {
                return Some(g.owner as usize);
            }
        }
        if self.pieces.is_empty() {
            return None;
        }
        self.piece_blocker(probe)
    }

    #[inline(never)]
    fn piece_blocker(&self, probe: &Probe) -> Option<usize> {
        let mut found = None;
        let b = &self.buckets;
        visit_cells_along(b.origin, b.cell, b.inv, (b.nx, b.ny), probe, |col, k| {
            for &item in b.items(col, k) {
                let piece = &self.pieces[item as usize];
                if piece.aabb.meets(&probe.aabb) && self.piece_hit(piece, probe) {
                    found = Some(piece.owner as usize);
                    return true;
                }
            }
            false
        });
        found
    }

    #[inline]
    fn piece_hit(&self, piece: &Piece, probe: &Probe) -> bool {
        match piece.kind {
            Kind::Convex { first, len } => {
                convex_hit(&self.edges[first as usize..(first + len) as usize], probe)
            }
            Kind::Rect(b) => box_hit(&b, probe),
            Kind::Disk { center, radius } => {
                probe.distance_to(center) < probe.r + radius - TOUCH_EPS
            }
            Kind::Wall { a, b } => wall_hit(a, b, probe),
            Kind::Seam { a, d, u0, u1 } => {
                probe.thin && {
                    // The band in its own frame: u along the seam, w across.
                    let frame = |x: Point| Point::new(d.dot(&(x - a)), d.perp(&(x - a)));
                    let lo = Point::new(u0, -TOUCH_EPS);
                    let hi = Point::new(u1, TOUCH_EPS);
                    segment_meets_open_box(frame(probe.p), frame(probe.q), lo, hi)
                }
            }
        }
    }
}

/// Visits the cells (col, k), k counted from the bottom, of a raster of
/// `cols × rows` squares of side `cell` (`inv` = 1 / `cell`) with bottom-left
/// corner `origin`, that the probe's capsule grown by `3·TOUCH_EPS` may meet:
/// column by column, the rows spanned by the part of the capsule over that
/// column (a superset of the cells met, linear in the capsule's length).
/// Stops as soon as `visit` returns `true`, and returns `true` then.
#[inline(always)]
fn visit_cells_along(
    origin: Point,
    cell: f64,
    inv: f64,
    (cols, rows): (usize, usize),
    probe: &Probe,
    mut visit: impl FnMut(usize, usize) -> bool,
) -> bool {
    let x_lo = (probe.aabb.min.x - origin.x) * inv;
    let x_hi = (probe.aabb.max.x - origin.x) * inv;
    let y_lo = (probe.aabb.min.y - origin.y) * inv;
    let y_hi = (probe.aabb.max.y - origin.y) * inv;
    if !(x_hi >= 0.0 && x_lo < cols as f64 && y_hi >= 0.0 && y_lo < rows as f64) {
        return false;
    }
    let (c0, c1) = (cell_index(x_lo, cols), cell_index(x_hi, cols));
    let (p, d) = (probe.p, probe.d);
    if c0 == c1 || d.x == 0.0 {
        let (k0, k1) = (cell_index(y_lo, rows), cell_index(y_hi, rows));
        for c in c0..=c1 {
            for k in k0..=k1 {
                if visit(c, k) {
                    return true;
                }
            }
        }
        return false;
    }
    let reach = probe.r + 3.0 * TOUCH_EPS;
    let inv_dx = 1.0 / d.x;
    for c in c0..=c1 {
        // The part of the core within `reach` of the column's strip.
        let xa = origin.x + c as f64 * cell - reach;
        let ta = (xa - p.x) * inv_dx;
        let tb = (xa + cell + 2.0 * reach - p.x) * inv_dx;
        let (t0, t1) = (ta.min(tb).max(0.0), ta.max(tb).min(1.0));
        if t0 > t1 {
            continue;
        }
        let (ya, yb) = (p.y + t0 * d.y, p.y + t1 * d.y);
        let k_lo = (ya.min(yb) - reach - origin.y) * inv;
        let k_hi = (ya.max(yb) + reach - origin.y) * inv;
        if k_hi < 0.0 || k_lo >= rows as f64 {
            continue;
        }
        let (k0, k1) = (cell_index(k_lo, rows), cell_index(k_hi, rows));
        for k in k0..=k1 {
            if visit(c, k) {
                return true;
            }
        }
    }
    false
}

/// Blocked cells along the probe, and for thin probes the seams between
/// blocked cells and the corners of four blocked cells.
#[inline(never)]
fn grid_hit(g: &IndexedGrid, probe: &Probe, near: Near) -> bool {
    let e = TOUCH_EPS;
    let cell_hit = |col: usize, k: usize| {
        if !g.blocked(col, k) {
            return false;
        }
        let x0 = g.origin.x + col as f64 * g.cell;
        let y0 = g.origin.y + k as f64 * g.cell;
        let (x1, y1) = (x0 + g.cell, y0 + g.cell);
        let cell = Aabb {
            min: Point::new(x0, y0),
            max: Point::new(x1, y1),
        };
        if box_hit(&cell, probe) {
            return true;
        }
        if !probe.thin {
            return false;
        }
        let band = |lx: f64, ly: f64, hx: f64, hy: f64| {
            segment_meets_open_box(probe.p, probe.q, Point::new(lx, ly), Point::new(hx, hy))
        };
        let right = col + 1 < g.width && g.blocked(col + 1, k);
        let above = k + 1 < g.height && g.blocked(col, k + 1);
        (right && band(x1 - e, y0 + e, x1 + e, y1 - e))
            || (above && band(x0 + e, y1 - e, x1 - e, y1 + e))
            || (right
                && above
                && g.blocked(col + 1, k + 1)
                && band(x1 - 2.0 * e, y1 - 2.0 * e, x1 + 2.0 * e, y1 + 2.0 * e))
    };
    match near {
        Near::None => false,
        Near::Some { cols, rows } => {
            if !probe.moving {
                // A disk well inside one cell meets that cell only, and
                // overlaps it deeply if it is blocked.
                let fx = (probe.p.x - g.origin.x) * g.inv;
                let fy = (probe.p.y - g.origin.y) * g.inv;
                let (col, k) = (cell_index(fx, g.width), cell_index(fy, g.height));
                let (ux, uy) = ((fx - col as f64) * g.cell, (fy - k as f64) * g.cell);
                let clearance = ux.min(g.cell - ux).min(uy).min(g.cell - uy);
                if clearance > probe.r + 4.0 * TOUCH_EPS {
                    return g.blocked(col, k);
                }
            }
            (rows.0..rows.1 + 1).any(|k| (cols.0..cols.1 + 1).any(|c| cell_hit(c, k)))
        }
        Near::Unknown => visit_cells_along(
            g.origin,
            g.cell,
            g.inv,
            (g.width, g.height),
            probe,
            cell_hit,
        ),
    }
}

/// Whether the probe overlaps the convex piece bounded by `edges` deeper
/// than TOUCH_EPS: separating axes (the piece's normals, the core's normal)
/// first, then the exact distance if the cores are disjoint.
#[inline]
fn convex_hit(edges: &[Edge], probe: &Probe) -> bool {
    let limit = probe.r - TOUCH_EPS;
    let (p, q) = (probe.p.coords, probe.q.coords);
    let mut gap = f64::NEG_INFINITY;
    for e in edges {
        let g = e.n.dot(&p).min(e.n.dot(&q)) - e.c;
        if g >= limit {
            return false;
        }
        gap = gap.max(g);
    }
    if probe.moving {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let m = probe.normal();
        for e in edges {
            let s = m.dot(&(e.a - probe.p));
            lo = lo.min(s);
            hi = hi.max(s);
        }
        let g = lo.max(-hi);
        if g >= limit {
            return false;
        }
        gap = gap.max(g);
    }
    if gap < 0.0 {
        return true;
    }
    let n = edges.len();
    let to_piece = |x: Point| {
        (0..n)
            .map(|i| distance_point_segment(x, edges[i].a, edges[(i + 1) % n].a))
            .fold(f64::INFINITY, f64::min)
    };
    let mut distance = to_piece(probe.p);
    if probe.moving {
        distance = distance.min(to_piece(probe.q));
        for e in edges {
            distance = distance.min(probe.distance_to(e.a));
        }
    }
    distance < limit
}

/// [`convex_hit`] for an axis-aligned box.
#[inline]
fn box_hit(b: &Aabb, probe: &Probe) -> bool {
    let limit = probe.r - TOUCH_EPS;
    let (p, q) = (probe.p, probe.q);
    let gx = (b.min.x - p.x.max(q.x)).max(p.x.min(q.x) - b.max.x);
    if gx >= limit {
        return false;
    }
    let gy = (b.min.y - p.y.max(q.y)).max(p.y.min(q.y) - b.max.y);
    if gy >= limit {
        return false;
    }
    let mut gap = gx.max(gy);
    if probe.moving {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let m = probe.normal();
        for corner in b.corners() {
            let s = m.dot(&(corner - p));
            lo = lo.min(s);
            hi = hi.max(s);
        }
        let g = lo.max(-hi);
        if g >= limit {
            return false;
        }
        gap = gap.max(g);
    }
    if gap < 0.0 {
        return true;
    }
    let distance = if probe.moving {
        let corners = b.corners();
        let mut d = distance_point_box(p, b).min(distance_point_box(q, b));
        for corner in corners {
            d = d.min(probe.distance_to(corner));
        }
        d
    } else {
        gx.max(0.0).hypot(gy.max(0.0))
    };
    distance < limit
}

/// Whether the probe meets the segment obstacle `ab` deeper than TOUCH_EPS,
/// or, for a thin probe (a point), comes within TOUCH_EPS of it at all.
/// Two crossing segments overlap by the smallest distance of an endpoint to
/// the other's line (their Minkowski difference is a parallelogram).
#[inline]
fn wall_hit(a: Point, b: Point, probe: &Probe) -> bool {
    if probe.thin {
        return thin_wall_distance(a, b, probe) <= TOUCH_EPS;
    }
    let limit = probe.r - TOUCH_EPS;
    if !probe.moving {
        return distance_point_segment(probe.p, a, b) < limit;
    }
    let w = b - a;
    let wl = w.norm();
    if wl == 0.0 {
        return probe.distance_to(a) < limit;
    }
    let (p, q) = (probe.p, probe.q);
    let (d1, d2) = (w.perp(&(p - a)) / wl, w.perp(&(q - a)) / wl);
    let (d3, d4) = (
        probe.d.perp(&(a - p)) / probe.d.norm(),
        probe.d.perp(&(b - p)) / probe.d.norm(),
    );
    if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
        let depth = d1.abs().min(d2.abs()).min(d3.abs()).min(d4.abs());
        return -depth < limit;
    }
    if limit <= 0.0 {
        return false;
    }
    let distance = distance_point_segment(p, a, b)
        .min(distance_point_segment(q, a, b))
        .min(probe.distance_to(a))
        .min(probe.distance_to(b));
    distance < limit
}

/// The distance from the probe's core to the segment `ab` (0 when they
/// cross).
#[inline]
fn thin_wall_distance(a: Point, b: Point, probe: &Probe) -> f64 {
    let (p, q) = (probe.p, probe.q);
    if !probe.moving {
        return distance_point_segment(p, a, b);
    }
    let w = b - a;
    let (d1, d2) = (w.perp(&(p - a)), w.perp(&(q - a)));
    let (d3, d4) = (probe.d.perp(&(a - p)), probe.d.perp(&(b - p)));
    if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
        return 0.0;
    }
    distance_point_segment(p, a, b)
        .min(distance_point_segment(q, a, b))
        .min(probe.distance_to(a))
        .min(probe.distance_to(b))
}

/// Whether the closed segment `pq` (a point when `p == q`) meets the open
/// box `(lo, hi)`: Liang–Barsky clipping with strict inequalities.
#[inline]
pub fn segment_meets_open_box(p: Point, q: Point, lo: Point, hi: Point) -> bool {
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (s, d, l, h) in [(p.x, q.x - p.x, lo.x, hi.x), (p.y, q.y - p.y, lo.y, hi.y)] {
        if d == 0.0 {
            if !(s > l && s < h) {
                return false;
            }
        } else {
            let (ta, tb) = ((l - s) / d, (h - s) / d);
            t0 = t0.max(ta.min(tb));
            t1 = t1.min(ta.max(tb));
        }
    }
    t0 < t1 || (p == q && t0 <= t1)
}

/// Whether obstacle `shape` overlaps the axis-aligned box `b` by more than
/// touching; a wall, whether it meets the open box. For solids the test
/// shrinks `b` by `TOUCH_EPS / 2` and asks whether the closed shapes meet:
/// whatever stays outside then overlaps `b` by less than `TOUCH_EPS` (at
/// most `TOUCH_EPS / √2` along any axis), so a body inside `b` touches at
/// most. A wall on `b`'s boundary does not overlap it (but a motion from
/// `b` to the box beside it would cross it: the caller's concern).
pub fn box_overlaps(b: &Aabb, shape: &Shape) -> bool {
    let s = TOUCH_EPS / 2.0;
    let inner = Aabb::from_corners(
        Point::new(b.min.x + s, b.min.y + s),
        Point::new(b.max.x - s, b.max.y - s),
    );
    match shape {
        Shape::Rect(r) => inner.meets(r),
        Shape::Disk { center, radius } => distance_point_box(*center, &inner) <= *radius,
        Shape::Polygon { pieces, .. } => pieces
            .iter()
            .any(|piece| convex_meets_box(&piece.vertices, &inner)),
        Shape::Segment(p, q) => segment_meets_open_box(*p, *q, b.min, b.max),
        Shape::Grid(g) => {
            let (cols, rows) = g.cells_overlapping(&inner);
            rows.into_iter().any(|row| {
                cols.clone()
                    .any(|col| g.is_blocked(col, row) && inner.meets(&g.cell_box(col, row)))
            })
        }
    }
}

/// Whether the closed convex polygon `v` (counter-clockwise) and the closed
/// box `b` meet: no separating axis among the box's and the polygon's edge
/// normals.
fn convex_meets_box(v: &[Point], b: &Aabb) -> bool {
    if !Aabb::around(v).meets(b) {
        return false;
    }
    let n = v.len();
    (0..n).all(|i| {
        let (a, c) = (v[i], v[(i + 1) % n]);
        // Outward normal of edge a → c of a counter-clockwise polygon.
        let normal = Vector::new(c.y - a.y, a.x - c.x);
        let box_min = b
            .corners()
            .iter()
            .map(|k| normal.dot(&(k - a)))
            .fold(f64::INFINITY, f64::min);
        // The polygon lies at ≤ 0 along its own outward normal.
        box_min <= 0.0
    })
}

/// The edges shared by two pieces (edges of a piece whose midpoint is not
/// within `1e-9 ×` the outline's size of the outline), once each, in
/// O(n log n) ([`polygon::proximity::shared_edges`]).
fn seams<'a>(
    outline: &[Point],
    vertices: &VertexIndex,
    pieces: impl Iterator<Item = &'a [Point]>,
) -> Vec<(Point, Point)> {
    let n = outline.len();
    let b = Aabb::around(outline);
    let tol = 1e-9 * b.width().max(b.height());
    shared_edges(outline, vertices, pieces, tol, |p, i| {
        distance_point_segment(p, outline[i], outline[(i + 1) % n])
    })
}

/// How far from its end `a` the band around the seam `a → b` starts, so
/// that the band (half-width ε) stays ε away from the outline edges at `a`:
/// a point u along the seam and w across is |u·sin α − w·cos α| from an edge
/// at angle α, which is ≥ ε when u ≥ ε·(1 + |cos α|)/sin α.
fn seam_end_margin(outline: &[Point], vertices: &VertexIndex, a: Point, b: Point) -> f64 {
    let n = outline.len();
    let Some(k) = vertices.of(a) else {
        return 2.0 * TOUCH_EPS;
    };
    let d = (b - a).normalize();
    let mut margin = TOUCH_EPS;
    for v in [outline[(k + n - 1) % n], outline[(k + 1) % n]] {
        let e = (v - a).normalize();
        margin = margin.max(TOUCH_EPS * (1.0 + d.dot(&e).abs()) / d.perp(&e).abs());
    }
    margin * 1.01
}

/// `floor(v)` clamped to `0 ..= n − 1`, for raster coordinates (a cast to
/// `i64` truncates and saturates; cheaper than `floor` and a cast to `usize`).
#[inline(always)]
fn cell_index(v: f64, n: usize) -> usize {
    let i = v as i64;
    if i <= 0 { 0 } else { (i as usize).min(n - 1) }
}

#[inline]
fn distance_point_box(x: Point, b: &Aabb) -> f64 {
    let dx = (b.min.x - x.x).max(x.x - b.max.x).max(0.0);
    let dy = (b.min.y - x.y).max(x.y - b.max.y).max(0.0);
    dx.hypot(dy)
}

fn grow(b: Aabb, by: f64) -> Aabb {
    let v = Vector::new(by, by);
    Aabb {
        min: b.min - v,
        max: b.max + v,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::random::random_world;
    use crate::fixtures::{grid, polygon_shape, rect, world};
    use crate::validator::{Validator, config_collision};
    use crate::{Config, Grid, RobotShape};
    use proptest::prelude::*;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    #[test]
    fn points_and_disks_against_each_kind() {
        let w = world(vec![
            rect(1.0, 1.0, 2.0, 2.0),
            Shape::Disk {
                center: p(5.0, 5.0),
                radius: 1.0,
            },
            Shape::Segment(p(8.0, 0.0), p(8.0, 4.0)),
            polygon_shape(&[p(1.0, 6.0), p(3.0, 6.0), p(2.0, 8.0)]).unwrap(),
        ]);
        let ix = ObstacleIndex::new(&w);
        assert_eq!(ix.disk_blocker(p(1.5, 1.5), 0.0), Some(0));
        assert!(ix.disk_free(p(2.0, 1.5), 0.0), "on the edge");
        assert!(ix.disk_free(p(2.5, 1.5), 0.5), "touching");
        assert!(!ix.disk_free(p(2.5, 1.5), 0.5 + 1e-8));
        assert_eq!(ix.disk_blocker(p(5.0, 6.5), 0.6), Some(1));
        assert!(ix.disk_free(p(5.0, 6.5), 0.5));
        assert!(
            !ix.disk_free(p(8.0, 2.0), 0.0),
            "a point on a wall is refused"
        );
        assert_eq!(ix.disk_blocker(p(8.0, 4.0 + 0.5e-9), 0.0), Some(2));
        assert!(ix.disk_free(p(8.0 + 2e-9, 2.0), 0.0));
        assert!(ix.disk_free(p(8.0, 4.0 + 2e-9), 0.0));
        assert_eq!(ix.disk_blocker(p(8.2, 2.0), 0.3), Some(2));
        assert!(ix.disk_free(p(8.3, 2.0), 0.3));
        assert_eq!(ix.disk_blocker(p(2.0, 7.0), 0.0), Some(3));
        assert!(ix.disk_free(p(2.0, 6.0), 0.0));
        assert!(ix.disk_free(p(2.0, 5.0), 1.0));
    }

    #[test]
    fn sweeps_touching_and_crossing() {
        let w = world(vec![
            rect(4.0, 4.0, 6.0, 6.0),
            Shape::Segment(p(8.0, 2.0), p(8.0, 8.0)),
        ]);
        let ix = ObstacleIndex::new(&w);
        // Through, along an edge, through a corner.
        assert_eq!(ix.sweep_blocker(p(1.0, 5.0), p(7.0, 5.0), 0.0), Some(0));
        assert!(ix.sweep_free(p(1.0, 6.0), p(7.0, 6.0), 0.0));
        assert!(ix.sweep_free(p(2.0, 4.0), p(6.0, 8.0), 0.0));
        // A disk rolling along the top, exactly touching.
        assert!(ix.sweep_free(p(1.0, 6.5), p(7.0, 6.5), 0.5));
        assert!(!ix.sweep_free(p(1.0, 6.5), p(7.0, 6.5), 0.5 + 1e-8));
        // The wall: crossing fails; a point touching it (its end, sliding
        // along it, reaching it or leaving it) is refused too, since the
        // next motion might leave on the other side.
        assert_eq!(ix.sweep_blocker(p(7.0, 5.0), p(9.0, 5.0), 0.0), Some(1));
        assert_eq!(ix.sweep_blocker(p(7.0, 8.0), p(9.0, 8.0), 0.0), Some(1));
        assert_eq!(ix.sweep_blocker(p(8.0, 1.0), p(8.0, 9.0), 0.0), Some(1));
        assert_eq!(ix.sweep_blocker(p(7.0, 5.0), p(8.0, 5.0), 0.0), Some(1));
        assert_eq!(ix.sweep_blocker(p(8.0, 5.0), p(9.0, 6.0), 0.0), Some(1));
        assert_eq!(
            ix.sweep_blocker(p(7.0, 8.0 + 0.5e-9), p(9.0, 8.0 + 0.5e-9), 0.0),
            Some(1)
        );
        assert!(ix.sweep_free(p(7.0, 8.0 + 2e-9), p(9.0, 8.0 + 2e-9), 0.0));
        assert!(ix.sweep_free(p(7.0, 5.0), p(8.0 - 2e-9, 5.0), 0.0));
        assert!(ix.sweep_free(p(8.0 + 2e-9, 1.0), p(8.0 + 2e-9, 9.0), 0.0));
        // A tiny disk is a point; a larger one may touch the wall.
        assert!(!ix.sweep_free(p(7.0, 8.0), p(9.0, 8.0), 0.5e-9));
        assert!(ix.sweep_free(p(7.0, 9.0), p(9.0, 9.0), 1.0));
        assert!(!ix.sweep_free(p(8.0, 1.0), p(8.0, 9.0), 0.1));
    }

    #[test]
    fn disk_between_two_walls_exactly_its_width_apart() {
        let w = world(vec![
            Shape::Segment(p(0.0, 2.0), p(10.0, 2.0)),
            Shape::Segment(p(0.0, 3.0), p(10.0, 3.0)),
            rect(0.0, 4.0, 10.0, 5.0),
        ]);
        let ix = ObstacleIndex::new(&w);
        assert!(ix.sweep_free(p(1.0, 2.5), p(9.0, 2.5), 0.5));
        assert!(!ix.sweep_free(p(1.0, 2.5), p(9.0, 2.5), 0.5 + 1e-8));
        assert!(ix.sweep_free(p(1.0, 3.5), p(9.0, 3.5), 0.5));
    }

    #[test]
    fn grid_corners_and_seams() {
        // Row 0 is the top: blocked cells [0,1]x[1,2] and [1,2]x[0,1].
        let w = world(vec![grid(1.0, p(0.0, 0.0), &["#.", ".#"])]);
        let ix = ObstacleIndex::new(&w);
        assert!(
            ix.sweep_free(p(0.5, 0.5), p(1.5, 1.5), 0.0),
            "diagonal through the corner"
        );
        assert!(!ix.sweep_free(p(0.5, 0.5), p(1.5, 0.5), 0.0));
        assert!(ix.disk_free(p(1.0, 1.0), 0.0));
        // A wall of two cells: its inner edge and the corner of four are inside.
        let w = world(vec![grid(1.0, p(0.0, 0.0), &["##.", "##.", "..."])]);
        let ix = ObstacleIndex::new(&w);
        assert!(
            !ix.disk_free(p(1.0, 1.0 + 1.0), 0.0),
            "corner of four blocked cells"
        );
        assert!(
            !ix.disk_free(p(1.0, 2.5), 0.0),
            "seam between two blocked cells"
        );
        assert!(
            !ix.sweep_free(p(1.0, 0.5), p(1.0, 3.5), 0.0),
            "sliding along a seam"
        );
        assert!(
            ix.sweep_free(p(0.0, 1.0), p(2.0, 1.0), 0.0),
            "along the outer boundary"
        );
        assert!(ix.sweep_free(p(2.0, 0.5), p(2.0, 3.5), 0.0));
        assert!(ix.disk_free(p(2.0, 1.0), 0.0));
    }

    #[test]
    fn polygon_seams_are_inside() {
        let l = polygon_shape(&[
            p(0.0, 0.0),
            p(4.0, 0.0),
            p(4.0, 2.0),
            p(2.0, 2.0),
            p(2.0, 4.0),
            p(0.0, 4.0),
        ])
        .unwrap();
        let Shape::Polygon { outline, pieces } = &l else {
            unreachable!()
        };
        let vertices = VertexIndex::new(outline);
        let shared = seams(
            outline,
            &vertices,
            pieces.iter().map(|pc| pc.vertices.as_slice()),
        );
        assert!(!shared.is_empty());
        let ix = ObstacleIndex::new(&world(vec![l.clone()]));
        for (a, b) in shared {
            assert!(!ix.disk_free(Point::from((a.coords + b.coords) / 2.0), 0.0));
            assert!(!ix.sweep_free(a, b, 0.0));
        }
        for i in 0..outline.len() {
            assert!(ix.sweep_free(outline[i], outline[(i + 1) % outline.len()], 0.0));
        }
    }

    #[test]
    fn long_sweeps_visit_only_the_cells_along_them() {
        // 512 x 512 cells; a blocked cell far off the diagonal does not
        // matter, one on it does.
        let mut cells = vec![1u8; 512 * 512];
        cells[10 * 512 + 500] = 0;
        let mut g = Grid {
            cell: 1.0 / 64.0,
            origin: p(1.0, 1.0),
            width: 512,
            height: 512,
            cells,
        };
        let w = world(vec![Shape::Grid(g.clone())]);
        let ix = ObstacleIndex::new(&w);
        assert!(ix.sweep_free(p(1.0, 1.0), p(9.0, 9.0), 0.0));
        g.cells[256 * 512 + 255] = 0;
        let ix = ObstacleIndex::new(&world(vec![Shape::Grid(g)]));
        assert!(!ix.sweep_free(p(1.0, 1.0), p(9.0, 9.0), 0.0));
        assert!(!ix.sweep_free(p(9.0, 9.0), p(1.0, 1.0), 0.01));
    }

    #[test]
    fn many_pieces_share_buckets() {
        let shapes: Vec<Shape> = (0..200)
            .map(|i| {
                let (x, y) = ((i % 20) as f64 * 0.5, (i / 20) as f64 * 1.0);
                rect(x, y, x + 0.2, y + 0.2)
            })
            .collect();
        let w = world(shapes);
        let ix = ObstacleIndex::new(&w);
        for (i, o) in w.obstacles.iter().enumerate() {
            let Shape::Rect(b) = &o.shape else {
                unreachable!()
            };
            let c = Point::from((b.min.coords + b.max.coords) / 2.0);
            assert_eq!(ix.disk_blocker(c, 0.0), Some(i));
        }
        assert!(ix.sweep_free(p(0.0, 0.5), p(10.0, 0.5), 0.1));
        assert!(!ix.sweep_free(p(0.0, 0.5), p(10.0, 0.5), 0.31));
    }

    // ------------------------------------------------ agreement with the validator

    /// `seams` as it was: every outline edge against every piece edge's
    /// midpoint, every seam against those taken. The oracle of the test
    /// below.
    fn all_pairs_seams(outline: &[Point], pieces: &[crate::ConvexPolygon]) -> Vec<(Point, Point)> {
        let n = outline.len();
        let b = Aabb::around(outline);
        let tol = 1e-9 * b.width().max(b.height());
        let mut out: Vec<(Point, Point)> = Vec::new();
        for v in pieces.iter().map(|p| &p.vertices) {
            for j in 0..v.len() {
                let (a, b) = (v[j], v[(j + 1) % v.len()]);
                let mid = Point::from((a.coords + b.coords) * 0.5);
                let on_outline = (0..n)
                    .any(|i| distance_point_segment(mid, outline[i], outline[(i + 1) % n]) <= tol);
                if !on_outline
                    && !out
                        .iter()
                        .any(|&(x, y)| (x, y) == (a, b) || (x, y) == (b, a))
                {
                    out.push((a, b));
                }
            }
        }
        out
    }

    fn probe_radius() -> impl Strategy<Value = f64> {
        prop_oneof![Just(0.0), 0.01..1.5f64]
    }

    fn validator_sweep_free(v: &Validator, p: Point, q: Point, r: f64) -> bool {
        let robot = if r == 0.0 {
            RobotShape::Point
        } else {
            RobotShape::Disk(r)
        };
        v.validate_path(
            &robot,
            &[Config::new(p.x, p.y, 0.0), Config::new(q.x, q.y, 0.0)],
            0.01,
        )
        .is_ok()
    }

    fn has_walls(w: &World) -> bool {
        w.obstacles
            .iter()
            .any(|o| matches!(o.shape, Shape::Segment(..)))
    }

    fn without_walls(w: &World) -> World {
        World {
            obstacles: w
                .obstacles
                .iter()
                .filter(|o| !matches!(o.shape, Shape::Segment(..)))
                .cloned()
                .collect(),
            ..w.clone()
        }
    }

    /// The distance from the segment `pq` (a point when `p == q`) to the
    /// nearest segment obstacle of `w`, by parry.
    fn wall_distance(w: &World, p: Point, q: Point) -> f64 {
        use parry2d_f64::math::Isometry;
        use parry2d_f64::shape::Segment;
        let id = Isometry::identity();
        w.obstacles
            .iter()
            .filter_map(|o| match o.shape {
                Shape::Segment(a, b) => Some(
                    parry2d_f64::query::distance(
                        &id,
                        &Segment::new(p, q),
                        &id,
                        &Segment::new(a, b),
                    )
                    .unwrap(),
                ),
                _ => None,
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Whether the verdict could flip within 1e-7 of `r` (exact contact,
    /// where rounding decides).
    fn ambiguous(ix: &ObstacleIndex, v: &Validator, p: Point, q: Point, r: f64) -> bool {
        let (lo, hi) = ((r - 1e-7).max(0.0), r + 1e-7);
        ix.sweep_free(p, q, lo) != ix.sweep_free(p, q, hi)
            || validator_sweep_free(v, p, q, lo) != validator_sweep_free(v, p, q, hi)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// The seams, found with the outline's vertices hashed and the
        /// midpoints swept, are those of the all-pairs search, in order.
        #[test]
        fn seams_are_those_of_the_all_pairs_search(
            v in prop::collection::vec((0..6i32, 0..6i32), 4..14),
            scale in prop::sample::select(vec![1.0, 1e-3, 7.5]),
        ) {
            let input: Vec<Point> = v.iter().map(|&(x, y)| p(x as f64 * scale, y as f64 * scale)).collect();
            if let Some(Shape::Polygon { outline, pieces }) = polygon_shape(&input) {
                let vertices = VertexIndex::new(&outline);
                prop_assert_eq!(
                    seams(&outline, &vertices, pieces.iter().map(|pc| pc.vertices.as_slice())),
                    all_pairs_seams(&outline, &pieces)
                );
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(5000))]

        #[test]
        /// Exact agreement, except for a point among segment obstacles: the
        /// planner refuses every contact with a segment, the validator only
        /// a passage from one side to the other. There a free sweep must be
        /// a valid path, and the planner's verdict is exactly "free of the
        /// other obstacles and farther than TOUCH_EPS from every segment".
        #[test]
        fn sweep_free_agrees_with_the_validator(
            w in random_world(),
            a in (-1.0..11.0f64, -1.0..11.0f64),
            b in (-1.0..11.0f64, -1.0..11.0f64),
            r in probe_radius(),
        ) {
            let (pa, pb) = (p(a.0, a.1), p(b.0, b.1));
            let ix = ObstacleIndex::new(&w);
            let v = Validator::new(&w);
            prop_assume!(!ambiguous(&ix, &v, pa, pb, r));
            let planner = ix.sweep_free(pa, pb, r);
            let referee = validator_sweep_free(&v, pa, pb, r);
            if r <= TOUCH_EPS && has_walls(&w) {
                if planner {
                    prop_assert!(referee);
                }
                let solid = without_walls(&w);
                let (ix2, v2) = (ObstacleIndex::new(&solid), Validator::new(&solid));
                prop_assume!(!ambiguous(&ix2, &v2, pa, pb, r));
                let d = wall_distance(&w, pa, pb);
                prop_assume!((d - TOUCH_EPS).abs() > 1e-12);
                let solid_free = ix2.sweep_free(pa, pb, r);
                prop_assert_eq!(solid_free, validator_sweep_free(&v2, pa, pb, r));
                prop_assert_eq!(planner, solid_free && d > TOUCH_EPS);
            } else {
                prop_assert_eq!(planner, referee);
            }
        }

        #[test]
        fn disk_free_agrees_with_config_collision(
            w in random_world(),
            a in (-1.0..11.0f64, -1.0..11.0f64),
            r in probe_radius(),
        ) {
            let pa = p(a.0, a.1);
            let ix = ObstacleIndex::new(&w);
            let v = Validator::new(&w);
            prop_assume!(!ambiguous(&ix, &v, pa, pa, r));
            let robot = if r == 0.0 { RobotShape::Point } else { RobotShape::Disk(r) };
            let at = Config::new(pa.x, pa.y, 0.0);
            let blocker = ix.disk_blocker(pa, r);
            let referee = config_collision(&w, &robot, at).is_none();
            if r <= TOUCH_EPS && has_walls(&w) {
                // Sitting on a segment is refused by the planner only.
                if blocker.is_none() {
                    prop_assert!(referee);
                }
                let d = wall_distance(&w, pa, pa);
                prop_assume!((d - TOUCH_EPS).abs() > 1e-12);
                let solid = without_walls(&w);
                let solid_free = ObstacleIndex::new(&solid).disk_free(pa, r);
                prop_assert_eq!(solid_free, config_collision(&solid, &robot, at).is_none());
                prop_assert_eq!(blocker.is_none(), solid_free && d > TOUCH_EPS);
            } else {
                prop_assert_eq!(blocker.is_none(), referee);
            }
            if let Some(i) = blocker {
                // The blocker named is one the validator agrees on (or a
                // segment the point touches).
                let alone = World { obstacles: vec![w.obstacles[i].clone()], ..w.clone() };
                prop_assert!(
                    config_collision(&alone, &robot, at).is_some()
                        || (r <= TOUCH_EPS && wall_distance(&alone, pa, pa) <= TOUCH_EPS)
                );
            }
        }

        /// Lattice paths among segment walls with integer ends (closed and
        /// open chains, T and X junctions, collinear overlaps): a point
        /// moving only along moves that `sweep_free` accepts never crosses
        /// a wall, so the validator accepts every such path.
        #[test]
        fn point_lattice_paths_among_segments_are_valid(
            walls in prop::collection::vec((0..9i32, 0..9i32, 0..9i32, 0..9i32), 1..7),
            chain in prop::collection::vec((0..9i32, 0..9i32), 3..7),
            closed in any::<bool>(),
            start in (0..17i32, 0..17i32),
            steps in prop::collection::vec((-2..3i32, -2..3i32), 1..30),
        ) {
            let q = |x: i32, y: i32| p(x as f64, y as f64);
            let mut shapes: Vec<Shape> = walls
                .iter()
                .map(|&(x0, y0, x1, y1)| Shape::Segment(q(x0, y0), q(x1, y1)))
                .collect();
            let n = chain.len();
            for i in 0..(if closed { n } else { n - 1 }) {
                let ((x0, y0), (x1, y1)) = (chain[i], chain[(i + 1) % n]);
                shapes.push(Shape::Segment(q(x0, y0), q(x1, y1)));
            }
            let mut w = world(shapes);
            w.bounds = Aabb { min: p(-100.0, -100.0), max: p(100.0, 100.0) };
            let ix = ObstacleIndex::new(&w);
            let mut at = p(start.0 as f64 * 0.5, start.1 as f64 * 0.5);
            let mut path = vec![Config::new(at.x, at.y, 0.0)];
            for (dx, dy) in steps {
                let next = p(at.x + dx as f64 * 0.5, at.y + dy as f64 * 0.5);
                if ix.sweep_free(at, next, 0.0) {
                    path.push(Config::new(next.x, next.y, 0.0));
                    at = next;
                }
            }
            let v = Validator::new(&w);
            prop_assert!(v.validate_path(&RobotShape::Point, &path, 0.01).is_ok(), "{:?}", path);
        }

        /// On a half-unit lattice over a unit grid every contact is exact:
        /// seams, corners and edges are met exactly, and the two must still
        /// agree (no tolerance band).
        #[test]
        fn lattice_moves_on_unit_grids_agree_exactly(
            bits in prop::collection::vec(prop::bool::weighted(0.5), 36),
            a in (0..13i32, 0..13i32),
            step in (-2..3i32, -2..3i32),
            r in prop_oneof![Just(0.0), Just(0.5), Just(0.25)],
        ) {
            let cells = bits.iter().map(|&b| if b { 0 } else { 1 }).collect();
            let mut w = world(vec![Shape::Grid(Grid { cell: 1.0, origin: p(0.0, 0.0), width: 6, height: 6, cells })]);
            w.bounds = Aabb { min: p(-100.0, -100.0), max: p(100.0, 100.0) };
            let pa = p(a.0 as f64 * 0.5, a.1 as f64 * 0.5);
            let pb = p(pa.x + step.0 as f64 * 0.5, pa.y + step.1 as f64 * 0.5);
            let ix = ObstacleIndex::new(&w);
            let v = Validator::new(&w);
            prop_assert_eq!(ix.sweep_free(pa, pb, r), validator_sweep_free(&v, pa, pb, r));
        }
    }
}

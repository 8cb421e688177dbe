//! The boundary of the union of the grown obstacles, as an arrangement of
//! non-crossing segments, with what the visibility test needs at each point.
//!
//! Input: convex polygons with interior (the grown obstacles) and walls
//! (segment obstacles of a point robot, without interior). Every edge is
//! split where it meets another edge (proper crossings, an end lying on
//! another edge, collinear overlaps) and where it passes through the start
//! or the goal; the pieces strictly inside another polygon are dropped, so
//! what remains is the boundary of the union: segments that meet only at
//! their ends. Polygon pieces keep their direction (interior on the left).
//! Two pieces of the *same* world obstacle lying on each other in opposite
//! directions are a seam inside that obstacle (two convex pieces of a
//! non-convex polygon, two blocked grid cells side by side) and are both
//! dropped: a point robot may not slide along a seam (the validator's rule).
//!
//! Nodes of the roadmap are the points that are vertices of the input
//! (obstacle vertices, wall ends), the start and the goal, inside `bounds`
//! and not strictly inside any polygon. Points made by crossings are ends of
//! pieces but never nodes: the union is locally concave there, and no
//! shortest path bends at such a point.

use std::collections::HashMap;

use crate::geometry::{Aabb, Point, Vector};

/// A piece of the union's boundary, or of a wall.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Seg {
    /// Point indices; for a polygon piece the interior lies on the left of
    /// `a → b`.
    pub a: u32,
    pub b: u32,
    pub wall: bool,
}

/// The arrangement of [`build`].
#[derive(Clone, Debug)]
pub struct Arrangement {
    pub points: Vec<Point>,
    /// Whether each point is a roadmap node.
    pub is_node: Vec<bool>,
    pub segs: Vec<Seg>,
    /// Per point, the segments that end there.
    pub incident: Vec<Vec<u32>>,
    /// Per point, the directions of the walls leaving it (exact duplicates
    /// merged), sorted counter-clockwise: they cut the directions around the
    /// point into sectors (see [`Arrangement::classify`]).
    pub rays: Vec<Vec<Vector>>,
    pub start: u32,
    pub goal: u32,
    /// The polygon edges that were cut: their points in order along the
    /// edge, each with whether the piece to the next one is boundary.
    pub chains: Vec<Vec<(u32, bool)>>,
    /// Per point, the cut edges it lies on: (chain, position).
    pub on_chain: Vec<Vec<(u32, u32)>>,
}

/// Where a direction lies among the rays of a point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Way {
    /// Strictly inside sector `i` (counter-clockwise of ray `i`, up to ray
    /// `i + 1`).
    Sector(usize),
    /// Exactly along ray `i`.
    Ray(usize),
}

/// A convex polygon (counter-clockwise) with the world obstacle it grew from.
#[derive(Clone, Debug)]
pub struct Grown {
    pub vertices: Vec<Point>,
    pub obstacle: usize,
}

/// A wall (segment obstacle of a point robot) and its obstacle.
#[derive(Clone, Copy, Debug)]
pub struct WallIn {
    pub a: Point,
    pub b: Point,
    pub obstacle: usize,
}

/// `cross(b - a, c - a)`: positive when `a, b, c` turn left.
pub fn orient(a: Point, b: Point, c: Point) -> f64 {
    (b - a).perp(&(c - a))
}

/// Whether the angle of `w` from the x axis lies in `[0, π)`.
pub fn upper_half(w: Vector) -> bool {
    w.y > 0.0 || (w.y == 0.0 && w.x > 0.0)
}

/// Compares the counter-clockwise angles from `o` to `a` and from `o` to
/// `b`, in `[0, 2π)`, exactly (half plane, then the cross product).
pub fn ccw_cmp(o: Vector, a: Vector, b: Vector) -> std::cmp::Ordering {
    let rot = |w: Vector| Vector::new(o.dot(&w), o.perp(&w));
    let (ra, rb) = (rot(a), rot(b));
    let half = |w: Vector| u8::from(!upper_half(w));
    half(ra).cmp(&half(rb)).then_with(|| {
        0.0.partial_cmp(&ra.perp(&rb))
            .unwrap_or(std::cmp::Ordering::Equal)
    })
}

/// Whether two non-zero vectors point the same way exactly.
pub fn same_dir(a: Vector, b: Vector) -> bool {
    a.perp(&b) == 0.0 && a.dot(&b) > 0.0
}

/// A uniform grid of buckets over a box, each listing the items whose
/// bounding boxes meet it.
pub struct Buckets {
    min: Point,
    cell: f64,
    nx: usize,
    ny: usize,
    items: Vec<Vec<u32>>,
}

impl Buckets {
    /// About `n` buckets over `extent`.
    pub fn new(extent: Aabb, n: usize) -> Self {
        let side = (n.max(1) as f64).sqrt().ceil().clamp(1.0, 1024.0);
        let size = extent.width().max(extent.height()).max(1e-9);
        let cell = size / side;
        let nx = ((extent.width() / cell).floor() as usize + 1).min(1025);
        let ny = ((extent.height() / cell).floor() as usize + 1).min(1025);
        Buckets {
            min: extent.min,
            cell,
            nx,
            ny,
            items: vec![Vec::new(); nx * ny],
        }
    }

    fn coord(&self, v: f64, lo: f64, n: usize) -> usize {
        let k = ((v - lo) / self.cell).floor();
        if k.is_nan() || k < 0.0 {
            0
        } else {
            (k as usize).min(n - 1)
        }
    }

    fn cell_of(&self, p: Point) -> (usize, usize) {
        (
            self.coord(p.x, self.min.x, self.nx),
            self.coord(p.y, self.min.y, self.ny),
        )
    }

    pub fn insert(&mut self, item: u32, b: &Aabb) {
        let (x0, y0) = self.cell_of(b.min);
        let (x1, y1) = self.cell_of(b.max);
        for y in y0..=y1 {
            for x in x0..=x1 {
                self.items[y * self.nx + x].push(item);
            }
        }
    }

    /// The items whose boxes may contain `p`.
    pub fn at(&self, p: Point) -> &[u32] {
        let (x, y) = self.cell_of(p);
        &self.items[y * self.nx + x]
    }

    /// Every pair of items sharing a bucket, each pair once: a pair is
    /// reported by the bucket holding the lower-left corner of the
    /// intersection of their boxes.
    pub fn pairs(&self, boxes: &[Aabb], mut f: impl FnMut(u32, u32)) {
        for y in 0..self.ny {
            for x in 0..self.nx {
                let list = &self.items[y * self.nx + x];
                for (k, &i) in list.iter().enumerate() {
                    for &j in &list[k + 1..] {
                        let (bi, bj) = (&boxes[i as usize], &boxes[j as usize]);
                        if bi.min.x > bj.max.x
                            || bj.min.x > bi.max.x
                            || bi.min.y > bj.max.y
                            || bj.min.y > bi.max.y
                        {
                            continue;
                        }
                        let corner = Point::new(bi.min.x.max(bj.min.x), bi.min.y.max(bj.min.y));
                        if self.cell_of(corner) == (x, y) {
                            f(i, j);
                        }
                    }
                }
            }
        }
    }
}

/// An exact key for a point (`-0` and `0` are one point).
fn key(p: Point) -> (u64, u64) {
    ((p.x + 0.0).to_bits(), (p.y + 0.0).to_bits())
}

/// The polygons with their bounding boxes and a bucket index, for "strictly
/// inside" queries.
pub struct PolygonIndex<'a> {
    polys: &'a [Grown],
    buckets: Buckets,
    /// A distance below which a point counts as on an edge's line.
    tol: f64,
}

impl<'a> PolygonIndex<'a> {
    pub fn new(polys: &'a [Grown], extent: Aabb, tol: f64) -> Self {
        let mut buckets = Buckets::new(extent, polys.len());
        for (i, p) in polys.iter().enumerate() {
            buckets.insert(i as u32, &Aabb::around(&p.vertices));
        }
        PolygonIndex {
            polys,
            buckets,
            tol,
        }
    }

    /// The first polygon (other than `skip`) whose interior contains `p`
    /// farther than the tolerance from its boundary.
    pub fn inside(&self, p: Point, skip: Option<usize>) -> Option<usize> {
        self.buckets
            .at(p)
            .iter()
            .map(|&i| i as usize)
            .filter(|&i| Some(i) != skip)
            .find(|&i| strictly_inside(&self.polys[i].vertices, p, self.tol))
    }
}

/// Whether `p` lies in the convex polygon farther than `tol` from each
/// edge's line.
pub fn strictly_inside(poly: &[Point], p: Point, tol: f64) -> bool {
    let n = poly.len();
    (0..n).all(|i| {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        orient(a, b, p) > tol * (b - a).norm()
    })
}

/// A directed piece by the exact keys of its ends.
type PieceKey = ((u64, u64), (u64, u64));
/// A piece's obstacle, whether it is a seam, and its ends.
type PieceInfo = (usize, bool, Point, Point);

/// An input edge before splitting.
struct RawEdge {
    a: Point,
    b: Point,
    /// Index of the polygon, or `None` for a wall.
    poly: Option<usize>,
    obstacle: usize,
    /// Points where the edge is cut, with their parameter along it.
    cuts: Vec<(f64, Point)>,
}

impl RawEdge {
    fn param(&self, p: Point) -> f64 {
        let d = self.b - self.a;
        (p - self.a).dot(&d) / d.norm_squared()
    }

    /// Cuts at `p` when it lies strictly between the ends.
    fn cut(&mut self, p: Point) {
        let t = self.param(p);
        if t > 0.0 && t < 1.0 && p != self.a && p != self.b {
            self.cuts.push((t, p));
        }
    }
}

/// Builds the arrangement (see the module documentation).
///
/// `tol` is the distance under which the start or the goal counts as lying
/// on an edge (the edge is then cut there) and under which a point counts
/// as on a polygon's boundary rather than inside.
pub fn build(
    polys: &[Grown],
    walls: &[WallIn],
    start: Point,
    goal: Point,
    bounds: Aabb,
    tol: f64,
) -> Arrangement {
    let mut edges: Vec<RawEdge> = Vec::new();
    let mut originals: HashMap<(u64, u64), ()> = HashMap::new();
    for (k, poly) in polys.iter().enumerate() {
        let n = poly.vertices.len();
        for i in 0..n {
            let (a, b) = (poly.vertices[i], poly.vertices[(i + 1) % n]);
            originals.insert(key(a), ());
            if a != b {
                edges.push(RawEdge {
                    a,
                    b,
                    poly: Some(k),
                    obstacle: poly.obstacle,
                    cuts: Vec::new(),
                });
            }
        }
    }
    for w in walls {
        originals.insert(key(w.a), ());
        originals.insert(key(w.b), ());
        if w.a != w.b {
            edges.push(RawEdge {
                a: w.a,
                b: w.b,
                poly: None,
                obstacle: w.obstacle,
                cuts: Vec::new(),
            });
        }
    }
    let boxes: Vec<Aabb> = edges.iter().map(|e| Aabb::around(&[e.a, e.b])).collect();
    let mut extent = Aabb::around(&[start, goal, bounds.min, bounds.max]);
    for b in &boxes {
        extent = Aabb::around(&[extent.min, extent.max, b.min, b.max]);
    }

    // Cut the edges where they meet.
    let mut buckets = Buckets::new(extent, edges.len());
    for (i, b) in boxes.iter().enumerate() {
        buckets.insert(i as u32, b);
    }
    let mut cuts: Vec<(usize, Point)> = Vec::new();
    buckets.pairs(&boxes, |i, j| {
        let (e, f) = (&edges[i as usize], &edges[j as usize]);
        let o1 = orient(e.a, e.b, f.a);
        let o2 = orient(e.a, e.b, f.b);
        let o3 = orient(f.a, f.b, e.a);
        let o4 = orient(f.a, f.b, e.b);
        if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
            let x = e.a + (e.b - e.a) * (o3 / (o3 - o4));
            cuts.push((i as usize, x));
            cuts.push((j as usize, x));
            return;
        }
        if o1 == 0.0 {
            cuts.push((i as usize, f.a));
        }
        if o2 == 0.0 {
            cuts.push((i as usize, f.b));
        }
        if o3 == 0.0 {
            cuts.push((j as usize, e.a));
        }
        if o4 == 0.0 {
            cuts.push((j as usize, e.b));
        }
    });
    for (i, p) in cuts {
        edges[i].cut(p);
    }
    for e in edges.iter_mut() {
        for s in [start, goal] {
            let d = e.b - e.a;
            let t = e.param(s);
            if t > 0.0 && t < 1.0 && (orient(e.a, e.b, s) / d.norm()).abs() <= tol {
                e.cut(s);
            }
        }
    }

    // Pieces; drop those inside another polygon, and seams.
    let index = PolygonIndex::new(polys, extent, tol);
    let mut pieces: HashMap<PieceKey, PieceInfo> = HashMap::new();
    let mut order: Vec<PieceKey> = Vec::new();
    let mut wall_pieces: Vec<(Point, Point)> = Vec::new();
    let mut cut_chains: Vec<Vec<Point>> = Vec::new();
    let mut seams: Vec<PieceKey> = Vec::new();
    // Wall pieces inside polygons: not segments of the arrangement, but
    // where one meets the boundary it still separates the two sides of the
    // wall there (the validator sees the whole wall).
    let mut hidden_walls: Vec<(Point, Point)> = Vec::new();
    for e in &mut edges {
        e.cuts.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut chain = vec![e.a];
        for &(_, p) in &e.cuts {
            if chain.last() != Some(&p) {
                chain.push(p);
            }
        }
        if chain.last() != Some(&e.b) {
            chain.push(e.b);
        }
        if e.poly.is_some() && chain.len() > 2 {
            cut_chains.push(chain.clone());
        }
        for w in chain.windows(2) {
            let (p, q) = (w[0], w[1]);
            let mid = Point::from((p.coords + q.coords) / 2.0);
            if index.inside(mid, e.poly).is_some() {
                if e.poly.is_none() {
                    hidden_walls.push((p, q));
                }
                continue;
            }
            match e.poly {
                None => wall_pieces.push(if key(p) < key(q) { (p, q) } else { (q, p) }),
                Some(k) => {
                    let (kp, kq) = (key(p), key(q));
                    if let Some(&(o, _, _, _)) = pieces.get(&(kq, kp))
                        && o == e.obstacle
                        && polys[k].obstacle == o
                    {
                        seams.push((kq, kp));
                        seams.push((kp, kq));
                        continue;
                    }
                    if pieces.insert((kp, kq), (e.obstacle, false, p, q)).is_none() {
                        order.push((kp, kq));
                    }
                }
            }
        }
    }
    for s in seams {
        if let Some(v) = pieces.get_mut(&s) {
            v.1 = true;
        }
    }
    wall_pieces.sort_by_key(|x| (key(x.0), key(x.1)));
    wall_pieces.dedup();

    // Points and segments.
    let mut ids: HashMap<(u64, u64), u32> = HashMap::new();
    let mut points: Vec<Point> = Vec::new();
    let mut intern = |p: Point, points: &mut Vec<Point>| -> u32 {
        *ids.entry(key(p)).or_insert_with(|| {
            points.push(p);
            (points.len() - 1) as u32
        })
    };
    let start_id = intern(start, &mut points);
    let goal_id = intern(goal, &mut points);
    let mut segs = Vec::new();
    for k in &order {
        let (_, seam, p, q) = pieces[k];
        if !seam {
            let (a, b) = (intern(p, &mut points), intern(q, &mut points));
            segs.push(Seg { a, b, wall: false });
        }
    }
    for &(p, q) in &wall_pieces {
        let (a, b) = (intern(p, &mut points), intern(q, &mut points));
        segs.push(Seg { a, b, wall: true });
    }
    let mut chains = Vec::new();
    let mut on_chain: Vec<Vec<(u32, u32)>> = Vec::new();
    for chain in &cut_chains {
        let mut out = Vec::with_capacity(chain.len());
        for (i, &p) in chain.iter().enumerate() {
            let boundary = chain.get(i + 1).is_some_and(|&q| {
                pieces
                    .get(&(key(p), key(q)))
                    .is_some_and(|&(_, seam, _, _)| !seam)
            });
            // Ends of pieces that are inside are no points of the arrangement.
            out.push((intern(p, &mut points), boundary));
        }
        chains.push(out);
    }
    let n = points.len();
    on_chain.resize(n, Vec::new());
    for (c, chain) in chains.iter().enumerate() {
        for (i, &(p, _)) in chain.iter().enumerate() {
            on_chain[p as usize].push((c as u32, i as u32));
        }
    }
    let mut incident = vec![Vec::new(); n];
    let mut rays: Vec<Vec<Vector>> = vec![Vec::new(); n];
    for (i, s) in segs.iter().enumerate() {
        incident[s.a as usize].push(i as u32);
        incident[s.b as usize].push(i as u32);
        if s.wall {
            let d = points[s.b as usize] - points[s.a as usize];
            rays[s.a as usize].push(d);
            rays[s.b as usize].push(-d);
        }
    }
    for &(p, q) in &hidden_walls {
        if let (Some(&a), Some(&b)) = (ids.get(&key(p)), ids.get(&key(q))) {
            rays[a as usize].push(q - p);
            rays[b as usize].push(p - q);
        } else if let Some(&a) = ids.get(&key(p)) {
            rays[a as usize].push(q - p);
        } else if let Some(&b) = ids.get(&key(q)) {
            rays[b as usize].push(p - q);
        }
    }
    for r in rays.iter_mut() {
        if r.len() > 1 {
            let o = r[0];
            r.sort_by(|x, y| ccw_cmp(o, *x, *y));
            r.dedup_by(|x, y| same_dir(*x, *y));
        }
    }
    let is_node = (0..n)
        .map(|i| {
            let p = points[i];
            let vertex =
                i as u32 == start_id || i as u32 == goal_id || originals.contains_key(&key(p));
            vertex && bounds.contains(p) && index.inside(p, None).is_none()
        })
        .collect();
    Arrangement {
        points,
        is_node,
        segs,
        incident,
        rays,
        start: start_id,
        goal: goal_id,
        chains,
        on_chain,
    }
}

impl Arrangement {
    /// For two points on one cut polygon edge, whether the motion between
    /// them along that edge stays on the union's boundary (every piece in
    /// between is boundary) and crosses no wall at a point in between;
    /// `None` when they share no cut edge. This decides such motions
    /// exactly, where the sweep would depend on how the cut points were
    /// rounded.
    pub fn along_cut_edge(&self, v: u32, p: u32) -> Option<bool> {
        let on_v = &self.on_chain[v as usize];
        let on_p = &self.on_chain[p as usize];
        let (c, i, j) = on_v.iter().find_map(|&(c, i)| {
            on_p.iter()
                .find(|&&(c2, _)| c2 == c)
                .map(|&(_, j)| (c, i.min(j) as usize, i.max(j) as usize))
        })?;
        let chain = &self.chains[c as usize];
        if !chain[i..j].iter().all(|&(_, boundary)| boundary) {
            return Some(false);
        }
        let d = self.points[p as usize] - self.points[v as usize];
        let mut sides = Sides::BOTH;
        for &(x, _) in &chain[i + 1..j] {
            sides = sides.pass(self, x, d);
        }
        Some(sides.open())
    }

    /// Whether leaving point `x` in direction `d` enters the interior of a
    /// polygon whose boundary passes through `x`: `d` lies strictly inside
    /// a sector that the boundary pieces at `x` leave on their left.
    pub fn into_interior(&self, x: u32, d: Vector) -> bool {
        let segs = &self.incident[x as usize];
        let p = self.points[x as usize];
        let dir = |s: &Seg| {
            if s.a == x {
                self.points[s.b as usize] - p
            } else {
                self.points[s.a as usize] - p
            }
        };
        for s in segs.iter().map(|&i| &self.segs[i as usize]) {
            if s.wall || s.a != x {
                continue;
            }
            // A piece leaving x: the interior is counter-clockwise of it, up
            // to the next boundary direction.
            let o = dir(s);
            let next = segs
                .iter()
                .map(|&i| &self.segs[i as usize])
                .filter(|t| !t.wall)
                .map(dir)
                .filter(|&w| !same_dir(w, o))
                .min_by(|a, b| ccw_cmp(o, *a, *b));
            if same_dir(d, o) {
                continue;
            }
            match next {
                None => return true,
                Some(w) => {
                    if ccw_cmp(o, d, w) == std::cmp::Ordering::Less {
                        return true;
                    }
                }
            }
        }
        false
    }

    /// Where direction `d` lies among the wall rays at point `x`
    /// (`Sector(0)` when there are none).
    pub fn classify(&self, x: u32, d: Vector) -> Way {
        let rays = &self.rays[x as usize];
        if rays.is_empty() {
            return Way::Sector(0);
        }
        let o = rays[0];
        for (i, r) in rays.iter().enumerate() {
            if same_dir(*r, d) {
                return Way::Ray(i);
            }
        }
        // The last ray counter-clockwise before d.
        let mut sector = 0;
        for (i, r) in rays.iter().enumerate() {
            if ccw_cmp(o, *r, d) == std::cmp::Ordering::Less {
                sector = i;
            }
        }
        Way::Sector(sector)
    }

    /// The sectors at `x` on the left and on the right of a motion leaving
    /// `x` in direction `d` (the same sector unless `d` runs along a wall).
    pub fn sides(&self, x: u32, d: Vector) -> [usize; 2] {
        let n = self.rays[x as usize].len().max(1);
        match self.classify(x, d) {
            Way::Sector(m) => [m, m],
            Way::Ray(i) => [i, (i + n - 1) % n],
        }
    }

    /// Number of sectors at `x` (1 without walls).
    pub fn sector_count(&self, x: u32) -> usize {
        self.rays[x as usize].len().max(1)
    }
}

/// Which sides of a straight motion along walls are still open: the
/// validator's rule for a point passing wall vertices
/// ([`crate::geometry::validator::Validator::check_wall_crossings`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sides {
    pub left: bool,
    pub right: bool,
}

impl Sides {
    pub const BOTH: Sides = Sides {
        left: true,
        right: true,
    };

    pub fn open(self) -> bool {
        self.left || self.right
    }

    /// The sides still open after passing through point `x` while moving in
    /// direction `d`.
    pub fn pass(self, arr: &Arrangement, x: u32, d: Vector) -> Sides {
        let n = arr.rays[x as usize].len();
        if n == 0 {
            return self;
        }
        let ccw = |i: usize| i;
        let cw = |i: usize| (i + n - 1) % n;
        let mut allowed = vec![false; n];
        match arr.classify(x, -d) {
            Way::Sector(m) => allowed[m] = self.open(),
            Way::Ray(i) => {
                allowed[cw(i)] |= self.left;
                allowed[ccw(i)] |= self.right;
            }
        }
        match arr.classify(x, d) {
            Way::Sector(m) => Sides {
                left: allowed[m],
                right: allowed[m],
            },
            Way::Ray(i) => Sides {
                left: allowed[ccw(i)],
                right: allowed[cw(i)],
            },
        }
    }
}

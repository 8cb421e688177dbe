//! Teams under grid semantics (SPEC 2.10, classic MAPF after Stern et al.
//! 2019): the referee's lattice ([`TeamGrid`]) and its judgement of a
//! team's paths ([`validate_team`]).
//!
//! The lattice is the cell centres of the world's bounds at spacing `cell`
//! (the lattice of `astar` with `sample center`); an agent's path is one
//! lattice point per step. The referee decides on its own, with the
//! validator, which points an agent may stand on and which moves between
//! 4-neighbours it may make: nothing a planner says about the grid is
//! believed.

use std::collections::{HashMap, VecDeque};

use crate::timed::{After, MovingObstacle, MovingShape, Timed, Waypoint, validate_trajectory};
use crate::validator::{DEFAULT_TOLERANCE, ValidationError, Validator};
use crate::{Config, Point, RobotShape, World};

/// The lattice of a team plan, seen by the referee: which points are free
/// for the agents' body and which 4-neighbour moves are.
#[derive(Clone, Debug)]
pub struct TeamGrid {
    /// The world point of lattice point (0, 0).
    pub first: Point,
    pub cell: f64,
    pub nx: usize,
    pub ny: usize,
    free: Vec<bool>,
    /// Whether the move from point `n` to its right (`[n][0]`) and upper
    /// (`[n][1]`) neighbour is free.
    moves: Vec<[bool; 2]>,
}

/// The most lattice points a team grid may have (a 4,096 × 4,096 map).
pub const MAX_TEAM_CELLS: usize = 1 << 24;

impl TeamGrid {
    /// The cell centres of `world`'s bounds at spacing `cell`, judged for
    /// `robot` by the validator. `None` when `cell` is not positive and
    /// finite or the lattice would have more than [`MAX_TEAM_CELLS`]
    /// points.
    pub fn new(world: &World, robot: &RobotShape, cell: f64, referee: &Validator) -> Option<Self> {
        let b = world.bounds;
        if !(cell.is_finite() && cell > 0.0) {
            return None;
        }
        let count = |extent: f64| {
            let span = extent / cell + 1e-9;
            if span >= 0.5 {
                (span - 0.5).floor() + 1.0
            } else {
                0.0
            }
        };
        let (nxf, nyf) = (count(b.max.x - b.min.x), count(b.max.y - b.min.y));
        if nxf * nyf > MAX_TEAM_CELLS as f64 || (nxf * nyf).is_nan() {
            return None;
        }
        let (nx, ny) = (nxf as usize, nyf as usize);
        let first = Point::new(b.min.x + 0.5 * cell, b.min.y + 0.5 * cell);
        let mut grid = TeamGrid {
            first,
            cell,
            nx,
            ny,
            free: Vec::with_capacity(nx * ny),
            moves: vec![[false; 2]; nx * ny],
        };
        for n in 0..nx * ny {
            let c = grid.config(n);
            let ok = referee
                .validate_path(robot, &[c], DEFAULT_TOLERANCE)
                .is_ok();
            grid.free.push(ok);
        }
        for n in 0..nx * ny {
            if !grid.free[n] {
                continue;
            }
            let (i, j) = (n % nx, n / nx);
            for (d, next) in [
                (0, (i + 1 < nx).then(|| n + 1)),
                (1, (j + 1 < ny).then(|| n + nx)),
            ] {
                if let Some(m) = next.filter(|&m| grid.free[m]) {
                    grid.moves[n][d] = referee
                        .validate_path(robot, &[grid.config(n), grid.config(m)], DEFAULT_TOLERANCE)
                        .is_ok();
                }
            }
        }
        Some(grid)
    }

    /// The world point of lattice point `n`.
    pub fn point(&self, n: usize) -> Point {
        let (i, j) = (n % self.nx, n / self.nx);
        Point::new(
            self.first.x + i as f64 * self.cell,
            self.first.y + j as f64 * self.cell,
        )
    }

    fn config(&self, n: usize) -> Config {
        let p = self.point(n);
        Config::new(p.x, p.y, 0.0)
    }

    /// The lattice point at `p`, when `p` is one (within 1e-9 of a cell).
    pub fn node(&self, p: Point) -> Option<usize> {
        lattice_index(self.first, self.cell, self.nx, self.ny, p)
    }

    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Whether an agent may stand on point `n`.
    pub fn is_free(&self, n: usize) -> bool {
        self.free[n]
    }

    /// Whether an agent may move from `a` to `b` in one step (4-neighbours,
    /// both free, the motion free).
    pub fn can_move(&self, a: usize, b: usize) -> bool {
        let (lo, hi) = if a < b { (a, b) } else { (b, a) };
        if hi == lo + 1 && lo % self.nx + 1 < self.nx {
            self.moves[lo][0]
        } else if hi == lo + self.nx {
            self.moves[lo][1]
        } else {
            false
        }
    }

    /// The free 4-neighbours `n` may move to.
    pub fn moves_from(&self, n: usize) -> impl Iterator<Item = usize> + '_ {
        let (i, j) = (n % self.nx, n / self.nx);
        let cands = [
            (i + 1 < self.nx).then(|| n + 1),
            (i > 0).then(|| n - 1),
            (j + 1 < self.ny).then(|| n + self.nx),
            (j > 0).then(|| n - self.nx),
        ];
        cands
            .into_iter()
            .flatten()
            .filter(move |&m| self.can_move(n, m))
    }

    /// Steps from every point to `goal` (`u32::MAX`: never), by
    /// breadth-first search.
    pub fn distances_to(&self, goal: usize) -> Vec<u32> {
        let mut dist = vec![u32::MAX; self.len()];
        if !self.free[goal] {
            return dist;
        }
        dist[goal] = 0;
        let mut queue = VecDeque::from([goal]);
        while let Some(n) = queue.pop_front() {
            let d = dist[n] + 1;
            for m in self.moves_from(n) {
                if dist[m] == u32::MAX {
                    dist[m] = d;
                    queue.push_back(m);
                }
            }
        }
        dist
    }
}

/// The index (row by row from `first`) of the point of the `nx` × `ny`
/// lattice at spacing `cell` that `p` is, within 1e-9 of a cell; `None` off
/// the lattice. The planners place agents on their lattice by the same rule.
pub fn lattice_index(first: Point, cell: f64, nx: usize, ny: usize, p: Point) -> Option<usize> {
    let fi = (p.x - first.x) / cell;
    let fj = (p.y - first.y) / cell;
    let (i, j) = (fi.round(), fj.round());
    let on = (fi - i).abs() <= 1e-9 && (fj - j).abs() <= 1e-9;
    (on && i >= 0.0 && j >= 0.0 && (i as usize) < nx && (j as usize) < ny)
        .then(|| j as usize * nx + i as usize)
}

/// Why a team's paths fail grid semantics: the step, the agent (and the
/// other one of a conflict) and the point.
#[derive(Clone, Debug, PartialEq)]
pub struct TeamError {
    pub step: usize,
    pub agent: usize,
    pub other: Option<usize>,
    pub at: Point,
    pub reason: String,
}

impl TeamError {
    /// As the validator's error, for the report: the step as the segment.
    pub fn into_validation(self, names: &[&str]) -> ValidationError {
        let name = |i: usize| names.get(i).copied().unwrap_or("?");
        let reason = match self.other {
            Some(o) => format!(
                "agents `{}` and `{}`: {}",
                name(self.agent),
                name(o),
                self.reason
            ),
            None => format!("agent `{}`: {}", name(self.agent), self.reason),
        };
        ValidationError {
            segment: self.step,
            at: Config::new(self.at.x, self.at.y, 0.0),
            obstacle: None,
            reason,
        }
    }
}

/// Each agent's cost: the step at which it reaches its goal for the last
/// time (0 for a path that never leaves it).
pub fn agent_cost(path: &[Point]) -> usize {
    match path.last() {
        Some(goal) => path.iter().rposition(|p| p != goal).map_or(0, |k| k + 1),
        None => 0,
    }
}

/// Judges a team's paths under grid semantics (SPEC 2.10): for each agent
/// (`ends[i]` its start and goal), a path of lattice points from its start
/// to its goal, each step a wait or a free move to a 4-neighbour; no two
/// agents on one point at a step (vertex conflict) nor swapping points in
/// one step (edge conflict), an agent staying at its goal after its path
/// ends. `Ok` gives each agent's cost ([`agent_cost`]).
pub fn validate_team(
    grid: &TeamGrid,
    ends: &[(Point, Point)],
    paths: &[Vec<Point>],
) -> Result<Vec<usize>, TeamError> {
    let err = |step, agent, other, at, reason: String| {
        Err(TeamError {
            step,
            agent,
            other,
            at,
            reason,
        })
    };
    if paths.len() != ends.len() {
        return err(
            0,
            0,
            None,
            Point::origin(),
            format!("{} paths for {} agents", paths.len(), ends.len()),
        );
    }
    // Each path as lattice points, checked on its own.
    let mut nodes: Vec<Vec<usize>> = Vec::with_capacity(paths.len());
    for (a, (path, &(start, goal))) in paths.iter().zip(ends).enumerate() {
        let Some(&first) = path.first() else {
            return err(0, a, None, start, "an empty path".into());
        };
        // An agent stands on the lattice point within 1e-9 of a cell of its
        // start and of its goal (the test every point of a path passes).
        if grid.node(first).is_none() || grid.node(first) != grid.node(start) {
            return err(
                0,
                a,
                None,
                first,
                format!("starts at ({}, {}), not at its start", first.x, first.y),
            );
        }
        let last = *path.last().unwrap_or(&first);
        if grid.node(last).is_none() || grid.node(last) != grid.node(goal) {
            return err(
                path.len() - 1,
                a,
                None,
                last,
                format!("ends at ({}, {}), not at its goal", last.x, last.y),
            );
        }
        let mut seq = Vec::with_capacity(path.len());
        for (k, &p) in path.iter().enumerate() {
            let Some(n) = grid.node(p) else {
                return err(
                    k,
                    a,
                    None,
                    p,
                    format!("({}, {}) is not a point of the lattice", p.x, p.y),
                );
            };
            if !grid.is_free(n) {
                return err(
                    k,
                    a,
                    None,
                    p,
                    format!("({}, {}) is not free for the agent", p.x, p.y),
                );
            }
            if let Some(&prev) = seq.last()
                && prev != n
                && !grid.can_move(prev, n)
            {
                return err(
                    k,
                    a,
                    None,
                    p,
                    "a step that is neither a wait nor a free move to a 4-neighbour".into(),
                );
            }
            seq.push(n);
        }
        nodes.push(seq);
    }
    let horizon = nodes.iter().map(Vec::len).max().unwrap_or(0);
    let at = |a: usize, t: usize| {
        let s = &nodes[a];
        s[t.min(s.len() - 1)]
    };
    let mut here: HashMap<usize, usize> = HashMap::with_capacity(nodes.len());
    let mut before: HashMap<usize, usize> = HashMap::with_capacity(nodes.len());
    for t in 0..horizon {
        std::mem::swap(&mut here, &mut before);
        here.clear();
        for a in 0..nodes.len() {
            let n = at(a, t);
            if let Some(&b) = here.get(&n) {
                return err(
                    t,
                    b,
                    Some(a),
                    grid.point(n),
                    format!(
                        "both at ({}, {}) at step {t}",
                        grid.point(n).x,
                        grid.point(n).y
                    ),
                );
            }
            here.insert(n, a);
        }
        if t == 0 {
            continue;
        }
        for a in 0..nodes.len() {
            let (from, to) = (at(a, t - 1), at(a, t));
            if from == to {
                continue;
            }
            if let Some(&b) = before.get(&to)
                && b != a
                && at(b, t) == from
            {
                let p = grid.point(from);
                return err(
                    t,
                    a.min(b),
                    Some(a.max(b)),
                    p,
                    format!("swap places between steps {} and {t}", t - 1),
                );
            }
        }
    }
    Ok(paths.iter().map(|p| agent_cost(p)).collect())
}

/// Agent `name` moving along `points` at `times`, then staying there for
/// good, as a moving obstacle of `radius` (continuous teams, SPEC 2.10):
/// what each agent is to the others, for the planner and the referee.
pub fn agent_obstacle(name: &str, radius: f64, points: &[Point], times: &[f64]) -> MovingObstacle {
    let mut route: Vec<Waypoint> = Vec::with_capacity(points.len());
    for (&at, &t) in points.iter().zip(times) {
        match route.last_mut() {
            // Times strictly increase on a route; at a repeated time the
            // later point holds.
            Some(last) if t <= last.t => last.at = at,
            _ => route.push(Waypoint { t, at }),
        }
    }
    MovingObstacle {
        name: format!("agent {name}"),
        shape: MovingShape::Disk(radius),
        route,
        after: After::Stay,
    }
}

/// Judges a team's trajectories in continuous time (SPEC 2.10): each
/// agent's trajectory (`points` with `times`) from its start to its goal
/// (within 1e-9), valid in space-time against the world, its moving
/// obstacles and every other agent as a moving obstacle (a disk of
/// `radius` on its trajectory, parked at its goal after it). `Ok` gives
/// each agent's arrival.
#[allow(clippy::too_many_arguments)]
pub fn validate_continuous_team(
    world: &World,
    moving: &[MovingObstacle],
    robot: &RobotShape,
    speed: f64,
    names: &[&str],
    ends: &[(Point, Point)],
    points: &[Vec<Point>],
    times: &[Vec<f64>],
) -> Result<Vec<f64>, TeamError> {
    let err = |agent: usize, at: Point, reason: String| {
        Err(TeamError {
            step: 0,
            agent,
            other: None,
            at,
            reason,
        })
    };
    if points.len() != ends.len() || times.len() != ends.len() {
        return err(
            0,
            Point::origin(),
            format!("{} trajectories for {} agents", points.len(), ends.len()),
        );
    }
    let radius = robot.radius();
    let others: Vec<MovingObstacle> = (0..ends.len())
        .map(|j| {
            agent_obstacle(
                names.get(j).copied().unwrap_or("?"),
                radius,
                &points[j],
                &times[j],
            )
        })
        .collect();
    let mut arrivals = Vec::with_capacity(ends.len());
    for (i, &(start, goal)) in ends.iter().enumerate() {
        let (p, t) = (&points[i], &times[i]);
        let (Some(&first), Some(&last)) = (p.first(), p.last()) else {
            return err(i, start, "an empty trajectory".into());
        };
        if p.len() != t.len() {
            return err(i, first, "a trajectory needs one time per point".into());
        }
        if (first - start).norm() > 1e-9 || (last - goal).norm() > 1e-9 {
            return err(i, first, "a trajectory from its start to its goal".into());
        }
        let mut among: Vec<MovingObstacle> = moving.to_vec();
        among.extend(
            others
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .map(|(_, o)| o.clone()),
        );
        let trajectory: Vec<Timed> = p
            .iter()
            .zip(t)
            .map(|(q, &t)| Timed {
                pose: Config::new(q.x, q.y, 0.0),
                t,
            })
            .collect();
        if let Err(e) = validate_trajectory(world, &among, robot, speed, &trajectory) {
            let other = e
                .obstacle
                .as_deref()
                .and_then(|o| o.strip_prefix("agent "))
                .and_then(|o| names.iter().position(|n| *n == o));
            return Err(TeamError {
                step: e.segment,
                agent: i,
                other,
                at: e.at.xy(),
                reason: e.reason,
            });
        }
        arrivals.push(*t.last().unwrap_or(&0.0));
    }
    Ok(arrivals)
}

#[cfg(test)]
mod tests;

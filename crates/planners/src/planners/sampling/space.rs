//! The configuration space of the sampling-based planners (SPEC 3.7): the
//! distance √(dx² + dy² + (c·dθ)²) with dθ the shorter arc, the motion
//! between two configurations (x and y linear, θ along the shorter arc, as
//! the validator interpolates), uniform samples in `bounds` × [0, 2π), and
//! Gammell et al.'s informed samples.
//!
//! For a car (a robot with a [`Steering`]) the distance is the length of
//! the shortest steering path (not symmetric for a Dubins car), a motion is
//! that path, θ is always sampled, and the index key is (x, y, 0): the
//! Euclidean distance of the reference points, a lower bound of every
//! steering length (an arc is never shorter than its chord), which
//! [`super::Run::k_nearest`] prunes with before it measures exact lengths.

use std::f64::consts::{PI, TAU};

use crate::geometry::steer::Steering;
use crate::geometry::{Aabb, Config, angle_diff, wrap_angle};
use crate::rng::SplitMix64;

/// The space a plan samples: `bounds` × [0, 2π) for a rotating robot,
/// `bounds` at the start's θ otherwise.
#[derive(Clone, Copy, Debug)]
pub struct Space {
    pub bounds: Aabb,
    /// Whether θ is a dimension (a polygon robot without `rotate no`).
    pub rotating: bool,
    /// The θ of every configuration of a robot that does not rotate.
    pub theta: f64,
    /// c, the weight of one radian in the distance (0 for a car, whose
    /// key leaves θ out).
    pub turn_cost: f64,
    /// A car's steering: the distance and the motions are its paths.
    pub steering: Option<Steering>,
}

impl Space {
    /// 3 when θ is a dimension, else 2: the d of SPEC 3.7's k.
    pub fn dims(&self) -> usize {
        if self.rotating { 3 } else { 2 }
    }

    /// The period of the index key's last axis (2π·c; 0 when θ is not a
    /// dimension).
    pub fn period(&self) -> f64 {
        if self.rotating {
            TAU * self.turn_cost
        } else {
            0.0
        }
    }

    /// The distance of SPEC 3.7 between `a` and `b`.
    pub fn distance(&self, a: Config, b: Config) -> f64 {
        if let Some(s) = self.steering {
            return s.distance(a, b);
        }
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        if self.rotating {
            let dt = self.turn_cost * angle_diff(a.theta, b.theta);
            (dx * dx + dy * dy + dt * dt).sqrt()
        } else {
            (dx * dx + dy * dy).sqrt()
        }
    }

    /// A lower bound of [`Space::distance`] between `a` and `b` either way,
    /// cheaper than it: a car's heading change at its turning radius
    /// ([`Steering::turn_bound`]); 0 otherwise.
    pub fn turn_bound(&self, a: Config, b: Config) -> f64 {
        self.steering.map_or(0.0, |s| s.turn_bound(a, b))
    }

    /// The nearest-neighbour key of `c`: (x, y, c·θ) with θ in [0, 2π),
    /// whose Euclidean distance with the last axis wrapped is
    /// [`Space::distance`].
    pub fn key(&self, c: Config) -> [f64; 3] {
        if self.rotating {
            [c.x, c.y, self.turn_cost * wrap_angle(c.theta)]
        } else {
            [c.x, c.y, 0.0]
        }
    }

    /// The configuration a fraction `t` ∈ [0, 1] of the way from `a` to
    /// `b` along the motion the validator checks (θ along the shorter arc,
    /// in [0, 2π)); `a` itself at 0 and `b` at 1.
    pub fn interpolate(&self, a: Config, b: Config, t: f64) -> Config {
        if t <= 0.0 {
            return a;
        }
        if t >= 1.0 {
            return b;
        }
        if let Some(s) = self.steering {
            let curve = s.shortest(a, b);
            let c = curve.config_at(a, t * curve.length());
            return c.wrapped();
        }
        let theta = if self.rotating {
            wrap_angle(a.theta + t * angle_diff(a.theta, b.theta))
        } else {
            self.theta
        };
        Config::new(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), theta)
    }

    /// `to` when it is at most `range` from `from`, else the configuration
    /// `range` along the motion towards it.
    pub fn steer(&self, from: Config, to: Config, range: f64) -> Config {
        let d = self.distance(from, to);
        if d <= range {
            to
        } else {
            self.interpolate(from, to, range / d)
        }
    }

    /// `from` when it is at most `range` from `to` (in the distance from
    /// `from` to `to`), else the configuration `range` before `to` on the
    /// motion from `from` to it: a tree whose motions run towards its root
    /// (RRT-Connect's goal tree) grows so, and its new motion is then the
    /// end of that one (for a Dubins car, a forward path away from `to`
    /// would need a loop to come back).
    pub fn steer_back(&self, from: Config, to: Config, range: f64) -> Config {
        let d = self.distance(from, to);
        if d <= range {
            from
        } else {
            self.interpolate(from, to, 1.0 - range / d)
        }
    }

    /// A configuration drawn uniformly in `bounds` × [0, 2π).
    pub fn uniform(&self, rng: &mut SplitMix64) -> Config {
        let b = &self.bounds;
        let x = rng.range(b.min.x, b.max.x);
        let y = rng.range(b.min.y, b.max.y);
        let theta = if self.rotating {
            rng.range(0.0, TAU)
        } else {
            self.theta
        };
        Config::new(x, y, theta)
    }

    /// A configuration near `c`: each of x and y displaced by a normal
    /// deviate of deviation `sigma`, θ by one of `sigma / c` (at most π),
    /// so the displacement has deviation `sigma` in the distance along each
    /// axis. May lie outside the bounds.
    pub fn gaussian_near(&self, c: Config, sigma: f64, rng: &mut SplitMix64) -> Config {
        let (gx, gy) = normal_pair(rng);
        // A car's θ moves by the heading change of an arc of length sigma.
        let weight = self.steering.map_or(self.turn_cost, |s| s.radius);
        let theta = if self.rotating {
            let s = if weight > 0.0 {
                (sigma / weight).min(PI)
            } else {
                PI
            };
            wrap_angle(c.theta + s * normal_pair(rng).0)
        } else {
            self.theta
        };
        Config::new(c.x + sigma * gx, c.y + sigma * gy, theta)
    }

    /// The measure of the whole space in the distance's units (area, or
    /// area × 2π·c).
    fn measure(&self) -> f64 {
        let area = self.bounds.width() * self.bounds.height();
        if self.rotating {
            area * self.period()
        } else {
            area
        }
    }
}

/// Two independent standard normal deviates (Box–Muller).
pub fn normal_pair(rng: &mut SplitMix64) -> (f64, f64) {
    // 1 − u ∈ (0, 1]: the logarithm is finite.
    let u = 1.0 - rng.next_f64();
    let v = rng.next_f64();
    let r = (-2.0 * u.ln()).sqrt();
    let (s, c) = (TAU * v).sin_cos();
    (r * c, r * s)
}

/// Gammell et al.'s informed set: the configurations q with
/// d(start, q) + d(q, goal) ≤ `cost`, which hold every path cheaper than
/// `cost`, sampled uniformly.
///
/// With θ a dimension the distance wraps, so a path may go round θ either
/// way: lifted to the cover ℝ² × ℝ of θ, a path from the start to the goal
/// ends at one of the goal's images `goal + 2πk` and stays in the prolate
/// hyperspheroid with foci the start and that image and transverse
/// diameter `cost`. The informed set is the union of those hyperspheroids
/// (finitely many are not empty) taken modulo 2π. A sample draws a
/// hyperspheroid with probability proportional to its volume and a point
/// uniformly inside it (the unit ball stretched and turned onto the focal
/// axis), and keeps it with probability 1 / (the number of (hyperspheroid,
/// image) pairs holding it) and when its (x, y) lies in the bounds: so the
/// samples kept are uniform on the informed set within the bounds. When
/// the hyperspheroids measure more than the space itself, plain uniform
/// samples tested against the set do better.
#[derive(Clone, Debug)]
pub struct Informed {
    /// The start's key in the cover: (x, y, c·θ).
    start: [f64; 3],
    /// Per non-empty hyperspheroid: its centre, its axes (unit columns
    /// scaled by the semi-axes) and its focus at the goal's image.
    ellipsoids: Vec<Ellipsoid>,
    cost: f64,
    /// Sample uniformly and test, rather than sample the hyperspheroids.
    rejection: bool,
    /// The set is taken for the whole space.
    everything: bool,
    dims: usize,
    period: f64,
    /// The goal's images and the shifts of θ tried: −reach ..= reach.
    reach: i32,
}

#[derive(Clone, Debug)]
struct Ellipsoid {
    centre: [f64; 3],
    /// Row i: the i-th axis of the unit ball mapped into the space.
    axes: [[f64; 3]; 3],
    goal: [f64; 3],
    volume: f64,
}

/// At most this many draws per informed sample before giving up.
const INFORMED_ATTEMPTS: usize = 1000;

/// Beyond this many turns of θ within the cost, the set is sampled by
/// rejection only.
const MAX_REACH: i32 = 8;

impl Informed {
    /// The informed set of paths from `start` to `goal` cheaper than `cost`.
    pub fn new(space: &Space, start: Config, goal: Config, cost: f64) -> Self {
        let dims = space.dims();
        let c = space.turn_cost;
        let s = [start.x, start.y, c * wrap_angle(start.theta)];
        // The goal's image nearest to the start, then the others outwards.
        let g0 = [
            goal.x,
            goal.y,
            s[2] + c * angle_diff(start.theta, goal.theta),
        ];
        let period = space.period();
        let mut ellipsoids = Vec::new();
        let turns = if dims == 3 && period > 0.0 {
            (cost / period).ceil() + 1.0
        } else {
            0.0
        };
        // So many turns: the set is (nearly) everything; uniform samples.
        let everything = turns > f64::from(MAX_REACH);
        let reach = if everything { 0 } else { turns as i32 };
        for k in -reach..=reach {
            let g = [g0[0], g0[1], g0[2] + f64::from(k) * period];
            if let Some(e) = Ellipsoid::new(&s, &g, cost, dims) {
                ellipsoids.push(e);
            }
        }
        let volume: f64 = ellipsoids.iter().map(|e| e.volume).sum();
        Informed {
            start: s,
            everything,
            rejection: volume >= space.measure(),
            ellipsoids,
            cost,
            dims,
            period,
            reach,
        }
    }

    /// Whether the configuration (as a key in the cover, θ in [0, 2π)·c)
    /// lies in the informed set, and how many (hyperspheroid, image)
    /// pairs hold it.
    fn holders(&self, q: &[f64; 3]) -> usize {
        let mut n = 0;
        for e in &self.ellipsoids {
            for j in -self.reach..=self.reach {
                let mut p = *q;
                p[2] += f64::from(j) * self.period;
                if dist(&p, &self.start, self.dims) + dist(&p, &e.goal, self.dims) <= self.cost {
                    n += 1;
                }
            }
        }
        n
    }

    /// A sample of the informed set within the bounds, or `None` when
    /// [`INFORMED_ATTEMPTS`] draws found none.
    pub fn sample(&self, space: &Space, rng: &mut SplitMix64) -> Option<Config> {
        if self.everything {
            return Some(space.uniform(rng));
        }
        let total: f64 = self.ellipsoids.iter().map(|e| e.volume).sum();
        for _ in 0..INFORMED_ATTEMPTS {
            if self.rejection || total <= 0.0 {
                let q = space.uniform(rng);
                if self.holders(&space.key(q)) > 0 {
                    return Some(q);
                }
                continue;
            }
            let mut pick = rng.next_f64() * total;
            let mut chosen = &self.ellipsoids[0];
            for e in &self.ellipsoids {
                chosen = e;
                if pick < e.volume {
                    break;
                }
                pick -= e.volume;
            }
            let p = chosen.sample(rng, self.dims);
            let q = if self.dims == 3 {
                let c = space.turn_cost;
                Config::new(p[0], p[1], if c > 0.0 { wrap_angle(p[2] / c) } else { 0.0 })
            } else {
                Config::new(p[0], p[1], space.theta)
            };
            if !space.bounds.contains(q.xy()) {
                continue;
            }
            let m = self.holders(&space.key(q)).max(1);
            if m == 1 || rng.next_f64() * m as f64 <= 1.0 {
                return Some(q);
            }
        }
        None
    }
}

fn dist(a: &[f64; 3], b: &[f64; 3], dims: usize) -> f64 {
    (0..dims).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt()
}

impl Ellipsoid {
    /// The prolate hyperspheroid with foci `s` and `g` and transverse
    /// diameter `cost`; `None` when empty (the foci farther apart than
    /// `cost`).
    fn new(s: &[f64; 3], g: &[f64; 3], cost: f64, dims: usize) -> Option<Self> {
        let dmin = dist(s, g, dims);
        if dmin > cost || !cost.is_finite() {
            return None;
        }
        let a = cost / 2.0;
        let b = ((cost * cost - dmin * dmin).max(0.0)).sqrt() / 2.0;
        let centre = [
            (s[0] + g[0]) / 2.0,
            (s[1] + g[1]) / 2.0,
            (s[2] + g[2]) / 2.0,
        ];
        // An orthonormal frame whose first axis runs from s to g.
        let mut e1 = [
            g[0] - s[0],
            g[1] - s[1],
            if dims == 3 { g[2] - s[2] } else { 0.0 },
        ];
        if dmin > 0.0 {
            e1.iter_mut().for_each(|x| *x /= dmin);
        } else {
            e1 = [1.0, 0.0, 0.0];
        }
        let (e2, e3) = if dims == 3 {
            // The coordinate axis least aligned with e1, made orthogonal.
            let pick = (0..3)
                .min_by(|&i, &j| e1[i].abs().total_cmp(&e1[j].abs()))
                .unwrap_or(0);
            let mut u = [0.0; 3];
            u[pick] = 1.0;
            let dot = u[0] * e1[0] + u[1] * e1[1] + u[2] * e1[2];
            let mut e2 = [u[0] - dot * e1[0], u[1] - dot * e1[1], u[2] - dot * e1[2]];
            let n = dist(&e2, &[0.0; 3], 3);
            e2.iter_mut().for_each(|x| *x /= n);
            let e3 = [
                e1[1] * e2[2] - e1[2] * e2[1],
                e1[2] * e2[0] - e1[0] * e2[2],
                e1[0] * e2[1] - e1[1] * e2[0],
            ];
            (e2, e3)
        } else {
            ([-e1[1], e1[0], 0.0], [0.0; 3])
        };
        let scale = |e: [f64; 3], r: f64| [e[0] * r, e[1] * r, e[2] * r];
        let volume = if dims == 3 {
            4.0 / 3.0 * PI * a * b * b
        } else {
            PI * a * b
        };
        Some(Ellipsoid {
            centre,
            axes: [scale(e1, a), scale(e2, b), scale(e3, b)],
            goal: *g,
            volume,
        })
    }

    /// A point drawn uniformly inside.
    fn sample(&self, rng: &mut SplitMix64, dims: usize) -> [f64; 3] {
        // A uniform point of the unit ball: a normal direction, radius u^(1/d).
        let ball = loop {
            let (a, b) = normal_pair(rng);
            let c = if dims == 3 { normal_pair(rng).0 } else { 0.0 };
            let n = (a * a + b * b + c * c).sqrt();
            if n > 0.0 {
                let r = rng.next_f64().powf(1.0 / dims as f64) / n;
                break [a * r, b * r, c * r];
            }
        };
        let mut p = self.centre;
        for (i, axis) in self.axes.iter().enumerate().take(dims) {
            for (pj, aj) in p.iter_mut().zip(axis) {
                *pj += ball[i] * aj;
            }
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point;

    fn space(rotating: bool) -> Space {
        Space {
            bounds: Aabb {
                min: Point::new(0.0, 0.0),
                max: Point::new(10.0, 10.0),
            },
            rotating,
            theta: 0.0,
            turn_cost: 2.0,
            steering: None,
        }
    }

    #[test]
    fn the_distance_takes_the_shorter_arc() {
        let s = space(true);
        let a = Config::new(0.0, 0.0, 0.1);
        let b = Config::new(3.0, 0.0, TAU - 0.1);
        assert!((s.distance(a, b) - (9.0f64 + 0.16).sqrt()).abs() < 1e-12);
        let k = (s.key(a), s.key(b));
        let tree = super::super::nn::KdTree::new(3, s.period());
        assert!((tree.distance2(&k.0, &k.1).sqrt() - s.distance(a, b)).abs() < 1e-12);
    }

    #[test]
    fn steering_stops_at_the_range_along_the_shorter_arc() {
        let s = space(true);
        let a = Config::new(0.0, 0.0, 0.2);
        let b = Config::new(0.0, 0.0, TAU - 0.2);
        let c = s.steer(a, b, 0.2); // 0.1 rad at c = 2
        assert!((c.theta - 0.1).abs() < 1e-12, "{c:?}");
        assert_eq!(s.steer(a, b, 1.0), b);
    }

    #[test]
    fn informed_samples_lie_in_the_informed_set_and_the_bounds() {
        for rotating in [false, true] {
            let s = space(rotating);
            let start = Config::new(1.0, 1.0, 0.3);
            let goal = Config::new(8.0, 7.0, if rotating { 5.9 } else { 0.0 });
            let best = 1.2 * s.distance(start, goal);
            let set = Informed::new(&s, start, goal, best);
            let mut rng = SplitMix64::new(4);
            for _ in 0..2000 {
                let q = set.sample(&s, &mut rng).expect("a sample");
                assert!(s.bounds.contains(q.xy()));
                assert!((0.0..TAU).contains(&q.theta));
                let through = s.distance(start, q) + s.distance(q, goal);
                assert!(through <= best + 1e-9, "{q:?}: {through} > {best}");
            }
        }
    }

    #[test]
    fn the_informed_set_goes_round_theta_both_ways() {
        // The goal a half turn away: both arcs are equally short, and the
        // samples turn either way.
        let s = space(true);
        let start = Config::new(5.0, 5.0, 0.0);
        let goal = Config::new(5.0, 5.0, PI);
        let set = Informed::new(&s, start, goal, 1.1 * s.distance(start, goal));
        let mut rng = SplitMix64::new(9);
        let (mut up, mut down) = (0, 0);
        for _ in 0..1000 {
            let q = set.sample(&s, &mut rng).expect("a sample");
            if q.theta < PI {
                up += 1;
            } else {
                down += 1;
            }
        }
        assert!(up > 300 && down > 300, "{up} {down}");
    }
}

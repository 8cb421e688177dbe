//! Steering functions for car-like robots (SPEC 2.4 `steer`, 3.8): the
//! shortest path of the reference point between two configurations when its
//! curvature is bounded by 1/ρ.
//!
//! - [`Model::Dubins`]: forward only (Dubins 1957). The shortest path is one
//!   of the six words LSL, RSR, RSL, LSR, RLR, LRL (`L`/`R` an arc of radius
//!   ρ to the left/right, `S` a straight). See [`dubins`].
//! - [`Model::ReedsShepp`]: forward and reverse (Reeds & Shepp 1990,
//!   "Optimal paths for a car that goes both forwards and backwards"). The
//!   shortest path is one of 48 words of at most five segments, with cusps
//!   where the direction changes; computed as OMPL's
//!   `ReedsSheppStateSpace` does (12 base formulas under timeflip, reflect
//!   and backwards). See [`reeds_shepp`].
//!
//! A path is a start configuration and up to five [`Segment`]s, each a turn
//! and a signed arc length of the reference point (negative = reverse). It
//! is evaluated in closed form ([`SteerPath::config_at`]): arcs exactly,
//! never integrated numerically.
//!
//! The radius must be positive (`ρ > 0`); nothing checks it here (the
//! language rejects `steer` with ρ ≤ 0). Lengths agree with OMPL 2.0.1's
//! `distance` to 1e-9 relative (`tests/steer_ompl.rs`).
//!
//! Numerical conventions: segments shorter than [`MIN_SEGMENT`] turning
//! radii are left out (so that rounding never makes a spurious cusp);
//! consecutive segments of the same turn and direction are merged. For
//! finite input the results are never NaN; a goal farther than
//! [`FAR`] turning radii has length +∞ and no segments.

pub mod dubins;
mod lanes;
pub mod reeds_shepp;

use std::f64::consts::TAU;

use super::Config;

/// Segments shorter than this many turning radii are left out of a path.
pub const MIN_SEGMENT: f64 = 1e-12;

/// Beyond this many turning radii between start and goal no path is
/// computed (length +∞): the formulas' squares would overflow.
pub const FAR: f64 = 1e150;

/// The words of `steer MODEL` (SPEC 2.4), in the order of [`Model`].
pub const MODEL_NAMES: &[&str] = &["dubins", "reeds_shepp"];

/// The steering model of a car robot (SPEC 2.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Model {
    /// Forward only: the six Dubins words.
    Dubins,
    /// Forward and reverse: the 48 Reeds–Shepp words.
    ReedsShepp,
}

/// A steering function: a model and its turning radius (ρ > 0, in world
/// units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Steering {
    /// Forward only or both ways.
    pub model: Model,
    /// The turning radius ρ of the reference point; must be positive.
    pub radius: f64,
}

/// The kind of a segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Turn {
    /// An arc of radius ρ turning left (counter-clockwise when driving
    /// forward).
    L,
    /// A straight.
    S,
    /// An arc of radius ρ turning right (clockwise when driving forward).
    R,
}

impl Turn {
    /// The letter of SPEC §5 `"segments"`: `"L"`, `"S"` or `"R"`.
    pub fn letter(self) -> &'static str {
        match self {
            Turn::L => "L",
            Turn::S => "S",
            Turn::R => "R",
        }
    }
}

/// One piece of a path: a turn and the signed arc length of the reference
/// point along it, in world units (negative = driven in reverse).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// Left arc, straight or right arc.
    pub turn: Turn,
    /// Signed arc length in world units; negative is reverse.
    pub length: f64,
}

impl Segment {
    /// The configuration reached from `from` by driving `length` (signed)
    /// along a segment of kind `turn` with turning radius `radius`, in
    /// closed form: the chord of the arc, 2ρ·sin(Δ/2) in the direction
    /// θ + Δ/2 where Δ is the heading change. The heading is not wrapped.
    pub fn advance(from: Config, turn: Turn, length: f64, radius: f64) -> Config {
        let delta = match turn {
            Turn::L => length / radius,
            Turn::S => 0.0,
            Turn::R => -length / radius,
        };
        let (chord, mid) = match turn {
            Turn::S => (length, from.theta),
            // ℓ·sin(Δ/2)/(Δ/2) = ±2ρ sin(Δ/2), the sign of the curvature.
            Turn::L => (2.0 * radius * (0.5 * delta).sin(), from.theta + 0.5 * delta),
            Turn::R => (
                -2.0 * radius * (0.5 * delta).sin(),
                from.theta + 0.5 * delta,
            ),
        };
        let (s, c) = mid.sin_cos();
        Config::new(from.x + chord * c, from.y + chord * s, from.theta + delta)
    }

    /// The configuration at the end of this segment from `from`.
    pub fn end(&self, from: Config, radius: f64) -> Config {
        Segment::advance(from, self.turn, self.length, radius)
    }
}

/// A steering path: up to five segments from a start configuration (which
/// the path does not store), its length and turning radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SteerPath {
    segments: [Segment; 5],
    count: usize,
    length: f64,
    radius: f64,
}

impl SteerPath {
    /// The empty path (start = goal): no segments, length 0.
    pub fn empty(radius: f64) -> Self {
        SteerPath {
            segments: [Segment {
                turn: Turn::S,
                length: 0.0,
            }; 5],
            count: 0,
            length: 0.0,
            radius,
        }
    }

    /// A path of the given raw pieces (turn, signed length in radii), scaled
    /// by the radius; `length` (in radii) is the word's length as the
    /// formulas sum it.
    fn from_pieces(
        pieces: impl IntoIterator<Item = (Turn, f64)>,
        length: f64,
        radius: f64,
    ) -> Self {
        let mut path = SteerPath::empty(radius);
        path.length = length * radius;
        for (turn, l) in pieces {
            if l.abs() < MIN_SEGMENT {
                continue;
            }
            let l = l * radius;
            if path.count > 0 {
                let last = &mut path.segments[path.count - 1];
                if last.turn == turn && (last.length < 0.0) == (l < 0.0) {
                    last.length += l;
                    continue;
                }
            }
            path.segments[path.count] = Segment { turn, length: l };
            path.count += 1;
        }
        path
    }

    /// The segments, in driving order.
    pub fn segments(&self) -> &[Segment] {
        &self.segments[..self.count]
    }

    /// The length: the reference point's arc length, forward and reverse
    /// alike (the sum of the segments' absolute lengths, as the word's
    /// formula sums it; equal to [`Steering::distance`]).
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The turning radius the path was made with.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The configuration at arc length `s` along the path from `from`
    /// (clamped to [0, the segments' total]), in closed form.
    pub fn config_at(&self, from: Config, s: f64) -> Config {
        let mut c = from;
        let mut left = s.max(0.0);
        for seg in self.segments() {
            let l = seg.length.abs();
            if left >= l {
                c = seg.end(c, self.radius);
                left -= l;
            } else {
                return Segment::advance(c, seg.turn, left.copysign(seg.length), self.radius);
            }
        }
        c
    }

    /// The configuration at the end of the path from `from` (the goal, to
    /// rounding; its heading is `from`'s plus the turns, not wrapped).
    pub fn end(&self, from: Config) -> Config {
        self.segments()
            .iter()
            .fold(from, |c, seg| seg.end(c, self.radius))
    }

    /// The number of cusps: changes of direction between consecutive
    /// segments.
    pub fn cusps(&self) -> usize {
        self.segments()
            .windows(2)
            .filter(|w| (w[0].length < 0.0) != (w[1].length < 0.0))
            .count()
    }

    /// The arc length driven in reverse.
    pub fn reverse_length(&self) -> f64 {
        self.segments()
            .iter()
            .filter(|s| s.length < 0.0)
            .map(|s| -s.length)
            .sum()
    }

    /// The total absolute heading change, in radians.
    pub fn turn(&self) -> f64 {
        self.segments()
            .iter()
            .filter(|s| s.turn != Turn::S)
            .map(|s| s.length.abs())
            .sum::<f64>()
            / self.radius
    }
}

/// The heading change `to − from`, into [−π, π] (finite even when the
/// difference of two huge headings would overflow).
fn heading_change(from: f64, to: f64) -> f64 {
    let d = to - from;
    let d = if d.is_finite() {
        d
    } else {
        to % TAU - from % TAU
    };
    // `fmod` returns its argument unchanged below one turn (it is exact),
    // so skipping it there gives the same bits.
    let d = if d.abs() < TAU { d } else { d % TAU };
    if d > std::f64::consts::PI {
        d - TAU
    } else if d < -std::f64::consts::PI {
        d + TAU
    } else {
        d
    }
}

impl Steering {
    /// A steering function of `model` with turning radius `radius` (> 0).
    pub fn new(model: Model, radius: f64) -> Self {
        debug_assert!(radius > 0.0, "a turning radius must be positive");
        Steering { model, radius }
    }

    /// Why no steering path joins two poses whose length is not finite,
    /// and what to do: they lie more than [`FAR`] turning radii apart.
    pub fn too_far_note(&self) -> String {
        format!(
            "the goal is more than {FAR:e} turning radii from the start (radius {:e}): no steering path is computed; use a larger radius",
            self.radius
        )
    }

    /// The goal in the start's frame, in turning radii, and the heading
    /// change; `None` when it is farther than [`FAR`] radii (or the
    /// difference overflows).
    fn local(&self, from: Config, to: Config) -> Option<(f64, f64, f64)> {
        let (dx, dy) = (to.x - from.x, to.y - from.y);
        let (s, c) = from.theta.sin_cos();
        let x = (c * dx + s * dy) / self.radius;
        let y = (-s * dx + c * dy) / self.radius;
        let phi = heading_change(from.theta, to.theta);
        (x.abs() <= FAR && y.abs() <= FAR).then_some((x, y, phi))
    }

    /// Whether `to` is `from` (same point, headings equal modulo 2π to
    /// 1e-12 rad): the empty path.
    fn same(from: Config, to: Config) -> bool {
        from.x == to.x && from.y == to.y && heading_change(from.theta, to.theta).abs() <= 1e-12
    }

    /// The Dubins problem (d, α, β) in turning radii, `None` when too far.
    fn dubins_local(&self, from: Config, to: Config) -> Option<(f64, f64, f64)> {
        let (dx, dy) = (to.x - from.x, to.y - from.y);
        let d = (dx * dx + dy * dy).sqrt() / self.radius;
        if d.is_nan() || d > FAR {
            return None;
        }
        let th = dy.atan2(dx);
        Some((
            d,
            dubins::mod2pi(heading_change(th, from.theta)),
            dubins::mod2pi(heading_change(th, to.theta)),
        ))
    }

    /// The shortest steering path from `from` to `to` over all the model's
    /// words (the first of equal-length words in the order of [`dubins`] or
    /// [`reeds_shepp`]).
    pub fn shortest(&self, from: Config, to: Config) -> SteerPath {
        if Steering::same(from, to) {
            return SteerPath::empty(self.radius);
        }
        let mut far = SteerPath::empty(self.radius);
        far.length = f64::INFINITY;
        match self.model {
            Model::ReedsShepp => {
                let Some((x, y, phi)) = self.local(from, to) else {
                    return far;
                };
                let w = reeds_shepp::shortest(x, y, phi);
                let turns = reeds_shepp::WORDS[w.word];
                SteerPath::from_pieces(
                    turns
                        .into_iter()
                        .zip(w.params)
                        .filter_map(|(t, p)| t.map(|t| (t, p))),
                    w.length,
                    self.radius,
                )
            }
            Model::Dubins => {
                let Some((d, alpha, beta)) = self.dubins_local(from, to) else {
                    return far;
                };
                let w = dubins::shortest(d, alpha, beta);
                SteerPath::from_pieces(
                    dubins::WORDS[w.word].into_iter().zip(w.params),
                    w.length,
                    self.radius,
                )
            }
        }
    }

    /// A lower bound of [`Steering::distance`] between `from` and `to`, in
    /// either direction: every path turns by at least their heading change,
    /// at the turning radius or wider. Less 1e-9 rad, far more than the
    /// lengths' rounding, and than the 1e-12 within which two headings are
    /// the same (a distance of 0).
    pub fn turn_bound(&self, from: Config, to: Config) -> f64 {
        self.radius * (heading_change(from.theta, to.theta).abs() - 1e-9).max(0.0)
    }

    /// The length of the shortest steering path from `from` to `to`, without
    /// building its segments (equal to `shortest(from, to).length()`). Not
    /// symmetric for Dubins.
    pub fn distance(&self, from: Config, to: Config) -> f64 {
        if Steering::same(from, to) {
            return 0.0;
        }
        match self.model {
            Model::ReedsShepp => match self.local(from, to) {
                Some((x, y, phi)) => reeds_shepp::shortest(x, y, phi).length * self.radius,
                None => f64::INFINITY,
            },
            Model::Dubins => match self.dubins_local(from, to) {
                Some((d, alpha, beta)) => dubins::shortest(d, alpha, beta).length * self.radius,
                None => f64::INFINITY,
            },
        }
    }
}

#[cfg(test)]
mod tests;

//! The motion a potential-field walk executes (SPEC 3.4: "Memory does not
//! grow with `limit steps`: the executed motion is kept in full up to 4
//! million steps, and validated as it is made beyond that").
//!
//! Up to [`FULL_MOVES`] moves every pose is kept, and the runner measures
//! and validates the list as for any planner. The move after that switches
//! to thinned recording: the full list is validated and measured once,
//! then every later move is measured as it is made (length, turn,
//! smoothness, exactly as the runner sums them) and validated by the
//! runner's referee ([`crate::contract::referee`]) in chunks of [`CHUNK`] poses, while the list keeps
//! every `stride`-th pose (the stride doubling whenever the list would
//! exceed [`FULL_MOVES`] + 1 poses) and the last one. The outcome then
//! carries the measures of the whole motion ([`MeasuredMotion`]).
//!
//! # Chunks
//! A chunk is validated as a path of its own. The validator's per-motion
//! checks are local, but its wall-crossing test (point robots and segment
//! obstacles) follows the path from contact to contact; it starts afresh
//! at a pose that touches no obstacle, just as it is at that pose in the
//! whole path. So each chunk after the first starts at the last pose of the
//! one before that has a positive clearance (the last pose, unless the walk
//! ends the chunk touching an obstacle), and the verdicts of the chunks are
//! the verdict on the whole motion.

use crate::contract::{MeasuredMotion, Referee};
use crate::geometry::path::corner_smoothness;
use crate::geometry::validator::ValidationError;
use crate::geometry::{Config, Point, angle_diff};

/// Moves kept in full (SPEC 3.4).
pub const FULL_MOVES: u64 = 4_000_000;

/// Poses validated at a time once the motion is thinned.
const CHUNK: usize = 1 << 16;

/// A pose at least this far from every obstacle touches none: a chunk may
/// start there (see the module documentation).
const CLEAR: f64 = 1e-6;

/// The executed motion, recorded as it is made.
pub(super) struct Motion<'w> {
    /// The runner's referee; without one a thinned motion is not validated.
    referee: Option<&'w dyn Referee>,
    /// Moves kept in full ([`FULL_MOVES`]; less in tests).
    full: u64,
    /// Poses validated at a time ([`CHUNK`]; less in tests).
    chunk: usize,
    /// Poses `0, stride, 2·stride, …` of the motion (every pose while the
    /// stride is 1).
    kept: Vec<Config>,
    stride: u64,
    /// Moves made: the motion has `moves + 1` poses.
    moves: u64,
    last: Config,
    /// Set once the motion passed [`FULL_MOVES`] moves.
    thinned: Option<Thinned<'w>>,
}

/// The measures of a thinned motion, and the poses not validated yet.
struct Thinned<'w> {
    referee: Option<&'w dyn Referee>,
    length: f64,
    turn: f64,
    smoothness: f64,
    /// The last two distinct (x, y) points, for the smoothness.
    corner: [Option<Point>; 2],
    clearance: f64,
    error: Option<ValidationError>,
    /// Poses from `pending_from` on, not validated yet (but the first).
    pending: Vec<Config>,
    pending_from: u64,
}

impl<'w> Motion<'w> {
    pub(super) fn new(referee: Option<&'w dyn Referee>, start: Config) -> Self {
        Self::with_sizes(referee, start, FULL_MOVES, CHUNK)
    }

    fn with_sizes(
        referee: Option<&'w dyn Referee>,
        start: Config,
        full: u64,
        chunk: usize,
    ) -> Self {
        Motion {
            referee,
            full,
            chunk,
            kept: vec![start],
            stride: 1,
            moves: 0,
            last: start,
            thinned: None,
        }
    }

    /// Moves made so far.
    pub(super) fn moves(&self) -> u64 {
        self.moves
    }

    /// Records one move, to `to`.
    pub(super) fn push(&mut self, to: Config) {
        let from = self.last;
        self.moves += 1;
        self.last = to;
        if let Some(t) = &mut self.thinned {
            t.record(from, to, self.chunk);
        }
        if self.moves.is_multiple_of(self.stride) {
            self.kept.push(to);
        }
        if self.thinned.is_none() && self.moves > self.full {
            // Every pose so far is kept (`kept[0]` is the start): measure
            // and validate them as the moves to come will be.
            let mut t = Thinned::new(self.referee, self.kept[0]);
            for w in self.kept.windows(2) {
                t.record(w[0], w[1], self.chunk);
            }
            self.thinned = Some(t);
        }
        if self.kept.len() as u64 > self.full + 1 {
            // Keep poses 0, 2·stride, 4·stride, …: every other one.
            self.stride *= 2;
            let mut k = 0;
            self.kept.retain(|_| {
                k += 1;
                k % 2 == 1
            });
        }
    }

    /// The poses kept (the last one included) and, for a thinned motion,
    /// the measures of the whole motion.
    pub(super) fn finish(mut self) -> (Vec<Config>, Option<MeasuredMotion>) {
        if !self.moves.is_multiple_of(self.stride) {
            self.kept.push(self.last);
        }
        let measured = self.thinned.map(|mut t| {
            t.flush();
            MeasuredMotion {
                poses: self.moves + 1,
                length: t.length,
                turn: t.turn,
                smoothness: t.smoothness,
                clearance: t.clearance,
                validation: t.error,
                stride: self.stride,
            }
        });
        (self.kept, measured)
    }
}

impl<'w> Thinned<'w> {
    /// Nothing measured yet, from the pose `first`.
    fn new(referee: Option<&'w dyn Referee>, first: Config) -> Self {
        Thinned {
            referee,
            length: 0.0,
            turn: 0.0,
            smoothness: 0.0,
            corner: [None, Some(first.xy())],
            clearance: if referee.is_some() { f64::INFINITY } else { f64::NAN },
            error: referee.is_none().then(|| ValidationError {
                segment: 0,
                at: first,
                obstacle: None,
                reason: format!(
                    "beyond {FULL_MOVES} moves the walk is validated as it is made, by the runner's referee, and none was lent: not validated"
                ),
            }),
            pending: vec![first],
            pending_from: 0,
        }
    }

    /// One more move: measured now, validated with its chunk.
    fn record(&mut self, from: Config, to: Config, chunk: usize) {
        self.measure(from, to);
        self.pending.push(to);
        if self.pending.len() >= chunk {
            self.flush();
        }
    }

    /// Adds the move `from → to` to the length, turn and smoothness, in
    /// the order the runner's sums take.
    fn measure(&mut self, from: Config, to: Config) {
        self.length += (to.x - from.x).hypot(to.y - from.y);
        self.turn += angle_diff(from.theta, to.theta).abs();
        let p = to.xy();
        match self.corner {
            [_, Some(b)] if b == p => {}
            [Some(a), Some(b)] => {
                self.smoothness += corner_smoothness(a, b, p);
                self.corner = [Some(b), Some(p)];
            }
            [_, b] => self.corner = [b, Some(p)],
        }
    }

    /// Validates the pending poses and keeps the overlap the next chunk
    /// starts with.
    fn flush(&mut self) {
        let Some(referee) = self.referee else {
            // Not validated (said at the start): nothing to keep.
            self.pending.clear();
            return;
        };
        if self.pending.len() < 2 {
            return;
        }
        if self.error.is_none()
            && let Err(mut e) = referee.validate(&self.pending)
        {
            e.segment += self.pending_from as usize;
            self.error = Some(e);
        }
        self.clearance = self.clearance.min(referee.clearance(&self.pending));
        let (pending, from) = overlap(referee, &self.pending, self.pending_from);
        self.pending = pending;
        self.pending_from = from;
    }
}

/// The poses a chunk after `poses` (whose first is pose `first` of the
/// motion) starts with: from the last one clear of every obstacle, or all
/// of them when none is.
fn overlap(referee: &dyn Referee, poses: &[Config], first: u64) -> (Vec<Config>, u64) {
    let from = poses
        .iter()
        .rposition(|&c| referee.clearance(&[c]) > CLEAR)
        .unwrap_or(0);
    (poses[from..].to_vec(), first + from as u64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contract::ValidatorReferee;
    use crate::geometry::path::{path_length, smoothness};
    use crate::geometry::validator::{DEFAULT_TOLERANCE, Validator};
    use crate::geometry::{Aabb, Obstacle, RobotShape, Shape, World};

    fn world() -> World {
        World {
            bounds: Aabb::from_corners(Point::new(0.0, 0.0), Point::new(100.0, 100.0)),
            obstacles: vec![Obstacle {
                name: "wall".into(),
                shape: Shape::Segment(Point::new(50.0, 10.0), Point::new(50.0, 90.0)),
            }],
        }
    }

    /// A zig-zag of `moves` moves left of the wall, touching it every 11th
    /// pose (so that some chunks cannot start at their predecessor's last
    /// pose).
    fn zigzag(moves: usize) -> Vec<Config> {
        (0..=moves)
            .map(|i| {
                if i % 11 == 10 {
                    return Config::new(50.0, 40.0, 0.0);
                }
                let x = 40.0 + (i % 7) as f64 * 0.5;
                let y = 40.0 + (i % 5) as f64 * 0.3;
                Config::new(x, y, 0.0)
            })
            .collect()
    }

    /// Records `all` with the given sizes.
    fn record(
        w: &World,
        robot: &RobotShape,
        all: &[Config],
        full: u64,
        chunk: usize,
    ) -> (Vec<Config>, Option<MeasuredMotion>) {
        let referee = ValidatorReferee::new(w, robot);
        let mut m = Motion::with_sizes(Some(&referee), all[0], full, chunk);
        for &c in &all[1..] {
            m.push(c);
        }
        m.finish()
    }

    /// Up to the full size nothing is thinned: every pose, no measures
    /// (the runner measures the list).
    #[test]
    fn short_motions_are_kept_in_full() {
        let (w, robot) = (world(), RobotShape::Point);
        let all = zigzag(100);
        let (kept, measured) = record(&w, &robot, &all, 100, 16);
        assert_eq!(kept, all);
        assert!(measured.is_none());
    }

    /// Beyond it, the measures are those of the whole motion, bit for bit,
    /// and the list keeps every stride-th pose and the last.
    #[test]
    fn thinned_motions_measure_as_the_whole_motion() {
        let (w, robot) = (world(), RobotShape::Point);
        for moves in [101, 250, 1001, 4099] {
            let all = zigzag(moves);
            let (kept, measured) = record(&w, &robot, &all, 100, 16);
            let m = measured.expect("thinned");
            assert_eq!(m.poses, all.len() as u64);
            assert_eq!(m.length, path_length(&all));
            assert_eq!(m.smoothness, smoothness(&all));
            assert_eq!(m.turn, 0.0);
            let v = Validator::new(&w);
            assert_eq!(m.clearance, v.clearance(&robot, &all, DEFAULT_TOLERANCE));
            assert_eq!(m.clearance, 0.0, "the zig-zag touches the wall");
            assert_eq!(m.validation, None);
            assert!(kept.len() <= 102, "{moves}: {} poses kept", kept.len());
            assert_eq!(kept.last(), all.last());
            let stride = m.stride as usize;
            assert!(
                stride >= 2 && stride * 102 > moves,
                "{moves}: stride {stride}"
            );
            for (k, c) in kept[..kept.len() - 1].iter().enumerate() {
                assert_eq!(*c, all[k * stride], "{moves}: pose {k}");
            }
        }
    }

    /// A move across the wall is found wherever it lies: in the part kept
    /// in full, at a chunk's seam, or later; with its index in the whole
    /// motion, as the validator reports it on the whole list.
    #[test]
    fn a_crossing_fails_the_motion_wherever_it_is() {
        let (w, robot) = (world(), RobotShape::Point);
        let v = Validator::new(&w);
        for at in [37, 100, 111, 127, 128, 300] {
            let mut all = zigzag(400);
            all.insert(at, Config::new(60.0, 50.0, 0.0));
            let whole = v
                .validate_path(&robot, &all, DEFAULT_TOLERANCE)
                .expect_err("crosses");
            let (_, measured) = record(&w, &robot, &all, 100, 16);
            let e = measured.and_then(|m| m.validation).expect("the crossing");
            assert_eq!(e, whole, "crossing at pose {at}");
        }
    }

    /// A point that steps onto the wall and off on the other side touches
    /// it twice and crosses it: only the validator's wall-crossing test,
    /// which follows the path, sees it. Found when the step onto the wall
    /// ends a chunk too.
    #[test]
    fn a_crossing_through_a_touch_is_found_across_chunk_seams() {
        let (w, robot) = (world(), RobotShape::Point);
        let v = Validator::new(&w);
        for moves in 120..160 {
            let mut all = zigzag(moves);
            all.push(Config::new(50.0, 45.0, 0.0));
            all.push(Config::new(55.0, 45.0, 0.0));
            let whole = v
                .validate_path(&robot, &all, DEFAULT_TOLERANCE)
                .expect_err("crosses");
            assert!(whole.reason.contains("crosses the wall"), "{whole:?}");
            let (_, measured) = record(&w, &robot, &all, 100, 16);
            let e = measured.and_then(|m| m.validation).expect("the crossing");
            assert_eq!(e, whole, "{moves} moves");
        }
    }

    /// Without a referee, a thinned motion is measured but says it was not
    /// validated (never a silent pass).
    #[test]
    fn without_a_referee_a_thinned_motion_is_not_validated() {
        let all = zigzag(300);
        let mut m = Motion::with_sizes(None, all[0], 100, 16);
        for &c in &all[1..] {
            m.push(c);
        }
        let (_, measured) = m.finish();
        let m = measured.expect("thinned");
        assert_eq!(m.length, path_length(&all));
        assert!(m.clearance.is_nan());
        let e = m.validation.expect("not validated");
        assert!(e.reason.contains("not validated"), "{e:?}");
    }
}

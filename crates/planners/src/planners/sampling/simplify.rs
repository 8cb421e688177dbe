//! Path simplification (SPEC 3.7 `simplify`): every change is kept only if
//! the motions it makes are free (checked in the path's direction, and
//! counted in `collision_checks`), so a simplified path passes the
//! validator as the raw one does. The start and the goal stay.
//!
//! - `shortcut`: first the waypoints that can be skipped are dropped
//!   (from each kept waypoint, the farthest one within
//!   [`SKIP_WINDOW`] ahead that it reaches by a free motion), then random
//!   shortcuts: two points drawn uniformly along the path (by cost) are
//!   joined directly when that is cheaper and the three motions it makes
//!   (into the first point along its segment, across, and out of the second
//!   point) are free — until [`PATIENCE`] tries in a row bring nothing (at
//!   most [`MAX_TRIES`] in all).
//! - `smooth`: `shortcut`, then up to [`SMOOTH_ROUNDS`] rounds of corner
//!   cutting in the manner of a B-spline (OMPL's `smoothBSpline`): every
//!   segment is split at its midpoint (when both halves are free), then
//!   each interior waypoint moves halfway towards the midpoint of its two
//!   neighbours when both motions to them are free.
//!
//! `limit time` covers the simplification too (it is part of the plan, and
//! of its `time_ms`): the waypoint pass, each shortcut try and each round of
//! corner cutting first read the clock, and once the time is up the path is
//! kept as simplified so far, with a note.

use crate::geometry::Config;

use super::Run;

/// Random shortcut tries in a row that bring nothing before `shortcut`
/// stops (SPEC 3.7: 100).
pub const PATIENCE: usize = 100;
/// The most random shortcut tries in all.
pub const MAX_TRIES: usize = 10_000;
/// How far ahead the waypoint pass looks.
pub const SKIP_WINDOW: usize = 64;
/// Corner-cutting rounds of `smooth`.
pub const SMOOTH_ROUNDS: usize = 5;
/// `smooth` splits no more segments once the path has this many waypoints.
pub const MAX_SMOOTH_NODES: usize = 4096;

/// Simplifies `path` (see the module documentation); `smooth` adds the
/// corner cutting. Each stage stops when the plan's `limit time` is up,
/// with the path as simplified so far (every change made was checked);
/// returns the path and whether the time limit stopped it.
pub fn simplify(run: &mut Run<'_>, path: Vec<Config>, smooth: bool) -> (Vec<Config>, bool) {
    let (path, stopped) = skip_waypoints(run, path);
    if stopped {
        return (path, true);
    }
    let (path, stopped) = shortcuts(run, path);
    if stopped || !smooth {
        return (path, stopped);
    }
    cut_corners(run, path)
}

/// From each kept waypoint, on to the farthest one (within the window)
/// that a free motion reaches; and whether the time limit stopped it (the
/// rest of the path kept as it was).
fn skip_waypoints(run: &mut Run<'_>, path: Vec<Config>) -> (Vec<Config>, bool) {
    if path.len() < 3 {
        return (path, false);
    }
    let mut out = vec![path[0]];
    let mut i = 0;
    while i + 1 < path.len() {
        if run.time_up() {
            out.extend_from_slice(&path[i + 1..]);
            return (out, true);
        }
        let mut j = (i + SKIP_WINDOW).min(path.len() - 1);
        while j > i + 1 && !run.motion_free(path[i], path[j]) {
            j -= 1;
        }
        out.push(path[j]);
        i = j;
    }
    (out, false)
}

/// Random shortcuts until [`PATIENCE`] tries in a row bring nothing; and
/// whether the time limit stopped them.
fn shortcuts(run: &mut Run<'_>, mut path: Vec<Config>) -> (Vec<Config>, bool) {
    let mut idle = 0;
    for _ in 0..MAX_TRIES {
        if idle >= PATIENCE || path.len() < 3 {
            break;
        }
        if run.time_up() {
            return (path, true);
        }
        idle += 1;
        let lengths: Vec<f64> = path
            .windows(2)
            .map(|w| run.space.distance(w[0], w[1]))
            .collect();
        let total: f64 = lengths.iter().sum();
        if total <= 0.0 {
            break;
        }
        let (s, t) = {
            let a = run.rng.next_f64() * total;
            let b = run.rng.next_f64() * total;
            (a.min(b), a.max(b))
        };
        let (i, fi) = locate(&lengths, s);
        let (j, fj) = locate(&lengths, t);
        if j <= i {
            continue; // within one segment: nothing to gain
        }
        let a = run.space.interpolate(path[i], path[i + 1], fi);
        let b = run.space.interpolate(path[j], path[j + 1], fj);
        let old = (1.0 - fi) * lengths[i] + lengths[i + 1..j].iter().sum::<f64>() + fj * lengths[j];
        let new = run.space.distance(a, b);
        if new >= old - 1e-9 * old.max(1.0) {
            continue;
        }
        if !(run.motion_free(a, b)
            && run.motion_free(path[i], a)
            && run.motion_free(b, path[j + 1]))
        {
            continue;
        }
        let mut next = Vec::with_capacity(path.len());
        next.extend_from_slice(&path[..=i]);
        if a != path[i] {
            next.push(a);
        }
        if b != path[j + 1] {
            next.push(b);
        }
        next.extend_from_slice(&path[j + 1..]);
        path = next;
        idle = 0;
    }
    (path, false)
}

/// The segment holding the point `s` along the path (by cost) and the
/// fraction of that segment before it.
fn locate(lengths: &[f64], mut s: f64) -> (usize, f64) {
    for (i, &l) in lengths.iter().enumerate() {
        if s < l || i + 1 == lengths.len() {
            return (
                i,
                if l > 0.0 {
                    (s / l).clamp(0.0, 1.0)
                } else {
                    0.0
                },
            );
        }
        s -= l;
    }
    (0, 0.0)
}

/// Corner cutting (see the module documentation); and whether the time
/// limit stopped it.
fn cut_corners(run: &mut Run<'_>, mut path: Vec<Config>) -> (Vec<Config>, bool) {
    for _ in 0..SMOOTH_ROUNDS {
        if path.len() < 2 {
            break;
        }
        if run.time_up() {
            return (path, true);
        }
        if path.len() * 2 <= MAX_SMOOTH_NODES {
            let mut split = Vec::with_capacity(path.len() * 2);
            split.push(path[0]);
            for w in path.windows(2) {
                let m = run.space.interpolate(w[0], w[1], 0.5);
                if run.motion_free(w[0], m) && run.motion_free(m, w[1]) {
                    split.push(m);
                }
                split.push(w[1]);
            }
            path = split;
        }
        let mut moved = false;
        for i in 1..path.len().saturating_sub(1) {
            let (prev, next) = (path[i - 1], path[i + 1]);
            let mid = run.space.interpolate(prev, next, 0.5);
            let c = run.space.interpolate(path[i], mid, 0.5);
            if run.space.distance(c, path[i]) <= 1e-9 {
                continue;
            }
            if run.motion_free(prev, c) && run.motion_free(c, next) {
                path[i] = c;
                moved = true;
            }
        }
        if !moved {
            break;
        }
    }
    (path, false)
}
